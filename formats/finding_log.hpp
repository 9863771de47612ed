// All findings of a capture, in capture order, for the report. Memory stays flat however many
// there are: beyond a few thousand they are spilled to an anonymous file in the temporary folder
// ($TMPDIR, else /tmp). Their counts stay exact whatever happens to the spill: a log that cannot
// spill (a folder that is missing or full) lists the findings it could keep and says why the
// others are not listed.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "core/finding.hpp"

namespace dpscope {

// How many findings of one kind and severity were found at one master and slave (both 0 for a
// finding no station can be named for).
struct FindingTally {
    FindingKind kind = FindingKind::StackedRequest;
    Severity severity = Severity::Error;
    bool has_stations = false;
    std::uint8_t master = 0;
    std::uint8_t slave = 0;
    std::uint64_t count = 0;
};

// $TMPDIR when it is set and not empty, else /tmp.
std::string default_spill_folder();

class FindingLog {
  public:
    // `spill_folder`: where the findings beyond those kept in memory go.
    explicit FindingLog(std::string spill_folder = default_spill_folder());
    ~FindingLog();
    FindingLog(const FindingLog&) = delete;
    FindingLog& operator=(const FindingLog&) = delete;

    void append(std::span<const Finding> findings);
    std::uint64_t size() const noexcept { return count_; }
    // Calls f for every finding in the order appended that the log can give: all of them, or
    // when spilling failed the first ones, up to where it failed. When the spill file cannot be
    // read back, the findings from there on are skipped. unlisted() and lost() say what was not
    // given and why.
    void for_each(const std::function<void(const Finding&)>& f) const;
    // Every finding appended, counted by kind, severity and stations (exact whatever happened
    // to the spill), in no particular order.
    void for_each_tally(const std::function<void(const FindingTally&)>& f) const;
    // How many findings for_each() does not give: those spilling could not keep, and (after a
    // for_each) those the spill file could not give back.
    std::uint64_t unlisted() const noexcept { return unlisted_ + unreadable_; }
    // Why findings are not listed, "" when all are. Not a value-or-error (so no Result): the log
    // goes on, and the report says this where it lists the findings.
    const std::string& lost() const noexcept { return lost_; }

  private:
    static constexpr std::size_t kKeepInMemory = 4096;
    // A record's usual size (its fixed part and a message), to reserve a batch's room once.
    static constexpr std::size_t kRecordBytesGuess = 320;
    void spill();

    std::string spill_folder_;
    // The findings after those in the spill file, as the records the file holds (a fixed part,
    // then the message's bytes): appending one is a copy into this buffer, spilling them one
    // write, and the buffer is used again after it.
    std::vector<char> records_;
    std::uint64_t in_memory_ = 0;  // findings in records_
    int spill_fd_ = -1;
    std::uint64_t spilled_bytes_ = 0;  // whole records in the spill file
    std::uint64_t spilled_ = 0;        // findings in the spill file
    bool spill_failed_ = false;        // nothing more is kept: later findings are only counted
    std::uint64_t count_ = 0;
    std::uint64_t unlisted_ = 0;                      // findings counted but not kept
    mutable std::uint64_t unreadable_ = 0;            // findings the spill file did not give back
    std::map<std::uint32_t, std::uint64_t> tallies_;  // by kind, severity, stations
    std::uint64_t* last_tally_ = nullptr;  // the count of the last finding's key (map nodes stay)
    std::uint32_t last_tally_key_ = 0;
    mutable std::string lost_;  // for_each() is const but may find the spill file unreadable
};

}  // namespace dpscope
