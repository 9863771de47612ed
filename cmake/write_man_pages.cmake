# The man pages (issue 32), made at build time from dpscope's own --help by help2man, so that
# the page and --help cannot drift: dpscope(1) from `dpscope --help`, and dpscope-SUB(1) from
# `dpscope SUB --help` for every subcommand `dpscope --help` lists. A page's NAME line is the
# first clause of the subcommand's description; its SEE ALSO names the other pages and the
# reference pages under docs/ (installed in /usr/share/doc/dpscope). The pages are gzipped as
# Debian installs man pages.
#   cmake -DDPSCOPE=path/to/dpscope -DHELP2MAN=path/to/help2man -DVERSION=0.1.0
#         -DOUTPUT_DIR=build/man -P cmake/write_man_pages.cmake
foreach(variable DPSCOPE HELP2MAN VERSION OUTPUT_DIR)
    if(NOT ${variable})
        message(FATAL_ERROR "write_man_pages.cmake: ${variable} is not set")
    endif()
endforeach()
find_program(GZIP_EXECUTABLE gzip REQUIRED)
file(REMOVE_RECURSE ${OUTPUT_DIR})
file(MAKE_DIRECTORY ${OUTPUT_DIR}/wrappers)

execute_process(COMMAND ${DPSCOPE} --help OUTPUT_VARIABLE help RESULT_VARIABLE status)
if(NOT status EQUAL 0)
    message(FATAL_ERROR "write_man_pages.cmake: ${DPSCOPE} --help failed (${status})")
endif()
# "Subcommands:" then one line a subcommand: "  NAME   Description ...".
string(REGEX MATCH "\nSubcommands:\n(.*)" listing "${help}")
string(REGEX REPLACE "\n\n.*" "" listing "${CMAKE_MATCH_1}")
string(REPLACE "\n" ";" lines "${listing}")
set(subcommands "")
set(see_also "")
foreach(line IN LISTS lines)
    if(line MATCHES "^  ([a-z0-9-]+) +(.*)$")
        set(name ${CMAKE_MATCH_1})
        set(description "${CMAKE_MATCH_2}")
        # The first clause: up to ':', '.', ' (' or ', e.g.'; its first letter in lower case.
        string(REGEX REPLACE "(:|\\.|, e\\.g\\.| \\().*" "" clause "${description}")
        string(SUBSTRING "${clause}" 0 1 first)
        string(SUBSTRING "${clause}" 1 -1 rest)
        string(TOLOWER "${first}" first)
        list(APPEND subcommands ${name})
        set(clause_${name} "${first}${rest}")
        string(APPEND see_also ".BR dpscope-${name} (1),\n")
    endif()
endforeach()
if(NOT subcommands)
    message(FATAL_ERROR "write_man_pages.cmake: no subcommand in ${DPSCOPE} --help")
endif()

set(docs "/usr/share/doc/dpscope")
file(WRITE ${OUTPUT_DIR}/see-also.h2m
"[SEE ALSO]
${see_also}.BR tshark (1),
.BR wireshark (1).
.PP
The reference pages: ${docs}/README.md (the front door), ${docs}/docs/cli.md (every option with
examples), ${docs}/docs/formats.md (the JSON, jsonl and CSV schemas), ${docs}/docs/findings.md,
${docs}/docs/inputs.md, ${docs}/docs/wireshark.md, ${docs}/docs/protocol/ (the protocol facts and
their sources). Sample captures are in /usr/share/dpscope/samples.
")

function(write_page program page name_text)
    execute_process(
        COMMAND ${HELP2MAN} --no-info --section=1 --name=${name_text}
                "--version-string=${page} ${VERSION}" --include=${OUTPUT_DIR}/see-also.h2m
                --output=${OUTPUT_DIR}/${page}.1 ${program}
        RESULT_VARIABLE status ERROR_VARIABLE error)
    if(NOT status EQUAL 0)
        message(FATAL_ERROR "write_man_pages.cmake: help2man for ${page} failed: ${error}")
    endif()
    execute_process(COMMAND ${GZIP_EXECUTABLE} -9nf ${OUTPUT_DIR}/${page}.1 RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
        message(FATAL_ERROR "write_man_pages.cmake: gzip ${page}.1 failed")
    endif()
endfunction()

write_page(${DPSCOPE} dpscope
           "a protocol analyzer for drive parameter channels on PROFIBUS DP and Danfoss serial buses")
foreach(name IN LISTS subcommands)
    # help2man runs a program with --help: a two-line script runs `dpscope NAME`.
    set(wrapper ${OUTPUT_DIR}/wrappers/dpscope-${name})
    file(WRITE ${wrapper} "#!/bin/sh\nexec '${DPSCOPE}' ${name} \"$@\"\n")
    file(CHMOD ${wrapper} PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ
         GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
    write_page(${wrapper} dpscope-${name} "${clause_${name}}")
endforeach()
file(REMOVE_RECURSE ${OUTPUT_DIR}/wrappers)
file(REMOVE ${OUTPUT_DIR}/see-also.h2m)
