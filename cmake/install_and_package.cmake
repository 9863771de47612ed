# What `cmake --install` puts where besides the binary, the extcap link, the plugin and the
# service (CMakeLists.txt, wireshark/CMakeLists.txt), and the Debian package and source tarball
# CPack makes of it (issue 32, docs/install.md).
#
# Made at build time from the built dpscope itself, so that they cannot drift from its options:
#   - the man pages, dpscope(1) and dpscope-SUB(1), by help2man from --help
#     (cmake/write_man_pages.cmake; skipped with a warning when help2man is missing);
#   - the bash and zsh completion scripts, by `dpscope completion bash|zsh`.
# Not in the sanitizer and coverage trees, which install nothing (their tests still run
# `dpscope completion` under the sanitizers).
set(dpscope_build_extras ON)
if(DPSCOPE_SANITIZE OR DPSCOPE_COVERAGE)
    set(dpscope_build_extras OFF)
endif()

find_program(HELP2MAN_EXECUTABLE help2man)
set(dpscope_man_dir ${CMAKE_CURRENT_BINARY_DIR}/man)
set(DPSCOPE_MAN_PAGES OFF)
if(HELP2MAN_EXECUTABLE AND dpscope_build_extras)
    set(DPSCOPE_MAN_PAGES ON)
    add_custom_command(
        OUTPUT ${dpscope_man_dir}/dpscope.1.gz
        COMMAND ${CMAKE_COMMAND} -DDPSCOPE=$<TARGET_FILE:dpscope> -DHELP2MAN=${HELP2MAN_EXECUTABLE}
                -DVERSION=${PROJECT_VERSION} -DOUTPUT_DIR=${dpscope_man_dir}
                -P ${PROJECT_SOURCE_DIR}/cmake/write_man_pages.cmake
        DEPENDS dpscope ${PROJECT_SOURCE_DIR}/cmake/write_man_pages.cmake
        COMMENT "The man pages, from dpscope --help (help2man)")
    add_custom_target(dpscope_man_pages ALL DEPENDS ${dpscope_man_dir}/dpscope.1.gz)
    install(DIRECTORY ${dpscope_man_dir}/ DESTINATION ${CMAKE_INSTALL_MANDIR}/man1
            FILES_MATCHING PATTERN "*.1.gz")
elseif(dpscope_build_extras)
    message(WARNING "help2man not found: no man pages (scripts/install-deps installs it)")
endif()

if(dpscope_build_extras)
    set(dpscope_completion_dir ${CMAKE_CURRENT_BINARY_DIR}/completion)
    add_custom_command(
        OUTPUT ${dpscope_completion_dir}/dpscope ${dpscope_completion_dir}/_dpscope
        COMMAND ${CMAKE_COMMAND} -E make_directory ${dpscope_completion_dir}
        COMMAND dpscope completion bash > ${dpscope_completion_dir}/dpscope
        COMMAND dpscope completion zsh > ${dpscope_completion_dir}/_dpscope
        DEPENDS dpscope
        COMMENT "The bash and zsh completion, from dpscope's options (dpscope completion)")
    add_custom_target(dpscope_completion ALL
                      DEPENDS ${dpscope_completion_dir}/dpscope ${dpscope_completion_dir}/_dpscope)
    # Where Debian's bash-completion and zsh look for a package's scripts.
    install(FILES ${dpscope_completion_dir}/dpscope
            DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
    install(FILES ${dpscope_completion_dir}/_dpscope
            DESTINATION ${CMAKE_INSTALL_DATADIR}/zsh/vendor-completions)
endif()

# The sample captures (without the golden tests' expected outputs) and the documentation.
install(DIRECTORY samples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/dpscope/samples
        PATTERN expected EXCLUDE)
install(FILES README.md CONTRIBUTING.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs DESTINATION ${CMAKE_INSTALL_DOCDIR})
set(dpscope_changelog ${CMAKE_CURRENT_BINARY_DIR}/packaging/changelog.gz)
add_custom_command(
    OUTPUT ${dpscope_changelog}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_CURRENT_BINARY_DIR}/packaging
    COMMAND gzip -9nc ${PROJECT_SOURCE_DIR}/packaging/changelog > ${dpscope_changelog}
    DEPENDS ${PROJECT_SOURCE_DIR}/packaging/changelog)
