#include "protocols/profibus/parameter_channel_model.hpp"

#include <iterator>

namespace dpscope {

namespace {

constexpr std::uint8_t kRead = 1, kWriteWord = 2, kWriteDword = 3, kReadDescription = 4,
                       kReadArray = 6, kReadCount = 9;
constexpr std::uint8_t kRejected = 7, kNoAuthority = 8, kSpontaneousWord = 9;
constexpr std::uint8_t kUndefinedCode = 13;
// GE AF-600 fault numbers [S002]: no network access to the parameter; factory setup selected.
constexpr std::uint16_t kGeNoNetworkAccess = 130, kGeFactorySetup = 131;
constexpr std::uint16_t kAlarmWordPnu = 538;

}  // namespace

ParameterChannelModel::ParameterChannelModel(Dialect dialect, std::int64_t master_give_up_ns)
    : dialect_(dialect),
      master_give_up_ns_(master_give_up_ns),
      parameters_{
          {520, false, 240, false}, {518, false, 500, false}, {516, true, 5000, false},
          {207, true, 1000, false}, {208, true, 1000, false}, {215, false, 10, false},
          {615, false, 0, true},
      } {}

ParameterChannelModel::Parameter* ParameterChannelModel::find_parameter(std::uint16_t pnu) {
    for (Parameter& p : parameters_)
        if (p.pnu == pnu) return &p;
    return nullptr;
}

SimulatedPcv ParameterChannelModel::choose_request(ChannelEnvironment& env) {
    bool profidrive = dialect_ == Dialect::Profidrive;
    std::uint64_t pick = env.random(100);
    if (pick < 10 && last_request_.rc == kRead) return last_request_;  // poll again
    if (pick < 55) {
        static constexpr std::uint16_t kReadable[] = {520, 518, 516, 207, 208, 215};
        return {kRead, kReadable[env.random(std::size(kReadable))], 0, 0};
    }
    if (pick < 67) {
        std::uint16_t pnu = env.random(2) ? 207 : 208;
        auto value = static_cast<std::uint32_t>(500 + 100 * env.random(20));
        std::uint8_t rc = profidrive && env.random(2) ? 13 : kWriteDword;  // 13: RAM + EEPROM
        return {rc, pnu, 0, value};
    }
    if (pick < 77) {
        std::uint8_t rc = profidrive && env.random(2) ? 14 : kWriteWord;
        return {rc, 215, 0, static_cast<std::uint32_t>(5 + env.random(20))};
    }
    if (pick < 87) return {kReadArray, 615, static_cast<std::uint8_t>(1 + env.random(10)), 0};
    if (pick < 94) return {kReadCount, 615, 0, 0};
    return {kReadDescription, 207, static_cast<std::uint8_t>(1 + env.random(4)), 0};
}

void ParameterChannelModel::master_step(ChannelEnvironment& env) {
    const std::int64_t now = env.now();
    const std::uint64_t cycle = env.cycle();
    const SimulatedPcv& seen = master_seen_answer_;
    const bool saw = master_saw_response_;
    // RC 9..12 where the dialect has spontaneous messages (ge has none: an undefined code).
    const bool spontaneous_seen =
        saw && response_code(dialect_, seen.rc).kind == ResponseKind::Spontaneous;
    // The master reacts to the response of the previous cycle (cycle - 1). The slave lags one
    // cycle, so only a response from a cycle after the request was first sent can answer it.
    const bool fresh = cycle >= request_cycle_ + 2;
    if (spontaneous_seen) {
        if (master_seen_spm_ != master_acked_slave_spm_) {  // a new message
            bool hold_back = spontaneous_late_ack_ && now - spontaneous_time_ < master_give_up_ns_;
            if (!hold_back) {
                master_spm_ = !master_spm_;  // acknowledge
                master_acked_slave_spm_ = master_seen_spm_;
            }
        }
    } else if (saw && fresh && master_busy_ && seen.rc != 0 &&
               response_code(dialect_, seen.rc).kind != ResponseKind::Undefined &&
               (seen.pnu == master_request_.pnu || seen.rc == kRejected ||
                seen.rc == kNoAuthority || answer_mismatched_)) {
        // An answer to this request (a late answer to an abandoned request names another PNU).
        // RC 7 and 8 need not echo the PNU. An injected wrong-PNU answer ends the request too.
        // A code the dialect does not define is no answer: the master keeps waiting.
        master_busy_ = false;
        answer_mismatched_ = false;  // consumed: its repeats answer nothing else
        last_request_ = master_request_;
        next_request_ = choose_request(env);
        has_next_ = true;
        bool positive = seen.rc != kRejected && seen.rc != kNoAuthority;
        // Straight on to the next request (no RC 0 cycle) only for another parameter than the
        // one the slave's answer shows, or its stale repeats would pass for the new answer.
        bool direct = positive && next_request_.pnu != last_request_.pnu &&
                      next_request_.pnu != seen.pnu && env.random(3) == 0;
        idle_cycles_ = direct ? 0 : static_cast<std::uint32_t>(1 + env.random(4));
    }
    if (master_busy_ && now - request_time_ > master_give_up_ns_) {
        master_busy_ = false;  // give up on it
        last_request_ = master_request_;
        has_next_ = false;
        idle_cycles_ = static_cast<std::uint32_t>(1 + env.random(3));
    }
    if (master_busy_ && env.inject(FaultKind::StackedRequest)) {
        // Another parameter than the pending one and than the last one answered: the slave's
        // register may still hold that answer, and a real master could not tell it from a new one.
        SimulatedPcv other = choose_request(env);
        for (std::uint16_t pnu : {std::uint16_t{520}, std::uint16_t{518}, std::uint16_t{516}}) {
            if (other.pnu != master_request_.pnu && other.pnu != last_request_.pnu &&
                other.pnu != master_seen_answer_.pnu)
                break;
            other = {kRead, pnu, 0, 0};
        }
        master_request_ = other;
        request_time_ = now;
        request_cycle_ = cycle;
    }
    const bool message_pending = spontaneous_seen && master_seen_spm_ != master_acked_slave_spm_;
    if (!message_pending && !spontaneous_active_ && env.inject(FaultKind::SpmViolation))
        master_spm_ = !master_spm_;
    if (!master_busy_) {
        if (idle_cycles_ > 0) {
            --idle_cycles_;
        } else if (!message_pending) {
            master_busy_ = true;
            master_request_ = has_next_ ? next_request_ : choose_request(env);
            has_next_ = false;
            request_time_ = now;
            request_cycle_ = cycle;
        }
    }
}

SimulatedPcv ParameterChannelModel::compute_answer(ChannelEnvironment& env) {
    const SimulatedPcv& r = current_;
    if (env.inject(FaultKind::RequestRejected)) {
        // A ge slave refuses with GE's own fault numbers [S002]: 131 (factory setup selected)
        // for a change, 130 (no network access to the parameter) for a read (which for which is
        // the simulator's choice); the others with 2 (limit exceeded).
        std::uint16_t error = 2;
        if (dialect_ == Dialect::Ge)
            error = request_code(dialect_, r.rc).is_change ? kGeFactorySetup : kGeNoNetworkAccess;
        // Half the time as in the Danfoss FCM 300 example: PCA 70 00, no PNU echo.
        if (env.random(2) == 0) return {kRejected, 0, 0, error};
        return {kRejected, r.pnu, r.ind, error};
    }
    if (request_code(dialect_, r.rc).is_change && env.inject(FaultKind::NoAuthority))
        return {kNoAuthority, r.pnu, r.ind, 0};
    Parameter* p = find_parameter(r.pnu);
    SimulatedPcv answer;
    switch (r.rc) {
        case kRead:
            answer = {static_cast<std::uint8_t>(p && p->dword ? 2 : 1), r.pnu, r.ind,
                      p ? p->value : 0};
            break;
        case kWriteWord:
        case 14:
            if (p) p->value = r.pva & 0xFFFF;
            answer = {1, r.pnu, r.ind, r.pva & 0xFFFF};
            break;
        case kWriteDword:
        case 13:
            if (p) p->value = r.pva;
            answer = {2, r.pnu, r.ind, r.pva};
            break;
        case kReadDescription: answer = {3, r.pnu, r.ind, 0x0405u + r.ind}; break;
        case kReadArray: answer = {4, r.pnu, r.ind, 0x0100u + r.ind}; break;
        case kReadCount: answer = {6, r.pnu, 0, 10}; break;
        default: answer = {kRejected, r.pnu, r.ind, 18}; break;
    }
    answer_mismatched_ = false;
    if (env.inject(FaultKind::MismatchedResponse)) {
        answer.pnu = static_cast<std::uint16_t>(r.pnu + 1);
        answer_mismatched_ = true;
    } else if (env.inject(FaultKind::UnexpectedResponseType)) {
        answer.rc = r.rc == kReadCount ? 1 : 6;
    }
    return answer;
}

void ParameterChannelModel::slave_step(ChannelEnvironment& env) {
    bool override_active = false;
    SimulatedPcv override_answer;
    if (!seen_valid_) {
        answer_ = {};
    } else {
        // The master acknowledges a spontaneous message by toggling its SPM.
        if (spontaneous_active_ && seen_spm_ != spontaneous_master_spm_)
            spontaneous_active_ = false;
        if (seen_.rc == 0) {
            working_ = false;
            current_ = {};
            answer_ = {};
        } else if (seen_ != current_) {
            current_ = seen_;
            working_ = true;
            ready_cycle_ = env.cycle() + env.random(3);
        }
        if (!spontaneous_active_) {
            bool start = false;
            bool late = false;
            if (working_ && env.inject(FaultKind::SpontaneousMessage)) {
                start = true;
            } else if (!working_ && !master_busy_ && seen_.rc == 0 &&
                       env.inject(FaultKind::SpontaneousUnacknowledged)) {
                start = late = true;
            }
            if (start) {
                slave_spm_ = !slave_spm_;
                spontaneous_active_ = true;
                spontaneous_late_ack_ = late;
                spontaneous_master_spm_ = seen_spm_;
                spontaneous_time_ = env.now();
                spontaneous_ = {kSpontaneousWord, kAlarmWordPnu, 0, 0x000A};
            }
        }
        if (working_ && env.cycle() >= ready_cycle_ && !spontaneous_active_) {
            if (env.inject(FaultKind::UnknownCode)) {
                override_active = true;  // the real answer follows in the next cycle
                // A ge slave's unknown code is one of the unused 9..12 [S002], others' RC 13.
                std::uint8_t code =
                    dialect_ == Dialect::Ge
                        ? static_cast<std::uint8_t>(kSpontaneousWord + env.random(4))
                        : kUndefinedCode;
                override_answer = {code, current_.pnu, current_.ind, 0};
            } else if (env.inject(FaultKind::ResponseTimeout)) {
                working_ = false;  // never answers
            } else {
                answer_ = compute_answer(env);
                working_ = false;
            }
        }
        // An orphan: an answer out of nothing, on a channel idle on both sides (the slave's last
        // output was RC 0 too, so it cannot pass for the previous answer repeated).
        if (!override_active && !working_ && !master_busy_ && seen_.rc == 0 && answer_.rc == 0 &&
            out_.rc == 0 && !spontaneous_active_ && env.inject(FaultKind::OrphanResponse)) {
            override_active = true;
            override_answer = {1, 520, 0, 240};
        }
    }
    if (override_active) {
        out_ = override_answer;
    } else if (spontaneous_active_) {
        out_ = spontaneous_;
    } else {
        out_ = answer_;
    }
}

void ParameterChannelModel::slave_sees_request() {
    seen_ = master_pcv();
    seen_spm_ = master_spm_;
    seen_valid_ = true;
}

void ParameterChannelModel::master_sees_response(bool delivered) {
    master_saw_response_ = delivered;
    if (delivered) {
        master_seen_answer_ = out_;
        master_seen_spm_ = slave_spm_;
    }
}

}  // namespace dpscope
