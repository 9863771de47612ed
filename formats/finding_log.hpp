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
    // Calls f for every finding in the order appended. False if the spill file could not be read
    // back (error() says why).
    bool for_each(const std::function<void(const Finding&)>& f) const;
    // Set when spilling failed; the findings not spilled are lost and the report says so.
    const std::string& error() const noexcept { return error_; }

  private:
    static constexpr std::size_t kKeepInMemory = 4096;
    void spill();

    std::vector<Finding> memory_;
    FILE* spill_ = nullptr;
    std::uint64_t count_ = 0;
    std::string error_;
};

}  // namespace dpscope
