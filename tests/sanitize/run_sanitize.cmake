# The sanitizer tier (tests/CMakeLists.txt): configure a Debug ASan+UBSan unity build of everything
# that does not touch LIGGGHTS/MPI into BINARY_DIR, build it on JOBS cores, run its unit tests but
# the Python-only ones, JOBS at a time. Not ctest --build-and-test: that runs make with MAKEFLAGS
# emptied and no -j, i.e. on one core (stop 25: 8.5 of the tier's 11 min, the other core idle).
# MESHES_FROM (optional): a directory of wheel meshes another build generated, used instead of
# generating them with the ASan wheel-mesh (~60 s of CPU; meshes/CMakeLists.txt).
#   cmake -DSOURCE_DIR=... -DBINARY_DIR=... -DGENERATOR=... -DJOBS=2 [-DMESHES_FROM=DIR] -P run_sanitize.cmake
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

# Compiled by clang (scripts/install-deps.sh installs it) with -g1 (line tables only, not -g's
# full debug info): ASan and UBSan still report file:line for every frame. CPU (user + sys) of
# the tier's build, 104 TUs, 2026-11-28: gcc -g 568 s, gcc -g1 501 s, clang -g1 345 s; its unit
# tests ran 164 s (gcc) and 175 s (clang) on one core. Without a clang++ that links ASan+UBSan
# (Debian: clang and libclang-rt-dev, only recommended by clang, so --no-install-recommends
# leaves it out) it falls back to the default compiler and says why.
find_program(WHEELSIM_SANITIZE_CXX clang++)
find_program(WHEELSIM_SANITIZE_CC clang)
set(compiler "")
set(why "clang/clang++ not found")
if(WHEELSIM_SANITIZE_CXX AND WHEELSIM_SANITIZE_CC)
  set(probe_dir ${BINARY_DIR}-probe)
  file(WRITE ${probe_dir}/probe.cpp "int main() { return 0; }\n")
  execute_process(COMMAND ${WHEELSIM_SANITIZE_CXX} -fsanitize=address,undefined
                          ${probe_dir}/probe.cpp -o ${probe_dir}/probe
                  RESULT_VARIABLE probe_rc OUTPUT_QUIET ERROR_VARIABLE probe_err)
  file(REMOVE_RECURSE ${probe_dir})
  if(probe_rc EQUAL 0)
    set(compiler -DCMAKE_CXX_COMPILER=${WHEELSIM_SANITIZE_CXX}
                 -DCMAKE_C_COMPILER=${WHEELSIM_SANITIZE_CC})
  else()
    string(STRIP "${probe_err}" probe_err)
    set(why "${WHEELSIM_SANITIZE_CXX} cannot link -fsanitize=address,undefined (${probe_err})")
  endif()
endif()
if(NOT compiler)
  message(STATUS "sanitizer tier: ${why}; building with the default compiler (slower; "
                 "scripts/install-deps.sh installs clang and libclang-rt-dev)")
endif()
# A unity build (CMake's CMAKE_UNITY_BUILD: each target's sources compiled 8 to a translation
# unit): at -O0 most of a TU's time is parsing the headers it shares with its neighbours (Eigen,
# GoogleTest, toml++, CLI11). CPU of the tier's build, 2026-12-02, beside a 2-rank LIGGGHTS run:
# 266 s in 105 TUs, 162 s in 35 unity TUs. The Release build stays one TU per file, so a file that
# leans on a neighbour's includes still fails there.
run_step(configure ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BINARY_DIR} -G ${GENERATOR} ${compiler}
         -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DWHEELSIM_SANITIZE=ON
         -DCMAKE_UNITY_BUILD=ON
         -DWHEELSIM_WITH_LIGGGHTS=OFF "-DWHEELSIM_MESHES_FROM=${MESHES_FROM}")
run_step(build ${CMAKE_COMMAND} --build ${BINARY_DIR} --parallel ${JOBS})
# Left out here, run in the Release tier: three long loops of plain arithmetic on fixed-size data
# (1e5-step energy and frequency runs of the 2-DOF rig model; batch means of 3 x 16 AR(1) series of
# 400 000 samples), ~90 s of the tier's CPU on a slow machine, whose code shorter tests of the tier
# run too (RigModel.DampingDissipatesEnergy, the RigSimulation runs, the other RunHealth tests).
set(numerics_only "^RigModel\\.EnergyConservedWithoutDampingOver1e5Steps$|^RigModel\\.SuspensionNaturalFrequencyWithin0p1Percent$|^RunHealth\\.BatchMeansStandardErrorOfAnAr1SignalWithin10Percent$")
run_step("unit tests under ASan+UBSan" ${CMAKE_CTEST_COMMAND} --test-dir ${BINARY_DIR} -L unit
         -LE python -E "${numerics_only}" -j ${JOBS} --output-on-failure)
