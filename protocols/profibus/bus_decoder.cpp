#include "protocols/profibus/bus_decoder.hpp"

#include <algorithm>
#include <vector>

namespace dpscope {

std::uint32_t DpTelegram::pcv_value(Direction direction) const noexcept {
    ValueWidth width = direction == Direction::Request ? request_code(dialect, pcv.rc).width
                                                       : response_code(dialect, pcv.rc).width;
    return dpscope::pcv_value(pcv, width);
}

std::string_view DpTelegram::pcv_meaning(Direction direction) const noexcept {
    return direction == Direction::Request ? request_code(dialect, pcv.rc).meaning
                                           : response_code(dialect, pcv.rc).meaning;
}

namespace {

// SD2 and SD3 carry a data unit; SD1, SD4 and the short acknowledgement SC do not.
bool is_data_frame(FrameType type) noexcept {
    return type == FrameType::Sd2 || type == FrameType::Sd3;
}

}  // namespace

bool carries_service_data(Service service, Direction direction, FrameType type) noexcept {
    switch (service) {
        case Service::SetPrm:
        case Service::ChkCfg:
        case Service::GlobalControl:
        case Service::SetSlaveAdd: return direction == Direction::Request;
        case Service::SlaveDiag:
        case Service::GetCfg: return direction == Direction::Response && is_data_frame(type);
        case Service::MsacC1:
        case Service::MsacC2: return is_data_frame(type);
        default: return false;
    }
}

BusDecoder::BusDecoder(DecoderOptions options) : options_(std::move(options)) {
    if (options_.gsd)
        for (std::size_t a = 0; a < stations_.size(); ++a)
            stations_[a].device = options_.gsd->forced(static_cast<std::uint8_t>(a));
    if (options_.naming) naming_.emplace(*options_.naming);
    for (const StationConfig& station : stations_)
        take_device_family(station);
}

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
    ByteReader reader(t.dp.fdl.du);
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
    parse_fdl(bytes, t.dp.fdl);
    t.frame = frame;
    t.time_ns = time_ns;
    t.bytes = bytes;
    t.naming = naming_ ? &naming_->naming() : nullptr;  // this decoder's (a clone has its own)
    t.dp.service = Service::Unknown;
    t.has_roles = false;
    t.master = t.slave = 0;
    t.request_frame = 0;
    t.dp.unanswered.reset();
    t.dp.ppo = PpoLayout{};
    t.dp.ppo_cfg_frame = 0;
    t.dp.has_pcv = false;
    t.dp.pcv = Pcv{};
    t.dp.pcd = {};
    t.dp.pcd_offset = 0;
    t.dp.service_data.reset();
    t.dp.slave_dpv1 = SlaveDpv1::Unknown;
    t.dp.device = nullptr;

    if (t.dp.fdl.type == FrameType::Invalid) {
        t.direction = Direction::Request;
        return t;
    }
    if (t.dp.fdl.is_request()) {
        decode_request(t);
    } else {
        decode_response(t);
    }
    std::uint8_t slave = t.has_roles ? t.slave : 0;
    t.dp.dialect = options_.dialect_of(slave);
    t.dp.pcd_profile = options_.pcd_profile_of(slave);
    decode_service_data(t);
    if (t.has_roles) t.dp.device = stations_[t.slave & 0x7F].device;
    return t;
}

void BusDecoder::decode_request(DecodedTelegram& t) {
    t.direction = Direction::Request;
    t.dp.service = classify_request(t.dp.fdl);
    if (has_pending_) {
        t.dp.unanswered = pending_;
        has_pending_ = false;
    }
    if (!t.dp.fdl.has_addresses) return;
    t.has_roles = true;
    t.master = t.dp.fdl.sa;
    t.slave = t.dp.fdl.da;
    if (t.dp.fdl.type == FrameType::Sd4 || !t.dp.fdl.has_fc) return;
    std::uint8_t function = t.dp.fdl.fc.function();
    // A request with a bad FCS or a reserved frame control byte is dropped by the station it is
    // for: no reply is due.
    if (function_expects_reply(function) && t.dp.fdl.da != kBroadcastAddress && t.dp.fdl.fcs_ok &&
        !t.dp.fdl.fc.is_reserved()) {
        pending_ = UnansweredRequest{t.frame, t.time_ns, t.master, t.slave, function, t.dp.service};
        has_pending_ = true;
    }
}