add_custom_target(dpscope_changelog ALL DEPENDS ${dpscope_changelog})
install(FILES ${dpscope_changelog} DESTINATION ${CMAKE_INSTALL_DOCDIR})

# ---- CPack: `cpack -G DEB` (the package preset) and the source tarball -------------------------
set(CPACK_PACKAGE_NAME dpscope)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "dpscope maintainers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "protocol analyzer for drive parameter channels on PROFIBUS DP and Danfoss serial buses")
set(CPACK_PACKAGE_DESCRIPTION
    "dpscope decodes PROFIBUS DP captures (pcap, pcapng, raw serial dumps, hex logs) down to the
PPO parameter channel and the DP-V1 PROFIdrive parameter access, and the Danfoss FC protocol and
VLT 2000 serial telegrams; it pairs every parameter request with its response, reports handshake
violations and bus health as text, JSON, Markdown, HTML or JUnit XML, sniffs live from an RS-485
adapter, and brings a Wireshark dissector plugin and extcap capture interface.")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER
    "dpscope maintainers <maintainers@users.noreply.h-seed-4616649c.example>")
set(CPACK_DEBIAN_PACKAGE_SECTION net)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # dpscope_0.1.0_amd64.deb
# The libraries' packages from what the binary and the plugin link (dpkg-shlibdeps): libpcap,
# libfmt, libmosquitto, libwireshark, libc, libstdc++. A Wireshark plugin loads only into the
# Wireshark minor version it was built against: that one, and no later.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
if(DPSCOPE_BUILD_WIRESHARK_PLUGIN AND DPSCOPE_WIRESHARK_VERSION MATCHES "^([0-9]+)\\.([0-9]+)")
    math(EXPR dpscope_next_minor "${CMAKE_MATCH_2} + 1")
    set(CPACK_DEBIAN_PACKAGE_DEPENDS
        "libwireshark-data (>= ${CMAKE_MATCH_1}.${CMAKE_MATCH_2}), libwireshark-data (<< ${CMAKE_MATCH_1}.${dpscope_next_minor})")
    set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "tshark | wireshark")
endif()
# Install into a staging root with DESTDIR, so that the absolute folders (Wireshark's plugin and
# extcap folders, /etc/dpscope) land inside the package.
set(CPACK_SET_DESTDIR ON)
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# The service's example config is a conffile.
set(CPACK_DEBIAN_PACKAGE_CONFFILES "")
if(DPSCOPE_SYSTEMD_UNIT_DIR)
    file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/packaging/conffiles "${DPSCOPE_CONFIG_DIR}/example.conf\n")
    set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_BINARY_DIR}/packaging/conffiles)
endif()

# The source tarball: the tree as git has it, without build trees and caches; `.commit` names the
# commit, for `dpscope --version` of a build from the tarball (cmake/write_build_info.cmake):
# cpack writes it into the source folder (git ignores it) before it copies the tree.
set(CPACK_SOURCE_GENERATOR TGZ)
set(CPACK_SOURCE_PACKAGE_FILE_NAME dpscope-${PROJECT_VERSION})
# Anchored at the source folder (a source folder under some build/ folder is still copied). A
# literal dot is written [.]: CPack reads these back from a generated file, where a backslash
# escape is CMake syntax first (policy CMP0010 warned of "\\." as an invalid escape).
set(dpscope_src "^${PROJECT_SOURCE_DIR}")
set(CPACK_SOURCE_IGNORE_FILES "${dpscope_src}/build/" "${dpscope_src}/[.]git(/|$)"
    "${dpscope_src}/[.]cache/" "${dpscope_src}/bench/data/" "[.]swp$")
set(CPACK_GENERATOR DEB)  # `cpack` without -G in the package tree
configure_file(${PROJECT_SOURCE_DIR}/packaging/cpack_project_config.cmake.in
               ${CMAKE_CURRENT_BINARY_DIR}/packaging/cpack_project_config.cmake @ONLY)
set(CPACK_PROJECT_CONFIG_FILE ${CMAKE_CURRENT_BINARY_DIR}/packaging/cpack_project_config.cmake)
include(CPack)
