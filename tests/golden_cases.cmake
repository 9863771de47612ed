# Golden cases: golden_case(NAME EXPECTED [EXIT n] ARGS...) runs `dpscope ARGS...` in the source
# directory with TZ=UTC LANG=C and compares standard output with EXPECTED. Refresh every expected
# file with one command:  cmake --build <build dir> --target update-golden
set(golden_script ${CMAKE_CURRENT_SOURCE_DIR}/run_golden.cmake)
set(golden_update_commands "")

function(golden_case name expected)
    set(args ${ARGN})
    set(exit_code 0)
    list(GET args 0 first)
    if(first STREQUAL "EXIT")
        list(GET args 1 exit_code)
        list(REMOVE_AT args 0 1)
    endif()
    string(REPLACE ";" "|" joined "${args}")
    set(command ${CMAKE_COMMAND} -DDPSCOPE=$<TARGET_FILE:dpscope> "-DARGS=${joined}"
                -DEXPECTED=${expected} -DEXIT_CODE=${exit_code} -DSOURCE_DIR=${PROJECT_SOURCE_DIR})
    add_test(NAME golden.${name} COMMAND ${command} -P ${golden_script})
    set_tests_properties(golden.${name} PROPERTIES LABELS golden)
    set(golden_update_commands ${golden_update_commands} COMMAND ${command} -DUPDATE=ON -P
                               ${golden_script} PARENT_SCOPE)
endfunction()

# One capture per PPO type, with and without a Chk_Cfg, in every input format.
foreach(sample ppo1 ppo2 ppo3 ppo4)
    golden_case(${sample}_text samples/expected/${sample}.txt decode samples/${sample}.pcap)
    golden_case(${sample}_jsonl samples/expected/${sample}.jsonl decode -T jsonl samples/${sample}.pcap)
