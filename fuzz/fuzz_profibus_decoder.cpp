// Feeds ONE PROFIBUS telegram to a BusDecoder (FDL, the DP service, DP-V1, PROFIdrive, the PPO
// split and the PCV), after a context the input's 2-byte header chooses, built with
// protocols/profibus/telegram_builder.hpp for the stations the telegram names: a Chk_Cfg announcing
// a PPO type, a Set_Prm enabling DP-V1, a PROFIdrive parameter request written on index 47, and the
// request the telegram may answer (Data_Exchange, a DP-V1 Read, Slave_Diag, Get_Cfg, Set_Prm, or
// the telegram itself). So a mutated response reaches the PPO/PCV split, the DP-V1 Read response
// and the PROFIdrive response named after its request. A custom mutator repairs the FDL framing
// (LE/LEr, repeated SD, FCS, ED: fuzz/support/checksum_repair.hpp) after libFuzzer's mutation,
// except one mutation in 16, so mutations reach the fields behind those checks. Nothing is
// rendered; the decoded telegram is walked (problems and their messages, every name lookup, the
// PROFIdrive values as text) and checked (fuzz/support/decoded_check.hpp: problem offsets and
// every view into the telegram lie in it).
//
// Input: byte 0: bits 0-1 dialect (vlt, ge, profidrive, vlt), bit 2 Chk_Cfg context, bit 3
// Set_Prm with DP-V1, bit 4 PROFIdrive Write context, bits 5-7 the request just before (0 none,
// 1 Data_Exchange, 2 DP-V1 Read index 47, 3 Slave_Diag, 4 Get_Cfg, 5 DP-V1 Read index 1, 6 Set_Prm,
// 7 the telegram itself). Byte 1: bits 0-2 the PPO type Chk_Cfg announces (1..5; 0, 6, 7 odd
// configurations), bit 3 --ppo for the slave as well, bits 4-5 PCD profile (unset, fc,
// profidrive), bit 6 the PROFIdrive request changes the value (else reads it), bit 7 two
// parameters (else one; a read of two asks for the second's description element 4, which the
// decoder, given the shipped databases' naming, learns from). Then the telegram (at most 255
// bytes).
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drives/parameter_naming.hpp"
#include "fuzz/support/checksum_repair.hpp"
#include "fuzz/support/decoded_check.hpp"
#include "fuzz/support/fuzz_input.hpp"
#include "protocols/profibus/bus_decoder.hpp"
#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/dpv1/dpv1.hpp"
#include "protocols/profibus/dpv1/profidrive.hpp"
#include "protocols/profibus/fdl.hpp"
#include "protocols/profibus/fdl_framing_rules.hpp"
#include "protocols/profibus/telegram_builder.hpp"

namespace {

using dpscope::Bytes;
using dpscope::fuzz::decoded_check;
using dpscope::fuzz::lies_in;

constexpr std::size_t kHeader = 2;

std::size_t repair(std::uint8_t* data, std::size_t size, std::size_t max_size, unsigned) {
    if (size <= kHeader || max_size <= kHeader) return size;
    return kHeader +
           dpscope::fuzz::repair_fdl_telegram(data + kHeader, size - kHeader, max_size - kHeader);
}

// Where the FDL framing rules and the decoder differ by design (docs/protocol/fdl-and-dp.md): the
// framer takes an SD2 with LE 3 (pyprofibus does), the parser reports LE outside 4..249.
bool documented_difference(const dpscope::Problem& problem, Bytes telegram) {
    return problem.kind == dpscope::ProblemKind::LengthOutOfRange && telegram.size() > 1 &&
           telegram[1] == 3;
}

// The master and slave the telegram names (its header's addresses, roles by FC bit 6).
struct Stations {
    std::uint8_t master = 2;
    std::uint8_t slave = 3;
};

Stations stations_of(Bytes t) {
    Stations s;
    if (t.empty()) return s;
    std::size_t at = 0;
    switch (t[0]) {
        case dpscope::kSd1:
        case dpscope::kSd3:
        case dpscope::kSd4: at = 1; break;
        case dpscope::kSd2: at = 4; break;
        default: return s;
    }
    if (t.size() < at + 2) return s;
    const std::uint8_t da = t[at] & 0x7F;
    const std::uint8_t sa = t[at + 1] & 0x7F;
    const bool request = t[0] == dpscope::kSd4 || (t.size() > at + 2 && (t[at + 2] & 0x40) != 0);
    s.master = request ? sa : da;
    s.slave = request ? da : sa;
    return s;
}

std::vector<std::uint8_t> cfg_of(std::uint8_t type) {
    switch (type) {
        case 1: return {0xF3, 0xF1};
        case 2: return {0xF3, 0xF5};
        case 3: return {0xF1};
        case 4: return {0xF5};
        case 5: return {0xF3, 0xF9};
        case 6: return {0xF3};
        case 7: return {0x13, 0x23, 0x00, 0xC1, 0x01, 0x01, 0x01};
        default: return {};
    }
}

// The decoder and the clock the context and the telegram go through.
// The decoder, with the context's telegrams built from specs.
struct Run : dpscope::fuzz::DecoderRun<dpscope::BusDecoder> {
    using DecoderRun::DecoderRun;

