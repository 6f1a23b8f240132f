# cmake -DEXE=strata_tests -P check_suites.cmake: fails when a test case is
# in none of the suites unit, render, slow (ctest would not run it) or when
# a test case's name holds a ';' (ctest would run a cut name that matches
# nothing, and report it passed).
execute_process(COMMAND ${EXE} --list-test-cases --no-colors=true
                OUTPUT_VARIABLE all RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXE} --list-test-cases failed: ${rc}")
endif()
string(FIND "${all}" ";" semicolon)
if(NOT semicolon EQUAL -1)
  message(FATAL_ERROR "a test case name holds ';', which ctest cuts:\n${all}")
endif()
execute_process(COMMAND ${EXE} --list-test-cases --no-colors=true --test-suite-exclude=unit,render,slow
                OUTPUT_VARIABLE rest RESULT_VARIABLE rc)
string(REGEX MATCH "passing the current filters: ([0-9]+)" found "${rest}")
if(NOT rc EQUAL 0 OR NOT found OR NOT CMAKE_MATCH_1 EQUAL 0)
  message(FATAL_ERROR "test cases in no labelled suite (unit, render, slow):\n${rest}")
endif()
string(REGEX MATCH "passing the current filters: ([0-9]+)" counted "${all}")
message(STATUS "${CMAKE_MATCH_1} test cases, each in a labelled suite")
