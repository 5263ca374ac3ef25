// A hash table from 64-bit keys to values, for the memo tables searches
// ask millions of times (flip recovery's failed rings and searches):
// open addressing with linear probing in a power-of-two array, so that a
// lookup is one multiply-shift and, mostly, one cache line; std::unordered_map
// spent most of its time there in an integer division and a chain of
// scattered nodes. Entries are never erased one by one; clear() empties
// the table in O(1) and keeps its storage.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cbr::mesh {

// The key of the edge between vertices a and b, the same in either order
// (never 0 for two different vertices).
inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}

template <class Value>
class KeyTable {
public:
    // The value of `key`, or nullptr.
    Value* find(std::uint64_t key) {
        if (slots_.empty()) return nullptr;
        for (std::size_t i = home(key);; i = (i + 1) & mask()) {
            Slot& s = slots_[i];
            if (s.stamp != stamp_) return nullptr;
            if (s.key == key) return &s.value;
        }
    }
    const Value* find(std::uint64_t key) const { return const_cast<KeyTable*>(this)->find(key); }

    // The value of `key`, value-initialised when it is new.
    Value& operator[](std::uint64_t key) {
        if (2 * (size_ + 1) > slots_.size()) grow();
        for (std::size_t i = home(key);; i = (i + 1) & mask()) {
            Slot& s = slots_[i];
            if (s.stamp != stamp_) {
                s.stamp = stamp_;
                s.key = key;
                s.value = Value{};
                ++size_;
                return s.value;
            }
            if (s.key == key) return s.value;
        }
    }

    std::size_t size() const { return size_; }

    // Empties the table and keeps its storage: a slot is used only when it
    // holds the current stamp, so a table emptied and filled again and
    // again (one per flip sweep) is neither cleared slot by slot nor grown
    // again from empty each time.
    void clear() {
        size_ = 0;
        if (++stamp_ != 0) return;
        for (Slot& s : slots_) s.stamp = 0;  // the stamps wrapped around: once in 2^32 clears
        stamp_ = 1;
    }

private:
    struct Slot {
        std::uint64_t key = 0;
        Value value{};
        std::uint32_t stamp = 0;  // used when equal to the table's stamp_
    };

    std::size_t mask() const { return slots_.size() - 1; }
    // Fibonacci hashing: the high bits of key times 2^64 / phi.
    std::size_t home(std::uint64_t key) const {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
    }

    void grow() {
        std::vector<Slot> old;
        old.swap(slots_);
        const std::size_t capacity = old.empty() ? 1024 : 2 * old.size();
        slots_.assign(capacity, Slot{});
        shift_ = 64;
        for (std::size_t c = capacity; c > 1; c >>= 1) --shift_;
        size_ = 0;
        for (Slot& s : old)
            if (s.stamp == stamp_) (*this)[s.key] = s.value;
    }

    std::vector<Slot> slots_;
    std::size_t size_ = 0;
    int shift_ = 64;
    std::uint32_t stamp_ = 1;  // never 0, the stamp of a slot never used
};

}  // namespace cbr::mesh
