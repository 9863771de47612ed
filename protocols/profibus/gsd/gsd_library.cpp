#include "protocols/profibus/gsd/gsd_library.hpp"

#include <algorithm>

namespace dpscope {

std::size_t GsdLibrary::add(GsdDevice device, const GsdDevice** shadowed) {
    const std::size_t index = devices_.size();
    devices_.push_back(std::move(device));
    if (shadowed) *shadowed = nullptr;
    if (const std::optional<std::uint16_t> ident = devices_.back().ident_number) {
        auto [it, added] = by_ident_.emplace(*ident, index);
        if (!added && shadowed) *shadowed = &devices_[it->second];
    }
    return index;
}

void GsdLibrary::force(std::uint8_t station, std::size_t index) noexcept {
    if (index < devices_.size()) forced_[station & 0x7F] = static_cast<std::int16_t>(index);
}

const GsdDevice* GsdLibrary::by_ident(std::uint16_t ident) const noexcept {
    auto it = by_ident_.find(ident);
    return it == by_ident_.end() ? nullptr : &devices_[it->second];
}

const GsdDevice* GsdLibrary::forced(std::uint8_t station) const noexcept {
    const std::int16_t index = forced_[station & 0x7F];
    return index < 0 ? nullptr : &devices_[static_cast<std::size_t>(index)];
}

std::string gsd_device_title(const GsdDevice& device) {
    std::string title = device.vendor;
    if (!device.model.empty()) {
        if (!title.empty()) title += ' ';
        title += device.model;
    }
    if (title.empty()) title = device.file;
    return title;
}

void match_gsd_modules(const GsdDevice& device, Bytes config, std::uint16_t offset,
                       std::span<const std::uint16_t> identifier_offsets,
                       std::vector<GsdModuleMatch>& out) {
    // Where each identifier starts, relative to `config`; a module must end where one starts
    // (or at the end).
    auto is_boundary = [&](std::size_t at) {
        if (at == config.size()) return true;
        return std::binary_search(identifier_offsets.begin(), identifier_offsets.end(),
                                  static_cast<std::uint16_t>(offset + at));
    };
    std::size_t identifier = 0;
    std::size_t at = 0;
    while (identifier < identifier_offsets.size()) {
        at = static_cast<std::size_t>(identifier_offsets[identifier] - offset);
        if (at >= config.size()) break;
        const GsdModule* best = nullptr;
        for (const GsdModule& m : device.modules) {
            const std::size_t n = m.config.size();
            if (n == 0 || n > config.size() - at) continue;
            if (best && n <= best->config.size()) continue;
            if (!std::equal(m.config.begin(), m.config.end(), config.begin() + at)) continue;
            if (!is_boundary(at + n)) continue;
            best = &m;
        }
        GsdModuleMatch match;
        match.offset = static_cast<std::uint16_t>(offset + at);
        match.first_identifier = static_cast<std::uint16_t>(identifier);
        match.module = best;
        std::size_t end = best ? at + best->config.size()
                               : (identifier + 1 < identifier_offsets.size()
                                      ? identifier_offsets[identifier + 1] - offset
                                      : config.size());
        std::size_t next = identifier + 1;
        while (next < identifier_offsets.size() &&
               static_cast<std::size_t>(identifier_offsets[next] - offset) < end)
            ++next;
        match.length = static_cast<std::uint16_t>(end - at);
        match.identifiers = static_cast<std::uint16_t>(next - identifier);
        out.push_back(match);
        identifier = next;
    }
}

namespace {

std::uint32_t type_bytes(GsdDataType type) noexcept {
    switch (type) {
        case GsdDataType::Unsigned16:
        case GsdDataType::Signed16: return 2;
        case GsdDataType::Unsigned32:
        case GsdDataType::Signed32: return 4;
        default: return 1;
    }
}

// The bytes a parameter block (a device's or a module's refs and consts) takes.
std::uint32_t block_length(const GsdDevice& device, std::span<const GsdPrmRef> refs,
                           std::span<const GsdPrmConst> consts) {
    std::uint32_t length = 0;
    for (const GsdPrmConst& c : consts)
        length = std::max(length, c.offset + static_cast<std::uint32_t>(c.bytes.size()));
    for (const GsdPrmRef& r : refs)
        if (const GsdUserPrm* prm = device.user_prm(r.reference))
            length = std::max(length, r.offset + type_bytes(prm->type));
    return length;
}

void read_block(const GsdDevice& device, const GsdModule* module, std::span<const GsdPrmRef> refs,
                Bytes user_prm, std::uint32_t base, std::uint16_t offset, GsdPrmReading& out) {
    for (const GsdPrmRef& r : refs) {
        const GsdUserPrm* prm = device.user_prm(r.reference);
        if (!prm) continue;
        const std::uint32_t at = base + r.offset;
        const std::uint32_t n = type_bytes(prm->type);
        if (at + n > user_prm.size()) continue;
        std::uint64_t raw = 0;
        for (std::uint32_t i = 0; i < n; ++i)
            raw = (raw << 8) | user_prm[at + i];
        std::int64_t value = 0;
        switch (prm->type) {
            case GsdDataType::Bit:
            case GsdDataType::BitArea: {
                const unsigned width = prm->last_bit - prm->first_bit + 1u;
                value = static_cast<std::int64_t>((raw >> prm->first_bit) & ((1u << width) - 1u));
                break;
            }
            case GsdDataType::Signed8: value = static_cast<std::int8_t>(raw); break;
            case GsdDataType::Signed16: value = static_cast<std::int16_t>(raw); break;
            case GsdDataType::Signed32: value = static_cast<std::int32_t>(raw); break;
            default: value = static_cast<std::int64_t>(raw); break;
        }
        GsdPrmValue v;
        v.prm = prm;
        v.module = module;
        v.offset = static_cast<std::uint16_t>(offset + at);
        v.value = value;
        v.in_range = prm->allowed.empty() ? value >= prm->min_value && value <= prm->max_value
                                          : std::find(prm->allowed.begin(), prm->allowed.end(),
                                                      value) != prm->allowed.end();
        if (prm->text_reference)
            if (const GsdPrmText* texts = device.prm_text(*prm->text_reference))
                for (const GsdValueText& t : texts->texts)
                    if (t.value == value) {
                        v.text = &t;
                        break;
                    }
        out.values.push_back(v);
    }
}

}  // namespace

void read_gsd_user_prm(const GsdDevice& device, std::span<const GsdModule* const> modules,
                       bool modules_known, Bytes user_prm, std::uint16_t offset,
                       GsdPrmReading& out) {
    out.values.clear();
    out.modules_known = modules_known;
    std::uint32_t device_length = block_length(device, device.prm_refs, device.prm_consts);
    device_length = std::max(device_length, device.user_prm_data_len.value_or(0));
    device_length =
        std::max(device_length, static_cast<std::uint32_t>(device.user_prm_data.size()));
    read_block(device, nullptr, device.prm_refs, user_prm, 0, offset, out);
    std::uint32_t at = device_length;
    if (modules_known)
        for (const GsdModule* m : modules) {
            if (!m) continue;
            read_block(device, m, m->prm_refs, user_prm, at, offset, out);
            at += block_length(device, m->prm_refs, m->prm_consts);
        }
    out.described_length = at;
}

void name_gsd_diag_bits(const GsdDevice& device, Bytes data, std::uint16_t offset,
                        std::vector<GsdDiagText>& out) {
    const std::size_t bits = data.size() * 8;
    for (const GsdValueText& b : device.unit_diag_bits) {
        if (b.value < 0 || static_cast<std::size_t>(b.value) >= bits) continue;
        const auto bit = static_cast<std::size_t>(b.value);
        if (((data[bit / 8] >> (bit % 8)) & 1u) == 0) continue;
        out.push_back(GsdDiagText{GsdDiagText::Source::Bit,
                                  static_cast<std::uint16_t>(offset + bit / 8),
                                  static_cast<std::uint32_t>(bit), 1, b.text});
    }
    for (const GsdDiagArea& area : device.unit_diag_areas) {
        if (area.last_bit >= bits || area.last_bit - area.first_bit >= 63) continue;
        std::int64_t value = 0;
        for (std::uint32_t bit = area.last_bit + 1; bit-- > area.first_bit;)
            value = (value << 1) | ((data[bit / 8] >> (bit % 8)) & 1);
        for (const GsdValueText& v : area.values)
            if (v.value == value) {
                out.push_back(GsdDiagText{GsdDiagText::Source::Area,
                                          static_cast<std::uint16_t>(offset + area.first_bit / 8),
                                          area.first_bit, value, v.text});
                break;
            }
    }
}

}  // namespace dpscope