void BusDecoder::decode_response(DecodedTelegram& t) {
    t.direction = Direction::Response;
    bool answers_pending =
        has_pending_ && (t.dp.fdl.type == FrameType::ShortAck ||
                         (t.dp.fdl.has_addresses && t.dp.fdl.da == pending_.master &&
                          t.dp.fdl.sa == pending_.slave));
    if (answers_pending) {
        t.dp.service = pending_.service;
        t.request_frame = pending_.frame;
        t.has_roles = true;
        t.master = pending_.master;
        t.slave = pending_.slave;
        has_pending_ = false;
        return;
    }
    t.dp.service = classify_unpaired_response(t.dp.fdl);
    if (t.dp.fdl.has_addresses) {
        t.has_roles = true;
        t.master = t.dp.fdl.da;
        t.slave = t.dp.fdl.sa;
    }
}

void BusDecoder::decode_service_data(DecodedTelegram& t) {
    if (!t.has_roles) return;
    if (t.dp.service == Service::DataExchange) {  // the hot path: nothing else to set up
        decode_data_exchange(t);
        return;
    }
    StationConfig& station = stations_[t.slave & 0x7F];
    if (carries_service_data(t.dp.service, t.direction, t.dp.fdl.type))
        read_service_data(t, station);
    else if (t.direction == Direction::Response && is_data_frame(t.dp.fdl.type))
        read_response_in_request_layout(t);
    t.dp.slave_dpv1 = station.dpv1;
}

void BusDecoder::read_response_in_request_layout(DecodedTelegram& t) {
    ByteReader du(t.dp.fdl.du, t.dp.fdl.du_offset);
    ProblemList not_reported;  // the response owes no data, so data that does not fit is no fault
    DpServiceData& data = t.dp.service_data;
    if (t.dp.service == Service::GlobalControl) {
        if (auto control = parse_global_control(du, not_reported))
            data.store_global_control(*control);
    } else if (t.dp.service == Service::SetSlaveAdd) {
        if (auto add = parse_set_slave_add(du, not_reported)) data.store_set_slave_add(*add);
    }
}

void BusDecoder::read_service_data(DecodedTelegram& t, StationConfig& station) {
    ByteReader du(t.dp.fdl.du, t.dp.fdl.du_offset);
    ProblemList& problems = t.dp.fdl.problems;
    DpServiceData& data = t.dp.service_data;
    switch (t.dp.service) {
        case Service::ChkCfg:
        case Service::GetCfg: {
            std::vector<CfgModule>& modules = data.store_cfg();
            parse_cfg(du, modules, problems);
            station.ppo = ppo_from_cfg(
                modules, t.dp.service == Service::ChkCfg ? PpoSource::ChkCfg : PpoSource::GetCfg);
            station.cfg_frame = t.frame;
            note_ppo_override(station, t.slave, t.frame);
            if (station.device) read_gsd(t, station);
            break;
        }
        case Service::SetPrm:
            if (auto prm = parse_set_prm(du, problems)) {
                data.store_set_prm(*prm);
                station.has_ident = true;
                station.ident = prm->ident;
                match_gsd(station, prm->ident);
                if (station.device) read_gsd(t, station);
                // A damaged Set_Prm is dropped by the slave: its DP-V1 mode stays as it was.
                if (t.dp.fdl.fcs_ok)
                    station.dpv1 = prm->dpv1_enabled() ? SlaveDpv1::Enabled : SlaveDpv1::Disabled;
            }
            break;
        case Service::SlaveDiag:
            if (auto diag = parse_slave_diag(du, problems)) {
                station.cfg_fault = (diag->station_status_1 & kDiagCfgFault) != 0;
                parse_extended_diag(ByteReader(diag->extended, diag->extended_offset),
                                    data.store_slave_diag(*diag), problems);
                match_gsd(station, diag->ident);
                if (station.device) read_gsd(t, station);
            }
            break;
        case Service::GlobalControl:
            if (auto control = parse_global_control(du, problems))
                data.store_global_control(*control);
            break;
        case Service::SetSlaveAdd:
            if (auto add = parse_set_slave_add(du, problems)) data.store_set_slave_add(*add);
            break;
        case Service::MsacC1:
        case Service::MsacC2: read_dpv1(t, du); break;
        default: break;
    }
}

