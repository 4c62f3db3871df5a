# One bad input: runs mfree in the scratch folder WORK, whose output folder "out" holds the
# results of an earlier run (the marker and previous.txt), and asserts what a user must get:
# exit code EXIT, an error message matching EXPECT (which names the file and the key, line or
# point), and the earlier results as they were, with nothing else left in WORK.
#   cmake -DMFREE=exe -DARGS="run;scene;--set;..." -DEXIT=1 -DEXPECT=regex -DWORK=dir -P check.cmake
# Paths the file system makes hostile are built in WORK for an argument that names them:
#   @LOOP@              a symbolic link to itself (WORK/loop)
#   @CHECKPOINT_LOOP@   a checkpoint folder (WORK/ck) whose step folder is a link to itself
#   @CHECKPOINT_STEP@   a checkpoint folder whose step number has 25 digits
#   @CHECKPOINT:EDIT@   a checkpoint folder (WORK/ck) holding the first checkpoint of the run
#                       of the other arguments (without --restart; hostile_checkpoint.py runs
#                       it in WORK/gen and kills it), with one edit and a hash that fits:
#                       ARRAY:INDEX=VALUE sets a value, step=VALUE the step (and its folder)
# A token that limits the run instead (anywhere among the arguments; it is taken out):
#   @FILE_SIZE_LIMIT@   files of at most 64 KiB (ulimit -f 64): a larger write fails
cmake_policy(SET CMP0054 NEW)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/out")
file(WRITE "${WORK}/out/.mfree-output" "written by mfree: a run replaces this folder as a whole\n")
file(WRITE "${WORK}/out/previous.txt" "the results of an earlier run\n")
set(made "")
if(ARGS MATCHES "@LOOP@")
  file(CREATE_LINK loop "${WORK}/loop" SYMBOLIC)
  list(TRANSFORM ARGS REPLACE "@LOOP@" "loop")
  list(APPEND made loop)
endif()
if(ARGS MATCHES "@CHECKPOINT_LOOP@")
  file(MAKE_DIRECTORY "${WORK}/ck")
  file(CREATE_LINK step_0000000002 "${WORK}/ck/step_0000000002" SYMBOLIC)
  list(TRANSFORM ARGS REPLACE "@CHECKPOINT_LOOP@" "ck")
  list(APPEND made ck)
endif()
if(ARGS MATCHES "@CHECKPOINT_STEP@")
  file(WRITE "${WORK}/ck/step_9999999999999999999999999/state.bin" "")
  list(TRANSFORM ARGS REPLACE "@CHECKPOINT_STEP@" "ck")
  list(APPEND made ck)
endif()
if(ARGS MATCHES "@CHECKPOINT:([^@]+)@")
  set(edit "${CMAKE_MATCH_1}")
  set(run ${ARGS})
  list(REMOVE_ITEM run "--restart" "@CHECKPOINT:${edit}@")
  find_program(PYTHON3 python3 REQUIRED)
  execute_process(COMMAND ${PYTHON3} "${CMAKE_CURRENT_LIST_DIR}/hostile_checkpoint.py" ${MFREE} "${WORK}/gen" "${WORK}/ck"
                          "${edit}" -- ${run}
                  RESULT_VARIABLE made_code ERROR_VARIABLE made_err)
  if(NOT made_code EQUAL 0)
    message(FATAL_ERROR "hostile_checkpoint.py failed (${made_code}): ${made_err}")
  endif()
  list(TRANSFORM ARGS REPLACE "@CHECKPOINT:[^@]+@" "ck")
  list(APPEND made ck)
endif()
set(limit "")
if(ARGS MATCHES "@FILE_SIZE_LIMIT@")
  list(REMOVE_ITEM ARGS "@FILE_SIZE_LIMIT@")
  set(limit sh -c "ulimit -f 64 && exec \"$0\" \"$@\"")
endif()
execute_process(COMMAND ${limit} ${MFREE} ${ARGS} WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE code
                OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
foreach(path IN LISTS made)
  file(REMOVE_RECURSE "${WORK}/${path}")
endforeach()
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
