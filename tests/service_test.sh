#!/usr/bin/env bash
# The service as installed (issue 30): `cmake --install` into a scratch root puts the binary, the
# unit dpscope-sniff@.service and /etc/dpscope/example.conf in place; systemd accepts the unit
# (systemd-analyze verify, when systemd is on the machine); the installed dpscope reads the
# example config (up to the serial port, which this machine does not have).
# Usage: service_test.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: service_test.sh BUILD_DIR}
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
fail() { echo "service_test: $*" >&2; exit 1; }

DESTDIR=$root cmake --install "$build" >"$root/install.log" 2>&1 || { cat "$root/install.log"; fail "cmake --install failed"; }
prefix=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
units=$(sed -n 's/^DPSCOPE_SYSTEMD_UNIT_DIR:PATH=//p' "$build/CMakeCache.txt")
configs=$(sed -n 's/^DPSCOPE_CONFIG_DIR:PATH=//p' "$build/CMakeCache.txt")
binary=$root$prefix/bin/dpscope
unit=$root$units/dpscope-sniff@.service
example=$root$configs/example.conf
for file in "$binary" "$unit" "$example"; do
    [[ -e $file ]] || fail "not installed: ${file#"$root"}"
done
grep -q "^ExecStart=$prefix/bin/dpscope sniff --config $configs/%i.conf --sighup reopen$" "$unit" ||
    fail "the unit's ExecStart is not the installed binary with the instance's config: $(grep ExecStart "$unit")"

# systemd's own check of the unit, with the installed binary in the place it names.
if command -v systemd-analyze >/dev/null 2>&1; then
    instance=$root/dpscope-sniff@line3.service
    sed "s#$prefix/bin/dpscope#$binary#" "$unit" >"$instance"
    output=$(systemd-analyze verify "$instance" 2>&1 || true)
    # Only what it says about this unit counts (a container may lack other units it looks at).
    if grep -q "dpscope-sniff@line3.service" <<<"$output"; then
        fail "systemd-analyze verify: $output"
    fi
fi

# The installed binary reads the installed example (the command line's interface wins).
set +e
output=$("$binary" sniff --config "$example" --interface /dev/dpscope-no-such-tty 2>&1)
code=$?
set -e
[[ $code -eq 2 ]] || fail "sniff --config example.conf: exit code $code, expected 2: $output"
grep -q "/dev/dpscope-no-such-tty" <<<"$output" || fail "sniff --config example.conf: $output"
echo "service_test: installed and verified under $root"