endforeach()
golden_case(ppo5_text samples/expected/ppo5.txt decode samples/ppo5.pcapng)
golden_case(ppo5_jsonl samples/expected/ppo5.jsonl decode -T jsonl samples/ppo5.pcapng)
golden_case(faults_text samples/expected/faults.txt EXIT 0 decode samples/faults.pcap)
golden_case(faults_jsonl samples/expected/faults.jsonl decode -T jsonl samples/faults.pcap)
golden_case(faults_summary samples/expected/faults.summary.txt decode -q samples/faults.pcap)
golden_case(profidrive_text samples/expected/profidrive.txt decode --dialect profidrive samples/profidrive.pcap)
golden_case(profidrive_jsonl samples/expected/profidrive.jsonl decode -T jsonl --dialect profidrive samples/profidrive.pcap)
golden_case(user0_text samples/expected/user0.txt decode samples/user0.pcap)
golden_case(midstream_text samples/expected/midstream.txt decode samples/midstream.pcap)
golden_case(midstream_ppo_option samples/expected/midstream.ppo4.txt decode --ppo 6=4 samples/midstream.pcap)
golden_case(serial_raw_text samples/expected/serial.txt decode samples/serial.raw)
# xxd and hexdump -C dumps of the same bytes decode to the same telegrams.
golden_case(serial_xxd_text samples/expected/serial.txt decode samples/serial.xxd)
golden_case(serial_hexdump_text samples/expected/serial.txt decode samples/serial.hexdump)
golden_case(terminal_hex_text samples/expected/terminal.txt decode samples/terminal.log)
golden_case(ppo1_verbose samples/expected/ppo1.verbose.txt decode -V -c 60 samples/ppo1.pcap)
golden_case(ppo2_csv samples/expected/ppo2.csv decode -T csv samples/ppo2.pcap)
golden_case(faults_station_filter samples/expected/faults.station4.txt decode --station 4 samples/faults.pcap)
golden_case(ppo1_pnu_filter samples/expected/ppo1.pnu207.txt decode --pnu 207 -T jsonl samples/ppo1.pcap)
golden_case(faults_pnu_filter samples/expected/faults.pnu207.txt decode --pnu 207 samples/faults.pcap)
golden_case(truncated_capture samples/expected/truncated.txt EXIT 3 decode samples/truncated.pcap)
# The Danfoss FC protocol: hand-made telegrams (samples/fc-examples.hex) in every decode format.
golden_case(fc_examples_text samples/expected/fc-examples.txt decode --bus fc samples/fc-examples.hex)
golden_case(fc_examples_jsonl samples/expected/fc-examples.jsonl decode --bus fc -T jsonl samples/fc-examples.hex)
golden_case(fc_examples_verbose samples/expected/fc-examples.verbose.txt decode --bus fc -V samples/fc-examples.hex)
golden_case(fc_examples_csv samples/expected/fc-examples.csv decode --bus fc -T csv samples/fc-examples.hex)
golden_case(fc_examples_summary samples/expected/fc-examples.summary.txt decode --bus fc -q samples/fc-examples.hex)
# Hand-made at 9600 baud: the drives answer 5 ms after a command's last byte.
golden_case(report_fc_examples_text samples/expected/report.fc-examples.txt report --bus fc samples/fc-examples.hex)
# A simulated FC bus (samples/fc.pcap, USER0 with the bus recorded: no --bus needed): four drives,
# both address formats, every FC fault twice; and a clean session.
golden_case(fc_text samples/expected/fc.txt decode samples/fc.pcap)
golden_case(fc_jsonl samples/expected/fc.jsonl decode -T jsonl samples/fc.pcap)
golden_case(fc_verbose samples/expected/fc.verbose.txt decode -V --station 17 -c 80 samples/fc.pcap)
golden_case(fc_csv samples/expected/fc.csv decode -T csv samples/fc.pcap)
golden_case(fc_pnu_text samples/expected/fc.pnu414.txt decode --pnu 414 samples/fc.pcap)
golden_case(report_fc_text samples/expected/report.fc.txt EXIT 1 report samples/fc.pcap)
golden_case(report_fc_json samples/expected/report.fc.json EXIT 1 report -T json samples/fc.pcap)
golden_case(report_fc_markdown samples/expected/report.fc.md EXIT 1 report -T markdown samples/fc.pcap)
golden_case(report_fc_html samples/expected/report.fc.html EXIT 1 report -T html samples/fc.pcap)
golden_case(report_fc_junit samples/expected/report.fc.junit.xml EXIT 1 report -T junit samples/fc.pcap)
golden_case(report_fc_clean_text samples/expected/report.fc-clean.txt report samples/fc-clean.pcap)
# The VLT 2000 serial telegram: a simulated bus (samples/vlt2000.pcap, USER0 with the bus
# recorded: no --bus needed) with four drives, every letter, broadcasts, the drives' own failures
# and every VLT 2000 fault; a clean session; hand-written telegrams in a plain-text log
# (samples/vlt2000-examples.txt: the worked example, the seed's value example, failures, a
# broadcast, "??").
golden_case(vlt2000_text samples/expected/vlt2000.txt decode samples/vlt2000.pcap)
golden_case(vlt2000_jsonl samples/expected/vlt2000.jsonl decode -T jsonl samples/vlt2000.pcap)
golden_case(vlt2000_verbose samples/expected/vlt2000.verbose.txt decode -V --station 17 -c 80 samples/vlt2000.pcap)
golden_case(vlt2000_csv samples/expected/vlt2000.csv decode -T csv samples/vlt2000.pcap)
golden_case(report_vlt2000_text samples/expected/report.vlt2000.txt EXIT 1 report samples/vlt2000.pcap)
golden_case(report_vlt2000_json samples/expected/report.vlt2000.json EXIT 1 report -T json samples/vlt2000.pcap)
golden_case(report_vlt2000_markdown samples/expected/report.vlt2000.md EXIT 1 report -T markdown samples/vlt2000.pcap)
golden_case(report_vlt2000_html samples/expected/report.vlt2000.html EXIT 1 report -T html samples/vlt2000.pcap)
golden_case(report_vlt2000_junit samples/expected/report.vlt2000.junit.xml EXIT 1 report -T junit samples/vlt2000.pcap)
golden_case(report_vlt2000_clean_text samples/expected/report.vlt2000-clean.txt report samples/vlt2000-clean.pcap)
golden_case(vlt2000_examples_text samples/expected/vlt2000-examples.txt decode --bus vlt2000 samples/vlt2000-examples.txt)
golden_case(vlt2000_examples_jsonl samples/expected/vlt2000-examples.jsonl decode --bus vlt2000 -T jsonl samples/vlt2000-examples.txt)

