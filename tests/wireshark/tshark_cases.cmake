# tshark with dpscope's plugin on every sample (label wireshark; included by tests/CMakeLists.txt
# when the plugin is built and tshark is found). Each sample is converted with
# `dpscope decode SAMPLE -w OUT.pcapng --linktype user0 -F pcapng` (tshark_test.sh), then:
#   wireshark.NAME.details  tshark -2 -V -O dpscope, compared with samples/expected/wireshark.NAME.txt
#   wireshark.NAME.fields   tshark -2 -T fields (the fields below), with .../wireshark.NAME.fields.txt
#   wireshark.NAME.filters  display filters select the frames `dpscope decode -T jsonl` reports
#                           (on the samples that name the checks they need; each check is a
#                           tshark run of its own, so the samples with nothing new for them, and
#                           inputs that repeat another's bytes, have none: CI time; the
#                           checks of one field's values only where named)
# The goldens are rewritten by the update-golden target, with dpscope's own.
set(tshark_test ${CMAKE_CURRENT_SOURCE_DIR}/wireshark/tshark_test.sh)
set(tshark_work_dir ${CMAKE_CURRENT_BINARY_DIR}/wireshark)
# The plugin folder is named after tshark's major.minor version.
execute_process(COMMAND ${TSHARK_EXECUTABLE} --version OUTPUT_VARIABLE tshark_version_text
                ERROR_QUIET)
string(REGEX MATCH "[0-9]+\\.[0-9]+" tshark_plugin_version "${tshark_version_text}")
set(tshark_environment
    DPSCOPE=$<TARGET_FILE:dpscope> DPSCOPE_PLUGIN=$<TARGET_FILE:dpscope_wireshark>
    WORK_DIR=${tshark_work_dir} WIRESHARK_PLUGIN_VERSION=${tshark_plugin_version}
    TSHARK=${TSHARK_EXECUTABLE} TZ=UTC LANG=C LC_ALL=C)
# Every bus's main fields, the links between telegrams, the findings and the packet comments.
set(tshark_fields
    frame.number dpscope.bus dpscope.direction dpscope.master dpscope.slave
    dpscope.request_frame dpscope.response_frame dpscope.response_time
    dpscope.fdl.sa dpscope.fdl.da dpscope.fdl.fcs_ok dpscope.dp.service dpscope.ppo.type
    dpscope.pcv.rc dpscope.pcv.pnu dpscope.pcv.value dpscope.pcv.error dpscope.pcd.ctw
    dpscope.pcd.stw dpscope.diag.status1 dpscope.dpv1.function dpscope.profidrive.id
    dpscope.profidrive.pnu dpscope.fc.address dpscope.fc.block dpscope.fc.ak dpscope.fc.pnu
    dpscope.fc.value dpscope.fc.fault dpscope.fc.bcc_ok dpscope.vlt2000.address
    dpscope.vlt2000.letter dpscope.vlt2000.parameter dpscope.vlt2000.value
    dpscope.vlt2000.reason dpscope.vlt2000.checksum dpscope.vlt2000.checksum_ok dpscope.problem
    dpscope.finding
    frame.comment)
set(tshark_field_args -T fields -E header=y -E quote=d)
foreach(field ${tshark_fields})
    list(APPEND tshark_field_args -e ${field})
endforeach()
set(tshark_update_commands "")