    void decode_built(const dpscope::TelegramSpec& spec) {
        const std::vector<std::uint8_t> bytes = dpscope::build_telegram(spec);
        (void)decode(Bytes(bytes));
    }
    void short_ack() {
        static constexpr std::uint8_t kAck[] = {dpscope::kShortAck};
        (void)decode(Bytes(kAck));
    }
};

// A request master -> slave on `dsap` (SSAP 62: the DP master), or on the default SAP.
dpscope::TelegramSpec request(const Stations& s, std::optional<std::uint8_t> dsap, Bytes du,
                              std::uint8_t ssap = dpscope::sap::kMaster) {
    return dpscope::TelegramSpec{s.slave,
                                 s.master,
                                 dpscope::request_fc(dpscope::FdlFunction::SrdHigh, false, true),
                                 dsap,
                                 dsap ? std::optional<std::uint8_t>(ssap) : std::nullopt,
                                 du};
}

dpscope::TelegramSpec response(const Stations& s, std::optional<std::uint8_t> ssap, Bytes du,
                               std::uint8_t dsap = dpscope::sap::kMaster) {
    return dpscope::TelegramSpec{s.master,
                                 s.slave,
                                 dpscope::response_fc(dpscope::FdlStatus::DataLow),
                                 ssap ? std::optional<std::uint8_t>(dsap) : std::nullopt,
                                 ssap,
                                 du};
}

// The PROFIdrive parameter request written on index 47: read or change one or two parameters.
std::vector<std::uint8_t> profidrive_write(bool change, bool two) {
    const std::uint8_t count = two ? 2 : 1;
    std::vector<std::uint8_t> pdu = {dpscope::dpv1_function::kWrite, 0x00,
                                     dpscope::kProfidriveIndex, 0x00};
    const std::vector<std::uint8_t> request_header = {
        0x2A, change ? dpscope::profidrive::kChangeValue : dpscope::profidrive::kRequestValue, 0x01,
        count};
    pdu.insert(pdu.end(), request_header.begin(), request_header.end());
    for (std::uint8_t i = 0; i < count; ++i) {
        // attribute value, 1 element, PNU 0x0100 + i, subindex 0; reading two, the second is
        // description element 4 (the variable attribute), which the decoder learns from
        const bool describe = !change && i == 1;
        const std::uint8_t address[] = {
            static_cast<std::uint8_t>(describe ? 0x20 : 0x10), 0x01, 0x01, i, 0x00,
            static_cast<std::uint8_t>(describe ? 4 : 0)};
        pdu.insert(pdu.end(), std::begin(address), std::end(address));
    }
    if (change) {
        for (std::uint8_t i = 0; i < count; ++i) {
            const std::uint8_t block[] = {0x06, 0x01, 0x12, static_cast<std::uint8_t>(0x34 + i)};
            pdu.insert(pdu.end(), std::begin(block), std::end(block));
        }
    }
    pdu[3] = static_cast<std::uint8_t>(pdu.size() - 4);
    return pdu;
}

// Decodes the context the header chooses for the stations `s`.
void decode_context(Run& run, const Stations& s, std::uint8_t h0, std::uint8_t h1, Bytes telegram) {
    using namespace dpscope;
    const std::uint8_t type = h1 & 0x07;
    if (h0 & 0x04) {
        const std::vector<std::uint8_t> cfg = cfg_of(type);
        run.decode_built(request(s, sap::kChkCfg, Bytes(cfg)));
        run.short_ack();
    }
    if (h0 & 0x08) {
        const std::uint8_t prm[] = {0x88, 10, 10, 11, 0x12, 0x34, 0x00, 0x80, 0x00, 0x00};
        run.decode_built(request(s, sap::kSetPrm, Bytes(prm)));
        run.short_ack();
    }
    if (h0 & 0x10) {
        const std::vector<std::uint8_t> write =
            profidrive_write((h1 & 0x40) != 0, (h1 & 0x80) != 0);
        run.decode_built(request(s, sap::kMsacC1, Bytes(write), sap::kMsacC1));
        const std::uint8_t echo[] = {dpv1_function::kWrite, 0x00, kProfidriveIndex, write[3]};
        run.decode_built(response(s, sap::kMsacC1, Bytes(echo), sap::kMsacC1));
    }
    switch (h0 >> 5) {
        case 1: {
            const PpoLayout layout = run.decoder.layout_for(s.slave, 12);
            const std::vector<std::uint8_t> out(layout.output_bytes != 0 ? layout.output_bytes : 12,
                                                0x04);
            run.decode_built(request(s, std::nullopt, Bytes(out)));
            break;
        }
        case 2:
        case 5: {
            const std::uint8_t index = (h0 >> 5) == 2 ? kProfidriveIndex : 1;
            const std::uint8_t read[] = {dpv1_function::kRead, 0x00, index, 240};
            run.decode_built(request(s, sap::kMsacC1, Bytes(read), sap::kMsacC1));
            break;
        }
        case 3: run.decode_built(request(s, sap::kSlaveDiag, Bytes())); break;
        case 4: run.decode_built(request(s, sap::kGetCfg, Bytes())); break;
        case 6: {
            const std::uint8_t prm[] = {0x88, 10, 10, 11, 0x12, 0x34, 0x00};
            run.decode_built(request(s, sap::kSetPrm, Bytes(prm)));
            break;
        }
        case 7: (void)run.decode(telegram); break;
        default: break;
    }
}

// Walks the PROFIBUS payload: every name the renderers look up, the PROFIdrive values as text,
// and every view into the telegram checked to lie in it.
std::size_t walk(const dpscope::DecodedTelegram& t) {
    using namespace dpscope;
    std::size_t total = fuzz::walk_problems(t);
    const DpTelegram& dp = t.dp;
    const FdlTelegram& fdl = dp.fdl;
    decoded_check(fdl.size <= t.bytes.size(), "the FDL telegram lies in the record");
    decoded_check(fuzz::lies_at(fdl.du, fdl.du_offset, t.bytes), "the data unit lies in it");
    total += frame_type_name(fdl.type).size() + service_name(dp.service).size();
    if (fdl.has_fc) {
        total += fdl.fc.is_request() ? request_function_name(fdl.fc).size()
                                     : response_status_name(fdl.fc.function()).size() +
                                           response_status_text(fdl.fc.function()).size() +
                                           station_type_name(fdl.fc.station_type()).size();
    }
    if (fdl.has_dsap) total += sap_name(fdl.dsap, fdl.is_request()).size();
    if (fdl.has_ssap) total += sap_name(fdl.ssap, !fdl.is_request()).size();
    if (dp.unanswered) total += service_name(dp.unanswered->service).size();
    if (dp.has_pcv) {
        total += dp.pcv_value(t.direction) + dp.pcv_meaning(t.direction).size();
        total += error_text_or_unknown(dp.dialect, static_cast<std::uint16_t>(dp.pcv.pva)).size();
    }
    decoded_check(lies_in(dp.pcd, t.bytes), "the PCD lie in the telegram");
    decoded_check(fuzz::lies_at(dp.pcd, dp.pcd_offset, t.bytes) || dp.pcd.empty(),
                  "the PCD lie at their offset");
    if (!dp.pcd.empty()) {
        const WordBits& bits = t.direction == Direction::Request
                                   ? control_word_bits(dp.pcd_profile, dp.danfoss_pcd())
                                   : status_word_bits(dp.pcd_profile, dp.danfoss_pcd());
        total += bits[0].when_1.size();
    }
    const DpServiceData& data = dp.service_data;
    if (const SlaveDiag* diag = data.slave_diag()) {
        decoded_check(fuzz::lies_at(diag->extended, diag->extended_offset, t.bytes),
                      "the extended diagnosis lies in the telegram");
        for (const DiagBlock& block : data.diag_blocks()) {
            decoded_check(lies_in(block.data, t.bytes), "a diagnosis block lies in the telegram");
            decoded_check(block.offset < t.bytes.size(), "a diagnosis block's header is in it");
            total += diag_block_type_name(block.type).size() +
                     channel_error_text(block.error_type).size() +
                     channel_type_text(block.channel_type).size() +
                     channel_io_text(block.io).size();
        }
    }
    if (const SetPrm* prm = data.set_prm()) {
        decoded_check(fuzz::lies_at(prm->user_prm, prm->user_prm_offset, t.bytes),
                      "the User_Prm_Data lie in the telegram");
        total += prm->watchdog_ms() +
                 (prm->has_dpv1_status ? dpv1_alarm_mode_text(prm->dpv1_status[2]).size() : 0);
    }
    if (const std::vector<CfgModule>* modules = data.cfg_modules()) {
        for (const CfgModule& module : *modules) {
            decoded_check(module.offset < t.bytes.size(), "an identifier byte is in the telegram");
            total += cfg_direction_name(module.direction).size() + module.input_bytes() +
                     module.output_bytes();
        }
    }
    if (const SetSlaveAdd* add = data.set_slave_add())
        decoded_check(lies_in(add->rem_slave_data, t.bytes), "Rem_Slave_Data lie in the telegram");
    if (const Dpv1Pdu* pdu = data.dpv1()) {
        decoded_check(fuzz::lies_at(pdu->data, pdu->data_offset, t.bytes) || pdu->data.empty(),
                      "the DP-V1 data lie in the telegram");
        decoded_check(
            lies_in(pdu->initiate.s_addr, t.bytes) && lies_in(pdu->initiate.d_addr, t.bytes),
            "the Initiate addresses lie in the telegram");
        total += dpv1_function_name(pdu->function).size() +
                 dpv1_error_decode_name(pdu->error_decode).size() +
                 dpv1_error_class_name(pdu->error_code_1).size() +
                 dpv1_error_code_name(pdu->error_code_1).size() +
                 dpv1_abort_instance_name(pdu->abort.instance_reason).size() +
                 dpv1_abort_reason_name(pdu->abort.instance_reason).size();
    }
    if (const ProfidriveMessage* message = data.profidrive()) {
        total += message->is_response ? profidrive_response_id_name(message->id).size()
                                      : profidrive_request_id_name(message->id).size();
        if (message->has_request)
            total += profidrive_response_answers(message->id, message->request_id) ? 1 : 0;
        for (const ProfidriveAddress& address : message->addresses)
            total += profidrive_attribute_name(address.attribute).size();
        static std::string text;
        for (const ProfidriveValueBlock& block : message->blocks) {
            decoded_check(
                fuzz::lies_at(block.values, block.values_offset, t.bytes) || block.values.empty(),
                "a value block lies in the telegram");
            total += profidrive_format_name(block.format).size();
            text.clear();
            append_profidrive_values(block, text);
            total += text.size();
            if (block.is_error())
                total += profidrive_error_text(block.error_number(), dp.dialect).size() +
                         (block.has_error_info() ? block.error_info() : 0);
        }
    }
    return total;
}

}  // namespace