void BusDecoder::match_gsd(StationConfig& station, std::uint16_t ident) noexcept {
    if (station.device || !options_.gsd) return;
    station.device = options_.gsd->by_ident(ident);
    take_device_family(station);
}

void BusDecoder::take_device_family(const StationConfig& station) noexcept {
    if (!station.device || !naming_) return;
    if (const auto family = family_of_device(station.device->vendor, station.device->model))
        naming_->naming().set_device_family(static_cast<std::uint8_t>(&station - stations_.data()),
                                            *family);
}

void BusDecoder::read_gsd(DecodedTelegram& t, StationConfig& station) {
    const GsdDevice& device = *station.device;
    DpServiceData& data = t.dp.service_data;
    if (const std::vector<CfgModule>* modules = data.cfg_modules()) {
        // The identifier offsets, for the module runs to end on an identifier.
        std::vector<std::uint16_t>& offsets = identifier_offsets_;
        offsets.clear();
        for (const CfgModule& m : *modules)
            offsets.push_back(m.offset);
        std::vector<GsdModuleMatch>& matches = data.store_gsd_modules();
        match_gsd_modules(device, t.dp.fdl.du, t.dp.fdl.du_offset, offsets, matches);
        station.gsd_modules_known = true;
        station.gsd_modules.clear();
        station.gsd_slots.clear();
        for (const GsdModuleMatch& m : matches) {
            station.gsd_modules.push_back(m.module);
            station.gsd_slots.insert(station.gsd_slots.end(), m.identifiers, m.module);
        }
    } else if (data.set_prm()) {
        // User_Prm_Data: every byte after the seven fixed ones.
        constexpr std::size_t kFixed = 7;
        const Bytes du = t.dp.fdl.du;
        const Bytes user = du.size() > kFixed ? du.subspan(kFixed) : Bytes{};
        read_gsd_user_prm(device, station.gsd_modules, station.gsd_modules_known, user,
                          static_cast<std::uint16_t>(t.dp.fdl.du_offset + kFixed),
                          data.store_gsd_prm());
    } else if (data.slave_diag()) {
        std::vector<GsdDiagText>& texts = data.store_gsd_diag();
        auto slot_text = [&](std::uint16_t offset, std::uint32_t slot) {
            const GsdModule* m =
                slot < station.gsd_slots.size() ? station.gsd_slots[slot] : nullptr;
            if (m)
                texts.push_back(GsdDiagText{GsdDiagText::Source::Slot, offset, slot, 0, m->name});
        };
        for (const DiagBlock& block : data.diag_blocks()) {
            const auto data_offset = static_cast<std::uint16_t>(block.offset + 1);
            switch (block.type) {
                case DiagBlockType::Device:
                    name_gsd_diag_bits(device, block.data, data_offset, texts);
                    break;
                case DiagBlockType::Identifier:
                    for (std::size_t bit = 0; bit < block.data.size() * 8; ++bit)
                        if ((block.data[bit / 8] >> (bit % 8)) & 1u)
                            slot_text(static_cast<std::uint16_t>(data_offset + bit / 8),
                                      static_cast<std::uint32_t>(bit));
                    break;
                case DiagBlockType::Channel: slot_text(block.offset, block.module); break;
                default: break;
            }
        }
    }
}

void BusDecoder::read_dpv1(DecodedTelegram& t, ByteReader du) {
    ProblemList& problems = t.dp.fdl.problems;
    DpServiceData& data = t.dp.service_data;
    Dpv1Pdu& pdu = data.store_dpv1();
    bool request = t.direction == Direction::Request;
    parse_dpv1_pdu(du, request, pdu, problems);
    if (!pdu.on_parameter_channel()) return;
    // The PROFIdrive message is what the length announces, as far as the data holds it.
    Bytes message = pdu.data.first(std::min<std::size_t>(pdu.length, pdu.data.size()));
    ByteReader reader(message, pdu.data_offset);
    if (request && pdu.is_write()) {
        ProfidriveMessage& parsed = data.store_profidrive();
        parse_profidrive_request(reader, parsed, problems);
        if (parsed.has_header) keep_profidrive_request(t, pdu, parsed);
    } else if (!request && pdu.is_read() && !message.empty()) {
        ProfidriveMessage& parsed = data.store_profidrive();
        parse_profidrive_response(reader, parsed, problems);
        if (KeptProfidriveRequest* kept = kept_profidrive_request(t, pdu)) {
            parsed.has_request = true;
            parsed.request_frame = kept->frame;
            parsed.request_id = kept->id;
            parsed.request_reference = kept->reference;
            parsed.addresses.assign(kept->addresses.begin(), kept->addresses.end());
            // A request names one response: a second one (an orphan) is not named after it.
            // A damaged response is read again by the master, so it answers nothing yet.
            if (t.dp.fdl.fcs_ok) {
                kept->answered = true;
                if (naming_) learn_descriptions(t, parsed);
            }
        }
    }
}

