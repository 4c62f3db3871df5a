# Runs a command that must fail cleanly: non-zero exit, an error message matching
# EXPECT (a regular expression), and no file left at OUTPUT.
#   cmake -DCOMMAND="a;b;c" -DEXPECT=regex -DOUTPUT=path -P expect_failure.cmake
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(code EQUAL 0)
  message(FATAL_ERROR "expected a failure, got exit code 0\n${out}${err}")
endif()
if(NOT "${err}" MATCHES "${EXPECT}")
  message(FATAL_ERROR "the error message does not match '${EXPECT}':\n${err}")
endif()
if(OUTPUT AND EXISTS "${OUTPUT}")
  message(FATAL_ERROR "a failed run left ${OUTPUT} behind")
endif()
message(STATUS "failed as expected (exit ${code}): ${err}")
