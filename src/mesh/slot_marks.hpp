// Per-index mark bits (per tetrahedron slot, or per vertex) that clear in
// O(1): the scratch sets of a search that runs again and again (one point
// insertion after another) without hashing and without clearing an array
// per run.
//
// Each index keeps one word: the round it was last written in (high 24
// bits) and its marks (low 8 bits). Starting a new round makes every mark
// read as clear; the array is only zero-filled when the round counter
// wraps (every 2^24 - 1 rounds).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/large_array.hpp"

namespace cbr::mesh {

class SlotMarks {
public:
    // Clears every mark and makes room for indices [0, size).
    void new_round(std::size_t size) {
        if (++round_ == kRoundLimit) {
            std::fill(word_.begin(), word_.end(), 0u);
            round_ = 1;
        }
        if (word_.size() < size) word_.resize(size, 0u);
    }

    // The marks of index i (0 beyond the size given to new_round).
    std::uint8_t marks(std::size_t i) const {
        if (i >= word_.size()) return 0;
        const std::uint32_t w = word_[i];
        return (w >> kMarkBits) == round_ ? static_cast<std::uint8_t>(w) : 0;
    }
    bool has(std::size_t i, std::uint8_t mark) const { return (marks(i) & mark) != 0; }
    // i must be below the size given to new_round.
    void set(std::size_t i, std::uint8_t mark) { word_[i] = (round_ << kMarkBits) | marks(i) | mark; }
    void clear(std::size_t i, std::uint8_t mark) {
        word_[i] = (round_ << kMarkBits) | static_cast<std::uint8_t>(marks(i) & ~mark);
    }

private:
    static constexpr int kMarkBits = 8;
    static constexpr std::uint32_t kRoundLimit = std::uint32_t{1} << (32 - kMarkBits);

    LargeArray<std::uint32_t> word_;
    std::uint32_t round_ = 0;  // 0: no round started (no word is ever "current")
};

}  // namespace cbr::mesh