void BusDecoder::learn_descriptions(const DecodedTelegram& t, const ProfidriveMessage& response) {
    const std::uint8_t id = response.id & static_cast<std::uint8_t>(~profidrive::kNegative);
    if (id != profidrive::kRequestValue && id != profidrive::kRequestValueDoubleWord) return;
    const std::size_t n = std::min(response.addresses.size(), response.blocks.size());
    for (std::size_t i = 0; i < n; ++i) {
        const ProfidriveAddress& address = response.addresses[i];
        const ProfidriveValueBlock& block = response.blocks[i];
        if (address.attribute != profidrive::kAttributeDescription || block.is_error() ||
            !block.complete)
            continue;
        naming_->described().learn(t.slave, address.pnu, address.subindex, block.values, t.frame,
                                   options_.naming->parameter(t.slave, address.pnu).row);
    }
}

void BusDecoder::keep_profidrive_request(const DecodedTelegram& t, const Dpv1Pdu& pdu,
                                         const ProfidriveMessage& request) {
    KeptProfidriveRequest* slot = nullptr;
    for (KeptProfidriveRequest& kept : profidrive_requests_)
        if (kept.master == t.master && kept.slave == t.slave && kept.slot == pdu.slot &&
            kept.index == pdu.index)
            slot = &kept;
    if (!slot && profidrive_requests_.size() < kKeptProfidriveRequests)
        slot = &profidrive_requests_.emplace_back();
    if (!slot)  // full: the request kept longest goes
        slot = &*std::min_element(profidrive_requests_.begin(), profidrive_requests_.end(),
                                  [](const auto& a, const auto& b) { return a.frame < b.frame; });
    slot->master = t.master;
    slot->slave = t.slave;
    slot->slot = pdu.slot;
    slot->index = pdu.index;
    slot->frame = t.frame;
    slot->id = request.id;
    slot->reference = request.reference;
    slot->answered = false;
    slot->addresses.assign(request.addresses.begin(), request.addresses.end());
}

BusDecoder::KeptProfidriveRequest* BusDecoder::kept_profidrive_request(
    const DecodedTelegram& t, const Dpv1Pdu& pdu) noexcept {
    for (KeptProfidriveRequest& kept : profidrive_requests_)
        if (kept.master == t.master && kept.slave == t.slave && kept.slot == pdu.slot &&
            kept.index == pdu.index)
            return kept.answered ? nullptr : &kept;
    return nullptr;
}

void BusDecoder::decode_data_exchange(DecodedTelegram& t) {
    Bytes du = t.dp.fdl.du;
    if (du.size() == 12 && t.direction == Direction::Request &&
        !stations_[t.slave & 0x7F].ppo.known())
        learn_length12_type(t);
    // Written in place: small structs returned by value cost store-forwarding stalls here.
    layout_for(t.slave, du.size(), t.dp.ppo);
    if (t.dp.ppo.source == PpoSource::ChkCfg || t.dp.ppo.source == PpoSource::GetCfg)
        t.dp.ppo_cfg_frame = stations_[t.slave & 0x7F].cfg_frame;
    ByteReader reader(du, t.dp.fdl.du_offset);
    if (t.dp.ppo.has_pcv) t.dp.has_pcv = read_pcv(reader, kPpoPkeLayout, t.dp.pcv);
    t.dp.pcd_offset = static_cast<std::uint16_t>(reader.offset());
    t.dp.pcd = reader.rest();
}

}  // namespace dpscope