# Conformance reports: a capture with every fault kind (exit 1: errors found) and a clean one.
golden_case(report_faults_text samples/expected/report.faults.txt EXIT 1 report samples/faults.pcap)
golden_case(report_faults_json samples/expected/report.faults.json EXIT 1 report -T json samples/faults.pcap)
golden_case(report_faults_markdown samples/expected/report.faults.md EXIT 1 report -T markdown samples/faults.pcap)
golden_case(report_faults_junit samples/expected/report.faults.junit.xml EXIT 1 report -T junit samples/faults.pcap)
golden_case(report_faults_html samples/expected/report.faults.html EXIT 1 report -T html samples/faults.pcap)
golden_case(report_faults_warning samples/expected/report.faults.station4.txt EXIT 1 report --station 4 --fail-on warning samples/faults.pcap)
golden_case(report_timeouts_text samples/expected/report.timeouts.txt EXIT 1 report samples/timeouts.pcap)
golden_case(report_timeouts_json samples/expected/report.timeouts.json EXIT 1 report -T json samples/timeouts.pcap)
golden_case(report_clean_text samples/expected/report.ppo2.txt report samples/ppo2.pcap)
golden_case(report_profidrive_json samples/expected/report.profidrive.json report -T json --dialect profidrive samples/profidrive.pcap)
# Two GE AF-600 slaves (ge dialect): GE fault numbers 130/131, an unknown code from RC 9..12.
golden_case(ge_text samples/expected/ge.txt decode --dialect ge samples/ge.pcap)
golden_case(ge_jsonl samples/expected/ge.jsonl decode -T jsonl --dialect ge samples/ge.pcap)
golden_case(report_ge_text samples/expected/report.ge.txt report --dialect ge samples/ge.pcap)
golden_case(report_ge_json samples/expected/report.ge.json report -T json --dialect ge samples/ge.pcap)
# The same decoded with the default dialect: each slave gets the hint to decode it as ge, from
# its fault number 130 or 131 (#27 point 14); in a capture cut after the first rejection (-c 90),
# slave 3 from that one telegram.
golden_case(ge_summary samples/expected/ge.summary.txt decode -q samples/ge.pcap)
golden_case(ge_short_summary samples/expected/ge.short.summary.txt decode -q -c 90 samples/ge.pcap)
golden_case(decode_faults_findings_jsonl samples/expected/faults.findings.jsonl decode -T jsonl --station 5 -c 120 samples/faults.pcap)
# DP-V1 parameter access (slave 4 speaks the PROFIdrive dialect): every decode and report format.
golden_case(dpv1_text samples/expected/dpv1.txt decode --dialect 4=profidrive samples/dpv1.pcap)
golden_case(dpv1_jsonl samples/expected/dpv1.jsonl decode -T jsonl --dialect 4=profidrive samples/dpv1.pcap)
golden_case(dpv1_verbose samples/expected/dpv1.verbose.txt decode -V --dialect 4=profidrive --station 5 -c 60 samples/dpv1.pcap)
golden_case(dpv1_csv samples/expected/dpv1.csv decode -T csv --dialect 4=profidrive samples/dpv1.pcap)
golden_case(report_dpv1_text samples/expected/report.dpv1.txt EXIT 1 report --dialect 4=profidrive samples/dpv1.pcap)
golden_case(report_dpv1_json samples/expected/report.dpv1.json EXIT 1 report -T json --dialect 4=profidrive samples/dpv1.pcap)
golden_case(report_dpv1_markdown samples/expected/report.dpv1.md EXIT 1 report -T markdown --dialect 4=profidrive samples/dpv1.pcap)
golden_case(report_dpv1_html samples/expected/report.dpv1.html EXIT 1 report -T html --dialect 4=profidrive samples/dpv1.pcap)
golden_case(report_dpv1_junit samples/expected/report.dpv1.junit.xml EXIT 1 report -T junit --dialect 4=profidrive samples/dpv1.pcap)
# Slaves described by GSD files (issue 29): vendor, modules, user parameters, diagnosis texts,
# the GSD checks and the report's device part.
golden_case(decode_gsd_text samples/expected/decode.gsd.txt decode --gsd-dir samples/gsd --baud 1500000 --dialect 4=profidrive -r samples/gsd.pcap)
golden_case(decode_gsd_verbose samples/expected/decode.gsd.verbose.txt decode -V -c 40 --gsd-dir samples/gsd --baud 1500000 --dialect 4=profidrive -r samples/gsd.pcap)
golden_case(decode_gsd_jsonl samples/expected/decode.gsd.jsonl decode -T jsonl -c 40 --gsd-dir samples/gsd --baud 1500000 --dialect 4=profidrive -r samples/gsd.pcap)
golden_case(report_gsd_text samples/expected/report.gsd.txt EXIT 1 report --gsd-dir samples/gsd --baud 1500000 --dialect 4=profidrive samples/gsd.pcap)
golden_case(report_gsd_json samples/expected/report.gsd.json EXIT 1 report -T json --gsd-dir samples/gsd --baud 1500000 --dialect 4=profidrive samples/gsd.pcap)
golden_case(report_gsd_markdown samples/expected/report.gsd.md EXIT 1 report -T markdown --gsd-dir samples/gsd --baud 1500000 --dialect 4=profidrive samples/gsd.pcap)
golden_case(report_gsd_html samples/expected/report.gsd.html EXIT 1 report -T html --gsd-dir samples/gsd --baud 1500000 --dialect 4=profidrive samples/gsd.pcap)
golden_case(report_gsd_junit samples/expected/report.gsd.junit.xml EXIT 1 report -T junit --gsd-dir samples/gsd --baud 1500000 --dialect 4=profidrive samples/gsd.pcap)

