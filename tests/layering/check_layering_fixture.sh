#!/usr/bin/env bash
# Proves that check_layering.sh catches violations: run on fixture/ (a tree with forbidden
# includes, allowed ones, a commented-out one and an unusual spelling; a protocol folder whose
# files take their layer from the end of their names), it must exit 1 and name
# exactly the violations listed in fixture.expected, file, line and include.
# Usage: check_layering_fixture.sh
set -uo pipefail

here=$(cd "$(dirname "$0")" && pwd)
actual=$(bash "$here/check_layering.sh" "$here/fixture" 2>/dev/null)
status=$?
if ((status != 1)); then
    echo "FAIL: check_layering.sh exited with $status on the fixture, expected 1" >&2
    exit 1
fi
if ! diff -u "$here/fixture.expected" <(printf '%s\n' "$actual"); then
    echo "FAIL: check_layering.sh did not report exactly fixture.expected" >&2
    exit 1
fi
echo "layering fixture: all $(wc -l <"$here/fixture.expected") violations reported"
