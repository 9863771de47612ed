// The event script of the structure-aware targets (fuzz_trackers, fuzz_renderers, fuzz_reports):
// the input is read as a sequence of events from which well-formed telegrams are BUILT (with
// protocols/profibus/telegram_builder.hpp and the simulator's FC and VLT 2000 builders), so that
// every mutation changes what happens on the bus (a station, a code, a PNU, a time step) rather
// than a checksum. A few events damage a telegram on purpose (a flipped byte, a cut, garbage), so
// the trackers' link rules are reached too.
//
// Input layout (FuzzInput; past the end every choice is 0):
//   byte 0  bus: 0 PROFIBUS DP, 1 Danfoss FC, 2 VLT 2000 (mod 3)
//   byte 1  options: bit 0 strict, bit 1 untimed (every time kNoTime), bits 2-3 the time-out
//           (1 s, 100 ms, 10 ms, 5 s), bits 4-5 the PROFIBUS dialect (vlt, ge, profidrive,
//           vlt), bit 6 FC PNU bits 11, bit 7 VLT 2000 checksum ignored
//   byte 2  the line rate (0, 9600, 19200, 187500, 1500000, 12000000 baud; mod 6); bits 7-6
//           where fuzz_renderers' rotation over the renderers starts
//   then per event: a time-step byte (bits 7-6 the scale: x10 us, x1 ms, x50 ms, x1 s: the last
//   passes every time-out), a kind byte, and the kind's fields (stations from a small set, RC/AK
//   codes, PNU, IND, values), until the input or `max_telegrams` ends.
// Seed makers write such scripts with ScriptWriter (below).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "core/code_tables.hpp"
#include "core/time.hpp"
#include "fuzz/support/fuzz_input.hpp"
#include "protocols/fc/fc_bus_model.hpp"
#include "protocols/fc/fc_decoder.hpp"
#include "protocols/fc/fc_tracker.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/fdl.hpp"
#include "protocols/profibus/session_tracker.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "protocols/vlt2000/vlt2000_bus_model.hpp"
#include "protocols/vlt2000/vlt2000_decoder.hpp"
#include "protocols/vlt2000/vlt2000_tracker.hpp"

namespace dpscope::fuzz {

enum class ScriptBus : std::uint8_t { Profibus, Fc, Vlt2000 };

// The PROFIBUS event kinds (the kind byte mod kProfibusKinds).
enum class DpEvent : std::uint8_t {
    Token,
    FdlStatus,       // SD1 poll (FDL_Status), answered or not
    DataExchange,    // request and response with a PPO (parameter request / response)
    DxRequest,       // only the request
    DxResponse,      // only a response
    ChkCfg,          // Chk_Cfg with a PPO type's configuration, short ack
    GetCfg,          // Get_Cfg and its answer
    SetPrm,          // Set_Prm (DPV1_Enable chosen), short ack
    SlaveDiag,       // Slave_Diag and its answer (status bits chosen)
    Dpv1Write,       // MSAC_C1 Write with a PROFIdrive parameter request, echo answer
    Dpv1Read,        // MSAC_C1 Read and its answer with a PROFIdrive parameter response
    Dpv1Error,       // MSAC_C1 request answered by a DP-V1 error PDU
    Dpv1C2,          // MSAC_C2 Initiate/Read on the class-2 SAPs
    ShortAck,        // an SC (E5) on its own
    Retry,           // the last request again (same FCB)
    Damaged,         // the last telegram again with one byte changed (bad FCS)
    Truncated,       // the last telegram cut short
    GlobalControl,   // broadcast Global_Control
    Garbage,         // a few bytes from the input
    NegativeAnswer,  // a request answered with RS/RR/UE/NR/DH/RDH status
    Count
};
inline constexpr std::uint8_t kProfibusKinds = static_cast<std::uint8_t>(DpEvent::Count);

enum class FcEvent : std::uint8_t {
    Pair,       // a command and the drive's response
    Command,    // a command alone
    Response,   // a response alone
    Broadcast,  // to address 0
    Damaged,    // the last telegram with one byte changed (bad BCC)
    Truncated,  // the last telegram cut short
    Repeat,     // the last telegram again
    Garbage,
    Count
};
inline constexpr std::uint8_t kFcKinds = static_cast<std::uint8_t>(FcEvent::Count);

enum class VltEvent : std::uint8_t {
    Pair,       // a command and the drive's reply
    Command,    // a command alone
    Reply,      // a reply alone
    Broadcast,  // address 00
    Damaged,    // the last telegram with one character changed
    Truncated,
    Repeat,
    Garbage,
    Count
};
inline constexpr std::uint8_t kVltKinds = static_cast<std::uint8_t>(VltEvent::Count);

// One telegram of the script: its bytes in TelegramScript::bytes.
struct ScriptedTelegram {
    std::size_t offset = 0;
    std::size_t size = 0;
    std::int64_t time_ns = kNoTime;
    std::uint64_t frame = 0;  // 1-based
};

struct TelegramScript {
    ScriptBus bus = ScriptBus::Profibus;
    bool strict = false;
    bool untimed = false;
    std::int64_t timeout_ns = 1'000'000'000;
    Dialect dialect = Dialect::Vlt;
    std::uint8_t fc_pnu_bits = 12;
    bool vlt2000_checksum = true;
    std::uint32_t baud = 0;
    // Where a rotation over renderers starts (fuzz_renderers): the line-rate byte's high bits.
    std::size_t turn = 0;
    std::vector<std::uint8_t> bytes;
    std::vector<ScriptedTelegram> telegrams;

