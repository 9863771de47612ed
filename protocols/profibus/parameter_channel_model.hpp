// The parameter channel (PCV) of one simulated PPO slave, both ends of it: the master's requests
// (what it asks next, when it takes a response as the answer, when it gives up, how it
// acknowledges a spontaneous message) and the slave's answering behaviour (it sees the master's
// PCV one cycle late, works a few cycles, answers from a small parameter table that writes change,
// sends spontaneous messages). The handshake faults are injected here, as the bus model arms them.
//
// The model knows nothing of FDL or of the bus: per cycle the bus model calls master_step, puts
// master_pcv() into the request, calls slave_step, puts slave_pcv() into the response, and then
// tells the model what each end saw (slave_sees_request, master_sees_response).
#pragma once

#include <cstdint>
#include <vector>

#include "core/code_tables.hpp"
#include "simulator/fault_kind.hpp"

namespace dpscope {

// The four words of a PCV as the simulator writes them (the SPM bit apart): request or response
// code, PNU, IND and the value.
struct SimulatedPcv {
    std::uint8_t rc = 0;
    std::uint16_t pnu = 0;
    std::uint8_t ind = 0;
    std::uint32_t pva = 0;
    bool operator==(const SimulatedPcv&) const = default;
};

// What a parameter-channel model draws on from the bus it runs on.
class ChannelEnvironment {
  public:
    // The session's one random sequence, shared with the bus model: the same seed, the same bytes.
    virtual std::uint64_t random(std::uint64_t bound) = 0;  // 0 <= r < bound
    // Takes a fault of this kind armed for this slave and records its injection; false when none
    // is armed.
    virtual bool inject(FaultKind kind) = 0;
    virtual std::int64_t now() const = 0;     // bus time, ns
    virtual std::uint64_t cycle() const = 0;  // Data_Exchange cycles since start-up

  protected:
    ~ChannelEnvironment() = default;
};

class ParameterChannelModel {
  public:
    ParameterChannelModel(Dialect dialect, std::int64_t master_give_up_ns);

    // The master reacts to the last response it saw and decides what its PCV says this cycle.
    void master_step(ChannelEnvironment& env);
    // The master's PCV in this cycle's request (all zero when it asks nothing) and its SPM bit.
    SimulatedPcv master_pcv() const { return master_busy_ ? master_request_ : SimulatedPcv{}; }
    bool master_spm() const { return master_spm_; }

    // The slave acts on the master's PCV of the previous cycle and decides what its PCV says.
    void slave_step(ChannelEnvironment& env);
    SimulatedPcv slave_pcv() const { return out_; }
    bool slave_spm() const { return slave_spm_; }

    // This cycle's request reached the slave (it acts on it in the next cycle).
    void slave_sees_request();
    // The master saw this cycle's response (delivered) or none (lost on the link).
    void master_sees_response(bool delivered);

  private:
    struct Parameter {
        std::uint16_t pnu;
        bool dword;
        std::uint32_t value;
        bool array;
    };

    SimulatedPcv choose_request(ChannelEnvironment& env);
    SimulatedPcv compute_answer(ChannelEnvironment& env);
    Parameter* find_parameter(std::uint16_t pnu);

    Dialect dialect_;
    std::int64_t master_give_up_ns_;
    std::vector<Parameter> parameters_;
    // Master side.
    bool master_busy_ = false;  // a request is out and not answered yet
    SimulatedPcv master_request_;
    SimulatedPcv last_request_;
    SimulatedPcv next_request_;
    bool has_next_ = false;
    std::int64_t request_time_ = 0;
    std::uint32_t idle_cycles_ = 0;
    bool master_spm_ = false;
    bool master_acked_slave_spm_ = false;  // the slave SPM of the last message acknowledged
    std::uint64_t request_cycle_ = 0;      // the cycle the current request was first sent
    bool master_saw_response_ = false;     // the master's view of the last response
    SimulatedPcv master_seen_answer_;
    bool master_seen_spm_ = false;
    // Slave side: it sees the master's PCV one cycle late.
    bool seen_valid_ = false;
    SimulatedPcv seen_;
    bool seen_spm_ = false;
    bool working_ = false;  // has a request it has not answered yet
    SimulatedPcv current_;
    std::uint64_t ready_cycle_ = 0;
    SimulatedPcv answer_;             // what the slave's PCV says now
    bool answer_mismatched_ = false;  // `answer_` is an injected wrong-PNU answer
    SimulatedPcv out_;                // what it sends this cycle
    bool slave_spm_ = false;
    bool spontaneous_active_ = false;
    bool spontaneous_late_ack_ = false;
    bool spontaneous_master_spm_ = false;  // the master's SPM when the message started
    std::int64_t spontaneous_time_ = 0;
    SimulatedPcv spontaneous_;
};

}  // namespace dpscope
