#!/usr/bin/env bash
# Layering check: every #include in a library directory may name only the include roots that
# library may depend on (CONTRIBUTING.md, "Layout"). Prints file:line and the forbidden include
# for each violation and exits 1; exits 0 when there is none.
# Usage: check_layering.sh SOURCE_DIR
set -euo pipefail

root=${1:?usage: check_layering.sh SOURCE_DIR}

# One line per directory: the directory, then the include roots its files may name ("*": any).
# The include root is the first component of the included path ("decoder/fdl.hpp" -> decoder,
# <pcap/pcap.h> -> pcap). A directory that does not exist yet is skipped. tests/, fuzz/ and bench/
# have no line: they may include anything.
rules='
decoder    decoder
simulator  decoder simulator
capture    decoder capture pcap
formats    decoder formats
wireshark  decoder capture formats wireshark
cli        *
'
# Include roots outside the rule table that are still guarded: a library may name them only when
# its line lists them. Everything else (the standard library, POSIX, fmt) is not checked.
guarded_external='tests fuzz bench pcap CLI gtest gmock benchmark'

guarded=" $guarded_external "
while read -r dir _; do
    [[ -n $dir ]] && guarded+="$dir "
done <<<"$rules"

include_pattern='^[[:space:]]*#[[:space:]]*include[[:space:]]*(["<]([^">]+)[">])'
violations=0
files=0
while read -r dir allowed; do
    [[ -z $dir || ! -d $root/$dir ]] && continue
    [[ $allowed == '*' ]] && continue
    while IFS= read -r file; do
        files=$((files + 1))
        line_number=0
        while IFS= read -r line || [[ -n $line ]]; do
            line_number=$((line_number + 1))
            [[ $line =~ $include_pattern ]] || continue
            path=${BASH_REMATCH[2]}
            first=${path%%/*}
            [[ $first == "$path" ]] && first=${first%%.*}  # <pcap.h> -> pcap
            [[ $guarded == *" $first "* ]] || continue
            [[ " $allowed " == *" $first "* ]] && continue
            echo "${file#"$root"/}:$line_number: forbidden #include ${BASH_REMATCH[1]}" \
                "($dir/ may include only: $allowed)"
            violations=$((violations + 1))
        done <"$file"
    done < <(find "$root/$dir" -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \
                  -o -name '*.cc' -o -name '*.in' \) | LC_ALL=C sort)
done <<<"$rules"

if ((violations > 0)); then
    echo "layering: $violations forbidden include(s) in $files file(s); the rules are in $0" >&2
    exit 1
fi
echo "layering: $files files checked, no forbidden include"
