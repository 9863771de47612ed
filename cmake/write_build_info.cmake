# Writes OUTPUT, a header naming the commit dpscope is built from (`dpscope --version`). Run at
# every build (the target dpscope_build_info); the file is rewritten only when the commit changes,
# so nothing is rebuilt otherwise. The commit is `git describe --always --dirty` of SOURCE_DIR; a
# tree that is no git clone (a source tarball) may carry it in SOURCE_DIR/.commit; else "unknown".
set(commit "")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS "${SOURCE_DIR}/.git")
    execute_process(COMMAND "${GIT_EXECUTABLE}" describe --always --dirty --abbrev=12
                    WORKING_DIRECTORY "${SOURCE_DIR}" OUTPUT_VARIABLE commit
                    OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE git_result)
    if(NOT git_result EQUAL 0)
        set(commit "")
    endif()
endif()
if(commit STREQUAL "" AND EXISTS "${SOURCE_DIR}/.commit")
    file(STRINGS "${SOURCE_DIR}/.commit" commit LIMIT_COUNT 1)
endif()
if(commit STREQUAL "")
    set(commit "unknown")
endif()
set(text "#pragma once\n\nnamespace dpscope {\ninline constexpr const char* kBuildCommit = \"${commit}\";\n}  // namespace dpscope\n")
if(EXISTS "${OUTPUT}")
    file(READ "${OUTPUT}" old)
else()
    set(old "")
endif()
if(NOT old STREQUAL text)
    file(WRITE "${OUTPUT}" "${text}")
endif()
