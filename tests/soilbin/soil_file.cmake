# A soil include file outside inputs/soils/, given by path (-var soil_file).
#   cmake -DCMD=<launcher|exe, '|'-separated> -DINPUTS_DIR=... -DOUT_DIR=... -DMODE=outside|lacking
#         -P soil_file.cmake
# The file is inputs/soils/ci.in copied to OUT_DIR/elsewhere/my_sand.in with soil_name my_sand and a
# marker print.
#   outside: in.soilbin runs in OUT_DIR/bed with the RELATIVE path ../elsewhere/my_sand.in and no
#            restart_file: the restart is named after soil_name (soilbin_my_sand.restart), the
#            .vars records the file's absolute path, the result block says soil = my_sand; then
#            resume.in, run from another directory (OUT_DIR/resume), includes that same file (the
#            marker), 20 steps.
#   lacking: the copy leaves soil_density out: in.soilbin stops naming the file and the variable.
cmake_minimum_required(VERSION 3.16)
foreach(v CMD INPUTS_DIR OUT_DIR MODE)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "soil_file.cmake: -D${v}=... is required")
  endif()
endforeach()
string(REPLACE "|" ";" cmd "${CMD}")
file(REMOVE_RECURSE "${OUT_DIR}")
file(MAKE_DIRECTORY "${OUT_DIR}/elsewhere" "${OUT_DIR}/bed" "${OUT_DIR}/resume")
file(READ "${INPUTS_DIR}/soils/ci.in" text)
string(REPLACE "variable soil_name string ci" "variable soil_name string my_sand\nprint \"my_sand.in: included\""
       text "${text}")
if(MODE STREQUAL "lacking")
  string(REGEX REPLACE "\nvariable soil_density [^\n]*" "" text "${text}")
endif()
set(soil "${OUT_DIR}/elsewhere/my_sand.in")
file(WRITE "${soil}" "${text}")

execute_process(
  COMMAND ${cmd} -in "${INPUTS_DIR}/in.soilbin" -log none -echo none -var inputs_dir "${INPUTS_DIR}"
          -var soil_file ../elsewhere/my_sand.in -var check_time 0.002 -var max_settle_time 0.006
  WORKING_DIRECTORY "${OUT_DIR}/bed"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
file(WRITE "${OUT_DIR}/bed/screen.txt" "${out}\n${err}")

if(MODE STREQUAL "lacking")
  set(expect "ERROR: soil file ${soil} does not define variable soil_density")
  string(FIND "${out}${err}" "${expect}" at)
  if(rc EQUAL 0 OR at EQUAL -1)
    message(FATAL_ERROR "expected a failure with '${expect}', got exit ${rc}:\n${out}\n${err}")
  endif()
  message(STATUS "failed as expected: ${expect}")
  return()
endif()

if(NOT rc EQUAL 0)
  message(FATAL_ERROR "in.soilbin exited with '${rc}' (${OUT_DIR}/bed/screen.txt):\n${err}")
endif()
set(restart "${OUT_DIR}/bed/soilbin_my_sand.restart")
if(NOT EXISTS "${restart}" OR NOT EXISTS "${restart}.vars")
  message(FATAL_ERROR "${restart} (named after the file's soil_name) or its .vars not written")
endif()
if(NOT out MATCHES "soilbin: soil = my_sand\n" OR NOT out MATCHES "my_sand.in: included")
  message(FATAL_ERROR "the result block does not say soil = my_sand, or the file was not read")
endif()
file(READ "${restart}.vars" vars)
foreach(line "variable soil index my_sand" "variable soil_file index ${soil}" "variable bed_dt index ")
  string(FIND "${vars}" "${line}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${restart}.vars lacks '${line}':\n${vars}")
  endif()
endforeach()
message(STATUS "bed soilbin_my_sand.restart; .vars records soil_file ${soil}")

execute_process(
  COMMAND ${cmd} -in "${INPUTS_DIR}/soilbin/resume.in" -log none -echo none
          -var inputs_dir "${INPUTS_DIR}" -var restart_file ../bed/soilbin_my_sand.restart
          -var resume_steps 20
  WORKING_DIRECTORY "${OUT_DIR}/resume"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
file(WRITE "${OUT_DIR}/resume/screen.txt" "${out}\n${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "soilbin: resume: soil file ${soil}\n"
   OR NOT out MATCHES "my_sand.in: included" OR NOT out MATCHES "soilbin: resume: soil my_sand,"
   OR NOT out MATCHES "soilbin: resume: ran 20 steps, atoms = [1-9]")
  message(FATAL_ERROR "resume.in (exit ${rc}) did not resume with ${soil}:\n${out}\n${err}")
endif()
message(STATUS "resume.in included ${soil} and ran 20 steps")