    Bytes telegram_bytes(const ScriptedTelegram& t) const noexcept {
        return Bytes(bytes.data() + t.offset, t.size);
    }
    // Every PROFIBUS slave is described by one GSD file (fuzz_gsd_device(), forced on every
    // address), so that the GSD reading of the decoder and the GSD rules of the tracker run on
    // every script; the tracker times answers at the script's line rate.
    DecoderOptions decoder_options() const {
        DecoderOptions o;
        o.dialect = dialect;
        o.gsd = fuzz_gsd_library();
        return o;
    }
    TrackerOptions tracker_options() const {
        TrackerOptions o;
        o.timeout_ns = timeout_ns;
        o.strict = strict;
        o.line_baud = baud;
        return o;
    }
    // A GSD file written for the fuzz targets: the PPO modules and more, user parameters over the
    // DP-V1 status bytes and a module's, diagnosis bits and an area, limits and timing.
    static std::shared_ptr<const GsdLibrary> fuzz_gsd_library() {
        static const std::shared_ptr<const GsdLibrary> library = [] {
            constexpr std::string_view kText = R"(#Profibus_DP
Vendor_Name = "dpscope fuzz"
Model_Name = "Fuzz device"
Ident_Number = 0x0402
Max_Module = 2
Max_Input_Len = 28
Max_Output_Len = 28
Max_Data_Len = 40
Max_Diag_Data_Len = 12
User_Prm_Data_Len = 3
Max_User_Prm_Data_Len = 6
MaxTsdr_9.6 = 60
MaxTsdr_19.2 = 60
MaxTsdr_187.5 = 60
MaxTsdr_1.5M = 150
MaxTsdr_12M = 800
Min_Slave_Intervall = 3
PrmText = 1
Text(0) = "off"
Text(1) = "on"
EndPrmText
ExtUserPrmData = 1 "DP-V1"
Bit(7) 1 0-1
Prm_Text_Ref = 1
EndExtUserPrmData
ExtUserPrmData = 2 "Alarms"
Unsigned8 0 0-3
EndExtUserPrmData
ExtUserPrmData = 3 "Gain"
Signed16 0 -50-50
EndExtUserPrmData
Ext_User_Prm_Data_Ref(0) = 1
Ext_User_Prm_Data_Ref(1) = 2
Unit_Diag_Bit(0) = "Bit zero"
Unit_Diag_Bit(9) = "Bit nine"
Unit_Diag_Area = 2-4
Value(1) = "One"
Unit_Diag_Area_End
Module = "PPO 1" 0xF3,0xF1
Ext_User_Prm_Data_Ref(0) = 3
EndModule
Module = "PPO 2" 0xF3,0xF5
EndModule
Module = "PPO 3" 0xF1
EndModule
Module = "PPO 4" 0xF5
EndModule
Module = "PPO 5" 0xF3,0xF9
EndModule
)";
            auto lib = std::make_shared<GsdLibrary>();
            Result<GsdDevice> device = parse_gsd(kText, "fuzz.gsd");
            if (!device) __builtin_trap();
            const std::size_t index = lib->add(std::move(*device));
            for (std::uint8_t a = 0; a < 128; ++a) lib->force(a, index);
            return lib;
        }();
        return library;
    }
    FcDecoderOptions fc_decoder_options() const {
        FcDecoderOptions o;
        o.pnu_bits = fc_pnu_bits;
        o.response_window_ns = timeout_ns;
        return o;
    }
    FcTrackerOptions fc_tracker_options() const {
        FcTrackerOptions o;
        o.timeout_ns = timeout_ns;
        o.line_baud = baud <= 115200 ? baud : 0;
        return o;
    }
    Vlt2000DecoderOptions vlt2000_decoder_options() const {
        Vlt2000DecoderOptions o;
        o.response_window_ns = timeout_ns;
        o.check_checksum = vlt2000_checksum;
        return o;
    }
    Vlt2000TrackerOptions vlt2000_tracker_options() const {
        Vlt2000TrackerOptions o;
        o.timeout_ns = timeout_ns;
        o.line_baud = baud <= 115200 ? baud : 0;
        return o;
    }
};

