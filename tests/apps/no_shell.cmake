# A scene's output folder reaches the plotting script as one argument, never through a shell:
# a folder named like a shell command runs nothing. Runs COMMAND (which must succeed) in the
# empty folder WORK and checks that no file INJECTED appeared and that the plots were drawn in
# the folder of that name.
#   cmake -DCOMMAND="a;b;c" -DWORK=path -DFOLDER=name -P no_shell.cmake
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
execute_process(COMMAND ${COMMAND} WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE code OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the run failed (exit ${code}):\n${out}${err}")
endif()
file(GLOB_RECURSE injected "${WORK}/*INJECTED*")
if(injected)
  message(FATAL_ERROR "a shell ran the scene's text: ${injected}")
endif()
file(GLOB plots "${WORK}/${FOLDER}/*.png")
if(NOT plots)
  message(FATAL_ERROR "no plot in '${WORK}/${FOLDER}':\n${out}${err}")
endif()
message(STATUS "no shell: plots in '${FOLDER}', nothing injected")
