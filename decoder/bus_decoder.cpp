#include "decoder/bus_decoder.hpp"

#include <vector>

namespace dpscope {

std::string_view direction_name(Direction direction) {
    return direction == Direction::Request ? "request" : "response";
}

std::uint32_t DecodedTelegram::pcv_value() const noexcept {
    ValueWidth width = direction == Direction::Request ? request_code(dialect, pcv.rc).width
                                                       : response_code(dialect, pcv.rc).width;
    return dpscope::pcv_value(pcv, width);
}

std::string_view DecodedTelegram::pcv_meaning() const noexcept {
    return direction == Direction::Request ? request_code(dialect, pcv.rc).meaning
                                           : response_code(dialect, pcv.rc).meaning;
}

BusDecoder::BusDecoder(DecoderOptions options) : options_(options) {}

void BusDecoder::layout_for(std::uint8_t slave, std::size_t du_length,
                            PpoLayout& layout) const noexcept {
    if (std::uint8_t type = options_.station_ppo[slave & 0x7F]; type != 0) {
        layout = ppo_layout_of_type(type, PpoSource::Option);
        return;
    }
    const StationConfig& config = stations_[slave & 0x7F];
    if (config.ppo.known()) {
        layout = config.ppo;
        return;
    }
    layout = ppo_from_length(du_length);
    if (du_length == 12 && config.length12_type == 4) {
        layout = ppo_layout_of_type(4, PpoSource::Length);
        layout.alternative = 1;
    }
}

void BusDecoder::note_ppo_override(StationConfig& station, std::uint8_t slave,
                                   std::uint64_t frame) const noexcept {
    std::uint8_t type = options_.station_ppo[slave & 0x7F];
    if (type == 0 || station.overridden_cfg_frame != 0) return;
    PpoLayout forced = ppo_layout_of_type(type, PpoSource::Option);
    const PpoLayout& announced = station.ppo;
    if (announced.type != forced.type || announced.output_bytes != forced.output_bytes ||
        announced.input_bytes != forced.input_bytes || announced.has_pcv != forced.has_pcv) {
        station.overridden_cfg_frame = frame;
        station.overridden_ppo = announced;
    }
}

void BusDecoder::learn_length12_type(const DecodedTelegram& t) {
    constexpr std::uint16_t kControlValid = 0x0400;
    ByteReader reader(t.fdl.du);
    auto first = reader.u16_be();
    reader.skip(6);
    auto fifth = reader.u16_be();
    if (!first || !fifth) return;
    StationConfig& config = stations_[t.slave & 0x7F];
    if (*fifth & kControlValid)
        config.length12_type = 1;
    else if (*first & kControlValid)
        config.length12_type = 4;
}

const DecodedTelegram& BusDecoder::decode(Bytes bytes, std::int64_t time_ns, std::uint64_t frame) {
    DecodedTelegram& t = current_;
    parse_fdl(bytes, t.fdl);
    t.frame = frame;
    t.time_ns = time_ns;
    t.bytes = bytes;
    t.service = Service::Unknown;
    t.has_roles = false;
    t.master = t.slave = 0;
    t.request_frame = 0;
    t.unanswered.reset();
    t.ppo = PpoLayout{};
    t.has_pcv = false;
    t.pcv = Pcv{};
    t.pcd = {};
    t.pcd_offset = 0;
    t.slave_dpv1 = SlaveDpv1::Unknown;

    if (t.fdl.type == FrameType::Invalid) {
        t.direction = Direction::Request;
        return t;
    }
    if (t.fdl.is_request()) {
        decode_request(t);
    } else {
        decode_response(t);
    }
    std::uint8_t slave = t.has_roles ? t.slave : 0;
    t.dialect = options_.dialect_of(slave);
    t.pcd_profile = options_.pcd_profile_of(slave);
    decode_service_data(t);
    return t;
}

void BusDecoder::decode_request(DecodedTelegram& t) {
    t.direction = Direction::Request;
    t.service = classify_request(t.fdl);
    if (pending_.valid) {
        t.unanswered = UnansweredRequest{pending_.frame, pending_.time_ns,  pending_.master,
                                         pending_.slave, pending_.function, pending_.service};
        pending_.valid = false;
    }
    if (!t.fdl.has_addresses) return;
    t.has_roles = true;
    t.master = t.fdl.sa;
    t.slave = t.fdl.da;
    if (t.fdl.type == FrameType::Sd4 || !t.fdl.has_fc) return;
    std::uint8_t function = t.fdl.fc.function();
    // A request with a bad FCS or a reserved frame control byte is dropped by the station it is
    // for: no reply is due.
    if (function_expects_reply(function) && t.fdl.da != kBroadcastAddress && t.fdl.fcs_ok &&
        !t.fdl.fc.is_reserved()) {
        pending_ = PendingRequest{true, t.frame, t.time_ns, t.master, t.slave, function, t.service};
    }
}

void BusDecoder::decode_response(DecodedTelegram& t) {
    t.direction = Direction::Response;
    bool answers_pending =
        pending_.valid &&
        (t.fdl.type == FrameType::ShortAck ||
         (t.fdl.has_addresses && t.fdl.da == pending_.master && t.fdl.sa == pending_.slave));
    if (answers_pending) {
        t.service = pending_.service;
        t.request_frame = pending_.frame;
        t.has_roles = true;
        t.master = pending_.master;
        t.slave = pending_.slave;
        pending_.valid = false;
        return;
    }
    t.service = classify_unpaired_response(t.fdl);
    if (t.fdl.has_addresses) {
        t.has_roles = true;
        t.master = t.fdl.da;
        t.slave = t.fdl.sa;
    }
}

void BusDecoder::decode_service_data(DecodedTelegram& t) {
    if (!t.has_roles) return;
    if (t.service == Service::DataExchange) {  // the hot path: nothing else to set up
        decode_data_exchange(t);
        return;
    }
    StationConfig& station = stations_[t.slave & 0x7F];
    ByteReader du(t.fdl.du, t.fdl.du_offset);
    ProblemList& problems = t.fdl.problems;
    bool request = t.direction == Direction::Request;
    // Only data-carrying responses have service data (not SC, not an SD1 acknowledgement).
    bool has_data = t.fdl.type == FrameType::Sd2 || t.fdl.type == FrameType::Sd3;
    switch (t.service) {
        case Service::ChkCfg:
            if (request) {
                std::vector<CfgModule> modules;
                parse_cfg(du, modules, problems);
                station.ppo = ppo_from_cfg(modules, PpoSource::ChkCfg);
                station.cfg_frame = t.frame;
                note_ppo_override(station, t.slave, t.frame);
            }
            break;
        case Service::GetCfg:
            if (!request && has_data) {
                std::vector<CfgModule> modules;
                parse_cfg(du, modules, problems);
                station.ppo = ppo_from_cfg(modules, PpoSource::GetCfg);
                station.cfg_frame = t.frame;
                note_ppo_override(station, t.slave, t.frame);
            }
            break;
        case Service::SetPrm:
            if (request) {
                if (auto prm = parse_set_prm(du, problems)) {
                    station.has_ident = true;
                    station.ident = prm->ident;
                    // A damaged Set_Prm is dropped by the slave: its DP-V1 mode stays as it was.
                    if (t.fdl.fcs_ok)
                        station.dpv1 =
                            prm->dpv1_enabled() ? SlaveDpv1::Enabled : SlaveDpv1::Disabled;
                }
            }
            break;
        case Service::SlaveDiag:
            if (!request && has_data) {
                if (auto diag = parse_slave_diag(du, problems)) {
                    station.cfg_fault = (diag->station_status_1 & kDiagCfgFault) != 0;
                    parse_extended_diag(ByteReader(diag->extended, diag->extended_offset),
                                        problems);
                }
            }
            break;
        case Service::GlobalControl:
            if (request) parse_global_control(du, problems);
            break;
        case Service::SetSlaveAdd:
            if (request) parse_set_slave_add(du, problems);
            break;
        default: break;
    }
    t.slave_dpv1 = station.dpv1;
}

void BusDecoder::decode_data_exchange(DecodedTelegram& t) {
    Bytes du = t.fdl.du;
    if (du.size() == 12 && t.direction == Direction::Request &&
        !stations_[t.slave & 0x7F].ppo.known())
        learn_length12_type(t);
    // Written in place: small structs returned by value cost store-forwarding stalls here.
    layout_for(t.slave, du.size(), t.ppo);
    ByteReader reader(du, t.fdl.du_offset);
    if (t.ppo.has_pcv) t.has_pcv = read_pcv(reader, t.pcv);
    t.pcd_offset = static_cast<std::uint16_t>(reader.offset());
    t.pcd = reader.rest();
}

}  // namespace dpscope