// Calls lane(decoder, tracker) with the decoder and the tracker of the script's bus, made with the
// script's options (fuzz_trackers, fuzz_renderers; fuzz_reports makes every tracker, as the report
// reads them all).
template <class Lane>
void with_script_bus(const TelegramScript& script, Lane&& lane) {
    switch (script.bus) {
        case ScriptBus::Profibus: {
            BusDecoder decoder(script.decoder_options());
            SessionTracker tracker(script.tracker_options());
            lane(decoder, tracker);
            break;
        }
        case ScriptBus::Fc: {
            FcDecoder decoder(script.fc_decoder_options());
            FcTracker tracker(script.fc_tracker_options());
            lane(decoder, tracker);
            break;
        }
        case ScriptBus::Vlt2000: {
            Vlt2000Decoder decoder(script.vlt2000_decoder_options());
            Vlt2000Tracker tracker(script.vlt2000_tracker_options());
            lane(decoder, tracker);
            break;
        }
    }
}

namespace script_detail {

inline constexpr std::uint32_t kBauds[] = {0, 9600, 19200, 187500, 1500000, 12000000};
inline constexpr std::int64_t kTimeouts[] = {1'000'000'000, 100'000'000, 10'000'000, 5'000'000'000};
inline constexpr Dialect kScriptDialects[] = {Dialect::Vlt, Dialect::Ge, Dialect::Profidrive,
                                              Dialect::Vlt};
// Stations: masters 1, 2; slaves 3..6 and 126 (a few more make the live list long).
inline constexpr std::uint8_t kMasters[] = {1, 2, 1, 1};
inline constexpr std::uint8_t kSlaves[] = {3, 4, 5, 6, 3, 4, 126, 0x7F};
// PNUs: small ones, the Danfoss ones the code tables name, PROFIdrive profile ones, big ones.
inline constexpr std::uint16_t kPnus[] = {0,   1,    2,    3,    100,  102,  200,  202,  303, 500,
                                          515, 615,  918,  922,  923,  944,  947,  964,  965, 975,
                                          980, 1000, 1615, 1617, 2047, 4095, 9999, 60000};
inline constexpr std::uint8_t kPpoLengths[] = {12, 20, 4, 12, 28};  // PPO 1..5 data units

class Builder {
  public:
    Builder(FuzzInput& in, TelegramScript& script, std::size_t max_telegrams)
        : in_(in), s_(script), max_(max_telegrams) {}

    void run() {
        while (!in_.empty() && s_.telegrams.size() < max_) {
            step_time();
            const std::uint8_t kind = in_.byte();
            switch (s_.bus) {
                case ScriptBus::Profibus:
                    profibus(static_cast<DpEvent>(kind % kProfibusKinds));
                    break;
                case ScriptBus::Fc: fc(static_cast<FcEvent>(kind % kFcKinds)); break;
                case ScriptBus::Vlt2000: vlt(static_cast<VltEvent>(kind % kVltKinds)); break;
            }
        }
    }

  private:
    // --- common -----------------------------------------------------------------------------
    void step_time() {
        const std::uint8_t b = in_.byte();
        static constexpr std::int64_t kScale[] = {10'000, 1'000'000, 50'000'000, 1'000'000'000};
        now_ += std::int64_t{b & 0x3F} * kScale[b >> 6];
    }
    // Starts a telegram: its bytes are appended to s_.bytes by the caller, then end() closes it.
    std::size_t begin() const noexcept { return s_.bytes.size(); }
    void end(std::size_t start) {
        if (s_.telegrams.size() >= max_ || s_.bytes.size() == start) {
            s_.bytes.resize(start);
            return;
        }
        ScriptedTelegram t;
        t.offset = start;
        t.size = s_.bytes.size() - start;
        t.time_ns = s_.untimed ? kNoTime : now_;
        t.frame = s_.telegrams.size() + 1;
        s_.telegrams.push_back(t);
        // The next telegram follows this one by its time on the line (about) plus a short gap.
        now_ += static_cast<std::int64_t>(t.size) * 1'000 + 100'000;
    }
    void add(const std::vector<std::uint8_t>& bytes) {
        const std::size_t start = begin();
        s_.bytes.insert(s_.bytes.end(), bytes.begin(), bytes.end());
        end(start);
    }
    // The last telegram again, changed: `mode` 0 the same, 1 one byte changed, 2 cut short.
    void again(int mode) {
        if (s_.telegrams.empty()) return;
        const ScriptedTelegram last = s_.telegrams.back();
        const std::size_t start = begin();
        for (std::size_t i = 0; i < last.size; ++i)
            s_.bytes.push_back(s_.bytes[last.offset + i]);
        std::uint8_t* bytes = s_.bytes.data() + start;
        if (mode == 1) {
            const std::size_t at = in_.byte() % last.size;
            const std::uint8_t x = in_.byte();
            bytes[at] = static_cast<std::uint8_t>(bytes[at] ^ (x == 0 ? 1 : x));
        } else if (mode == 2) {
            s_.bytes.resize(start + in_.byte() % last.size);
        }
        end(start);
    }
    void garbage() {
        const std::size_t start = begin();
        for (std::uint8_t b : in_.bytes(1 + in_.byte() % 8))
            s_.bytes.push_back(b);
        end(start);
    }
    std::uint16_t pnu() {
        const std::uint8_t b = in_.byte();
        return b < 0xE0 ? kPnus[b % std::size(kPnus)] : static_cast<std::uint16_t>(in_.u16());
    }
    std::uint32_t value() {
        const std::uint8_t b = in_.byte();
        switch (b & 3) {
            case 0: return b >> 2;
            case 1: return in_.u16();
            case 2: return in_.u32();
            default: return 0xFFFFFFFFu - (b >> 2);
        }
    }

