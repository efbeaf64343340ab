# clang-format: `cmake --build build --target format-check` fails on any C++ file of the project
# that clang-format (the repository's .clang-format) would change; `--target format` rewrites them.
# The ctest `format.check` (label unit) runs the check, so CI does. Debian 12's clang-format 14 is
# the reference version (scripts/install-deps.sh installs it): other versions format differently.
find_program(WHEELSIM_CLANG_FORMAT NAMES clang-format-14 clang-format)
set(_format_dirs bench cli config_messages coupler geometry liggghts_fix meshes scm soil_lab tests
                 wheel_dynamics)
set(_format_files)
foreach(dir IN LISTS _format_dirs)
  file(GLOB_RECURSE _found CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/${dir}/*.cpp"
       "${PROJECT_SOURCE_DIR}/${dir}/*.h" "${PROJECT_SOURCE_DIR}/${dir}/*.hpp")
  list(APPEND _format_files ${_found})
endforeach()
list(SORT _format_files)
if(WHEELSIM_CLANG_FORMAT)
  add_custom_target(format-check
    COMMAND "${WHEELSIM_CLANG_FORMAT}" --dry-run -Werror ${_format_files}
    WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
    COMMENT "clang-format check of the project's C++ files"
    VERBATIM)
  add_custom_target(format
    COMMAND "${WHEELSIM_CLANG_FORMAT}" -i ${_format_files}
    WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
    COMMENT "clang-format of the project's C++ files"
    VERBATIM)
  add_test(NAME format.check
           COMMAND "${WHEELSIM_CLANG_FORMAT}" --dry-run -Werror ${_format_files}
           WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}")
  set_tests_properties(format.check PROPERTIES LABELS unit TIMEOUT 300)
else()
  message(WARNING "clang-format not found: no format-check target and no format.check test "
                  "(scripts/install-deps.sh installs it)")
endif()
