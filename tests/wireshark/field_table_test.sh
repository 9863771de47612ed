#!/usr/bin/env bash
# The field table of docs/wireshark.md against the fields the plugin registers (`tshark -G fields`):
#   field_table_test.sh PLUGIN WIRESHARK_PAGE FINDINGS_PAGE FORMATS_PAGE
# (docs/wireshark.md, docs/findings.md, docs/formats.md). Every registered dpscope.* field must
# have a row with its type (tshark's type without FT_) in WIRESHARK_PAGE's "## Fields" table, and
# every row must name a registered field. A row may name a run of numbered fields:
# `dpscope.pcd.ctw.bit0` to `dpscope.pcd.ctw.bit15`. The expert infos (FT_NONE) must be
# dpscope.problem.KIND or dpscope.finding.KIND (one name whatever the severity), KIND a problem
# kind FORMATS_PAGE names (its "Problem kinds:" lists) or a kind of FINDINGS_PAGE's table, and
# every finding kind must have one.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ $# -eq 4 ] || {
    echo "usage: field_table_test.sh PLUGIN WIRESHARK_PAGE FINDINGS_PAGE FORMATS_PAGE" >&2
    exit 2
}
plugin=$1 wireshark_page=$2 findings_page=$3 formats_page=$4
for page in "$wireshark_page" "$findings_page" "$formats_page"; do
    [ -r "$page" ] || {
        echo "$page: cannot be read" >&2
        exit 1
    }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

bash "$here/run_tshark.sh" "$plugin" none -G fields >"$work/all" 2>"$work/errors" || {
    echo "tshark -G fields failed: $(cat "$work/errors")" >&2
    exit 1
}
awk -F'\t' '$1 == "F" && $5 == "dpscope" && $4 != "FT_NONE" { sub(/^FT_/, "", $4); print $3 "\t" $4 }' \
    "$work/all" | sort >"$work/registered"
awk -F'\t' '$1 == "F" && $5 == "dpscope" && $4 == "FT_NONE" { print $3 }' "$work/all" |
    sort >"$work/experts"
if [ "$(wc -l <"$work/registered")" -lt 10 ]; then
    echo "tshark lists $(wc -l <"$work/registered") dpscope fields: was the plugin loaded?" >&2
    exit 1
fi

# The rows of the table headed "| field | type | meaning |" in the page's "## Fields" section:
# | `name` | TYPE | meaning |.
awk '/^#+ / { inside = ($0 == "## Fields") }
     inside && $0 == "| field | type | meaning |" { table = 1; next }
     table && !/^\|/ { table = 0 }
     table && !/^\|---/' "$wireshark_page" |
    while IFS='|' read -r _ name type _; do
        type=$(echo "$type" | tr -d ' ')
        if [[ "$name" =~ ^\ *\`([a-z0-9_.]+[a-z_.])([0-9]+)\`\ to\ \`([a-z0-9_.]+[a-z_.])([0-9]+)\`\ *$ ]] &&
            [ "${BASH_REMATCH[1]}" = "${BASH_REMATCH[3]}" ]; then
            for ((n = BASH_REMATCH[2]; n <= BASH_REMATCH[4]; ++n)); do
                printf '%s%d\t%s\n' "${BASH_REMATCH[1]}" "$n" "$type"
            done
        elif [[ "$name" =~ ^\ *\`([a-z0-9_.]+)\`\ *$ ]]; then
            printf '%s\t%s\n' "${BASH_REMATCH[1]}" "$type"
        else
            printf 'unreadable row:%s\n' "$name"
        fi
    done | sort >"$work/documented"
status=0
if ! diff "$work/registered" "$work/documented" >"$work/difference"; then
    echo "$wireshark_page's field table (>) differs from the plugin's fields (<):" >&2
    cat "$work/difference" >&2
    status=1
fi

# Expert infos: finding kinds from the Findings table, problem kinds from the formats page.
grep -oE '^\| `[a-z0-9_]+` \| (note|warning|error)' "$findings_page" | sed -E 's/^\| `([a-z0-9_]+)`.*/\1/' |
    sort -u >"$work/finding_kinds"
awk '/^(FC |VLT 2000 )?[Pp]roblem kinds:/ { on = 1 } on { print } on && /\.$/ { on = 0 }' \
    "$formats_page" |
    grep -oE '`[a-z0-9_]+`' | tr -d '`' | sort -u >"$work/problem_kinds"
if [ "$(wc -l <"$work/finding_kinds")" -lt 10 ]; then
    echo "$findings_page: the Findings table was not found" >&2
    exit 1
fi
if [ "$(wc -l <"$work/problem_kinds")" -lt 10 ]; then
    echo "$formats_page: the problem kinds were not found" >&2
    exit 1
fi
while read -r expert; do
    if [[ "$expert" =~ ^dpscope\.problem\.([a-z0-9_]+)$ ]]; then
        grep -qx "${BASH_REMATCH[1]}" "$work/problem_kinds" ||
            { echo "expert info $expert: $formats_page names no such problem kind" >&2; status=1; }
    elif [[ "$expert" =~ ^dpscope\.finding\.([a-z0-9_]+)$ ]]; then
        grep -qx "${BASH_REMATCH[1]}" "$work/finding_kinds" ||
            { echo "expert info $expert: $findings_page's table has no such kind" >&2; status=1; }
    else
        echo "expert info $expert: neither dpscope.problem.KIND nor dpscope.finding.KIND" >&2
        status=1
    fi
done <"$work/experts"
while read -r kind; do
    grep -qx "dpscope.finding.$kind" "$work/experts" ||
        { echo "finding kind $kind has no expert info dpscope.finding.$kind" >&2; status=1; }
done <"$work/finding_kinds"
[ "$status" -ne 0 ] ||
    echo "$(wc -l <"$work/registered") fields and $(wc -l <"$work/experts") expert infos match" \
        "$wireshark_page, $findings_page and $formats_page"
exit "$status"
