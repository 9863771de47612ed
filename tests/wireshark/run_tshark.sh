#!/usr/bin/env bash
# Runs tshark on one capture with dpscope's plugin loaded:
#   run_tshark.sh PLUGIN CAPTURE|none [TSHARK ARGS...]
# Wireshark ignores personal plugins and WIRESHARK_PLUGIN_DIR when run with special privileges, so
# as root tshark runs as nobody (setpriv). The plugin and the capture are copied to a fresh
# temporary folder readable by everyone (the build tree may not be); tshark reads the copy (none:
# no capture, for tshark -G) and writes to standard output. HOME is a folder in there too, so no
# personal preference of whoever runs the tests changes the output. Exit code: tshark's; 2 on a usage error.
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: run_tshark.sh PLUGIN CAPTURE|none [TSHARK ARGS...]" >&2
    exit 2
fi
plugin=$1
capture=$2
shift 2
files=("$plugin")
[ "$capture" = none ] || files+=("$capture")
for file in "${files[@]}"; do
    if [ ! -r "$file" ]; then
        echo "run_tshark.sh: cannot read $file" >&2
        exit 2
    fi
done
tshark=${TSHARK:-tshark}
# The plugin folder is named after Wireshark's major.minor version ("4.0"): given by the build
# (WIRESHARK_PLUGIN_VERSION, from libwireshark's pkg-config), else asked of tshark.
version=${WIRESHARK_PLUGIN_VERSION:-}
if [ -z "$version" ]; then
    version=$("$tshark" --version 2>/dev/null | sed -n '1s/.* \([0-9][0-9]*\.[0-9][0-9]*\)\.[0-9].*/\1/p')
fi
if ! [[ "$version" =~ ^[0-9]+\.[0-9]+$ ]]; then
    echo "run_tshark.sh: cannot read the version of $tshark" >&2
    exit 2
fi
workdir=$(mktemp -d "${TMPDIR:-/tmp}/dpscope-tshark.XXXXXX")
trap 'rm -rf "$workdir"' EXIT
mkdir -p "$workdir/plugins/$version/epan" "$workdir/home"
cp "$plugin" "$workdir/plugins/$version/epan/dpscope.so"
read_capture=()
if [ "$capture" != none ]; then
    cp "$capture" "$workdir/capture.pcapng"
    read_capture=(-r "$workdir/capture.pcapng")
fi
chmod -R a+rX "$workdir"
run=(env HOME="$workdir/home" WIRESHARK_PLUGIN_DIR="$workdir/plugins" TZ=UTC LANG=C LC_ALL=C)
if [ "$(id -u)" -eq 0 ]; then
    run=(setpriv --reuid=65534 --regid=65534 --clear-groups "${run[@]}")
fi
status=0
"${run[@]}" "$tshark" "${read_capture[@]}" "$@" || status=$?
exit $status
