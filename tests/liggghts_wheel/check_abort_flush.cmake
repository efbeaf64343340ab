# ctest driver: run a deck that aborts with error->one at step 3 (fix wheelsim/selftest
# abort_at 3) and check that (a) the job fails, (b) the error message reached the screen output,
# (c) the log file opened by the deck's `log` command holds the thermo lines of steps 0–2, i.e.
# was flushed before MPI_Abort (without liggghts-wheel's flush it is empty: checked by hand with
# a build lacking flush_before_abort.cpp).
# Variables: LAUNCH (list: launcher + executable), DECK, WORKDIR.
file(REMOVE_RECURSE "${WORKDIR}")
file(MAKE_DIRECTORY "${WORKDIR}")
execute_process(
  COMMAND ${LAUNCH} -in "${DECK}" -var selftest_args "abort_at 3" -var deck_log 1
          -log none
  WORKING_DIRECTORY "${WORKDIR}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(rc EQUAL 0)
  message(FATAL_ERROR "expected the aborting run to fail, it exited 0:\n${out}\n${err}")
endif()
if(NOT "${out}${err}" MATCHES "deliberate one-rank error at step 3")
  message(FATAL_ERROR "the error->one message was lost; output was:\n${out}\n${err}")
endif()
if(NOT EXISTS "${WORKDIR}/deck.log")
  message(FATAL_ERROR "the deck's log file ${WORKDIR}/deck.log was not created")
endif()
file(STRINGS "${WORKDIR}/deck.log" thermo_lines REGEX "^ +2 +3 +3 *$")
if(NOT thermo_lines)
  file(READ "${WORKDIR}/deck.log" log_text)
  message(FATAL_ERROR "deck.log lacks the step-2 thermo line (not flushed before abort):\n${log_text}")
endif()
message(STATUS "abort flushed the log and kept the message (rc=${rc})")
