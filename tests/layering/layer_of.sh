# The layer (role) of a source file, by the rule in check_layering.sh's header comment and in
# protocols/CMakeLists.txt (dpscope_source_role); sourced by check_layering.sh and check_roles.sh.
# layer_of PATH: the layer of PATH relative to the source root ("" when it has none).
layer_of() {
    local path=$1 first=${1%%/*} name stem
    case $first in
        core | drives) echo decoder ;;
        capture | simulator | formats | wireshark | cli | monitor) echo "$first" ;;
        protocols)
            name=${path##*/}
            stem=${name%%.*}
            case $stem in
                *_describe | *_render | *_report_section) echo formats ;;
                *_model) echo simulator ;;
                *_tree) echo wireshark ;;
                *) echo decoder ;;
            esac ;;
        *) echo "" ;;
    esac
}