DPSCOPE_FUZZ_REPAIRING_MUTATOR(repair, 16)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    dpscope::fuzz::FuzzInput in(data, size);
    const std::uint8_t h0 = in.byte();
    const std::uint8_t h1 = in.byte();
    const Bytes telegram = in.rest();

    dpscope::DecoderOptions options;
    static constexpr dpscope::Dialect kDialect[] = {dpscope::Dialect::Vlt, dpscope::Dialect::Ge,
                                                    dpscope::Dialect::Profidrive,
                                                    dpscope::Dialect::Vlt};
    options.dialect = kDialect[h0 & 0x03];
    switch ((h1 >> 4) & 0x03) {
        case 1: options.pcd_profile = dpscope::PcdProfile::Fc; break;
        case 2: options.pcd_profile = dpscope::PcdProfile::Profidrive; break;
        default: break;
    }
    const Stations s = stations_of(telegram);
    if (h1 & 0x08) options.station_ppo[s.slave] = static_cast<std::uint8_t>((h1 & 0x07) % 6);

    // Names from the shipped databases, with what the drive describes first: the description
    // answers reach the learning (drives/described_parameters.hpp).
    static const std::shared_ptr<const dpscope::ParameterNaming> naming =
        std::make_shared<dpscope::ParameterNaming>(
            dpscope::shipped_parameter_database(), dpscope::Protocol::ProfibusDp,
            std::array<dpscope::Dialect, dpscope::kStationCount>{}, dpscope::DriveHints{});
    options.naming = naming;
    Run run(options);
    decode_context(run, s, h0, h1, telegram);
    dpscope::fuzz::decode_and_check(run, telegram, dpscope::Protocol::ProfibusDp,
                                    dpscope::fdl_framing_rules(), true, walk,
                                    &documented_difference);
    return 0;
}
