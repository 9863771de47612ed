// The 16 bit meanings of a control or status word as jsonl writes them, a JSON array of names
// (["ramp","no coasting",...]), written once for each word and copied after that. A bus repeats
// its few control and status words telegram after telegram, and the array is over 300 bytes of
// the line: copying it whole took the FC and VLT 2000 jsonl lines' largest piece (issue 31).
//
// Direct-mapped: 64 slots, each holding one (table, key) and its array. A key is whatever decides
// the 16 names with the table (the word, and for VLT 2000 its kept groups); a miss writes the
// array with a JsonWriter, so the text is the writer's own.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "formats/json_writer.hpp"

namespace dpscope {

class BitMeaningsJson {
  public:
    // The array for `key` under `table`; `meaning_of(bit)` gives bit 0..15's name (the program's
    // own text: JsonWriter::name()) when the array is not kept yet.
    template <typename MeaningOf>
    std::string_view array(const void* table, std::uint32_t key, MeaningOf&& meaning_of) {
        Slot& slot = slots_[(key ^ (key >> 6) ^ (reinterpret_cast<std::uintptr_t>(table) >> 4)) %
                            slots_.size()];
        if (slot.table != table || slot.key != key || slot.json.empty()) {
            fmt::memory_buffer scratch;
            {
                JsonWriter w(scratch);
                w.begin_array();
                for (unsigned bit = 0; bit < 16; ++bit)
                    w.name(meaning_of(bit));
                w.end_array();
            }
            slot.table = table;
            slot.key = key;
            slot.json.assign(scratch.data(), scratch.size());
        }
        return slot.json;
    }

  private:
    struct Slot {
        const void* table = nullptr;
        std::uint32_t key = 0;
        std::string json;
    };
    std::array<Slot, 64> slots_{};
};

}  // namespace dpscope
