# Writes CTEST_FILE with one ctest test per GoogleTest suite of TEST_EXECUTABLE, named after the
# suite and running it with --gtest_filter=SUITE.* in WORKING_DIRECTORY (tests/CMakeLists.txt uses
# it in sanitizer builds, where starting a test process costs more than most tests take).
# Usage: cmake -D TEST_EXECUTABLE=... -D WORKING_DIRECTORY=... -D CTEST_FILE=... -P gtest_suites.cmake
execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
                WORKING_DIRECTORY "${WORKING_DIRECTORY}"
                OUTPUT_VARIABLE listing
                ERROR_VARIABLE errors
                RESULT_VARIABLE result
                TIMEOUT 120)
if(NOT result EQUAL 0)
    message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests failed (${result}):\n${listing}${errors}")
endif()
# A suite's line starts in the first column and ends its name with a dot ("FdlTest.",
# "SessionTrackerTest/FaultScenarioTest.", "Suite/0.  # TypeParam = ..."); its tests are indented.
string(REPLACE ";" "," listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")
set(content "")
set(count 0)
foreach(line IN LISTS lines)
    if(line MATCHES "^([A-Za-z0-9_/]+)\\.( .*)?$")
        set(suite "${CMAKE_MATCH_1}")
        string(APPEND content
            "add_test([=[${suite}]=] [=[${TEST_EXECUTABLE}]=] [=[--gtest_filter=${suite}.*]=])\n"
            "set_tests_properties([=[${suite}]=] PROPERTIES WORKING_DIRECTORY [=[${WORKING_DIRECTORY}]=]"
            " ENVIRONMENT [=[TZ=UTC;LANG=C;LC_ALL=C]=])\n")
        math(EXPR count "${count} + 1")
    endif()
endforeach()
if(count EQUAL 0)
    message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests listed no test suite:\n${listing}")
endif()
file(WRITE "${CTEST_FILE}" "${content}")
