// PROFIdrive parameter access over DP-V1 of one simulated slave, both ends of it: the class-1
// master writes a parameter request to slot 0, index 47 (MSAC_C1), the slave echoes the Write's
// header, the master reads until the slave has the response ready (the first reads are answered
// "state conflict", DE 80 B5 00), then reads the parameter response. The slave answers from a
// parameter table of its dialect (Danfoss FC for vlt, PROFIdrive profile parameters for
// profidrive) that change requests write. The dpv1_* faults are injected here, as the bus model
// arms them. Facts: docs/protocol/dpv1-parameter-access.md.
//
// The model knows nothing of FDL: per cycle the bus model asks master_request for the PDU the
// master sends (none while it waits between requests), sends it, and sends back slave_response.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/code_tables.hpp"
#include "protocols/profibus/parameter_channel_model.hpp"

namespace dpscope {

class Dpv1ParameterModel {
  public:
    Dpv1ParameterModel(Dialect dialect, std::uint8_t address, std::int64_t master_give_up_ns);

    // The master's DP-V1 PDU this cycle (a Write with a parameter request, or a Read), or false
    // when it sends none.
    bool master_request(ChannelEnvironment& env, std::vector<std::uint8_t>& pdu);
    // The slave's answer to the PDU master_request gave: the Write's header echoed, a DP-V1 error
    // PDU, or the Read response with the parameter response.
    void slave_response(ChannelEnvironment& env, std::vector<std::uint8_t>& pdu);

    // One parameter of the slave's table.
    struct Parameter {
        std::uint16_t pnu = 0;
        std::uint8_t format = 0;
        std::uint8_t array_size = 0;  // 0: a single value, else the number of elements
        bool writable = false;
        std::uint32_t low = 0, high = 0;      // change limits (numeric formats; float bits)
        std::vector<std::uint32_t> values;    // one per element (float: the bits)
        std::string string;                   // VisibleString and OctetString values
        std::vector<std::string_view> texts;  // the text of each value (text attribute)
    };
    // One parameter of a request; `values` are a change request's.
    struct Item {
        std::uint8_t attribute = 0;
        std::uint8_t elements = 1;
        std::uint16_t pnu = 0;
        std::uint16_t subindex = 0;
        std::uint8_t format = 0;
        std::vector<std::uint32_t> values;
    };
    struct Request {
        std::uint8_t reference = 0;
        std::uint8_t id = 0;
        std::uint8_t axis = 0;
        std::vector<Item> items;
    };

  private:
    // What the master asks next; the faults that shape a request are taken here.
    enum class Shape : std::uint8_t {
        Any,
        MultiRead,
        ArrayRead,
        StandardChange,
        Refused,
        UnknownAttribute,  // dpv1_unknown_code: a read with an attribute no dialect defines
    };
    Request choose_request(ChannelEnvironment& env, Shape shape);
    Item read_item(ChannelEnvironment& env, const Parameter& p, bool whole_array);
    Item change_item(ChannelEnvironment& env, const Parameter& p);
    const Parameter& pick(ChannelEnvironment& env, bool (*fits)(const Parameter&));
    std::vector<std::uint8_t> encode_request(const Request& request) const;
    // The slave's parameter response to `request` (applies the changes it accepts).
    std::vector<std::uint8_t> answer(ChannelEnvironment& env, const Request& request);
    Parameter* find(std::uint16_t pnu);
    std::uint8_t next_reference();

    enum class MasterState : std::uint8_t { Idle, Reading };

    Dialect dialect_;
    std::uint8_t axis_;
    std::int64_t master_give_up_ns_;
    std::vector<Parameter> parameters_;
    // Master side.
    MasterState master_state_ = MasterState::Idle;
    std::uint32_t idle_cycles_ = 2;
    std::uint8_t reference_ = 0;  // the last request reference used (1..255)
    std::int64_t write_time_ = 0;
    std::vector<std::uint8_t> sent_;  // the PDU master_request gave
    // Slave side.
    bool pending_ = false;  // holds a request it has not answered yet
    Request request_;
    std::uint32_t polls_left_ = 0;         // reads to answer with state conflict first
    bool never_ready_ = false;             // dpv1_response_timeout
    bool answer_as_read_ = false;          // dpv1_unexpected_response_id
    bool drop_last_parameter_ = false;     // dpv1_parameter_count_mismatch
    bool short_block_ = false;             // dpv1_length_error
    std::vector<std::uint8_t> last_data_;  // the last parameter response (dpv1_orphan_response)
};

}  // namespace dpscope
