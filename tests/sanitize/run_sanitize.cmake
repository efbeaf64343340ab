# The sanitizer tier (tests/CMakeLists.txt): configure a Debug ASan+UBSan build of everything that
# does not touch LIGGGHTS/MPI into BINARY_DIR, build it on JOBS cores, run its unit tests but the
# Python-only ones, JOBS at a time. Not ctest --build-and-test: that runs make with MAKEFLAGS
# emptied and no -j, i.e. on one core (stop 25: 8.5 of the tier's 11 min, the other core idle).
#   cmake -DSOURCE_DIR=... -DBINARY_DIR=... -DGENERATOR=... -DJOBS=2 -P run_sanitize.cmake
foreach(var SOURCE_DIR BINARY_DIR GENERATOR JOBS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_sanitize.cmake: -D${var}=... is required")
  endif()
endforeach()

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "sanitizer tier: ${what} failed (${rc})")
  endif()
endfunction()

# -g1 (line tables only, not -g's full debug info): ASan and UBSan still report file:line for
# every frame, and the build's compile CPU fell from 506 s to 440 s (104 TUs, idle 2 cores,
# 2026-11-28).
run_step(configure ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BINARY_DIR} -G ${GENERATOR}
         -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DWHEELSIM_SANITIZE=ON
         -DWHEELSIM_WITH_LIGGGHTS=OFF)
run_step(build ${CMAKE_COMMAND} --build ${BINARY_DIR} --parallel ${JOBS})
run_step("unit tests under ASan+UBSan" ${CMAKE_CTEST_COMMAND} --test-dir ${BINARY_DIR} -L unit
         -LE python -j ${JOBS} --output-on-failure)
