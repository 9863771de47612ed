#!/usr/bin/env bash
# The man pages (issue 32), made by help2man from --help: dpscope(1) and dpscope-SUB(1) for every
# subcommand `dpscope --help` lists; each renders with man, its NAME line names the page, and it
# names every long option its --help lists, so page and --help do not drift.
# Usage: man_pages_test.sh MAN_DIR DPSCOPE
set -uo pipefail
man_dir=${1:?usage: man_pages_test.sh MAN_DIR DPSCOPE}
dpscope=${2:?usage: man_pages_test.sh MAN_DIR DPSCOPE}
status=0
render() { MANWIDTH=1000 man --nh --nj -l "$1" 2>/dev/null | col -b; }
check_page() {
    local page=$1
    shift
    local file=$man_dir/$page.1.gz
    if [[ ! -f $file ]]; then
        echo "$page: no $file" >&2
        status=1
        return
    fi
    local text
    text=$(render "$file")
    [[ -n $text ]] || { echo "$page: man renders nothing" >&2; status=1; return; }
    grep -qE "^ +$page - " <<<"$text" || { echo "$page: no NAME line '$page - ...'" >&2; status=1; }
    local option
    for option in $("$@" --help | grep -oE '^  (-[A-Za-z0-9],)?--[a-z0-9-]+' | grep -oE -- '--[a-z0-9-]+$'); do
        grep -qF -- "$option" <<<"$text" || { echo "$page: does not name $option" >&2; status=1; }
    done
}
check_page dpscope "$dpscope"
subcommands=$("$dpscope" --help | sed -n '/^Subcommands:/,/^$/p' | awk 'NR > 1 && NF {print $1}')
[[ -n $subcommands ]] || { echo "dpscope --help lists no subcommand" >&2; exit 1; }
for sub in $subcommands; do
    check_page "dpscope-$sub" "$dpscope" "$sub"
done
# Nothing more than those pages.
count=$(ls "$man_dir"/*.1.gz | wc -l)
expected=$(($(wc -w <<<"$subcommands") + 1))
((count == expected)) || { echo "$count pages in $man_dir, expected $expected" >&2; status=1; }
((status == 0)) && echo "man pages: ok ($count pages)"
exit $status
