# Profile-guided optimisation (DPSCOPE_PGO; the package preset turns it on). The build first makes
# an instrumented dpscope of the same sources in BUILD/pgo/instrumented (an ExternalProject), runs
# it over simulated sessions of every bus and the bundled samples (scripts/pgo-train), and then
# compiles everything with the profile that run wrote (BUILD/pgo/profile). The dpscope built that
# way is then run over the same inputs (dpscope_pgo_check, part of the build's "all"), and its
# outputs must equal the instrumented build's, or the build fails. An incremental build recompiles
# only the files that changed; the others keep the code of the profile they were compiled with.
# docs/performance.md, "Profile-guided package", has the figures; docs/decisions.md says why only
# the package is built this way.
#
# Included by the top-level CMakeLists.txt before any target; dpscope_pgo_finish() at its end,
# once every target exists.

option(DPSCOPE_PGO "Build with profile-guided optimisation (GCC; trains an instrumented build first)"
       OFF)
# Set only by the instrumented build that DPSCOPE_PGO makes: where its runs write the profile.
set(DPSCOPE_PGO_GENERATE "" CACHE PATH
    "Internal to DPSCOPE_PGO: the instrumented build writes its profile to this folder")
mark_as_advanced(DPSCOPE_PGO_GENERATE)

set(dpscope_pgo_folder ${CMAKE_BINARY_DIR}/pgo)
set(dpscope_pgo_profile ${dpscope_pgo_folder}/profile)
set(dpscope_pgo_training ${dpscope_pgo_folder}/training)

if(DPSCOPE_PGO_GENERATE)
    # The profile's files are named by the objects' paths below this build's folder
    # (-fprofile-prefix-path): the optimised build finds them under the same names.
    add_compile_options(-fprofile-generate=${DPSCOPE_PGO_GENERATE} -fprofile-update=single
                        -fprofile-prefix-path=${CMAKE_BINARY_DIR})
    add_link_options(-fprofile-generate=${DPSCOPE_PGO_GENERATE})
