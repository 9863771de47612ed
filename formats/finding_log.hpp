// All findings of a capture, in capture order, for the report. Memory stays flat however many
// there are: beyond a few thousand they are spilled to an anonymous temporary file.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "decoder/finding.hpp"

namespace dpscope {

class FindingLog {
  public:
    FindingLog() = default;
    ~FindingLog();
    FindingLog(const FindingLog&) = delete;
    FindingLog& operator=(const FindingLog&) = delete;

    void append(std::span<const Finding> findings);
    std::uint64_t size() const noexcept { return count_; }
    // Calls f for every finding in the order appended. When the spill file cannot be read back,
    // the findings from there on are skipped and lost() says so.
    void for_each(const std::function<void(const Finding&)>& f) const;
    // What was lost and why, "" when nothing was: set when spilling failed (the findings not
    // spilled are counted but cannot be listed) or reading the spill file back did. Not a
    // value-or-error (so no Result): the log goes on, and the report warns with this at the end.
    const std::string& lost() const noexcept { return lost_; }

  private:
    static constexpr std::size_t kKeepInMemory = 4096;
    void spill();

    std::vector<Finding> memory_;
    FILE* spill_ = nullptr;
    std::uint64_t count_ = 0;
    mutable std::string lost_;  // for_each() is const but may find the spill file unreadable
};

}  // namespace dpscope
