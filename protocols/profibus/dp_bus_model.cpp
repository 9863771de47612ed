// The PROFIBUS DP bus model of the simulator (simulator/simulator.hpp): the Simulator's members
// that make DP telegrams. The start-up, the Data_Exchange of each slave with its process data,
// parameter channel and the link and handshake faults injected into it, DP-V1 parameter access,
// a lost slave and its parameterisation anew, and the token ring with its gap polls. The session
// that runs it (clock, queue, cycles, faults armed): simulator/simulator.cpp.
#include <algorithm>
#include <optional>

#include "protocols/profibus/dp_service.hpp"
#include "protocols/profibus/telegram_builder.hpp"
#include "simulator/session_defaults.hpp"
#include "simulator/simulator.hpp"

namespace dpscope {

namespace {

// Configuration identifiers as in the Danfoss GSD (module-consistent PCD).
std::vector<std::uint8_t> cfg_bytes_of(std::uint8_t ppo_type) {
    switch (ppo_type) {
        case 1: return {0xF3, 0xF1};
        case 2: return {0xF3, 0xF5};
        case 3: return {0xF1};
        case 4: return {0xF5};
        default: return {0xF3, 0xF9};
    }
}

// Set_Prm's parameter data: lock, watchdog 10 x 10 ms, min TSDR 11 bit times, the ident number,
// group 0; DPV1_Status_1..3 with DPV1_Enable (bit 7 of the first) for a DP-V1 slave.
std::vector<std::uint8_t> prm_bytes_of(const SimulatedSlave& config, std::uint16_t ident) {
    std::vector<std::uint8_t> prm = {
        0x88, 10, 10, 11, static_cast<std::uint8_t>(ident >> 8), static_cast<std::uint8_t>(ident),
        0x00};
    if (config.dialect == Dialect::Profidrive || config.dpv1) {
        prm.push_back(0x80);
        prm.push_back(0x00);
        prm.push_back(0x00);
    }
    return prm;
}

}  // namespace

void Simulator::generate_start_up() {
    const std::uint8_t master = options_.master;
    for (Slave& slave : slaves_) {
        const std::uint8_t address = slave.config.address;
        auto request = [&](std::optional<std::uint8_t> dsap, std::vector<std::uint8_t> du,
                           FdlFunction function) {
            TelegramSpec spec{address,
                              master,
                              request_fc(function, slave.fcb, true),
                              dsap,
                              dsap ? std::optional<std::uint8_t>(sap::kMaster) : std::nullopt,
                              Bytes(du)};
            emit(build_telegram(spec), 60 + random(40));
        };
        auto response = [&](std::uint8_t ssap, std::vector<std::uint8_t> du) {
            TelegramSpec spec{master,       address, response_fc(FdlStatus::DataLow),
                              sap::kMaster, ssap,    Bytes(du)};
            emit(build_telegram(spec), 30 + random(70));
            slave.fcb = !slave.fcb;
        };
        auto short_ack = [&] {
            std::vector<std::uint8_t> ack;
            append_short_ack(ack);
            emit(std::move(ack), 30 + random(70));
            slave.fcb = !slave.fcb;
        };
        auto ident_hi = static_cast<std::uint8_t>(slave.ident >> 8);
        auto ident_lo = static_cast<std::uint8_t>(slave.ident);

        emit(build_telegram({address, master, request_fc(FdlFunction::FdlStatus), {}, {}, {}}),
             100);
        emit(build_telegram({master, address, response_fc(FdlStatus::Ok), {}, {}, {}}),
             30 + random(70));
        slave.fcb = true;  // the first SRD after FDL_Status carries FCB = 1, FCV = 1
        request(sap::kSlaveDiag, {}, FdlFunction::SrdHigh);
        response(sap::kSlaveDiag, {0x02, 0x05, 0x00, kNoMasterAddress, ident_hi, ident_lo});
        request(sap::kSetPrm, prm_bytes_of(slave.config, slave.ident), FdlFunction::SrdHigh);
        short_ack();
        request(sap::kChkCfg, cfg_bytes_of(slave.config.ppo_type), FdlFunction::SrdHigh);
        short_ack();
        request(sap::kSlaveDiag, {}, FdlFunction::SrdHigh);
        response(sap::kSlaveDiag, {0x00, 0x0C, 0x00, master, ident_hi, ident_lo});
    }
    std::vector<std::uint8_t> operate = {0x00, 0x00};
    emit(build_telegram({kBroadcastAddress, master, request_fc(FdlFunction::SdnHigh),
                         sap::kGlobalControl, sap::kMaster, Bytes(operate)}),
         100);
    if (!options_.ring_masters.empty()) {
        pass_token_ring();
        return;
    }
    std::vector<std::uint8_t> token;
    append_token(token, master, master);
    emit(std::move(token), 40);
}

bool Simulator::address_in_use(std::uint8_t address) const {
    if (address == options_.master) return true;
    if (std::find(options_.ring_masters.begin(), options_.ring_masters.end(), address) !=
        options_.ring_masters.end())
        return true;
    return std::any_of(slaves_.begin(), slaves_.end(),
                       [&](const Slave& slave) { return slave.config.address == address; });
}

void Simulator::pass_token_ring() {
    const std::int64_t hold_ns = std::max<std::int64_t>(std::int64_t{options_.token_hold_us} * 1000,
                                                        bit_ns(40));  // at least the sync pause
    std::uint8_t holder = options_.master;
    for (std::size_t i = 0; i < options_.ring_masters.size(); ++i) {
        const std::uint8_t next = options_.ring_masters[i];
        std::vector<std::uint8_t> token;
        append_token(token, next, holder);
        if (i == 0) {
            emit(std::move(token), 40);
        } else {
            emit_after(std::move(token), 0);  // the previous holder's hold ends now
        }
        const std::int64_t received = now_;
        // Gap maintenance now and then: is there a new station at the next free address?
        if (cycle_ % 20 == 10) {
            std::uint8_t& gap = ring_gap_addresses_[i];
            emit(build_telegram({gap, next, request_fc(FdlFunction::FdlStatus), {}, {}, {}}), 60);
            advance(bit_ns(100));  // slot time expires
            for (int tries = 0; tries < 126; ++tries) {
                gap = static_cast<std::uint8_t>(gap >= 125 ? 1 : gap + 1);
                if (!address_in_use(gap)) break;
            }
        }
        if (now_ - received < hold_ns) advance(hold_ns - (now_ - received));
        holder = next;
    }
    std::vector<std::uint8_t> token;
    append_token(token, options_.master, holder);
    emit_after(std::move(token), 0);
}

void Simulator::request_srd(Slave& slave, std::optional<std::uint8_t> dsap,
                            std::vector<std::uint8_t> du) {
    TelegramSpec spec{slave.config.address,
                      options_.master,
                      request_fc(FdlFunction::SrdHigh, slave.fcb, true),
                      dsap,
                      dsap ? std::optional<std::uint8_t>(sap::kMaster) : std::nullopt,
                      Bytes(du)};
    emit(build_telegram(spec), 60 + random(40));
}

void Simulator::answer_sd2(Slave& slave, std::optional<std::uint8_t> ssap,
                           std::vector<std::uint8_t> du, FdlStatus status) {
    TelegramSpec spec{options_.master,
                      slave.config.address,
                      response_fc(status),
                      ssap ? std::optional<std::uint8_t>(sap::kMaster) : std::nullopt,
                      ssap,
                      Bytes(du)};
    emit(build_telegram(spec), 30 + random(70));
    slave.fcb = !slave.fcb;
}

void Simulator::answer_short_ack(Slave& slave) {
    std::vector<std::uint8_t> ack;
    append_short_ack(ack);
    emit(std::move(ack), 30 + random(70));
    slave.fcb = !slave.fcb;
}

void Simulator::silent_poll(std::size_t index) {
    // A lost slave: the master asks for its diagnosis instead of exchanging data, repeats the
    // request once (retry limit 1) and hears nothing.
    Slave& slave = slaves_[index];
    request_srd(slave, sap::kSlaveDiag, {});
    advance(bit_ns(100));  // slot time expires
    request_srd(slave, sap::kSlaveDiag, {});
    advance(bit_ns(100));
    slave.fcb = !slave.fcb;
    if (--slave.silent == 0) slave.reparameterise = true;
}

void Simulator::parameterise_again(std::size_t index, Reparameterisation change) {
    // The slave answers the master's Slave_Diag: not parameterised (Station_Not_Ready, Prm_Req,
    // no master); the master parameterises and configures it, and checks its diagnosis again.
    Slave& slave = slaves_[index];
    const auto ident_hi = static_cast<std::uint8_t>(slave.ident >> 8);
    const auto ident_lo = static_cast<std::uint8_t>(slave.ident);
    request_srd(slave, sap::kSlaveDiag, {});
    answer_sd2(slave, sap::kSlaveDiag, {0x02, 0x05, 0x00, kNoMasterAddress, ident_hi, ident_lo});
    std::vector<std::uint8_t> prm =
        prm_bytes_of(slave.config,
                     change == Reparameterisation::WrongIdent ? slave.ident ^ 0x0100 : slave.ident);
    if (change == Reparameterisation::UserByteAdded) prm.push_back(0x00);
    if (change == Reparameterisation::UserByteOutOfRange) {
        prm.resize(std::max<std::size_t>(prm.size(), 10), 0x00);
        prm[8] = 0x01;  // DPV1_Status_2: an alarm enabled
    }
    request_srd(slave, sap::kSetPrm, prm);
    answer_short_ack(slave);
    std::vector<std::uint8_t> cfg = cfg_bytes_of(slave.config.ppo_type);
    if (change == Reparameterisation::FreePlaceAdded) cfg.push_back(0x00);
    if (change == Reparameterisation::ModulesTwice) cfg.insert(cfg.end(), cfg.begin(), cfg.end());
    request_srd(slave, sap::kChkCfg, cfg);
    answer_short_ack(slave);
    request_srd(slave, sap::kSlaveDiag, {});
    answer_sd2(slave, sap::kSlaveDiag, {0x00, 0x0C, 0x00, options_.master, ident_hi, ident_lo});
}

// A slave's parameter-channel model draws on the session's random sequence, on the faults armed
// for that slave, and on the bus clock.
class Simulator::SlaveEnvironment final : public ChannelEnvironment {
  public:
    SlaveEnvironment(Simulator& simulator, std::size_t index)
        : simulator_(simulator), index_(index) {}
    std::uint64_t random(std::uint64_t bound) override { return simulator_.random(bound); }
    bool inject(FaultKind kind) override { return simulator_.inject(kind, index_); }
    std::int64_t now() const override { return simulator_.now_; }
    std::uint64_t cycle() const override { return simulator_.cycle_; }

