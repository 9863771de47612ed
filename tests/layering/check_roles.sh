#!/usr/bin/env bash
# The build puts every file of protocols/ into the library of the layer its name says: the rule
# in protocols/CMakeLists.txt (dpscope_source_role) and the one the layering check reads
# (layer_of.sh) must agree, and no .cpp under protocols/ may be left out of the build. Reads the
# build's compile_commands.json; prints each file that is wrong and exits 1, else exits 0.
# Usage: check_roles.sh SOURCE_DIR BUILD_DIR
set -euo pipefail

root=${1:?usage: check_roles.sh SOURCE_DIR BUILD_DIR}
build=${2:?usage: check_roles.sh SOURCE_DIR BUILD_DIR}
source "$(dirname "${BASH_SOURCE[0]}")/layer_of.sh"
commands=$build/compile_commands.json
[[ -r $commands ]] || { echo "check_roles: no $commands" >&2; exit 1; }
plugin_built=0
grep -q 'dpscope_wireshark\.dir' "$commands" && plugin_built=1

wrong=0
checked=0
while IFS= read -r file; do
    relative=${file#"$root"/}
    layer=$(layer_of "$relative")
    # The object each target builds from this file: -o CMakeFiles/dpscope_LIB.dir/....o
    libraries=$(grep -F -- "$relative.o " "$commands" | grep -o 'dpscope_[a-z]*\.dir' | sort -u |
                sed 's/^dpscope_//; s/\.dir$//' | tr '\n' ' ' || true)
    checked=$((checked + 1))
    if [[ -z $libraries ]]; then
        [[ $layer == wireshark && $plugin_built == 0 ]] && continue
        echo "$relative: not built (its folder's CMakeLists.txt does not list it)"
        wrong=$((wrong + 1))
    elif [[ $libraries != "$layer " ]]; then
        echo "$relative: built into dpscope_${libraries% } but its name says the $layer layer"
        wrong=$((wrong + 1))
    fi
done < <(find "$root/protocols" -name '*.cpp' | LC_ALL=C sort)

if ((wrong > 0)); then
    echo "roles: $wrong of $checked protocol files in the wrong library" >&2
    exit 1
fi
echo "roles: $checked protocol files, each in the library of its layer"