    // --- PROFIBUS DP --------------------------------------------------------------------------
    std::uint8_t& fcb(std::uint8_t master, std::uint8_t slave) {
        return fcb_[(master & 1) * 128 + (slave & 0x7F)];
    }
    // A request's FC: SRD high with FCV and the link's alternating FCB (`retry`: the same FCB).
    std::uint8_t next_fc(std::uint8_t master, std::uint8_t slave, FdlFunction function) {
        std::uint8_t& bit = fcb(master, slave);
        bit = static_cast<std::uint8_t>(bit ^ 1);
        return request_fc(function, bit != 0, true);
    }
    void dp(std::uint8_t da, std::uint8_t sa, std::uint8_t fc, std::optional<std::uint8_t> dsap,
            std::optional<std::uint8_t> ssap, const std::vector<std::uint8_t>& du) {
        const std::size_t start = begin();
        append_telegram(s_.bytes, TelegramSpec{da, sa, fc, dsap, ssap, Bytes(du)});
        end(start);
    }
    void short_ack() {
        const std::size_t start = begin();
        append_short_ack(s_.bytes);
        end(start);
    }
    // The PPO data unit: PKW (PKE: RC/AK 4 bits, SPM, PNU 11 bits; IND; PVA) then PCD words.
    std::vector<std::uint8_t> ppo(std::uint8_t type_index) {
        std::vector<std::uint8_t> du;
        const std::uint8_t length = kPpoLengths[type_index % std::size(kPpoLengths)];
        if (length >= 12) {
            const std::uint8_t code = in_.byte();
            append_pcv(du, static_cast<std::uint8_t>(code & 0x0F), (code & 0x10) != 0,
                       static_cast<std::uint16_t>(pnu() & 0x7FF), in_.byte(), value());
        }
        while (du.size() < length) {
            const std::uint16_t word = in_.u16();
            append_u16_be(du, word);
        }
        du.resize(length);
        return du;
    }
    void data_exchange(std::uint8_t master, std::uint8_t slave, bool request, bool response) {
        const std::uint8_t type = in_.byte();
        if (request) {
            std::vector<std::uint8_t> du = ppo(type);
            dp(slave, master, next_fc(master, slave, FdlFunction::SrdHigh), std::nullopt,
               std::nullopt, du);
        }
        if (response) {
            std::vector<std::uint8_t> du = ppo(type);
            const std::uint8_t status = in_.byte();
            dp(master, slave,
               response_fc((status & 0x80) ? FdlStatus::DataHigh : FdlStatus::DataLow),
               std::nullopt, std::nullopt, du);
        }
    }
    // A DP service request on `dsap` and the answer (`answer` empty: a short acknowledge).
    void service(std::uint8_t master, std::uint8_t slave, std::uint8_t dsap,
                 const std::vector<std::uint8_t>& du, const std::vector<std::uint8_t>* answer) {
        dp(slave, master, next_fc(master, slave, FdlFunction::SrdHigh), dsap, sap::kMaster, du);
        if (answer == nullptr)
            short_ack();
        else
            dp(master, slave, response_fc(FdlStatus::DataLow), sap::kMaster, dsap, *answer);
    }
    static std::vector<std::uint8_t> cfg_of(std::uint8_t type) {
        switch (type % 6) {
            case 0: return {0xF3, 0xF1};
            case 1: return {0xF3, 0xF5};
            case 2: return {0xF1};
            case 3: return {0xF5};
            case 4: return {0xF3, 0xF9};
            default: return {0xC0, 0x03, 0x03};  // a special-format module
        }
    }
    // A PROFIdrive parameter request (read or change) for DP-V1 index 47.
    std::vector<std::uint8_t> profidrive_request() {
        const std::uint8_t head = in_.byte();
        const bool change = (head & 1) != 0;
        const std::uint8_t count = static_cast<std::uint8_t>(1 + (head >> 1) % 3);
        std::vector<std::uint8_t> pdu = {in_.byte(), static_cast<std::uint8_t>(change ? 2 : 1),
                                         static_cast<std::uint8_t>(head >> 6), count};
        static constexpr std::uint8_t kAttributes[] = {0x10, 0x20, 0x30, 0x00};
        static constexpr std::uint8_t kFormats[] = {0x42, 0x43, 0x06, 0x07, 0x08, 0x02, 0x03,
                                                    0x04, 0x05, 0x09, 0x0A, 0x41, 0x44, 0x01};
        std::vector<std::uint8_t> elements;
        for (std::uint8_t i = 0; i < count; ++i) {
            const std::uint8_t b = in_.byte();
            pdu.push_back(kAttributes[b & 3]);
            elements.push_back(static_cast<std::uint8_t>(b >> 6));
            pdu.push_back(elements.back());
            append_u16_be(pdu, pnu());
            append_u16_be(pdu, static_cast<std::uint16_t>(in_.byte() % 20));
        }
        if (change)
            for (std::uint8_t i = 0; i < count; ++i) {
                const std::uint8_t format = kFormats[in_.byte() % std::size(kFormats)];
                const std::uint8_t n = std::max<std::uint8_t>(1, elements[i]);
                pdu.push_back(format);
                pdu.push_back(n);
                for (std::uint8_t k = 0; k < n; ++k)
                    append_value(pdu, format);
            }
        return pdu;
    }
    void append_value(std::vector<std::uint8_t>& pdu, std::uint8_t format) {
        const std::uint32_t v = value();
        int size = profidrive_size(format);
        if (size == 0) size = 1 + in_.byte() % 6;
        for (int i = size - 1; i >= 0; --i)
            pdu.push_back(static_cast<std::uint8_t>(i < 4 ? v >> (8 * i) : 0));
    }
    static int profidrive_size(std::uint8_t format) noexcept {
        switch (format) {
            case 0x01:
            case 0x02:
            case 0x05:
            case 0x41: return 1;
            case 0x03:
            case 0x06:
            case 0x42:
            case 0x44: return 2;
            case 0x04:
            case 0x07:
            case 0x08:
            case 0x43: return 4;
            default: return 0;
        }
    }
    // A PROFIdrive parameter response: values (or errors) for `count` parameters.
    std::vector<std::uint8_t> profidrive_response() {
        const std::uint8_t head = in_.byte();
        static constexpr std::uint8_t kIds[] = {0x01, 0x02, 0x81, 0x82, 0x01, 0x03};
        const std::uint8_t id = kIds[head % std::size(kIds)];
        const std::uint8_t count = static_cast<std::uint8_t>(1 + (head >> 3) % 3);
        std::vector<std::uint8_t> pdu = {in_.byte(), id, 0, count};
        if (id == 0x02) return pdu;  // a change's positive answer has no values
        static constexpr std::uint8_t kFormats[] = {0x42, 0x43, 0x44, 0x06, 0x07, 0x08, 0x02,
                                                    0x03, 0x04, 0x09, 0x0A, 0x41, 0x01, 0x05};
        for (std::uint8_t i = 0; i < count; ++i) {
            const std::uint8_t b = in_.byte();
            const std::uint8_t format =
                (id & 0x80) || (b & 0x80) ? std::uint8_t{0x44} : kFormats[b % std::size(kFormats)];
            const std::uint8_t n = static_cast<std::uint8_t>(1 + (b >> 4) % 3);
            pdu.push_back(format);
            pdu.push_back(n);
            for (std::uint8_t k = 0; k < n; ++k) {
                if (format == 0x44) {
                    append_u16_be(pdu, static_cast<std::uint16_t>(in_.byte() % 0x70));
                } else {
                    append_value(pdu, format);
                }
            }
        }
        return pdu;
    }
    // A DP-V1 exchange on MSAC_C1 (or, `c2`, MSAC_C2) between master and slave.
    void dpv1(std::uint8_t master, std::uint8_t slave, DpEvent kind) {
        const std::uint8_t b = in_.byte();
        const std::uint8_t slot = (b & 0x80) ? in_.byte() : 0;
        const std::uint8_t index = (b & 0x40) ? in_.byte() : 47;
        const bool c2 = kind == DpEvent::Dpv1C2;
        const std::uint8_t dsap =
            c2 ? ((b & 1) ? sap::kResourceManager : std::uint8_t{40}) : sap::kMsacC1;
        const std::uint8_t ssap = c2 ? sap::kMsacC2Master : sap::kMsacC1;
        const bool write = kind == DpEvent::Dpv1Write || (kind != DpEvent::Dpv1Read && (b & 2));
        const std::uint8_t function = c2 && (b & 1) ? std::uint8_t{0x57}
                                      : write       ? std::uint8_t{0x5F}
                                                    : std::uint8_t{0x5E};
        std::vector<std::uint8_t> request = {function, slot, index};
        std::vector<std::uint8_t> data;
        if (write) data = profidrive_request();
        if (c2 && function == 0x57) {
            // Initiate: reserved, Alignment, Features, Profile features, Profile ident, address.
            request = {0x57, 0,    0,    0,    0x01, 0x00, 0x00, 0x00,
                       0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0x00};
        } else {
            request.push_back(static_cast<std::uint8_t>(write ? data.size() : 240));
            request.insert(request.end(), data.begin(), data.end());
        }
        if ((b & 0x30) == 0x30 && request.size() > 4)
            request.resize(4 + in_.byte() % (request.size() - 4));
        dp(slave, master, next_fc(master, slave, FdlFunction::SrdHigh), dsap, ssap, request);
        std::vector<std::uint8_t> answer;
        if (kind == DpEvent::Dpv1Error) {
            static constexpr std::uint8_t kCodes[] = {0xB5, 0xB0, 0xB2, 0xA0, 0xA9, 0xB6,
                                                      0xC3, 0xB7, 0xA2, 0xD0, 0x81};
            answer = {static_cast<std::uint8_t>(function | 0x80),
                      (b & 8) ? std::uint8_t{0xFE} : std::uint8_t{0x80},
                      kCodes[in_.byte() % std::size(kCodes)], in_.byte()};
        } else if (write) {
            answer = {function, slot, index, static_cast<std::uint8_t>(data.size())};
        } else {
            const std::vector<std::uint8_t> response =
                (b & 4) ? std::vector<std::uint8_t>{} : profidrive_response();
            answer = {function, slot, index, static_cast<std::uint8_t>(response.size())};
            answer.insert(answer.end(), response.begin(), response.end());
        }
        dp(master, slave, response_fc(FdlStatus::DataLow), ssap, dsap, answer);
    }
    void profibus(DpEvent kind) {
        const std::uint8_t who = in_.byte();
        const std::uint8_t master = kMasters[who & 3];
        const std::uint8_t slave = kSlaves[(who >> 2) % std::size(kSlaves)];
        switch (kind) {
            case DpEvent::Token: {
                const std::size_t start = begin();
                append_token(s_.bytes, (who & 0x20) ? kMasters[(who + 1) & 3] : master, master);
                end(start);
                break;
            }
            case DpEvent::FdlStatus:
                dp(slave, master, request_fc(FdlFunction::FdlStatus), std::nullopt, std::nullopt,
                   {});
                if (who & 0x40)
                    dp(master, slave, response_fc(FdlStatus::Ok, (who & 0x80) ? 0x30 : 0x00),
                       std::nullopt, std::nullopt, {});
                break;
            case DpEvent::DataExchange: data_exchange(master, slave, true, true); break;
            case DpEvent::DxRequest: data_exchange(master, slave, true, false); break;
            case DpEvent::DxResponse: data_exchange(master, slave, false, true); break;
            case DpEvent::ChkCfg:
                service(master, slave, sap::kChkCfg, cfg_of(in_.byte()), nullptr);
                break;
            case DpEvent::GetCfg: {
                const std::vector<std::uint8_t> cfg = cfg_of(in_.byte());
                service(master, slave, sap::kGetCfg, {}, &cfg);
                break;
            }
            case DpEvent::SetPrm: {
                const std::uint8_t b = in_.byte();
                std::vector<std::uint8_t> prm = {
                    0x88, 10, 10, 11, 0x07, static_cast<std::uint8_t>(0x50 + (b & 3)), 0x00};
                if (b & 4) {
                    prm.push_back((b & 8) ? 0x80 : 0x00);
                    prm.push_back(0x00);
                    prm.push_back(0x00);
                }
                service(master, slave, sap::kSetPrm, prm, nullptr);
                break;
            }
            case DpEvent::SlaveDiag: {
                const std::uint8_t b1 = in_.byte();
                const std::uint8_t b2 = in_.byte();
                std::vector<std::uint8_t> diag = {b1,   static_cast<std::uint8_t>(b2 | 0x04),
                                                  0x00, (b1 & 0x01) ? std::uint8_t{255} : master,
                                                  0x07, 0x50};
                if (b2 & 0x80) {
                    diag.push_back(0x44);  // a device-related block: header + 3 bytes
                    diag.push_back(in_.byte());
                    diag.push_back(in_.byte());
                    diag.push_back(in_.byte());
                }
                service(master, slave, sap::kSlaveDiag, {}, &diag);
                break;
            }
            case DpEvent::Dpv1Write:
            case DpEvent::Dpv1Read:
            case DpEvent::Dpv1Error:
            case DpEvent::Dpv1C2: dpv1(master, slave, kind); break;
            case DpEvent::ShortAck: short_ack(); break;
            case DpEvent::Retry: {
                // The last request again: its FCB is the same.
                for (std::size_t i = s_.telegrams.size(); i-- > 0;) {
                    const ScriptedTelegram t = s_.telegrams[i];
                    const Bytes b = s_.telegram_bytes(t);
                    if (b.size() > 6 && (b[0] == 0x68 || b[0] == 0xA2) &&
                        (b[b[0] == 0x68 ? 6 : 3] & 0x40)) {
                        const std::size_t start = begin();
                        s_.bytes.insert(
                            s_.bytes.end(),
                            s_.bytes.begin() + static_cast<std::ptrdiff_t>(t.offset),
                            s_.bytes.begin() + static_cast<std::ptrdiff_t>(t.offset + t.size));
                        end(start);
                        break;
                    }
                }
                break;
            }
            case DpEvent::Damaged: again(1); break;
            case DpEvent::Truncated: again(2); break;
            case DpEvent::GlobalControl:
                dp(kBroadcastAddress, master, request_fc(FdlFunction::SdnHigh), sap::kGlobalControl,
                   sap::kMaster, {in_.byte(), 0x00});
                break;
            case DpEvent::Garbage: garbage(); break;
            case DpEvent::NegativeAnswer: {
                static constexpr FdlStatus kNegative[] = {
                    FdlStatus::UserError, FdlStatus::NoResource,
                    FdlStatus::NoService, FdlStatus::NoResponseData,
                    FdlStatus::DataHigh,  FdlStatus::NotReceivedDataHigh};
                const std::uint8_t b = in_.byte();
                if (b & 0x80)
                    dp(slave, master, next_fc(master, slave, FdlFunction::SrdHigh), sap::kSlaveDiag,
                       sap::kMaster, {});
                else
                    dp(slave, master, next_fc(master, slave, FdlFunction::SrdHigh), std::nullopt,
                       std::nullopt, ppo(b));
                dp(master, slave, response_fc(kNegative[b % std::size(kNegative)]), std::nullopt,
                   std::nullopt, {});
                break;
            }
            case DpEvent::Count: break;
        }
    }

