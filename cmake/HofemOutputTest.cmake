# hofem_output_test(NAME <name> REGEX <pattern> [EXIT <n|nonzero>] [SKIP_EXIT <n>] [STDIN <file>]
#                   COMMAND <cmd> [args...])
#
# A test judged by its exit status and its output (verification/tools/expect_output.py).
# ctest's PASS_REGULAR_EXPRESSION would replace the exit status as the verdict, so a
# command that fails while printing the expected words would pass; the ctest
# tests.exit_status_judged (verification/tools/check_test_verdicts.py) keeps that
# property out of the suite. Extra properties go through set_tests_properties as usual;
# with SKIP_EXIT n, set SKIP_RETURN_CODE n too (the wrapper passes n through).
#
# PARSE_ARGV keeps a ';' inside an argument (python3 -c "a; b", a pattern "x; y")
# as part of that argument instead of splitting it as a list separator.
# COMMAND runs under Python, so name an executable target as $<TARGET_FILE:tgt>:
# add_test turns a bare target name into its path only when it is the first word.
get_filename_component(HOFEM_EXPECT_OUTPUT ${CMAKE_CURRENT_LIST_DIR}/../verification/tools/expect_output.py ABSOLUTE)
function(hofem_output_test)
  cmake_parse_arguments(PARSE_ARGV 0 T "" "NAME;REGEX;EXIT;SKIP_EXIT;STDIN" "COMMAND")
  if(NOT T_NAME OR NOT DEFINED T_REGEX OR NOT T_COMMAND OR T_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "hofem_output_test: NAME, REGEX and COMMAND are required (unparsed: ${T_UNPARSED_ARGUMENTS})")
  endif()
  if(NOT DEFINED T_EXIT)
    set(T_EXIT 0)
  endif()
  set(options --exit=${T_EXIT})
  if(DEFINED T_SKIP_EXIT)
    list(APPEND options --skip-exit=${T_SKIP_EXIT})
  endif()
  if(T_STDIN)
    list(APPEND options --stdin=${T_STDIN})
  endif()
  # --regex=...: one argument even when the pattern starts with '-' (e.g. "--degree").
  add_test(NAME ${T_NAME}
    COMMAND /usr/bin/python3 ${HOFEM_EXPECT_OUTPUT} "--regex=${T_REGEX}" ${options} -- ${T_COMMAND})
endfunction()
