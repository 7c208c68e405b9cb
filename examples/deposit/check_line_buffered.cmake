# examples/deposit/check_line_buffered.cmake — a driver's log is line-buffered even when
# redirected to a file (issue #9: a run killed before its first progress line left an empty log).
# Runs COMMAND (a ;-list) with stdout to LOG, kills it after SECONDS, and requires EXPECT in LOG.
#   cmake -DCOMMAND=... -DLOG=... -DSECONDS=... -DEXPECT=... -P check_line_buffered.cmake
file(REMOVE "${LOG}")
execute_process(COMMAND ${COMMAND} OUTPUT_FILE "${LOG}" ERROR_VARIABLE err TIMEOUT ${SECONDS} RESULT_VARIABLE rc)
file(READ "${LOG}" text)
if(NOT text MATCHES "${EXPECT}")
  message(FATAL_ERROR "after ${SECONDS} s (result: ${rc}) the redirected log does not hold '${EXPECT}':\n${text}\n${err}")
endif()
message(STATUS "the log of the killed run holds its first lines (result: ${rc})")
