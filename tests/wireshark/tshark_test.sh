#!/usr/bin/env bash
# tshark with dpscope's plugin on the samples (ctest label wireshark, tests/CMakeLists.txt).
#
#   tshark_test.sh golden  NAME SAMPLE EXPECTED [--update] -- DECODE ARGS -- TSHARK ARGS
#   tshark_test.sh filters NAME SAMPLE REQUIRED -- DECODE ARGS -- TSHARK ARGS
#
# Both convert SAMPLE (relative to the source directory, the working directory) with
# `dpscope decode DECODE ARGS SAMPLE -w OUT.pcapng --linktype user0 -F pcapng` and run tshark -2 on
# the result (run_tshark.sh: the plugin loaded, as nobody when run as root) with TSHARK ARGS.
# golden: tshark's standard output compared with EXPECTED (--update rewrites EXPECTED).
# filters: the frames each display filter selects must be exactly the frames whose
# `dpscope decode -T jsonl` line (of the converted capture, same DECODE ARGS) says so; REQUIRED
# (comma-separated check names, - for none) must select at least one frame, so the check is not vacuous.
# The checks of one field's values (field_check: cfg_ppo, letter, ...) run only where REQUIRED names
# them; expert_kinds (each dpscope.finding.KIND and dpscope.problem.KIND against jsonl's kinds) runs
# on every sample with a finding or a problem.
# Environment: DPSCOPE (the executable), DPSCOPE_PLUGIN (dpscope.so), WORK_DIR (a scratch folder),
# WIRESHARK_PLUGIN_VERSION (optional, "4.0").
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
fail() {
    echo "tshark_test.sh: $*" >&2
    exit 1
}
[ $# -ge 4 ] || fail "usage: tshark_test.sh golden|filters NAME SAMPLE EXPECTED|REQUIRED ..."
mode=$1 name=$2 sample=$3 fourth=$4
shift 4
update=no
if [ "${1:-}" = --update ]; then
    update=yes
    shift
fi
[ "${1:-}" = -- ] || fail "expected -- before the decode arguments"
shift
decode_args=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do
    decode_args+=("$1")
    shift
done
[ "${1:-}" = -- ] || fail "expected -- before the tshark arguments"
shift
tshark_args=("$@")
: "${DPSCOPE:?DPSCOPE is not set}" "${DPSCOPE_PLUGIN:?DPSCOPE_PLUGIN is not set}"
: "${WORK_DIR:?WORK_DIR is not set}"
export TZ=UTC LANG=C LC_ALL=C
mkdir -p "$WORK_DIR"
converted="$WORK_DIR/$name.$mode.pcapng"
errors="$WORK_DIR/$name.$mode.stderr"

# The conversion: decode's own exit code says whether the input was whole (3: truncated); what
# was read is converted in every case (on 3 into "$converted.partial"), so it is not judged here.
rm -f "$converted" "$converted.partial"
status=0
"$DPSCOPE" decode "${decode_args[@]}" "$sample" -w "$converted" --linktype user0 -F pcapng \
    >/dev/null 2>"$errors" || status=$?
if [ "$status" = 3 ] && [ -s "$converted.partial" ]; then mv "$converted.partial" "$converted"; fi
[ -s "$converted" ] || fail "$sample: dpscope decode wrote no capture (exit $status): $(cat "$errors")"

tshark() {
    local out=$1
    shift
    if ! bash "$here/run_tshark.sh" "$DPSCOPE_PLUGIN" "$converted" -2 "${tshark_args[@]}" "$@" \
        >"$out" 2>"$errors"; then
        fail "$sample: tshark $*: $(cat "$errors")"
    fi
    # The plugin and tshark must not complain (a warning here is a bad preference or a failed load).
    [ ! -s "$errors" ] || fail "$sample: tshark $* wrote to standard error: $(cat "$errors")"
}

if [ "$mode" = golden ]; then
    expected=$fourth
    actual="$WORK_DIR/$name.golden.actual"
    tshark "$actual"
    if [ "$update" = yes ]; then
        cp "$actual" "$expected"
        echo "updated $expected"
        exit 0
    fi
    [ -f "$expected" ] || fail "$expected is missing; run: cmake --build <build dir> --target update-golden"
    if ! cmp -s "$expected" "$actual"; then
        diff -u "$expected" "$actual" | head -c 6000 >&2 || true
        fail "tshark on $sample differs from $expected (refresh with: cmake --build <build dir> --target update-golden)"
    fi
    exit 0
fi
[ "$mode" = filters ] || fail "unknown mode $mode (golden or filters)"
command -v jq >/dev/null || fail "jq is needed (scripts/install-deps)"

jsonl="$WORK_DIR/$name.filters.jsonl"
"$DPSCOPE" decode "${decode_args[@]}" -T jsonl "$converted" >"$jsonl" 2>"$errors" || true
[ -s "$jsonl" ] || fail "dpscope decode -T jsonl $converted wrote nothing: $(cat "$errors")"
telegrams=$(wc -l <"$jsonl")
frames=$(jq -r .frame "$jsonl" | wc -l)
[ "$telegrams" -eq "$frames" ] || fail "dpscope decode -T jsonl: lines without a frame number"

required=()
[ "$fourth" = - ] || IFS=, read -r -a required <<<"$fourth"
checked=0
failures=0
ran=,  # the names of the checks run, comma-separated
# check NAME FILTER JQ: the frames FILTER selects must be the frames JQ (a jq condition on a line)
# selects; expected and actual as one frame number a line.
check() {
    local check_name=$1 filter=$2 condition=$3
    local want="$WORK_DIR/$name.$check_name.want" got="$WORK_DIR/$name.$check_name.got"
    jq -r "select($condition) | .frame" "$jsonl" >"$want"
    tshark "$got" -Y "$filter" -T fields -e frame.number
    if ! cmp -s "$want" "$got"; then
        echo "$sample: -Y '$filter' selects $(wc -l <"$got") frames, dpscope decode $(wc -l <"$want") ($condition):" >&2
        diff "$want" "$got" | head -20 >&2 || true
        failures=$((failures + 1))
    fi
    for need in ${required[@]+"${required[@]}"}; do
        if [ "$need" = "$check_name" ] && [ ! -s "$want" ]; then
            echo "$sample: $check_name selects no frame; the sample has such telegrams" >&2
            failures=$((failures + 1))
        fi
    done
    checked=$((checked + 1))
    ran+="$check_name,"
}
# field_check NAME FILTER JQ: a check of one field's values, run only on the samples that require
# it (a tshark run each: CI time).
field_check() {
    [[ ",$fourth," == *",$1,"* ]] || return 0
    check "$@"
}
bus=$(jq -r 'if .fc_protocol then "fc" elif .vlt2000 then "vlt2000" else "profibus" end' "$jsonl" | sort -u)
case "$bus" in
    profibus)
        check rc7 'dpscope.pcv.rc == 7' '.pcv != null and .pcv.rc == 7'
        # Fields that hold a value, not a wording of it (the wording is the item's text).
        field_check cfg_ppo 'dpscope.cfg.ppo == 1' '.cfg.ppo == 1'
        field_check watchdog 'dpscope.prm.watchdog_ms == 1000 && dpscope.prm.wd_fact_1 == 10' \
            '.prm.watchdog_ms == 1000 and .prm.wd_fact_1 == 10'
        field_check pd_value 'dpscope.profidrive.value == 300' \
            '[.profidrive.parameters[]?.numbers // [] | .[] | select(. == 300)] | length > 0'
        field_check initiate 'dpscope.dpv1.profile_ident_number == 0x1234' \
            '.dpv1.initiate.profile_ident_number == 4660'
        field_check abort 'dpscope.dpv1.abort.reason == 3' '.dpv1.abort.reason == 3'
        ;;
    fc) check ak7 'dpscope.fc.ak == 7' '.fc_protocol.ak == 7' ;;
    vlt2000)
        check failed 'dpscope.vlt2000.failed == 1' '.vlt2000.failed == true'
        # The letter and the checksum as sent; a verdict only where one was made: a checksum
        # switched off (??) is not judged, a failed reply or a C command carries no value.
        field_check letter 'dpscope.vlt2000.letter == "U"' '.vlt2000.letter == "U"'
        field_check checksum_off 'dpscope.vlt2000.checksum == "??"' \
            '.vlt2000.checksum_disabled == true'
        field_check checksum_bad 'dpscope.vlt2000.checksum_ok == 0' '.vlt2000.checksum_ok == false'
        field_check checksum_judged 'dpscope.vlt2000.checksum_ok' '.vlt2000.checksum_ok != null'
        field_check negative 'dpscope.vlt2000.negative' '.vlt2000.negative != null'
        field_check value 'dpscope.vlt2000.value' '.vlt2000.value_text != null'
        # A number, compared as one (a string field compares "7" > "50").
        field_check value_number 'dpscope.vlt2000.value >= 50' \
            '.vlt2000.value != null and .vlt2000.value >= 50'
        ;;
    *) fail "$converted: one bus expected, dpscope decode says: $bus" ;;
