#include "io/vertex_welder.hpp"

#include <cstring>

namespace cbr::io::detail {

namespace {

std::uint64_t bits(double d) {
    if (d == 0.0) d = 0.0;  // -0.0 == 0.0, so they must hash alike
    std::uint64_t u = 0;
    std::memcpy(&u, &d, sizeof u);
    return u;
}

std::uint64_t mix(std::uint64_t h) {  // splitmix64 finaliser
    h ^= h >> 30;
    h *= 0xbf58476d1ce4e5b9ULL;
    h ^= h >> 27;
    h *= 0x94d049bb133111ebULL;
    return h ^ (h >> 31);
}

}  // namespace

void VertexWelder::reserve(std::size_t points) {
    std::size_t cap = 16;
    while (cap < 2 * points) cap *= 2;
    if (cap <= slots_.size()) return;
    slots_.assign(cap, -1);
    used_ = 0;
    // Re-insert what is already there (reserve is normally called first).
    const std::size_t n = mesh_.xyz.size() / 3;
    for (std::size_t v = 0; v < n; ++v) {
        slots_[slot_of(mesh_.xyz[3 * v], mesh_.xyz[3 * v + 1], mesh_.xyz[3 * v + 2])] = static_cast<std::int64_t>(v);
        ++used_;
    }
}

void VertexWelder::grow() { reserve(slots_.empty() ? 8 : slots_.size()); }

// The slot holding (x, y, z), or the empty slot where it belongs.
std::size_t VertexWelder::slot_of(double x, double y, double z) const {
    const std::size_t mask = slots_.size() - 1;
    std::size_t s = static_cast<std::size_t>(mix(bits(x) ^ mix(bits(y) ^ mix(bits(z))))) & mask;
    for (;; s = (s + 1) & mask) {
        const std::int64_t v = slots_[s];
        if (v < 0) return s;
        const double* p = &mesh_.xyz[3 * static_cast<std::size_t>(v)];
        if (p[0] == x && p[1] == y && p[2] == z) return s;
    }
}

std::int64_t VertexWelder::id(double x, double y, double z) {
    if (2 * (used_ + 1) > slots_.size()) grow();
    const std::size_t s = slot_of(x, y, z);
    if (slots_[s] >= 0) return slots_[s];
    const auto v = static_cast<std::int64_t>(mesh_.xyz.size() / 3);
    mesh_.xyz.push_back(x);
    mesh_.xyz.push_back(y);
    mesh_.xyz.push_back(z);
    slots_[s] = v;
    ++used_;
    return v;
}

}  // namespace cbr::io::detail
