#!/usr/bin/env bash
# Layering check: every #include in a source file may name only files of the layers that file's
# layer may depend on (capture -> decoder -> trackers -> formats, never upward; CONTRIBUTING.md,
# "Layout"). Prints file:line and the forbidden include for each violation and exits 1; exits 0
# when there is none.
# Usage: check_layering.sh SOURCE_DIR
#
# A file's layer (its role) is read from where it lives and, inside protocols/, from the end of
# its name, the rule protocols/CMakeLists.txt uses to put the file into its library:
#   core/...                                     decoder
#   capture/, simulator/, formats/, wireshark/, cli/ ...   the folder's name
#   protocols/.../*_describe.*, *_render.*, *_report_section.*   formats
#   protocols/.../*_model.*                      simulator
#   protocols/.../*_tree.*                       wireshark
#   protocols/... anything else                  decoder (framing, payload, codes, tracker)
# tests/, fuzz/ and bench/ have no layer: they may include anything. An include is checked by the
# layer of the file it names (the same rule) or, for a guarded library outside the tree (libpcap,
# CLI11, GoogleTest, Google Benchmark), by its name; the standard library, POSIX and fmt are not
# checked.
set -euo pipefail

root=${1:?usage: check_layering.sh SOURCE_DIR}

# One line per layer: the layer, then the layers (and guarded libraries) its files may include.
rules='
decoder    decoder
simulator  decoder simulator
capture    decoder capture pcap
formats    decoder formats
wireshark  decoder capture formats wireshark
monitor    decoder monitor mosquitto
cli        *
'
declare -A allowed_by_layer=()
while read -r layer allowed; do
    [[ -n $layer ]] && allowed_by_layer[$layer]=$allowed
done <<<"$rules"
guarded_external=' tests fuzz bench pcap CLI gtest gmock benchmark mosquitto '

# layer_of PATH: the layer of a path relative to the source root ("" when it has none).
source "$(dirname "${BASH_SOURCE[0]}")/layer_of.sh"

include_pattern='^[[:space:]]*#[[:space:]]*include[[:space:]]*(["<]([^">]+)[">])'
violations=0
files=0
while IFS= read -r file; do
    relative=${file#"$root"/}
    layer=$(layer_of "$relative")
    [[ -z $layer ]] && continue
    allowed=${allowed_by_layer[$layer]}
    [[ $allowed == '*' ]] && continue
    files=$((files + 1))
    line_number=0
    while IFS= read -r line || [[ -n $line ]]; do
        line_number=$((line_number + 1))
        [[ $line =~ $include_pattern ]] || continue
        path=${BASH_REMATCH[2]}
        spelled=${BASH_REMATCH[1]}
        first=${path%%/*}
        [[ $first == "$path" ]] && first=${first%%.*}  # <pcap.h> -> pcap
        if [[ $guarded_external == *" $first "* ]]; then
            target=$first
        else
            target=$(layer_of "$path")
            [[ -z $target ]] && continue
        fi
        [[ " $allowed " == *" $target "* ]] && continue
        echo "$relative:$line_number: forbidden #include $spelled (a $layer file may include" \
            "only: $allowed; this names $target)"
        violations=$((violations + 1))
    done <"$file"
done < <(find "$root" \( -path "$root/build" -o -path "$root/.git" -o -path "$root/tests" \
              -o -path "$root/fuzz" -o -path "$root/bench" \) -prune -o -type f \
              \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' -o -name '*.cc' -o -name '*.in' \) \
              -print | LC_ALL=C sort)

if ((violations > 0)); then
    echo "layering: $violations forbidden include(s) in $files file(s); the rules are in $0" >&2
    exit 1
fi
echo "layering: $files files checked, no forbidden include"
