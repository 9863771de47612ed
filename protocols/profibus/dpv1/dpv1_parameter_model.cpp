#include "protocols/profibus/dpv1/dpv1_parameter_model.hpp"

#include <algorithm>
#include <bit>
#include <iterator>
#include <optional>

#include "protocols/profibus/dpv1/dpv1.hpp"
#include "protocols/profibus/dpv1/profidrive.hpp"
#include "protocols/profibus/telegram_builder.hpp"

namespace dpscope {

namespace {

using Parameter = Dpv1ParameterModel::Parameter;

constexpr std::uint8_t kSlot = 0;
constexpr std::uint8_t kReadMax = 240;  // the most a Read accepts: the PROFIdrive maximum
// An attribute none of the tables has (value 0x10, description 0x20, text 0x30 [S003]).
constexpr std::uint8_t kUnknownAttribute = 0x40;
// Error numbers of a format-0x44 block.
constexpr std::uint16_t kErrorUnknownPnu = 0x00, kErrorReadOnly = 0x01, kErrorLimits = 0x02,
                        kErrorSubindex = 0x03, kErrorNoTexts = 0x0F, kErrorAddress = 0x16,
                        kErrorFormat = 0x17;
// Error_Code_1 of the Write error PDUs dpv1_error_pdu sends: invalid index, access denied,
// invalid range (an error in the request header), resource busy.
constexpr std::uint8_t kWriteErrors[] = {0xB0, 0xB6, 0xB7, 0xC2};

std::uint32_t float_bits(float value) { return std::bit_cast<std::uint32_t>(value); }
float bits_float(std::uint32_t bits) { return std::bit_cast<float>(bits); }

bool is_string(std::uint8_t format) { return format == 0x09 || format == 0x0A; }

// Danfoss FC parameters (PNU = the parameter number without its dash: 3-41 is 341).
std::vector<Parameter> vlt_parameters() {
    return {
        {100,
         0x05,
         0,
         true,
         0,
         3,
         {1},
         {},
         {"Speed open loop", "Speed closed loop", "Torque", "Process"}},  // 1-00 Configuration Mode
        {120, 0x07, 0, false, 0, 0, {550}, {}, {}},      // 1-20 Motor Power, 0.01 kW
        {122, 0x06, 0, false, 0, 0, {400}, {}, {}},      // 1-22 Motor Voltage
        {123, 0x06, 0, false, 0, 0, {50}, {}, {}},       // 1-23 Motor Frequency
        {124, 0x07, 0, false, 0, 0, {1200}, {}, {}},     // 1-24 Motor Current, 0.01 A
        {125, 0x06, 0, false, 0, 0, {1460}, {}, {}},     // 1-25 Motor Nominal Speed
        {341, 0x07, 0, true, 1, 360000, {300}, {}, {}},  // 3-41 Ramp 1 Up Time, 0.01 s
        {342, 0x07, 0, true, 1, 360000, {300}, {}, {}},  // 3-42 Ramp 1 Down Time
        {412, 0x06, 0, true, 0, 1000, {0}, {}, {}},      // 4-12 Speed Low Limit, 0.1 Hz
        {414, 0x06, 0, true, 0, 1000, {650}, {}, {}},    // 4-14 Speed High Limit
        {1530, 0x05, 10, false, 0, 0, {14, 13, 14, 2, 0, 0, 0, 0, 0, 0}, {}, {}},  // Alarm Log
        {1531, 0x03, 10, false, 0, 0, {412, 0xFFF6, 398, 0, 0, 0, 0, 0, 0, 0}, {}, {}},
        {1532, 0x36, 10, false, 0, 0, {3600000, 3599000, 1200, 0, 0, 0, 0, 0, 0, 0}, {}, {}},
        {1540, 0x09, 0, false, 0, 0, {}, "FC-302", {}},      // 15-40 FC Type
        {1543, 0x09, 0, false, 0, 0, {}, "05.11", {}},       // 15-43 Software Version
        {1603, 0x23, 0, false, 0, 0, {0x0F07}, {}, {}},      // 16-03 Status Word
        {1605, 0x21, 0, false, 0, 0, {0x2000}, {}, {}},      // 16-05 Main Actual Value [%]
        {1616, 0x04, 0, false, 0, 0, {0xFFFFFFF4}, {}, {}},  // 16-16 Torque [Nm]
        {1690, 0x07, 0, false, 0, 0, {0}, {}, {}},           // 16-90 Alarm Word
    };
}

// PROFIdrive profile parameters (900 and up) and a few drive parameters.
std::vector<Parameter> profidrive_parameters(std::uint8_t address) {
    return {
        {918, 0x06, 0, false, 0, 0, {address}, {}, {}},  // node address
        {922, 0x06, 0, false, 0, 0, {1}, {}, {}},        // telegram selection
        {930,
         0x06,
         0,
         true,
         1,
         3,
         {1},
         {},
         {"reserved", "speed control", "positioning", "torque control"}},  // operating mode
        {944, 0x06, 0, false, 0, 0, {2}, {}, {}},                          // fault message counter
        {947, 0x06, 8, false, 0, 0, {7860, 30005, 0, 0, 0, 0, 0, 0}, {}, {}},  // fault numbers
        {964, 0x06, 7, false, 0, 0, {0x002A, 0x0001, 0x0410, 2024, 0x1503, 1, 0}, {}, {}},
        {965, 0x0A, 0, false, 0, 0, {}, std::string("\x03\x29", 2), {}},  // profile 3, V4.1
        {975, 0x06, 8, false, 0, 0, {0x002A, 0x0001, 0x0410, 2024, 0x1503, 1, 0, 0}, {}, {}},
        {980,
         0x06,
         12,
         false,
         0,
         0,
         {918, 922, 930, 944, 947, 964, 965, 975, 980, 1082, 1120, 1121},
         {},
         {}},  // number list of defined parameters
        {1082, 0x08, 0, true, float_bits(0), float_bits(6000), {float_bits(1500)}, {}, {}},
        {1120, 0x08, 0, true, float_bits(0), float_bits(999), {float_bits(10)}, {}, {}},
        {1121, 0x08, 0, true, float_bits(0), float_bits(999), {float_bits(10)}, {}, {}},
        {2000, 0x08, 0, true, float_bits(6), float_bits(6000), {float_bits(1500)}, {}, {}},
        {61000, 0x09, 0, false, 0, 0, {}, "drive-" + std::to_string(address), {}},
    };
}

bool within(const Parameter& p, std::uint32_t value) {
    switch (p.format) {
        case 0x08:
            return bits_float(value) >= bits_float(p.low) &&
                   bits_float(value) <= bits_float(p.high);
        case 0x03:
        case 0x04: {
            auto v = static_cast<std::int32_t>(value);
            return v >= static_cast<std::int32_t>(p.low) && v <= static_cast<std::int32_t>(p.high);
        }
        default: return value >= p.low && value <= p.high;
    }
}

void append_value(std::vector<std::uint8_t>& out, std::uint8_t format, std::uint32_t value) {
    switch (profidrive_format_size(format)) {
        case 1: out.push_back(static_cast<std::uint8_t>(value)); break;
        case 2: append_u16_be(out, static_cast<std::uint16_t>(value)); break;
        default:
            append_u16_be(out, static_cast<std::uint16_t>(value >> 16));
            append_u16_be(out, static_cast<std::uint16_t>(value));
            break;
    }
}

// A value block: format, number of values, the value bytes, a pad byte to even length.
void append_block(std::vector<std::uint8_t>& out, std::uint8_t format, std::uint8_t count,
                  const std::vector<std::uint8_t>& bytes) {
    out.push_back(format);
    out.push_back(count);
    out.insert(out.end(), bytes.begin(), bytes.end());
    if (bytes.size() % 2 != 0) out.push_back(0x00);
}

void append_error_block(std::vector<std::uint8_t>& out, std::uint16_t error,
                        std::optional<std::uint16_t> info) {
    std::vector<std::uint8_t> bytes;
    append_u16_be(bytes, error);
    if (info) append_u16_be(bytes, *info);
    append_block(out, profidrive::kFormatError, info ? 2 : 1, bytes);
}

bool is_change(std::uint8_t id) {
    return id == profidrive::kChangeValue || id == profidrive::kChangeValueNonVolatile ||
           id == profidrive::kChangeValueDoubleWord;
}

std::vector<std::uint8_t> dpv1_header(std::uint8_t function, std::size_t length) {
    return {function, kSlot, kProfidriveIndex, static_cast<std::uint8_t>(length)};
}

}  // namespace

Dpv1ParameterModel::Dpv1ParameterModel(Dialect dialect, std::uint8_t address,
                                       std::int64_t master_give_up_ns)
    : dialect_(dialect),
      // Danfoss: always axis 0 [S003]; a PROFIdrive drive object 1, as ABB's examples.
      axis_(danfoss_family(dialect) ? 0 : 1),
      master_give_up_ns_(master_give_up_ns),
      parameters_(danfoss_family(dialect) ? vlt_parameters() : profidrive_parameters(address)) {}

Dpv1ParameterModel::Parameter* Dpv1ParameterModel::find(std::uint16_t pnu) {
    for (Parameter& p : parameters_)
        if (p.pnu == pnu) return &p;
    return nullptr;
}

std::uint8_t Dpv1ParameterModel::next_reference() {
    reference_ = reference_ == 0xFF ? 1 : static_cast<std::uint8_t>(reference_ + 1);
    return reference_;
}

const Parameter& Dpv1ParameterModel::pick(ChannelEnvironment& env, bool (*fits)(const Parameter&)) {
    std::vector<std::size_t> candidates;
    for (std::size_t i = 0; i < parameters_.size(); ++i)
        if (fits(parameters_[i])) candidates.push_back(i);
    return parameters_[candidates[env.random(candidates.size())]];
}

Dpv1ParameterModel::Item Dpv1ParameterModel::read_item(ChannelEnvironment& env, const Parameter& p,
                                                       bool whole_array) {
    Item item{profidrive::kAttributeValue, 1, p.pnu, 0, 0, {}};
    if (p.array_size > 1) {
        const std::uint32_t most =
            whole_array ? p.array_size : std::min<std::uint32_t>(4, p.array_size);
        const std::uint32_t least = whole_array ? 2 : 1;
        const auto elements = static_cast<std::uint8_t>(least + env.random(most - least + 1));
        item.elements = elements;
        item.subindex = static_cast<std::uint16_t>(env.random(p.array_size - elements + 1u));
    }
    return item;
}

Dpv1ParameterModel::Item Dpv1ParameterModel::change_item(ChannelEnvironment& env,
                                                         const Parameter& p) {
    Item item{profidrive::kAttributeValue, 1, p.pnu, 0, p.format, {}};
    std::uint32_t value = 0;
    if (p.format == 0x08) {
        const auto low = static_cast<std::uint64_t>(bits_float(p.low));
        const auto high = static_cast<std::uint64_t>(bits_float(p.high));
        value = float_bits(static_cast<float>(low + env.random(high - low + 1)));
    } else {
        value = static_cast<std::uint32_t>(p.low + env.random(std::uint64_t{p.high} - p.low + 1));
    }
    item.values = {value};
    return item;
}

Dpv1ParameterModel::Request Dpv1ParameterModel::choose_request(ChannelEnvironment& env,
                                                               Shape shape) {
    Request r;
    r.reference = next_reference();
    r.id = profidrive::kRequestValue;
    r.axis = axis_;
    auto any = [](const Parameter&) { return true; };
    auto array = [](const Parameter& p) { return p.array_size > 1; };
    auto writable = [](const Parameter& p) { return p.writable; };
    auto change_id = [&] {
        // Danfoss also takes 0x42, the change stored in non-volatile memory [S003].
        return danfoss_family(dialect_) && env.random(2) == 0 ? profidrive::kChangeValueNonVolatile
                                                              : profidrive::kChangeValue;
    };
    // `count` different parameters of those that fit.
    auto several = [&](bool (*fits)(const Parameter&), std::size_t count) {
        std::vector<const Parameter*> chosen;
        for (int tries = 0; chosen.size() < count && tries < 64; ++tries) {
            const Parameter& p = pick(env, fits);
            if (std::find(chosen.begin(), chosen.end(), &p) == chosen.end()) chosen.push_back(&p);
        }
        return chosen;
    };
    std::uint64_t choice = env.random(100);
    if (shape == Shape::MultiRead || (shape == Shape::Any && choice >= 35 && choice < 50)) {
        for (const Parameter* p : several(any, 2 + env.random(3)))
            r.items.push_back(read_item(env, *p, env.random(3) == 0));
    } else if (shape == Shape::ArrayRead || (shape == Shape::Any && choice >= 50 && choice < 62)) {
        r.items.push_back(read_item(env, pick(env, array), true));
    } else if (shape == Shape::UnknownAttribute) {
        r.items.push_back({kUnknownAttribute, 1, pick(env, any).pnu, 0, 0, {}});
    } else if (shape == Shape::StandardChange) {
        r.id = profidrive::kChangeValue;
        r.items.push_back(change_item(env, pick(env, writable)));
    } else if (shape == Shape::Refused) {
        // A request the drive refuses: a negative response with error numbers.
        const std::uint16_t unknown = danfoss_family(dialect_) ? 9999 : 4242;
        switch (env.random(5)) {
            case 0:  // an unknown parameter, after one that reads
                if (env.random(2) == 0) r.items.push_back(read_item(env, pick(env, any), false));
                r.items.push_back({profidrive::kAttributeValue, 1, unknown, 0, 0, {}});
                break;
            case 1: {  // an array element past the end
                const Parameter& p = pick(env, array);
                r.items.push_back({profidrive::kAttributeValue,
                                   1,
                                   p.pnu,
                                   static_cast<std::uint16_t>(p.array_size + env.random(5)),
                                   0,
                                   {}});
                break;
            }
            case 2: {  // a value beyond the limits, maybe after a change that is taken
                r.id = change_id();
                std::vector<const Parameter*> chosen = several(writable, 1 + env.random(2));
                for (std::size_t i = 0; i < chosen.size(); ++i) {
                    Item item = change_item(env, *chosen[i]);
                    if (i + 1 == chosen.size())
                        item.values[0] =
                            chosen[i]->format == 0x08
                                ? float_bits(bits_float(chosen[i]->high) + 1000)
                                : chosen[i]->high + 1 + static_cast<std::uint32_t>(env.random(100));
                    r.items.push_back(item);
                }
                break;
            }
            case 3: {  // a change of a read-only parameter
                r.id = change_id();
                const Parameter& p = pick(
                    env, [](const Parameter& q) { return !q.writable && !is_string(q.format); });
                r.items.push_back({profidrive::kAttributeValue,
                                   1,
                                   p.pnu,
                                   0,
                                   p.format,
                                   {p.values.empty() ? 0 : p.values[0]}});
                break;
            }
            default: {  // the text of a parameter without texts
                const Parameter& p = pick(env, [](const Parameter& q) { return q.texts.empty(); });
                r.items.push_back({profidrive::kAttributeText, 1, p.pnu, 0, 0, {}});
                break;
            }
        }
    } else if (choice < 35) {
        r.items.push_back(read_item(env, pick(env, any), false));
    } else if (choice < 77) {
        r.id = change_id();
        r.items.push_back(change_item(env, pick(env, writable)));
    } else if (choice < 85) {
        r.id = change_id();
        for (const Parameter* p : several(writable, 2))
            r.items.push_back(change_item(env, *p));
    } else if (choice < 93) {
        // Description element 1: the identifier (data type, bit 10 "additional text").
        r.items.push_back({profidrive::kAttributeDescription, 1, pick(env, any).pnu, 1, 0, {}});
    } else {
        const Parameter& p = pick(env, [](const Parameter& q) { return !q.texts.empty(); });
        r.items.push_back({profidrive::kAttributeText,
                           1,
                           p.pnu,
                           static_cast<std::uint16_t>(env.random(p.texts.size())),
                           0,
                           {}});
    }
    return r;
}

std::vector<std::uint8_t> Dpv1ParameterModel::encode_request(const Request& request) const {
    std::vector<std::uint8_t> out = {request.reference, request.id, request.axis,
                                     static_cast<std::uint8_t>(request.items.size())};
    for (const Item& item : request.items) {
        out.push_back(item.attribute);
        out.push_back(item.elements);
        append_u16_be(out, item.pnu);
        append_u16_be(out, item.subindex);
    }
    if (!is_change(request.id)) return out;
    for (const Item& item : request.items) {
        std::vector<std::uint8_t> bytes;
        for (std::uint32_t value : item.values)
            append_value(bytes, item.format, value);
        append_block(out, item.format, static_cast<std::uint8_t>(item.values.size()), bytes);
    }
    return out;
}

std::vector<std::uint8_t> Dpv1ParameterModel::answer(ChannelEnvironment& env,
                                                     const Request& request) {
    const bool change = is_change(request.id);
    std::vector<std::uint8_t> blocks;
    std::size_t count = request.items.size();
    bool negative = false;
    bool shortened = false;
    for (std::size_t i = 0; i < request.items.size(); ++i) {
        const Item& item = request.items[i];
        if (drop_last_parameter_ && count >= 2 && i + 1 == request.items.size()) {
            --count;  // dpv1_parameter_count_mismatch: the last parameter is left out
            break;
        }
        Parameter* p = find(item.pnu);
        std::optional<std::uint16_t> error;
        std::optional<std::uint16_t> info;
        const std::uint32_t size = p ? std::max<std::uint32_t>(1, p->array_size) : 0;
        if (!p) {
            error = kErrorUnknownPnu;
            append_error_block(blocks, *error, std::nullopt);
        } else if (change) {
            if (item.attribute != profidrive::kAttributeValue) {
                error = kErrorAddress;
            } else if (!p->writable) {
                error = kErrorReadOnly;
                info = item.subindex;
            } else if (item.format != p->format) {
                error = kErrorFormat;
            } else if (item.subindex >= size) {
                error = kErrorSubindex;
                info = item.subindex;
            } else if (item.values.empty() || !within(*p, item.values[0])) {
                error = kErrorLimits;
                info = item.subindex;
            } else {
                p->values[item.subindex] = item.values[0];
            }
            if (error) {
                append_error_block(blocks, *error, info);
            } else if (answer_as_read_) {  // dpv1_unexpected_response_id: answered as a read
                std::vector<std::uint8_t> bytes;
                append_value(bytes, p->format, item.values[0]);
                append_block(blocks, p->format, 1, bytes);
            } else {
                append_block(blocks, profidrive::kFormatZero, 0, {});
            }
        } else if (profidrive_attribute_name(item.attribute).empty()) {
            // An attribute the drive does not have: illegal parameter address [P:MCA101 p30].
            error = kErrorAddress;
            append_error_block(blocks, *error, std::nullopt);
        } else if (item.attribute == profidrive::kAttributeDescription) {
            if (item.subindex != 1) {
                error = kErrorSubindex;
                append_error_block(blocks, *error, item.subindex);
            } else {
                std::vector<std::uint8_t> bytes;
                append_u16_be(
                    bytes, static_cast<std::uint16_t>(p->format | (p->texts.empty() ? 0 : 0x0400)));
                append_block(blocks, 0x23, 1, bytes);
            }
        } else if (item.attribute == profidrive::kAttributeText) {
            if (p->texts.empty()) {
                error = kErrorNoTexts;
            } else if (item.subindex >= p->texts.size()) {
                error = kErrorSubindex;
                info = item.subindex;
            }
            if (error) {
                append_error_block(blocks, *error, info);
            } else {
                std::string_view text = p->texts[item.subindex];
                append_block(blocks, 0x09, static_cast<std::uint8_t>(text.size()),
                             std::vector<std::uint8_t>(text.begin(), text.end()));
            }
        } else if (is_string(p->format)) {
            if (item.subindex != 0) {
                append_error_block(blocks, kErrorSubindex, item.subindex);
                error = kErrorSubindex;
            } else {
                append_block(blocks, p->format, static_cast<std::uint8_t>(p->string.size()),
                             std::vector<std::uint8_t>(p->string.begin(), p->string.end()));
            }
        } else if (item.elements == 0 || item.subindex + std::uint32_t{item.elements} > size) {
            error = kErrorSubindex;
            append_error_block(blocks, *error, item.subindex);
        } else {
            std::uint8_t values = item.elements;
            if (short_block_ && !shortened && values >= 2) {
                --values;  // dpv1_length_error: one value fewer than the elements asked for
                shortened = true;
            }
            std::vector<std::uint8_t> bytes;
            for (std::uint32_t k = 0; k < values; ++k)
                append_value(bytes, p->format, p->values[item.subindex + k]);
            append_block(blocks, p->format, values, bytes);
        }
        if (error) negative = true;
    }
    std::uint8_t id = change ? profidrive::kChangeValue : profidrive::kRequestValue;
    if (negative) id |= profidrive::kNegative;
    if (answer_as_read_ && change && !negative) id = profidrive::kRequestValue;
    std::uint8_t reference = request.reference;
    if (env.inject(FaultKind::Dpv1ReferenceMismatch))
        reference = reference == 0xFF ? 1 : static_cast<std::uint8_t>(reference + 1);
    std::vector<std::uint8_t> out = {reference, id, request.axis, static_cast<std::uint8_t>(count)};
    // A positive change response is the header alone.
    if (!change || negative || answer_as_read_) out.insert(out.end(), blocks.begin(), blocks.end());
    return out;
}

bool Dpv1ParameterModel::master_request(ChannelEnvironment& env, std::vector<std::uint8_t>& pdu) {
    pdu.clear();
    const std::int64_t now = env.now();
    if (master_state_ == MasterState::Reading && now - write_time_ > master_give_up_ns_) {
        master_state_ = MasterState::Idle;  // give up on it
        idle_cycles_ = static_cast<std::uint32_t>(1 + env.random(3));
    }
    std::optional<Request> write;
    Shape shape = Shape::Any;
    if (master_state_ == MasterState::Reading) {
        if (env.inject(FaultKind::Dpv1StackedRequest)) {
            write = choose_request(env, shape);  // without reading the pending response
        } else {
            pdu = dpv1_header(dpv1_function::kRead, kReadMax);
        }
    } else if (idle_cycles_ > 0) {
        --idle_cycles_;
        // A read with nothing written: the slave answers with a response all the same.
        if (!pending_ && env.inject(FaultKind::Dpv1OrphanResponse))
            pdu = dpv1_header(dpv1_function::kRead, kReadMax);
    } else {
        if (env.inject(FaultKind::Dpv1NegativeResponse))
            shape = Shape::Refused;
        else if (env.inject(FaultKind::Dpv1UnexpectedResponseId))
            shape = Shape::StandardChange;
        else if (env.inject(FaultKind::Dpv1ParameterCountMismatch))
            shape = Shape::MultiRead;
        else if (env.inject(FaultKind::Dpv1LengthError))
            shape = Shape::ArrayRead;
        else if (env.inject(FaultKind::Dpv1UnknownCode))
            shape = Shape::UnknownAttribute;
        write = choose_request(env, shape);
    }
    if (write) {
        answer_as_read_ = shape == Shape::StandardChange;
        drop_last_parameter_ = shape == Shape::MultiRead;
        short_block_ = shape == Shape::ArrayRead;
        std::vector<std::uint8_t> data = encode_request(*write);
        pdu = dpv1_header(dpv1_function::kWrite, data.size());
        pdu.insert(pdu.end(), data.begin(), data.end());
        request_ = std::move(*write);
        master_state_ = MasterState::Reading;
        write_time_ = now;
    }
    sent_ = pdu;
    return !pdu.empty();
}

void Dpv1ParameterModel::slave_response(ChannelEnvironment& env, std::vector<std::uint8_t>& pdu) {
    pdu.clear();
    if (sent_.empty()) return;
    if (sent_[0] == dpv1_function::kWrite) {
        if (env.inject(FaultKind::Dpv1ErrorPdu)) {
            // The write is refused: the master drops the request.
            pdu = {dpv1_function::kWrite | dpv1_function::kNegative, kDpv1ErrorDecodeDpv1,
                   kWriteErrors[env.random(std::size(kWriteErrors))], 0x00};
            pending_ = false;
            master_state_ = MasterState::Idle;
            idle_cycles_ = static_cast<std::uint32_t>(1 + env.random(4));
            return;
        }
        // The request replaces one not answered yet (a stacked request).
        pending_ = true;
        polls_left_ = static_cast<std::uint32_t>(1 + env.random(3));
        never_ready_ = env.inject(FaultKind::Dpv1ResponseTimeout);
        pdu.assign(sent_.begin(), sent_.begin() + 4);  // the header echoed, no data
        return;
    }
    // A Read.
    std::vector<std::uint8_t> data;
    if (pending_) {
        if (never_ready_ || polls_left_ > 0) {
            if (polls_left_ > 0) --polls_left_;
            pdu = {dpv1_function::kRead | dpv1_function::kNegative, kDpv1ErrorDecodeDpv1,
                   kDpv1StateConflict, 0x00};
            return;
        }
        data = answer(env, request_);
        pending_ = false;
        answer_as_read_ = drop_last_parameter_ = short_block_ = false;
        last_data_ = data;
        master_state_ = MasterState::Idle;
        idle_cycles_ = static_cast<std::uint32_t>(1 + env.random(4));
    } else if (!last_data_.empty()) {
        data = last_data_;  // an orphan: the last response once more
    } else {
        // An orphan before any request: the first parameter's value under the next reference.
        const Parameter& p = parameters_.front();
        const auto reference = static_cast<std::uint8_t>(reference_ == 0xFF ? 1 : reference_ + 1);
        data = {reference, profidrive::kRequestValue, axis_, 1};
        std::vector<std::uint8_t> bytes;
        append_value(bytes, p.format, p.values.empty() ? 0 : p.values[0]);
        append_block(data, p.format, 1, bytes);
    }
    pdu = dpv1_header(dpv1_function::kRead, data.size());
    pdu.insert(pdu.end(), data.begin(), data.end());
}

}  // namespace dpscope
