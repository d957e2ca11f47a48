# Runs EXE with ARGS and requires exit status STATUS and a single-line stderr
# matching PATTERN (used by the CLI error-path tests).
separate_arguments(arg_list UNIX_COMMAND "${ARGS}")
# Progress lines (a scene's "set-up" line before its mesh fails to load) are not
# part of the error message checked here.
set(ENV{HOFEM_PROGRESS} 0)
execute_process(COMMAND ${EXE} ${arg_list} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL STATUS)
  message(FATAL_ERROR "exit status ${rc}, expected ${STATUS}; stderr: ${err}")
endif()
string(STRIP "${err}" err_stripped)
if(err_stripped MATCHES "\n")
  message(FATAL_ERROR "error message is not one line:\n${err}")
endif()
if(NOT err_stripped MATCHES "^hofem: error: ")
  message(FATAL_ERROR "error message does not start with 'hofem: error: ': ${err}")
endif()
if(NOT err_stripped MATCHES "${PATTERN}")
  message(FATAL_ERROR "error message does not match '${PATTERN}': ${err}")
endif()
