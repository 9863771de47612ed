// The Wireshark dissector plugin: captures of link type USER0 (147) as dpscope writes them, decoded
// by dpscope's own decoder library and judged by its trackers (wireshark/capture_replay.hpp), so
// that Wireshark shows what `dpscope decode` shows. The plugin only turns a DecodedTelegram into
// Wireshark's tree, columns and expert info; it parses no byte itself. This file holds the
// preferences, the capture's state, the columns, the parts of the tree every protocol has (the
// request/response link, problems and findings), the dissector and its registration. The
// registration table is dissector_fields.hpp; what differs by protocol (columns, subtree) is each
// protocol's record in the table of protocol trees (wireshark/protocol_tree.hpp), filled in by
// its own file (profibus_tree.cpp, fc_tree.cpp, vlt2000_tree.cpp).
#include <wireshark.h>
// wireshark.h first: it sets up what the epan headers need.
#include <epan/expert.h>
#include <epan/packet.h>
#include <epan/prefs.h>
#include <epan/proto.h>
#include <epan/tvbuff.h>
#include <fmt/format.h>

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "capture/bus_tag.hpp"
#include "capture/gsd_files.hpp"
#include "core/protocol_descriptor.hpp"
#include "formats/describe.hpp"
#include "wireshark/capture_replay.hpp"
#include "wireshark/dissector_fields.hpp"
#include "wireshark/protocol_tree.hpp"
#include "wireshark/tree.hpp"

extern "C" {
WS_DLL_PUBLIC_DEF extern const gchar plugin_version[];
WS_DLL_PUBLIC_DEF extern const int plugin_want_major;
WS_DLL_PUBLIC_DEF extern const int plugin_want_minor;
WS_DLL_PUBLIC void plugin_register(void);
}

const gchar plugin_version[] = DPSCOPE_PLUGIN_VERSION;
const int plugin_want_major = WIRESHARK_VERSION_MAJOR;
const int plugin_want_minor = WIRESHARK_VERSION_MINOR;

