#!/usr/bin/env bash
# Proves that check_roles.sh catches a protocol file built into the wrong library and one left
# out of the build: a made-up tree and compile_commands.json in a temporary folder.
# Usage: check_roles_fixture.sh
set -uo pipefail

here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/src/protocols/toy" "$work/build"
touch "$work/src/protocols/toy/"{toy_decoder,toy_describe,toy_bus_model,toy_tracker}.cpp
entry() {  # entry LIBRARY FILE
    printf '{"command": "c++ -o CMakeFiles/dpscope_%s.dir/protocols/toy/%s.o -c x", "file": "x"},\n' "$1" "$2"
}
{
    echo '['
    entry decoder toy_decoder.cpp
    entry formats toy_describe.cpp
    entry decoder toy_bus_model.cpp  # wrong: a *_model file belongs to the simulator
    echo ']'                         # toy_tracker.cpp: not built at all
} >"$work/build/compile_commands.json"
actual=$(bash "$here/check_roles.sh" "$work/src" "$work/build" 2>/dev/null)
status=$?
expected='protocols/toy/toy_bus_model.cpp: built into dpscope_decoder but its name says the simulator layer
protocols/toy/toy_tracker.cpp: not built (its folder'"'"'s CMakeLists.txt does not list it)'
if ((status != 1)) || [[ $actual != "$expected" ]]; then
    echo "FAIL: check_roles.sh exited with $status and said:" >&2
    printf '%s\n' "$actual" >&2
    exit 1
fi
echo "roles fixture: both faults reported"
