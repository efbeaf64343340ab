# liggghts_wheel.precompiled_models: the contact-model combination liggghts-wheel compiles itself
# (liggghts_fix/precompiled_contact_models.cpp) against LIGGGHTS' generic class for the same
# combination. A small dry_sand bin (hertz, tangential history, cohesion sjkr, rolling cdt: pair
# and walls) is poured and settled for 2000+ steps twice:
#   - with the registration: the banner counts 8 combinations and LIGGGHTS prints no "not located
#     in any whitelist" warning (our class was chosen);
#   - with WHEELSIM_GENERIC_CONTACT_MODELS=1: the banner says so and the warning appears (the
#     library itself lacks the combination, so the comparison is against its generic class);
#   - the two restart files are identical byte for byte (the same model code, the same physics).
#   cmake -DLAUNCH=<mpirun...;liggghts-wheel> -DINPUTS_DIR=... -DWORKDIR=... -P this
foreach(var LAUNCH INPUTS_DIR WORKDIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_precompiled_models.cmake: -D${var}=... is required")
  endif()
endforeach()

function(run_bin mode)
  set(dir "${WORKDIR}/${mode}")
  file(REMOVE_RECURSE "${dir}")
  file(MAKE_DIRECTORY "${dir}")
  set(env "")
  if(mode STREQUAL "generic")
    set(env WHEELSIM_GENERIC_CONTACT_MODELS=1)
  endif()
  execute_process(
    COMMAND ${CMAKE_COMMAND} -E env ${env} ${LAUNCH} -in "${INPUTS_DIR}/in.soilbin" -log none
            -echo none -var inputs_dir "${INPUTS_DIR}" -var out_dir "${dir}"
            -var restart_file "${dir}/bed.restart" -var soil dry_sand -var bin_length 0.10
            -var bin_width 0.08 -var fill_height 0.03 -var check_time 0.01
            -var max_settle_time 0.15
    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${mode} run failed (${rc}):\n${out}\n${err}")
  endif()
  set(${mode}_out "${out}${err}" PARENT_SCOPE)
endfunction()

run_bin(precompiled)
run_bin(generic)

if(NOT precompiled_out MATCHES "8 contact-model combination\\(s\\) precompiled")
  message(FATAL_ERROR "precompiled run: banner does not count 8 combinations:\n${precompiled_out}")
endif()
if(precompiled_out MATCHES "not located in any whitelist")
  message(FATAL_ERROR "precompiled run: LIGGGHTS still chose its generic class (whitelist warning)")
endif()
if(NOT generic_out MATCHES "0 contact-model combination\\(s\\) precompiled \\(WHEELSIM_GENERIC_CONTACT_MODELS=1\\)")
  message(FATAL_ERROR "generic run: the banner does not say the registration is off:\n${generic_out}")
endif()
if(NOT generic_out MATCHES "not located in any whitelist")
  message(FATAL_ERROR "generic run: no whitelist warning — this LIGGGHTS build has the combination "
                      "itself, or the switch did not work; the comparison is void")
endif()
if(NOT precompiled_out MATCHES "soilbin: particles = ([0-9]+)")
  message(FATAL_ERROR "precompiled run: no particle count in its output")
endif()
set(n "${CMAKE_MATCH_1}")
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${WORKDIR}/precompiled/bed.restart"
                        "${WORKDIR}/generic/bed.restart" RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "the restart files differ: the precompiled combination does not reproduce "
                      "LIGGGHTS' generic class (${n} particles)")
endif()
message(STATUS "precompiled and generic classes: identical restart files (${n} particles)")