namespace dpscope::wireshark {
namespace {

int proto_dpscope = -1;
dissector_handle_t dpscope_handle = nullptr;

// ---- preferences ------------------------------------------------------------------------------

// The bus preference: 0 "auto", then protocol k of the table of protocol trees as value k + 1,
// named as --bus names it (the name is what a preferences file stores). Wireshark keeps pointers
// to the array and to its strings, so both live as long as the program; the names are copied, as
// a string_view need not end in a NUL.
constexpr gint kBusAuto = 0;
const enum_val_t* bus_values() {
    struct Values {
        std::vector<std::string> names;
        std::vector<enum_val_t> list;
        Values() {
            const auto trees = protocol_trees();
            for (const ProtocolTree* tree : trees)
                names.emplace_back(protocol_name(tree->protocol));
            list.push_back(
                {"auto", "From the capture (dpscope's tag, else the first byte)", kBusAuto});
            for (std::size_t k = 0; k < trees.size(); ++k)
                list.push_back(
                    {names[k].c_str(), trees[k]->bus_description, static_cast<gint>(k + 1)});
            list.push_back({nullptr, nullptr, 0});
        }
    };
    static const Values values;
    return values.list.data();
}
const enum_val_t kDialectValues[] = {{"vlt", "vlt (Danfoss VLT 5000)", 0},
                                     {"ge", "ge (GE AF-600/AF-650)", 1},
                                     {"profidrive", "profidrive (PROFIdrive PKW)", 2},
                                     {nullptr, nullptr, 0}};
const enum_val_t kPnuBitsValues[] = {
    {"12", "12 (FC series)", 12}, {"11", "11 (VLT 2800, FCD 300)", 11}, {nullptr, nullptr, 0}};

struct Preferences {
    gint bus = kBusAuto;
    gint dialect = 0;
    guint timeout_ms = 1000;
    guint fc_response_ms = 20;
    gint fc_pnu_bits = 12;
    guint baud = 9600;
    gboolean vlt2000_checksum = TRUE;
    gboolean strict = FALSE;
    const char* gsd_folder = "";  // GSD files (issue 29): every *.gsd / *.gs? in it
};
Preferences prefs;

// The GSD files of the gsd_folder preference, read again only when it names another folder; a
// folder that cannot be read, or a file that does not parse, is a warning in Wireshark's log.
std::shared_ptr<const GsdLibrary> gsd_library_of_preference() {
    static std::string loaded_folder;
    static std::shared_ptr<const GsdLibrary> library;
    const std::string folder = prefs.gsd_folder ? prefs.gsd_folder : "";
    if (folder == loaded_folder) return library;
    loaded_folder = folder;
    library.reset();
    if (folder.empty()) return library;
    Result<LoadedGsdFiles> loaded = load_gsd_files({}, std::vector<std::string>{folder});
    if (!loaded) {
        ws_warning("dpscope: preference gsd_folder: %s", loaded.error().c_str());
        return library;
    }
    for (const std::string& warning : loaded->warnings)
        ws_warning("dpscope: %s", warning.c_str());
    library = std::move(loaded->library);
    return library;
}

// The decoder and tracker options from the preferences, each range-checked as dpscope's command
// line checks it; a value out of range is set back to its default with a warning.
ReplayOptions options_from_preferences() {
    auto checked = [](guint& value, guint low, guint high, guint fallback, const char* name) {
        if (value < low || value > high) {
            ws_warning("dpscope: preference %s = %u is out of range %u to %u; using %u", name,
                       value, low, high, fallback);
            value = fallback;
        }
    };
    checked(prefs.timeout_ms, 1, 3'600'000, 1000, "timeout_ms");
    checked(prefs.fc_response_ms, 1, 60'000, 20, "fc_response_ms");
    checked(prefs.baud, 300, 12'000'000, 9600, "baud");
    static constexpr Dialect kDialects[] = {Dialect::Vlt, Dialect::Ge, Dialect::Profidrive};
    ReplayChoices choices;
    choices.dialect = kDialects[prefs.dialect >= 0 && prefs.dialect < 3 ? prefs.dialect : 0];
    choices.timeout_ms = prefs.timeout_ms;
    choices.strict = prefs.strict;
    choices.fc_response_ms = prefs.fc_response_ms;
    choices.line_baud = prefs.baud;
    choices.fc_pnu_bits = static_cast<std::uint8_t>(prefs.fc_pnu_bits == 11 ? 11 : 12);
    choices.vlt2000_checksum = prefs.vlt2000_checksum;
    ReplayOptions options = replay_options(choices);
    options.decoder.gsd = gsd_library_of_preference();
    return options;
}

// ---- the capture's state ----------------------------------------------------------------------

// One capture at a time: set up at the first telegram, dropped when the capture is closed or the
// preferences change (Wireshark then dissects everything again).
std::unique_ptr<CaptureReplay> capture;

void forget_capture() { capture.reset(); }

// The bus of the capture: the preference, else the tag of a pcapng interface dpscope wrote, else
// the first telegram's first byte (dpscope's rule for an untagged USER0 capture; an empty first
// telegram is of the default bus, the first of the table).
Protocol choose_protocol(packet_info* pinfo, tvbuff_t* tvb) {
    const auto trees = protocol_trees();
    if (prefs.bus > kBusAuto && static_cast<std::size_t>(prefs.bus) <= trees.size())
        return trees[static_cast<std::size_t>(prefs.bus) - 1]->protocol;
    if (pinfo->rec && (pinfo->rec->presence_flags & WTAP_HAS_INTERFACE_ID)) {
        const char* description = epan_get_interface_description(
            pinfo->epan, pinfo->rec->rec_header.packet_header.interface_id);
        if (description) {
            std::string_view text(description);
            if (text.starts_with(kPcapngBusTagPrefix))
                if (auto tagged = protocol_from_name(text.substr(kPcapngBusTagPrefix.size())))
                    return *tagged;
        }
    }
    if (tvb_captured_length(tvb) == 0) return protocol_table().front()->protocol;
    return protocol_of_untagged_user0(tvb_get_guint8(tvb, 0));
}

// ---- the tree every protocol has, and the columns -----------------------------------------------

// The request/response link: a response names its request and the time since it; a request the
// response that answered it.
void add_link(const Tree& tree, const DecodedTelegram& t) {
    if (t.direction == Direction::Response && t.request_frame != 0) {
        tree.generated(
            tree.uint(hf_request_frame, 0, 0, static_cast<std::uint32_t>(t.request_frame)));
        const std::int64_t request_ns = capture->time_of(t.request_frame);
        if (request_ns != kNoTime && t.has_time()) {
            const std::int64_t ns = t.time_ns - request_ns;
            nstime_t delta;
            delta.secs = static_cast<time_t>(ns / 1'000'000'000);
            delta.nsecs = static_cast<int>(ns % 1'000'000'000);
            tree.generated(
                proto_tree_add_time(tree.get(), hf_response_time, nullptr, 0, 0, &delta));
        }
    } else if (t.direction == Direction::Request) {
        if (const std::uint64_t response = capture->response_frame(t.frame))
            tree.generated(
                tree.uint(hf_response_frame, 0, 0, static_cast<std::uint32_t>(response)));
    }
}

void add_problems_and_findings(const Tree& top, packet_info* pinfo, const DecodedTelegram& t,
                               std::span<const Finding> findings) {
    if (!t.problems().empty()) {
        Tree tree = top.text(0, 0, kEttProblems, "Problems");
        for (const Problem& p : t.problems()) {
            const std::string name(problem_kind_name(p.kind));
            const std::string message = problem_message(p);
            proto_item* item = tree.string(
                hf_problem, p.offset, 1, name,
                fmt::format("{} ({}): {}", name, severity_name(problem_severity(p.kind)), message));
            expert_add_info_format(pinfo, item, &ei_problem[static_cast<std::size_t>(p.kind)], "%s",
                                   message.c_str());
        }
    }
    if (findings.empty()) return;
    Tree tree = top.text(0, 0, kEttFindings, "Findings");
    for (const Finding& f : findings) {
        const std::string name(finding_kind_name(f.kind));
        proto_item* item =
            tree.string(hf_finding, 0, 0, name,
                        fmt::format("{} {}: {}", severity_name(f.severity), name, f.message));
        Tree sub = tree.sub(item, kEttFindings);
        sub.string(hf_finding_severity, 0, 0, std::string(severity_name(f.severity)));
        if (f.request_frame != 0)
            sub.uint(hf_finding_request, 0, 0, static_cast<std::uint32_t>(f.request_frame));
        expert_add_info_format(
            pinfo, item,
            &ei_finding[static_cast<std::size_t>(f.kind)][static_cast<std::size_t>(f.severity)],
            "%s", f.message.c_str());
    }
}

// Runs of spaces (the text format's column padding) shrink to one for the Info column.
std::string info_text(const DecodedTelegram& t, std::span<const Finding> findings) {
    TextBuffer b;
    append_telegram_columns(b, t, findings);
    std::string info;
    info.reserve(b.size());
    for (char c : std::string_view(b.data(), b.size())) {
        if (c == ' ' && (info.empty() || info.back() == ' ')) continue;
        info.push_back(c);
    }
    while (!info.empty() && info.back() == ' ')
        info.pop_back();
    return info;
}

// Source and destination as the text line has them (the protocol's record words them).
void set_address_columns(packet_info* pinfo, const DecodedTelegram& t) {
    const AddressColumns columns = protocol_tree(t.protocol).address_columns(t);
    if (!columns.source.empty()) {
        col_add_str(pinfo->cinfo, COL_DEF_SRC, columns.source.c_str());
        col_add_str(pinfo->cinfo, COL_DEF_DST, columns.destination.c_str());
    }
}

int dissect_dpscope(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void*) {
    const guint length = tvb_captured_length(tvb);
    if (!capture)
        capture = std::make_unique<CaptureReplay>(choose_protocol(pinfo, tvb),
                                                  options_from_preferences());
    const std::uint64_t frame = pinfo->num;
    const std::int64_t time_ns =
        pinfo->fd->has_ts
            ? static_cast<std::int64_t>(pinfo->abs_ts.secs) * 1'000'000'000 + pinfo->abs_ts.nsecs
            : kNoTime;
    const Bytes bytes =
        length == 0 ? Bytes() : Bytes(tvb_get_ptr(tvb, 0, static_cast<gint>(length)), length);
    const DecodedTelegram& t = PINFO_FD_VISITED(pinfo) || capture->seen(frame)
                                   ? capture->decode_again(frame, bytes, time_ns)
                                   : capture->first_pass(frame, bytes, time_ns);
    const std::span<const Finding> findings = capture->findings(frame);

    const ProtocolTree& capture_bus = protocol_tree(capture->protocol());
    col_set_str(pinfo->cinfo, COL_PROTOCOL, capture_bus.column);
    set_address_columns(pinfo, t);
    col_clear(pinfo->cinfo, COL_INFO);
    col_add_str(pinfo->cinfo, COL_INFO, info_text(t, findings).c_str());

    proto_item* top_item = proto_tree_add_item(tree, proto_dpscope, tvb, 0, -1, ENC_NA);
    proto_item_append_text(top_item, ": %s", capture_bus.column);
    Tree top(proto_item_add_subtree(top_item, ett[kEttTop]), tvb);
    top.string(hf_bus, 0, 0, std::string(protocol_name(capture->protocol())));
    top.string(hf_direction, 0, 0, std::string(direction_name(t.direction)));
    const ProtocolTree& telegram_bus = protocol_tree(t.protocol);
    if (t.has_roles) {
        if (telegram_bus.shows_master) top.uint(hf_master, 0, 0, t.master);
        top.uint(hf_slave, 0, 0, t.slave);
    }
    add_link(top, t);
    telegram_bus.add_subtree(top, t);
    add_problems_and_findings(top, pinfo, t, findings);
    return static_cast<int>(length);
}

void register_dpscope() {
    // The buses in words, as the --bus help texts name them (a new bus is named here by hand:
    // the title is in every Wireshark golden output).
    proto_dpscope = proto_register_protocol("dpscope (PROFIBUS DP, FC protocol, VLT 2000)",
                                            "dpscope", "dpscope");
    register_fields(proto_dpscope);

    module_t* module = prefs_register_protocol(proto_dpscope, forget_capture);
    prefs_register_enum_preference(module, "bus", "Bus",
                                   "The bus the USER0 capture carries (dpscope --bus)", &prefs.bus,
                                   bus_values(), FALSE);
    prefs_register_enum_preference(module, "dialect", "Parameter-channel dialect",
                                   "Code tables of the PROFIBUS parameter channel (--dialect)",
                                   &prefs.dialect, kDialectValues, FALSE);
    prefs_register_uint_preference(module, "timeout_ms", "Time-out (ms, 1-3600000)",
                                   "A request unanswered for longer is a finding (--timeout-ms)",
                                   10, &prefs.timeout_ms);
    prefs_register_uint_preference(module, "fc_response_ms", "FC late response (ms, 1-60000)",
                                   "An FC drive answering later is a finding (--fc-response-ms)",
                                   10, &prefs.fc_response_ms);
    prefs_register_enum_preference(module, "fc_pnu_bits", "FC PNU bits",
                                   "PKE bits holding the PNU (--fc-pnu-bits)", &prefs.fc_pnu_bits,
                                   kPnuBitsValues, FALSE);
    prefs_register_uint_preference(module, "baud", "Line baud rate (300-12000000)",
                                   "FC and VLT 2000: the line's rate (--baud)", 10, &prefs.baud);
    prefs_register_bool_preference(module, "vlt2000_checksum", "Check the VLT 2000 checksum",
                                   "--vlt2000-checksum check (on) or ignore (off)",
                                   &prefs.vlt2000_checksum);
    prefs_register_bool_preference(module, "strict", "Strict",
                                   "RC 8 after a read request is an unexpected response (--strict)",
                                   &prefs.strict);
    prefs_register_directory_preference(
        module, "gsd_folder", "GSD folder",
        "PROFIBUS: a folder of GSD files (*.gsd and the language variants), matched to slaves by "
        "Ident_Number (--gsd-dir); empty: none",
        &prefs.gsd_folder);

    dpscope_handle = register_dissector("dpscope", dissect_dpscope, proto_dpscope);
    register_init_routine(forget_capture);
    register_cleanup_routine(forget_capture);
}

// USER0 is Wireshark's "DLT_USER" protocol by default; dpscope's dissector takes it over (the
// plugins' handoffs run after the built-in ones). The user DLT table can still name "dpscope"
// for USER1..15.
void handoff_dpscope() { dissector_add_uint("wtap_encap", WTAP_ENCAP_USER0, dpscope_handle); }

}  // namespace
}  // namespace dpscope::wireshark

void plugin_register(void) {
    static proto_plugin plugin;
    plugin.register_protoinfo = dpscope::wireshark::register_dpscope;
    plugin.register_handoff = dpscope::wireshark::handoff_dpscope;
    proto_register_plugin(&plugin);
}
