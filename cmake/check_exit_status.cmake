# cmake -DCOMMAND=<exe;args...> -DSTATUS=<n> [-DEXPECT=<regex>] -P check_exit_status.cmake
# Runs COMMAND and fails unless it exits with STATUS and (when given) its stderr matches EXPECT.
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT "${rc}" STREQUAL "${STATUS}")
  message(FATAL_ERROR "exit status ${rc}, expected ${STATUS}\nstdout: ${out}\nstderr: ${err}")
endif()
if(DEFINED EXPECT AND NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
endif()
message(STATUS "exit status ${rc} as expected: ${err}")