elseif(DPSCOPE_PGO)
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
        message(FATAL_ERROR "DPSCOPE_PGO needs GCC (the profile is GCC's -fprofile-generate)")
    endif()
    if(DPSCOPE_SANITIZE OR DPSCOPE_COVERAGE OR DPSCOPE_BUILD_FUZZERS)
        message(FATAL_ERROR "DPSCOPE_PGO is for a release build, not with sanitizers, "
                            "coverage or fuzzers")
    endif()
    include(ExternalProject)
    # The same configuration as this build (its type, compiler and flags, where it finds the
    # libraries, position-independent code when the plugin is built), without tests or
    # benchmarks; only dpscope is built. Flags that change the code (a distribution's hardening
    # flags) must be the same in both builds, or GCC finds the profile's functions changed.
    string(TOUPPER "${CMAKE_BUILD_TYPE}" dpscope_pgo_type)
    set(dpscope_pgo_args
        -DCMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE}
        -DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}
        -DCMAKE_CXX_FLAGS=${CMAKE_CXX_FLAGS}
        -DCMAKE_CXX_FLAGS_${dpscope_pgo_type}=${CMAKE_CXX_FLAGS_${dpscope_pgo_type}}
        -DCMAKE_EXE_LINKER_FLAGS=${CMAKE_EXE_LINKER_FLAGS}
        -DCMAKE_EXE_LINKER_FLAGS_${dpscope_pgo_type}=${CMAKE_EXE_LINKER_FLAGS_${dpscope_pgo_type}}
        -DDPSCOPE_PGO_GENERATE=${dpscope_pgo_profile}
        -DDPSCOPE_BUILD_TESTS=OFF -DDPSCOPE_BUILD_BENCH=OFF
        -DDPSCOPE_BUILD_WIRESHARK_PLUGIN=${DPSCOPE_BUILD_WIRESHARK_PLUGIN})
    foreach(variable CMAKE_TOOLCHAIN_FILE CMAKE_PREFIX_PATH CMAKE_CXX_COMPILER_LAUNCHER)
        if(DEFINED ${variable} AND NOT "${${variable}}" STREQUAL "")
            # A list's ";" travels as "|" (LIST_SEPARATOR below).
            string(REPLACE ";" "|" value "${${variable}}")
            list(APPEND dpscope_pgo_args "-D${variable}=${value}")
        endif()
    endforeach()
    # With make, the instrumented build takes its jobs from this build's -j (the jobserver).
    if(CMAKE_GENERATOR MATCHES "Makefiles")
        set(dpscope_pgo_build_command $(MAKE) dpscope)
    else()
        set(dpscope_pgo_build_command ${CMAKE_COMMAND} --build <BINARY_DIR> --target dpscope)
    endif()
    ExternalProject_Add(dpscope_pgo_instrumented
        SOURCE_DIR ${PROJECT_SOURCE_DIR}
        BINARY_DIR ${dpscope_pgo_folder}/instrumented
        LIST_SEPARATOR |
        CMAKE_ARGS ${dpscope_pgo_args}
        BUILD_COMMAND ${dpscope_pgo_build_command}
        BUILD_BYPRODUCTS ${dpscope_pgo_folder}/instrumented/dpscope
        INSTALL_COMMAND ""
        # Its sources are this build's: make decides whether anything is to be rebuilt.
        BUILD_ALWAYS ON)
    # A new instrumented dpscope, a changed sample or training script trains again, from an empty
    # profile (the training copies the samples it reads: its check reads the same ones).
    file(GLOB dpscope_pgo_samples CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/samples/*.pcap
         ${PROJECT_SOURCE_DIR}/samples/*.pcapng ${PROJECT_SOURCE_DIR}/samples/serial.*
         ${PROJECT_SOURCE_DIR}/samples/terminal.log ${PROJECT_SOURCE_DIR}/samples/fc-examples.hex
         ${PROJECT_SOURCE_DIR}/samples/vlt2000-examples.txt)
    add_custom_command(
        OUTPUT ${dpscope_pgo_training}/trained
        COMMAND ${CMAKE_COMMAND} -E rm -rf ${dpscope_pgo_profile} ${dpscope_pgo_training}
        COMMAND ${PROJECT_SOURCE_DIR}/scripts/pgo-train train
                ${dpscope_pgo_folder}/instrumented/dpscope ${dpscope_pgo_training}
        DEPENDS dpscope_pgo_instrumented ${dpscope_pgo_folder}/instrumented/dpscope
                ${PROJECT_SOURCE_DIR}/scripts/pgo-train
                ${PROJECT_SOURCE_DIR}/bench/simulated_sessions.sh ${dpscope_pgo_samples}
        COMMENT "Training the instrumented dpscope (scripts/pgo-train)"
        VERBATIM)
    add_custom_target(dpscope_pgo_profile DEPENDS ${dpscope_pgo_training}/trained)
    # Code the training did not run is optimised as without a profile
    # (-fprofile-partial-training); a file without a profile (the tests, the plugin's own files)
    # is no error (-Wno-missing-profile; dpscope_pgo_finish() asks for a warning where dpscope's
    # own files lack one). A function GCC finds changed since the profile stays an error, except in
    # the generated parameter databases, whose path differs in the instrumented build (so GCC
    # finds their start-up functions neither matching nor there: both warnings off for that file).
    add_compile_options(-fprofile-use=${dpscope_pgo_profile} -fprofile-partial-training
                        -fprofile-prefix-path=${CMAKE_BINARY_DIR} -Wno-missing-profile)
endif()

# Every target of `folder` and its subfolders, in `out`.
function(dpscope_pgo_targets folder out)
    get_property(targets DIRECTORY ${folder} PROPERTY BUILDSYSTEM_TARGETS)
    get_property(subfolders DIRECTORY ${folder} PROPERTY SUBDIRECTORIES)
    foreach(subfolder IN LISTS subfolders)
        dpscope_pgo_targets(${subfolder} more)
        list(APPEND targets ${more})
    endforeach()
    set(${out} ${targets} PARENT_SCOPE)
endfunction()

# The static libraries of this project that `target` links, directly or through others, in `out`
# (each once, whatever cycles the links make).
function(dpscope_pgo_linked_libraries target out)
    set(found "")
    set(queue ${target})
    while(queue)
        list(POP_FRONT queue current)
        get_target_property(linked ${current} LINK_LIBRARIES)
        foreach(library IN LISTS linked)
            if(TARGET ${library} AND NOT library IN_LIST found)
                get_target_property(imported ${library} IMPORTED)
                get_target_property(type ${library} TYPE)
                if(NOT imported AND type STREQUAL "STATIC_LIBRARY")
                    list(APPEND found ${library})
                    list(APPEND queue ${library})
                endif()
            endif()
        endforeach()
    endwhile()
    set(${out} ${found} PARENT_SCOPE)
endfunction()

# With DPSCOPE_PGO: every target that compiles waits for the profile; dpscope's own files warn when
# they find none (the names no longer match); and the build checks dpscope against the
# instrumented build's outputs.
function(dpscope_pgo_finish)
    if(NOT DPSCOPE_PGO OR DPSCOPE_PGO_GENERATE)
        return()
    endif()
    dpscope_pgo_targets(${PROJECT_SOURCE_DIR} targets)
    foreach(target IN LISTS targets)
        get_target_property(type ${target} TYPE)
        if(type MATCHES "^(EXECUTABLE|STATIC_LIBRARY|SHARED_LIBRARY|MODULE_LIBRARY|OBJECT_LIBRARY)$")
            add_dependencies(${target} dpscope_pgo_profile)
        endif()
    endforeach()
    dpscope_pgo_linked_libraries(dpscope libraries)
    foreach(target dpscope ${libraries})
        target_compile_options(${target} PRIVATE -Wmissing-profile -Wno-error=missing-profile)
    endforeach()
    set_source_files_properties(
        ${dpscope_shipped_databases_cpp} DIRECTORY ${PROJECT_SOURCE_DIR}
        PROPERTIES COMPILE_OPTIONS "-Wno-coverage-mismatch;-Wno-missing-profile")
    # Run again whenever dpscope is relinked or the training ran again.
    add_custom_command(
        OUTPUT ${dpscope_pgo_training}/checked
        COMMAND ${PROJECT_SOURCE_DIR}/scripts/pgo-train check $<TARGET_FILE:dpscope>
                ${dpscope_pgo_training}
        COMMAND ${CMAKE_COMMAND} -E touch ${dpscope_pgo_training}/checked
        DEPENDS dpscope ${dpscope_pgo_training}/trained ${PROJECT_SOURCE_DIR}/scripts/pgo-train
        COMMENT "Checking the profile-guided dpscope against the instrumented one"
        VERBATIM)
    add_custom_target(dpscope_pgo_check ALL DEPENDS ${dpscope_pgo_training}/checked)
endfunction()