  private:
    Simulator& simulator_;
    std::size_t index_;
};

void Simulator::parameter_access(std::size_t index) {
    Slave& slave = slaves_[index];
    const std::uint8_t master = options_.master;
    const std::uint8_t address = slave.config.address;
    SlaveEnvironment environment(*this, index);
    std::vector<std::uint8_t> pdu;
    if (!slave.dpv1->master_request(environment, pdu)) return;
    emit(build_telegram({address, master, request_fc(FdlFunction::SrdHigh, slave.fcb, true),
                         sap::kMsacC1, sap::kMsacC1, Bytes(pdu)}),
         40 + random(30));
    slave.dpv1->slave_response(environment, pdu);
    emit(build_telegram({master, address, response_fc(FdlStatus::DataLow), sap::kMsacC1,
                         sap::kMsacC1, Bytes(pdu)}),
         30 + random(70));
    slave.fcb = !slave.fcb;
}

void Simulator::exchange(std::size_t index) {
    Slave& slave = slaves_[index];
    const std::uint8_t master = options_.master;
    const std::uint8_t address = slave.config.address;
    if (slave.silent > 0) {
        silent_poll(index);
        return;
    }
    if (slave.reparameterise) {
        // Back from station_lost: it answers the master's Slave_Diag again.
        parameterise_again(index);
        slave.reparameterise = false;
        --recovering_;
        return;
    }
    if (inject(FaultKind::Garbage, index)) {
        std::vector<std::uint8_t> junk(3 + random(10));
        for (std::uint8_t& b : junk) {
            b = static_cast<std::uint8_t>(random(256));
            if (is_start_delimiter(b) || b == kEndDelimiter) b ^= 0x01;
        }
        emit(std::move(junk), 20);
    }
    if (inject(FaultKind::AnswerWrongKind, index)) {
        // The master checks the station with FDL_Status; the slave answers with data.
        emit(build_telegram({address, master, request_fc(FdlFunction::FdlStatus), {}, {}, {}}),
             60 + random(40));
        std::vector<std::uint8_t> data = {0x0F, 0x07};
        emit(
            build_telegram({master, address, response_fc(FdlStatus::DataLow), {}, {}, Bytes(data)}),
            30 + random(70));
        slave.fcb = true;  // the first SRD after FDL_Status carries FCB = 1
    }
    SlaveEnvironment environment(*this, index);
    if (slave.channel) slave.channel->master_step(environment);

    // Master outputs: PCV, control word, main reference, further PCD words.
    std::vector<std::uint8_t> output;
    if (slave.channel) {
        const SimulatedPcv request = slave.channel->master_pcv();
        append_pcv(output, request.rc, slave.channel->master_spm(), request.pnu, request.ind,
                   request.pva);
    }
    append_u16_be(output, 0x047F);
    append_u16_be(output, slave.reference);
    output.resize(slave.layout.output_bytes, 0);
    if (inject(FaultKind::ConfigMismatch, index)) {
        output.insert(output.end(), {0x00, 0x00});
    }
    std::vector<std::uint8_t> request_bytes =
        build_telegram({address,
                        master,
                        request_fc(FdlFunction::SrdHigh, slave.fcb, true),
                        {},
                        {},
                        Bytes(output)});
    emit(request_bytes, 40 + random(30));

    // Slave inputs: PCV, status word, main actual value, further PCD words.
    if (slave.channel) slave.channel->slave_step(environment);
    std::vector<std::uint8_t> input;
    if (slave.channel) {
        const SimulatedPcv answer = slave.channel->slave_pcv();
        append_pcv(input, answer.rc, slave.channel->slave_spm(), answer.pnu, answer.ind,
                   answer.pva);
    }
    bool at_reference = slave.actual == slave.reference;
    append_u16_be(input, at_reference ? 0x0F07 : 0x0E07);
    append_u16_be(input, slave.actual);
    for (std::uint16_t extra = 240; input.size() < slave.layout.input_bytes; extra += 10)
        append_u16_be(input, extra);
    std::vector<std::uint8_t> response_bytes =
        build_telegram({master, address, response_fc(FdlStatus::DataLow), {}, {}, Bytes(input)});

    // The slave now knows this cycle's master PCV (it acts on it in the next cycle).
    if (slave.channel) slave.channel->slave_sees_request();

    // Link faults. The master retries once (with the same FCB) when a response is lost or
    // damaged; after that it moves on.
    enum class Fate { Delivered, Lost, BadFcs, Truncated };
    Fate first = Fate::Delivered;
    bool retry_lost = false;
    bool second_retry = false;  // repeats: the first repeat is lost too
    if (inject(FaultKind::FdlRetry, index)) {
        first = Fate::Lost;
    } else if (inject(FaultKind::FdlNoResponse, index)) {
        first = Fate::Lost;
        retry_lost = true;
    } else if (inject(FaultKind::FcsError, index)) {
        first = Fate::BadFcs;
    } else if (inject(FaultKind::MalformedTelegram, index)) {
        first = Fate::Truncated;
    } else if (inject(FaultKind::StationLost, index)) {
        // Silent from now on for kStationLostCycles cycles, this one included.
        first = Fate::Lost;
        retry_lost = true;
        slave.silent = kStationLostCycles - 1;
        slave.reparameterise = slave.silent == 0;
        ++recovering_;
    } else if (inject(FaultKind::Repeats, index)) {
        first = Fate::Lost;
        second_retry = true;
    }
    // What the slave answers when its response gets through.
    enum class Answer { Data, ShortAck, Refusal, DataHigh };
    Answer answer = Answer::Data;
    bool resync = false;
    bool answer_twice = false;
    Reparameterisation change = Reparameterisation::AsBefore;
    bool long_diagnosis = false;
    bool late = false;
    if (first == Fate::Delivered) {
        if (inject(FaultKind::AnswerShortAck, index)) {
            answer = Answer::ShortAck;
        } else if (inject(FaultKind::Refusal, index)) {
            answer = Answer::Refusal;
        } else if (inject(FaultKind::Resync, index)) {
            answer = Answer::DataHigh;
            resync = true;
        } else if (inject(FaultKind::DiagFault, index)) {
            answer = Answer::DataHigh;
        } else if (inject(FaultKind::GsdIdentMismatch, index)) {
            answer = Answer::DataHigh;
            resync = true;
            change = Reparameterisation::WrongIdent;
        } else if (inject(FaultKind::GsdUnknownModule, index)) {
            answer = Answer::DataHigh;
            resync = true;
            change = Reparameterisation::FreePlaceAdded;
        } else if (inject(FaultKind::GsdConfigLimit, index)) {
            answer = Answer::DataHigh;
            resync = true;
            change = Reparameterisation::ModulesTwice;
        } else if (inject(FaultKind::GsdUserPrmLength, index)) {
            answer = Answer::DataHigh;
            resync = true;
            change = Reparameterisation::UserByteAdded;
        } else if (inject(FaultKind::GsdUserPrmRange, index)) {
            answer = Answer::DataHigh;
            resync = true;
            change = Reparameterisation::UserByteOutOfRange;
        } else if (inject(FaultKind::GsdDiagTooLong, index)) {
            answer = Answer::DataHigh;
            long_diagnosis = true;
        } else if (inject(FaultKind::GsdLateResponse, index)) {
            late = true;
        } else if (inject(FaultKind::AnswerNotAsked, index)) {
            answer_twice = true;
        }
    }
    bool delivered = true;
    switch (first) {
        case Fate::Delivered:
            switch (answer) {
                case Answer::Data: emit(response_bytes, late ? 400 : 30 + random(70)); break;
                case Answer::ShortAck: {
                    std::vector<std::uint8_t> ack;
                    append_short_ack(ack);
                    emit(std::move(ack), 30 + random(70));
                    delivered = false;
                    break;
                }
                case Answer::Refusal:
                    emit(build_telegram(
                             {master, address, response_fc(FdlStatus::NoService), {}, {}, {}}),
                         30 + random(70));
                    delivered = false;
                    break;
                case Answer::DataHigh:
                    emit(build_telegram({master,
                                         address,
                                         response_fc(FdlStatus::DataHigh),
                                         {},
                                         {},
                                         Bytes(input)}),
                         30 + random(70));
                    break;
            }
            if (answer_twice) emit(response_bytes, 30 + random(70));
            break;
        case Fate::Lost: advance(bit_ns(100)); break;  // slot time expires
        case Fate::BadFcs: {
            std::vector<std::uint8_t> bad = response_bytes;
            bad[bad.size() - 2] ^= 0x5A;
            emit(std::move(bad), 30 + random(70));
            break;
        }
        case Fate::Truncated: {
            std::vector<std::uint8_t> cut(response_bytes.begin(), response_bytes.end() - 2);
            emit(std::move(cut), 30 + random(70));
            break;
        }
    }
    if (second_retry) {
        emit(request_bytes, 40 + random(30));  // the first repeat, lost as well
        advance(bit_ns(100));
    }
    if (first != Fate::Delivered) {
        emit(request_bytes, 40 + random(30));  // retry: same telegram, same FCB
        if (retry_lost) {
            advance(bit_ns(100));
            delivered = false;
        } else {
            emit(response_bytes, 30 + random(70));
        }
    }
    if (slave.channel) slave.channel->master_sees_response(delivered);
    slave.fcb = !slave.fcb;
    if (answer == Answer::DataHigh) {
        // Diagnosis pending: the master asks for it before the next Data_Exchange.
        if (resync) {
            // The slave left data exchange (a watchdog, a restart): parameterised again.
            parameterise_again(index, change);
        } else {
            const auto ident_hi = static_cast<std::uint8_t>(slave.ident >> 8);
            const auto ident_lo = static_cast<std::uint8_t>(slave.ident);
            request_srd(slave, sap::kSlaveDiag, {});
            // Ext_Diag with a device-related block (header: length 3, two bytes); with
            // long_diagnosis one of 14 (header: length 14, thirteen bytes).
            std::vector<std::uint8_t> diag = {0x08, 0x0C, 0x00, master, ident_hi, ident_lo};
            if (long_diagnosis) {
                diag.push_back(0x0E);
                diag.insert(diag.end(), {0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
                                         0x00, 0x00, 0x00});
            } else {
                diag.insert(diag.end(), {0x03, 0x01, 0x00});
            }
            answer_sd2(slave, sap::kSlaveDiag, diag);
        }
    }

    // Process data: the drive ramps toward the reference; the reference moves now and then.
    if (slave.actual < slave.reference)
        slave.actual =
            static_cast<std::uint16_t>(std::min<int>(slave.reference, slave.actual + 0x100));
    if (slave.actual > slave.reference)
        slave.actual =
            static_cast<std::uint16_t>(std::max<int>(slave.reference, slave.actual - 0x100));
    if (cycle_ % 400 == 399) {
        static constexpr std::uint16_t kReferences[] = {0x1000, 0x2000, 0x3000, 0x4000};
        slave.reference = kReferences[random(std::size(kReferences))];
    }
    // The master polls the slave again at once: two polls closer than a cycle.
    if (inject(FaultKind::GsdPollInterval, index)) exchange(index);
}

// PROFIBUS DP in the simulated session (simulator/bus_model.hpp): the session makes its traffic
// itself (no model), checks its faults against the slaves and judges which slave takes one.
namespace {

Result<void> check_profibus_session_faults(const SimulatorOptions& options) {
    return check_faults(options.faults, detail::slaves_or_default(options), options.cycles);
}

}  // namespace

const SimulatedBus& profibus_simulated_bus() noexcept {
    static const SimulatedBus bus{
        .protocol = Protocol::ProfibusDp,
        .make_model = nullptr,
        .check_faults = check_profibus_session_faults,
        .span_bound_ns = detail::profibus_session_span_bound_ns,
        .fault_applies = nullptr,
        .runs_on_ns = nullptr,
        .character_bits = 11,  // 8E1
    };
    return bus;
}

}  // namespace dpscope
