# One bad input: runs mfree in the scratch folder WORK, whose output folder "out" holds the
# results of an earlier run (the marker and previous.txt), and asserts what a user must get:
# exit code EXIT, an error message matching EXPECT (which names the file and the key, line or
# point), and the earlier results as they were, with nothing else left in WORK.
#   cmake -DMFREE=exe -DARGS="run;scene;--set;..." -DEXIT=1 -DEXPECT=regex -DWORK=dir -P check.cmake
cmake_policy(SET CMP0054 NEW)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/out")
file(WRITE "${WORK}/out/.mfree-output" "written by mfree: a run replaces this folder as a whole\n")
file(WRITE "${WORK}/out/previous.txt" "the results of an earlier run\n")
execute_process(COMMAND ${MFREE} ${ARGS} WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE code
                OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
if(NOT code STREQUAL "${EXIT}")
  message(FATAL_ERROR "expected exit code ${EXIT}, got ${code}\n${stdout}${err}")
endif()
if(NOT "${err}" MATCHES "${EXPECT}")
  message(FATAL_ERROR "the error message does not match '${EXPECT}':\n${err}")
endif()
file(GLOB left LIST_DIRECTORIES true RELATIVE "${WORK}" "${WORK}/*" "${WORK}/.*")
file(GLOB kept LIST_DIRECTORIES true RELATIVE "${WORK}/out" "${WORK}/out/*" "${WORK}/out/.*")
file(READ "${WORK}/out/previous.txt" previous)
if(NOT left STREQUAL "out" OR NOT kept STREQUAL ".mfree-output;previous.txt" OR
   NOT previous STREQUAL "the results of an earlier run\n")
  message(FATAL_ERROR "the failed run changed its folder: ${WORK} holds '${left}', out holds '${kept}'")
endif()
message(STATUS "refused as expected (exit ${code}): ${err}")