    // --- Danfoss FC -------------------------------------------------------------------------
    // The address byte: 1-126 (bit 7) or 1-31 format for drives 1, 2, 3, 31, 126.
    std::uint8_t fc_adr(std::uint8_t who) const noexcept {
        static constexpr std::uint8_t kDrives[] = {1, 2, 3, 31, 1, 2, 126, 5};
        const std::uint8_t drive = kDrives[who & 7];
        return (who & 8) && drive <= 31 ? drive : static_cast<std::uint8_t>(0x80 | drive);
    }
    // The data of a block: process (PCD1, PCD2), parameter (PKE, IND, PWE, PCD) or text.
    std::vector<std::uint8_t> fc_data(std::uint8_t shape, std::uint8_t ak) {
        std::vector<std::uint8_t> data;
        if ((shape & 3) != 0) {
            const std::uint16_t p = pnu();
            const std::uint16_t pke = static_cast<std::uint16_t>(ak << 12 | (p & 0x0FFF));
            append_u16_be(data, pke);
            const std::uint8_t ind_high =
                (shape & 4) ? ((shape & 8) ? kFcTextWrite : kFcTextRead) : 0;
            data.push_back(ind_high);
            data.push_back(in_.byte());
            if ((shape & 3) == 2) {  // a text block: n characters
                const std::uint8_t n = in_.byte() % 12;
                for (std::uint8_t i = 0; i < n; ++i)
                    data.push_back(static_cast<std::uint8_t>('A' + i));
            } else {
                const std::uint32_t v = value();
                for (int i = 3; i >= 0; --i)
                    data.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
            }
        }
        append_u16_be(data, in_.u16());
        append_u16_be(data, in_.u16());
        return data;
    }
    void fc(FcEvent kind) {
        const std::uint8_t who = in_.byte();
        const std::uint8_t adr = fc_adr(who);
        switch (kind) {
            case FcEvent::Pair:
            case FcEvent::Command:
            case FcEvent::Response: {
                const std::uint8_t codes = in_.byte();
                const std::uint8_t shape = in_.byte();
                if (kind != FcEvent::Response)
                    add(build_fc_telegram(adr, fc_data(shape, codes & 0x0F)));
                if (kind != FcEvent::Command) {
                    // The answer's AK: 1, 2, 7 (with a fault code), 15 for text, or any.
                    static constexpr std::uint8_t kAnswers[] = {1, 2, 7, 15, 0, 1, 2, 1};
                    const std::uint8_t ak = (codes & 0x80)
                                                ? static_cast<std::uint8_t>(codes >> 4 & 0x0F)
                                                : kAnswers[codes >> 4 & 7];
                    add(build_fc_telegram(adr, fc_data(shape, ak)));
                }
                break;
            }
            case FcEvent::Broadcast: {
                const std::uint8_t shape = in_.byte();
                add(build_fc_telegram((who & 8) ? std::uint8_t{0x20} : std::uint8_t{0x80},
                                      fc_data(shape, in_.byte() & 0x0F)));
                break;
            }
            case FcEvent::Damaged: again(1); break;
            case FcEvent::Truncated: again(2); break;
            case FcEvent::Repeat: again(0); break;
            case FcEvent::Garbage: garbage(); break;
            case FcEvent::Count: break;
        }
    }

