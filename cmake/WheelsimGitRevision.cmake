# Writes OUTPUT_DIR/wheelsim_version.h (WHEELSIM_VERSION, WHEELSIM_GIT_REVISION) and
# OUTPUT_DIR/VERSION (an installed copy's "<version> <revision>") from the checkout at SOURCE_DIR.
# Run by the target wheelsim_git_revision at every build (cmake -P), not at configure time only,
# so a binary names the commit it was built from; "+dirty" when tracked files differ from that
# commit (the same mark as wheelsim_post.usage.git_revision). A file is rewritten only
# when its text changes, so an unchanged revision recompiles nothing.
#   cmake -DSOURCE_DIR=... -DOUTPUT_DIR=... -DVERSION=... -P WheelsimGitRevision.cmake
foreach(var SOURCE_DIR OUTPUT_DIR VERSION)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "WheelsimGitRevision.cmake: -D${var}=... is required")
  endif()
endforeach()
execute_process(COMMAND git rev-parse --short=12 HEAD
                WORKING_DIRECTORY "${SOURCE_DIR}"
                OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 0 OR NOT revision)
  set(revision "unknown")  # a source tree without git (an unpacked release)
else()
  execute_process(COMMAND git diff --quiet HEAD --
                  WORKING_DIRECTORY "${SOURCE_DIR}" RESULT_VARIABLE dirty ERROR_QUIET)
  if(dirty EQUAL 1)
    string(APPEND revision "+dirty")
  endif()
endif()
function(write_if_changed path text)
  set(old "")
  if(EXISTS "${path}")
    file(READ "${path}" old)
  endif()
  if(NOT old STREQUAL text)
    file(WRITE "${path}" "${text}")
  endif()
endfunction()
write_if_changed("${OUTPUT_DIR}/wheelsim_version.h"
  "#pragma once\n#define WHEELSIM_VERSION \"${VERSION}\"\n#define WHEELSIM_GIT_REVISION \"${revision}\"\n")
write_if_changed("${OUTPUT_DIR}/VERSION" "${VERSION} ${revision}\n")
