#!/usr/bin/env bash
# dpscope completion bash|zsh (issue 32): the bash script completes subcommands, options and
# option values, as a user pressing Tab would get them; the zsh script is the bash one under
# bashcompinit. Usage: completion_test.sh DPSCOPE
set -uo pipefail
dpscope=${1:?usage: completion_test.sh DPSCOPE}
here=$(cd "$(dirname "$0")" && pwd)
status=0
script=$("$dpscope" completion bash) || { echo "dpscope completion bash failed" >&2; exit 1; }
bash -n <<<"$script" || { echo "the bash script is not valid bash" >&2; exit 1; }
eval "$script"

# complete LINE: COMPREPLY for the last word of LINE (a trailing space starts a new, empty word).
complete_line() {
    read -r -a COMP_WORDS <<<"$1"
    [[ $1 == *" " ]] && COMP_WORDS+=("")
    COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
    COMPREPLY=()
    _dpscope
}
# expect LINE WORD...: every WORD is offered for LINE.
expect() {
    local line=$1 word
    shift
    complete_line "$line"
    for word in "$@"; do
        # A loop, not printf | grep -q: under pipefail, grep leaving early fails the pipe.
        local offered=false reply
        for reply in "${COMPREPLY[@]}"; do [[ $reply == "$word" ]] && offered=true; done
        if ! $offered; then
            echo "'$line<TAB>' does not offer '$word' (offered: ${COMPREPLY[*]})" >&2
            status=1
        fi
    done
}
# expect_only LINE WORD...: exactly these words are offered.
expect_only() {
    local line=$1
    shift
    complete_line "$line"
    if [[ "${COMPREPLY[*]}" != "$*" ]]; then
        echo "'$line<TAB>' offers '${COMPREPLY[*]}', expected '$*'" >&2
        status=1
    fi
}

expect_only "dpscope de" decode
expect "dpscope " completion decode filter hex params report simulate sniff stats --version
expect_only "dpscope decode -T " text verbose jsonl csv
expect_only "dpscope report --format j" json junit
expect_only "dpscope decode --bus " profibus fc vlt2000
expect_only "dpscope decode --dialect " vlt ge profidrive
expect "dpscope simulate --fault " stacked_request fc_no_response vlt2000_checksum_error station_lost
expect "dpscope decode --drive " fc vlt5000 af600
expect "dpscope decode --" --display-filter --station --pnu --write --allow-empty
expect "dpscope sniff --" --baud --parity --mqtt
# Every subcommand's every long option of --help is offered after '--'.
for sub in $("$dpscope" --help | sed -n '/^Subcommands:/,/^$/p' | awk 'NR > 1 && NF {print $1}'); do
    mapfile -t options < <("$dpscope" "$sub" --help | grep -oE '^  (-[A-Za-z0-9],)?--[a-z0-9-]+' |
        grep -oE -- '--[a-z0-9-]+$')
    ((${#options[@]} > 0)) || { echo "$sub --help lists no option" >&2; status=1; }
    expect "dpscope $sub --" "${options[@]}"
done
# A file name after -r and as a positional.
cd "$(mktemp -d)" && touch capture-one.pcap && expect_only "dpscope decode -r capture-o" capture-one.pcap
expect_only "dpscope decode capture-o" capture-one.pcap
rm -f capture-one.pcap

zsh_script=$("$dpscope" completion zsh) || { echo "dpscope completion zsh failed" >&2; exit 1; }
[[ $zsh_script == "#compdef dpscope"* ]] || { echo "the zsh script does not start with #compdef" >&2; status=1; }
# The same words: the bash script's cases, under the function name _dpscope_bash.
cases=${script#*"    case \$sub in"}
cases=${cases%%"complete -F"*}
[[ $zsh_script == *"_dpscope_bash() {"*"$cases"* ]] ||
    { echo "the zsh script does not hold the bash one's cases" >&2; status=1; }
# zsh itself, where it is installed: Tab in an interactive zsh (zsh_completion_test.zsh).
if command -v zsh >/dev/null; then
    folder=$(mktemp -d)
    printf '%s\n' "$zsh_script" >"$folder/_dpscope"
    timeout 120 zsh -f "$here/zsh_completion_test.zsh" "$dpscope" "$folder" ||
        { echo "zsh does not complete 'dpscope de<TAB>' and 'dpscope decode -T j<TAB>'" >&2; status=1; }
    rm -rf "$folder"
else
    echo "completion: zsh is not installed, its Tab not tried"
fi
"$dpscope" completion fish >/dev/null 2>&1
[[ $? == 2 ]] || { echo "dpscope completion fish: expected exit code 2" >&2; status=1; }
# A full disk is said, with exit code 4 (output could not be written).
if [[ -w /dev/full ]]; then
    err=$("$dpscope" completion bash 2>&1 >/dev/full)
    code=$?
    [[ $code == 4 && $err == *"No space left on device"* ]] ||
        { echo "completion to /dev/full: exit $code, '$err'" >&2; status=1; }
fi
((status == 0)) && echo "completion: ok"
exit $status