    // --- VLT 2000 -----------------------------------------------------------------------------
    std::vector<std::uint8_t> vlt_telegram(std::uint8_t address, char letter) {
        static constexpr char kIndex[][7] = {"000001", "000003", "+00008", "00000A", "999999"};
        Vlt2000Fields f;
        f.address = address;
        f.letter = letter;
        const std::uint8_t b = in_.byte();
        f.word = (b & 1) ? in_.u16() : Vlt2000BusModel::kRunWord;
        f.parameter = static_cast<std::uint16_t>(pnu() % 10000);
        f.negative = (b & 2) != 0;
        f.digits = value() % 100000;
        f.decimals = static_cast<std::uint8_t>((b >> 2) % 10);
        if (letter == 'I') f.index = kIndex[(b >> 6) % std::size(kIndex)];
        f.checksum_disabled = (b & 0xE0) == 0xE0;
        return vlt2000_telegram(f);
    }
    void vlt(VltEvent kind) {
        static constexpr std::uint8_t kDrives[] = {1, 2, 5, 99, 1, 2, 31, 7};
        static constexpr char kLetters[] = {'C', 'R', 'U', 'I', 'R', 'C', 'X', 'r'};
        const std::uint8_t who = in_.byte();
        const std::uint8_t address = kDrives[who & 7];
        const char letter = kLetters[(who >> 3) & 7];
        switch (kind) {
            case VltEvent::Pair:
            case VltEvent::Command:
            case VltEvent::Reply:
                if (kind != VltEvent::Reply) add(vlt_telegram(address, letter));
                if (kind != VltEvent::Command)
                    add(vlt_telegram((who & 0x40) ? kDrives[(who + 1) & 7] : address,
                                     (who & 0x80) ? kLetters[(who + 1) & 7] : letter));
                break;
            case VltEvent::Broadcast: add(vlt_telegram(0, letter)); break;
            case VltEvent::Damaged: again(1); break;
            case VltEvent::Truncated: again(2); break;
            case VltEvent::Repeat: again(0); break;
            case VltEvent::Garbage: garbage(); break;
            case VltEvent::Count: break;
        }
    }