esac
check finding 'dpscope.finding' '.findings | length > 0'
check problem 'dpscope.problem' '.problems | length > 0'
check comment 'frame.comment' '.findings | length > 0'
check expert '_ws.expert' '(.findings | length > 0) or (.problems | length > 0)'
check expert_error '_ws.expert.severity == "Error"' \
    '([.findings[], .problems[] | select(.severity == "error")] | length > 0)'

# Each expert info by name: dpscope.finding.KIND and dpscope.problem.KIND select the frames with
# such a finding or problem, whatever its severity (one tshark run, a column per kind).
kinds=$(jq -r '(.findings[] | "finding.\(.kind)"), (.problems[] | "problem.\(.kind)")' "$jsonl" | sort -u)
if [ -z "$kinds" ] && [[ ",$fourth," == *",expert_kinds,"* ]]; then
    echo "$sample: expert_kinds has no finding or problem to check; the sample has such telegrams" >&2
    failures=$((failures + 1))
    ran+="expert_kinds,"
elif [ -n "$kinds" ]; then
    want="$WORK_DIR/$name.expert_kinds.want" got="$WORK_DIR/$name.expert_kinds.got"
    jq -r '"\(.frame) finding.\(.findings[].kind)", "\(.frame) problem.\(.problems[].kind)"' \
        "$jsonl" | sort -u >"$want"
    columns=()
    for kind in $kinds; do columns+=(-e "dpscope.$kind"); done
    tshark "$got.table" -T fields -e frame.number "${columns[@]}"
    # A column holds 1 (or 1,1,...) where the frame has that expert info.
    awk -F'\t' -v kinds="$(echo $kinds)" 'BEGIN { split(kinds, kind, " ") }
        { for (i = 2; i <= NF; ++i) if ($i != "") print $1 " " kind[i - 1] }' "$got.table" |
        sort -u >"$got"
    if ! cmp -s "$want" "$got"; then
        echo "$sample: the expert infos dpscope.finding.KIND / dpscope.problem.KIND are not the frames' kinds (frame kind):" >&2
        diff "$want" "$got" | head -20 >&2 || true
        failures=$((failures + 1))
    fi
    checked=$((checked + 1))
    ran+="expert_kinds,"
fi

# The comment's text: each finding as `severity kind: message`, one a line.
want="$WORK_DIR/$name.comment_text.want" got="$WORK_DIR/$name.comment_text.got"
jq -r 'select(.findings | length > 0)
       | "\(.frame)\t\([.findings[] | "\(.severity) \(.kind): \(.message)"] | join("\\n"))"' \
    "$jsonl" >"$want"
tshark "$got" -Y frame.comment -T fields -e frame.number -e frame.comment
if ! cmp -s "$want" "$got"; then
    echo "$sample: the packet comments are not the findings:" >&2
    diff "$want" "$got" | head -20 >&2 || true
    failures=$((failures + 1))
fi
for need in ${required[@]+"${required[@]}"}; do
    [[ "$ran" == *",$need,"* ]] || fail "$sample: required check $need is not run for bus $bus"
done
[ "$failures" -eq 0 ] || fail "$sample: $failures of $checked display-filter checks failed"
echo "$sample: $checked display filters select the frames dpscope decode reports ($telegrams telegrams)"