# wireshark_case(NAME SAMPLE GOLDEN REQUIRED [DECODE args...] [TSHARK args...]): GOLDEN names the
# expected files (two inputs with the same bytes share them); REQUIRED the display-filter checks
# (tshark_test.sh) that must select at least one frame of this sample; "-": no filters test.
function(wireshark_case name sample golden required)
    cmake_parse_arguments(PARSE_ARGV 4 case "" "" "DECODE;TSHARK")
    set(run ${CMAKE_COMMAND} -E env ${tshark_environment} bash ${tshark_test})
    set(details ${run} golden ${name}.details ${sample} samples/expected/wireshark.${golden}.txt)
    set(fields ${run} golden ${name}.fields ${sample}
               samples/expected/wireshark.${golden}.fields.txt)
    set(tail -- ${case_DECODE} -- ${case_TSHARK})
    add_test(NAME wireshark.${name}.details COMMAND ${details} ${tail} -V -O dpscope
             WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    add_test(NAME wireshark.${name}.fields COMMAND ${fields} ${tail} ${tshark_field_args}
             WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
    set_tests_properties(wireshark.${name}.details wireshark.${name}.fields
                         PROPERTIES LABELS wireshark TIMEOUT 300)
    if(NOT required STREQUAL "-")
        add_test(NAME wireshark.${name}.filters
                 COMMAND ${run} filters ${name} ${sample} ${required} ${tail}
                 WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
        set_tests_properties(wireshark.${name}.filters PROPERTIES LABELS wireshark TIMEOUT 300)
    endif()
    # One update per golden, by the first case using it.
    get_property(updated GLOBAL PROPERTY dpscope_tshark_goldens)
    if(NOT golden IN_LIST updated)
        set_property(GLOBAL APPEND PROPERTY dpscope_tshark_goldens ${golden})
        set(tshark_update_commands ${tshark_update_commands}
            COMMAND ${details} --update ${tail} -V -O dpscope
            COMMAND ${fields} --update ${tail} ${tshark_field_args} PARENT_SCOPE)
    endif()
endfunction()

# Every input dpscope reads, with the options its golden_case uses (the dialect is also the
# plugin's preference; dpv1's per-slave dialect has no preference, so dpv1 runs with the default).
wireshark_case(bus_health samples/bus-health.pcap bus_health finding,comment,expert)
wireshark_case(dpv1 samples/dpv1.pcap dpv1
               finding,comment,expert,expert_error,cfg_ppo,watchdog,pd_value)
# DP-V1 PDUs no sample has: error PDUs of a warning (class 0xA) and a note (0xB), an MSAC_C2
# Initiate, its response and an Abort, and a Slave_Diag with a device- and a channel-related block.
# A hex log written by hand (each telegram's FCS summed), not by the simulator.
wireshark_case(dpv1_pdus tests/wireshark/dpv1-pdus.hex dpv1_pdus
               finding,comment,expert,expert_kinds,initiate,abort)
wireshark_case(faults samples/faults.pcap faults
               rc7,finding,problem,comment,expert,expert_error,cfg_ppo,watchdog)
wireshark_case(fc_clean samples/fc-clean.pcap fc_clean -)
wireshark_case(fc_examples samples/fc-examples.hex fc_examples ak7,finding,comment,expert
               DECODE --bus fc)
wireshark_case(fc samples/fc.pcap fc ak7,finding,problem,comment,expert,expert_error)
wireshark_case(ge samples/ge.pcap ge rc7,finding,comment,expert DECODE --dialect ge
               TSHARK -o dpscope.dialect:ge)
# Slaves described by GSD files (issue 29): the gsd_folder preference.
wireshark_case(gsd samples/gsd.pcap gsd finding,comment,expert
               DECODE --gsd-dir samples/gsd --baud 1500000
               TSHARK -o dpscope.gsd_folder:samples/gsd -o dpscope.baud:1500000)
wireshark_case(midstream samples/midstream.pcap midstream -)
foreach(ppo ppo1 ppo2 ppo3 ppo4)
    wireshark_case(${ppo} samples/${ppo}.pcap ${ppo} -)
endforeach()
wireshark_case(ppo5 samples/ppo5.pcapng ppo5 -)
wireshark_case(profidrive samples/profidrive.pcap profidrive -
               DECODE --dialect profidrive TSHARK -o dpscope.dialect:profidrive)
set(serial_required finding,problem,comment,expert,expert_error)
wireshark_case(serial_raw samples/serial.raw serial ${serial_required})
wireshark_case(serial_xxd samples/serial.xxd serial -)
wireshark_case(serial_hexdump samples/serial.hexdump serial -)
wireshark_case(terminal samples/terminal.log terminal -)
wireshark_case(timeouts samples/timeouts.pcap timeouts finding,comment,expert,expert_error)
wireshark_case(truncated samples/truncated.pcap truncated -)
wireshark_case(user0 samples/user0.pcap user0 -)
wireshark_case(vlt2000_clean samples/vlt2000-clean.pcap vlt2000_clean -)
# The VLT 2000 fields that hold the characters as sent (letter, checksum) and the verdicts made only
# where one was (checksum_ok, negative, value), the value a number.
set(vlt2000_field_checks letter,checksum_off,checksum_judged,negative,value,value_number)
wireshark_case(vlt2000_examples samples/vlt2000-examples.txt vlt2000_examples
               failed,finding,comment,expert,${vlt2000_field_checks} DECODE --bus vlt2000)
wireshark_case(vlt2000 samples/vlt2000.pcap vlt2000
               failed,finding,problem,comment,expert,expert_error,checksum_bad,${vlt2000_field_checks})

# The checks themselves fail when they should: a required check on a sample without such
# telegrams (ppo1 has no RC 7), and tshark judging with another time-out than the conversion.
set(run_filters ${CMAKE_COMMAND} -E env ${tshark_environment} bash ${tshark_test} filters)
add_test(NAME wireshark.detects_vacuous_filter
         COMMAND ${run_filters} vacuous samples/ppo1.pcap rc7 -- --
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(wireshark.detects_vacuous_filter PROPERTIES
    PASS_REGULAR_EXPRESSION "rc7 selects no frame; the sample has such telegrams")
add_test(NAME wireshark.detects_filter_mismatch
         COMMAND ${run_filters} mismatch samples/timeouts.pcap finding -- -- -o dpscope.timeout_ms:1
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(wireshark.detects_filter_mismatch PROPERTIES
    PASS_REGULAR_EXPRESSION "-Y 'dpscope.finding' selects [0-9]+ frames, dpscope decode 3")
set_tests_properties(wireshark.detects_vacuous_filter wireshark.detects_filter_mismatch
                     PROPERTIES LABELS wireshark TIMEOUT 300)

# The field table of docs/wireshark.md against the fields the plugin registers, and the expert
# infos against the finding kinds of docs/findings.md and the problem kinds of docs/formats.md.
add_test(NAME wireshark.field_table
         COMMAND ${CMAKE_COMMAND} -E env ${tshark_environment} bash
                 ${CMAKE_CURRENT_SOURCE_DIR}/wireshark/field_table_test.sh
                 $<TARGET_FILE:dpscope_wireshark> ${PROJECT_SOURCE_DIR}/docs/wireshark.md
                 ${PROJECT_SOURCE_DIR}/docs/findings.md ${PROJECT_SOURCE_DIR}/docs/formats.md)
set_tests_properties(wireshark.field_table PROPERTIES LABELS wireshark TIMEOUT 120)

add_custom_target(update-golden-wireshark ${tshark_update_commands}
    DEPENDS dpscope dpscope_wireshark
    COMMENT "Rewriting samples/expected/wireshark.* from the current dpscope and its plugin"
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    VERBATIM)