    FuzzInput& in_;
    TelegramScript& s_;
    std::size_t max_;
    std::int64_t now_ = 1'700'000'000'000'000'000;
    std::uint8_t fcb_[256] = {};
};

}  // namespace script_detail

// Reads the script's header and events from `in` into `script` (cleared first): at most
// `max_telegrams` telegrams.
inline void build_telegram_script(FuzzInput& in, TelegramScript& script,
                                  std::size_t max_telegrams) {
    script.bytes.clear();
    script.telegrams.clear();
    script.bus = static_cast<ScriptBus>(in.byte() % 3);
    const std::uint8_t options = in.byte();
    script.strict = (options & 1) != 0;
    script.untimed = (options & 2) != 0;
    script.timeout_ns = script_detail::kTimeouts[(options >> 2) & 3];
    script.dialect = script_detail::kScriptDialects[(options >> 4) & 3];
    script.fc_pnu_bits = (options & 0x40) ? 11 : 12;
    script.vlt2000_checksum = (options & 0x80) == 0;
    const std::uint8_t line = in.byte();
    script.baud = script_detail::kBauds[line % std::size(script_detail::kBauds)];
    script.turn = line >> 6;
    script_detail::Builder(in, script, max_telegrams).run();
}

// Writes scripts for the seed makers: the header, then events as the bytes the builder reads.
class ScriptWriter {
  public:
    ScriptWriter(ScriptBus bus, std::uint8_t options, std::uint8_t baud_index) {
        bytes_ = {static_cast<std::uint8_t>(bus), options, baud_index};
    }
    // One event: a time step byte, the kind, then its field bytes.
    ScriptWriter& event(std::uint8_t time_step, std::uint8_t kind,
                        std::initializer_list<std::uint8_t> fields) {
        bytes_.push_back(time_step);
        bytes_.push_back(kind);
        bytes_.insert(bytes_.end(), fields.begin(), fields.end());
        return *this;
    }
    const std::vector<std::uint8_t>& bytes() const noexcept { return bytes_; }

  private:
    std::vector<std::uint8_t> bytes_;
};

}  // namespace dpscope::fuzz
