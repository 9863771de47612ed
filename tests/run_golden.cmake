# Runs one golden case: dpscope with ARGS (a ;-list) in SOURCE_DIR, standard output compared with
# EXPECTED. With UPDATE=ON the expected file is rewritten instead. EXIT_CODE is the exit code the
# run must have (default 0).
string(REPLACE "|" ";" ARGS "${ARGS}")
if(NOT DEFINED EXIT_CODE)
    set(EXIT_CODE 0)
endif()
execute_process(
    COMMAND ${CMAKE_COMMAND} -E env TZ=UTC LANG=C LC_ALL=C ${DPSCOPE} ${ARGS}
    WORKING_DIRECTORY ${SOURCE_DIR}
    OUTPUT_VARIABLE actual
    ERROR_VARIABLE errors
    RESULT_VARIABLE result)
if(NOT "${result}" STREQUAL "${EXIT_CODE}")
    message(FATAL_ERROR "dpscope ${ARGS}: exit code ${result}, expected ${EXIT_CODE}\n${errors}")
endif()
if(UPDATE)
    file(WRITE ${SOURCE_DIR}/${EXPECTED} "${actual}")
    message(STATUS "updated ${EXPECTED}")
    return()
endif()
if(NOT EXISTS ${SOURCE_DIR}/${EXPECTED})
    message(FATAL_ERROR "${EXPECTED} is missing; run: cmake --build <build dir> --target update-golden")
endif()
file(READ ${SOURCE_DIR}/${EXPECTED} expected)
if(NOT actual STREQUAL expected)
    string(RANDOM LENGTH 8 tag)
    set(actual_file ${CMAKE_CURRENT_BINARY_DIR}/golden-actual-${tag}.txt)
    file(WRITE ${actual_file} "${actual}")
    execute_process(COMMAND diff -u ${SOURCE_DIR}/${EXPECTED} ${actual_file}
                    OUTPUT_VARIABLE difference)
    string(SUBSTRING "${difference}" 0 6000 difference)
    message(FATAL_ERROR "dpscope ${ARGS}: output differs from ${EXPECTED} "
                        "(refresh with: cmake --build <build dir> --target update-golden)\n"
                        "${difference}")
endif()
