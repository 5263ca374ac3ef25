// The shells whose edge removal found no valid ring triangulation, so that
// a search that meets the same shell again skips the dynamic program.
//
// Whether some triangulation of a shell's ring makes only positive
// tetrahedra (remove_edge's kNoValidTriangulation) depends on nothing but
// u, v and the ring as a cyclic sequence: the points never move during
// flips, and the rotation at which a walk starts the ring only renames the
// same set of triangulations. Flip recovery's nested removals meet the
// same shells again and again (70-92% of its removals on octocat, the golf
// ball, the upsampled box and the guide arm repeat one that failed), each
// costing an O(n^3) search.
//
// A shell is kept as a 64-bit hash of its canonical form. Two shells with
// one hash would make a removal that could succeed be skipped: never a
// wrong mesh, only a missed flip, and as deterministic as the rest.
#pragma once

#include <cstddef>
#include <cstdint>

#include "mesh/ball_shell.hpp"
#include "mesh/key_table.hpp"

namespace cbr::mesh {

class FailedRings {
public:
    static constexpr std::size_t kMinRing = 6;
    // The canonical hash of the shell of uv: the same for (v, u) with the
    // ring reversed (the same tetrahedra) and for any rotation of the ring.
    static std::uint64_t key(VertexId u, VertexId v, const Shell& s) {
        const std::size_t n = s.ring.size();
        const bool reversed = u > v;
        std::uint64_t h = mix(kSeed, reversed ? v : u);
        h = mix(h, reversed ? u : v);
        if (n == 0) return h;
        std::size_t first = 0;
        for (std::size_t i = 1; i < n; ++i)
            if (s.ring[i] < s.ring[first]) first = i;
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t i = reversed ? (first + n - k) % n : (first + k) % n;
            h = mix(h, s.ring[i]);
        }
        return h;
    }

    bool contains(std::uint64_t key) const { return failed_.find(key) != nullptr; }
    void insert(std::uint64_t key) { failed_[key] = true; }

private:
    static constexpr std::uint64_t kSeed = 0x9E3779B97F4A7C15ull;
    // One step of a multiply-xorshift mix (splitmix64's finaliser).
    static std::uint64_t mix(std::uint64_t h, std::uint64_t x) {
        h ^= x + kSeed + (h << 6) + (h >> 2);
        h ^= h >> 30;
        h *= 0xBF58476D1CE4E5B9ull;
        h ^= h >> 27;
        h *= 0x94D049BB133111EBull;
        return h ^ (h >> 31);
    }

    KeyTable<bool> failed_;
};

}  // namespace cbr::mesh
