// The registration table: every protocol dpscope decodes, one line each. Everything else about a
// protocol lives in its folder under protocols/ and is found from this line by name:
//
//   X(Enum, name, Payload, member)
//     Enum     its value of `Protocol` (core/telegram.hpp); the first line is the default bus
//     name     what --bus takes and captures record; also the prefix of what its folder provides
//     Payload  its payload type, the member `member` of DecodedTelegram
//
// What a protocol's folder provides, each in the file of its role (CONTRIBUTING.md, "Adding a
// protocol"); a line here without one of them fails to link, naming the function:
//   ProtocolDescriptor <name>_protocol()   decoder layer   <name>_protocol.cpp
//     (with its decoder and tracker factories, make_decoder and make_tracker: the lanes the
//     commands' pipeline and the Wireshark plugin feed, core/protocol_lane.hpp)
//   <name>_text_columns, <name>_verbose,   formats layer   <name>_render.cpp
//   <name>_jsonl_keys, <name>_csv_columns
//   BusReport <name>_bus_report()          formats layer   <name>_report_section.cpp
//   SimulatedBus <name>_simulated_bus()    simulator layer <name>_bus_model.cpp
//   ProtocolTree <name>_tree()             wireshark layer <name>_tree.cpp
// (the records are returned as const references). The per-layer tables are made from this list:
// protocols/protocol_table.cpp (the descriptors, core/protocol_descriptor.hpp),
// formats/protocol_rendering.hpp (the telegram formats: direct calls, so that they inline),
// formats/bus_reports.cpp (the report, formats/report_model.hpp),
// simulator/simulated_buses.cpp (the simulator, simulator/bus_model.hpp) and
// wireshark/protocol_trees.cpp (the plugin, wireshark/protocol_tree.hpp).
// Adding a protocol is its folder and its line here (with its payload's include); issue 28
// proved it with a toy fourth protocol (tests/toy_protocol/). What a protocol may still want
// outside its folder is data, not code: rows in the problem and finding catalogues, its options
// (protocols/lane_options.hpp and the command line), its filterable Wireshark fields.
#pragma once

#include "protocols/fc/fc_telegram.hpp"
#include "protocols/profibus/dp_telegram.hpp"
#include "protocols/vlt2000/vlt2000_telegram.hpp"

// PROFIBUS DP (FDL, DP-V0 with the PPO parameter channel, DP-V1/PROFIdrive): the payload `dp`.
// The Danfoss FC protocol on RS-485: the payload `fc`.
// The VLT 2000 serial telegram (ASCII; VLT 3000, 3500): the payload `vlt2000`.
#define DPSCOPE_PROTOCOLS(X)                    \
    X(ProfibusDp, profibus, DpTelegram, dp)     \
    X(Fc, fc, FcTelegram, fc)                   \
    X(Vlt2000, vlt2000, Vlt2000Telegram, vlt2000)