# Bus health (dpscope stats, issue 12): the capture with every link fault (FCS errors, garbage, a
# slave silent, an FDL retry) in every stats format, simulated at 1500000 baud (scripts/
# make-samples: simulate's default), so the bus load is known; and a clean bus, good (exit 0).
foreach(format text json markdown csv html)
    set(extension ${format})
    if(format STREQUAL "markdown")
        set(extension md)
    elseif(format STREQUAL "text")
        set(extension txt)
    endif()
    golden_case(stats_faults_${format} samples/expected/stats.faults.${extension} EXIT 1 stats -T ${format} --baud 1500000 samples/faults.pcap)
endforeach()
golden_case(stats_clean_text samples/expected/stats.ppo2.txt stats --baud 1500000 samples/ppo2.pcap)
# The bus-health sample (scripts/make-samples: two masters in the token ring, five slaves, each
# bus-health fault once): every stats format, and the report's bus-health section.
foreach(format text json markdown csv html)
    set(extension ${format})
    if(format STREQUAL "markdown")
        set(extension md)
    elseif(format STREQUAL "text")
        set(extension txt)
    endif()
    golden_case(stats_bus_health_${format} samples/expected/stats.bus-health.${extension} EXIT 1 stats -T ${format} --baud 1500000 samples/bus-health.pcap)
endforeach()
golden_case(report_bus_health_text samples/expected/report.bus-health.txt report --baud 1500000 samples/bus-health.pcap)
golden_case(report_bus_health_junit samples/expected/report.bus-health.junit.xml report -T junit --baud 1500000 samples/bus-health.pcap)
# Drive parameter databases (issue 29): dpscope params lists a family of the test database
# (tests/params/testdrive.params) in each format, and the shipped FC series database.
golden_case(params_testdrive_text samples/expected/params.testdrive.txt params --params tests/params/testdrive.params --family testdrive)
golden_case(params_testdrive_json samples/expected/params.testdrive.json params --params tests/params/testdrive.params -T json --family testdrive motor)
golden_case(params_testdrive_csv samples/expected/params.testdrive.csv params --params tests/params/testdrive.params -T csv 16-)
golden_case(params_fc_text samples/expected/params.fc.txt params --family fc)

add_custom_target(update-golden ${golden_update_commands}
    DEPENDS dpscope
    COMMENT "Rewriting samples/expected/ from the current dpscope"
    VERBATIM)
