#include "delaunay/spatial_sort.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "mesh/large_array.hpp"

namespace cbr::delaunay {
namespace {

constexpr int kHilbertBits = 16;               // 2^16 cells per axis: 48-bit keys
constexpr std::size_t kSmallestRound = 1024;   // BRIO: below this, one round
constexpr std::size_t kRoundDivisor = 4;       // each round is 1/4 of the next

std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

struct KeyedId {
    std::uint64_t key;
    mesh::VertexId id;
};
// One per point, shuffled and sorted in place (mesh/large_array.hpp).
using KeyedIds = mesh::LargeArray<KeyedId>;

// LSD radix sort on the low `key_bits` bits, 8 bits a pass; stable.
void radix_sort(KeyedIds& items, int key_bits) {
    KeyedIds buffer(items.size());
    for (int shift = 0; shift < key_bits; shift += 8) {
        std::array<std::size_t, 257> count{};
        for (const KeyedId& it : items) ++count[((it.key >> shift) & 0xFF) + 1];
        if (count[1 + ((items.front().key >> shift) & 0xFF)] == items.size()) continue;  // one bucket
        for (int b = 0; b < 256; ++b) count[b + 1] += count[b];
        for (const KeyedId& it : items) buffer[count[(it.key >> shift) & 0xFF]++] = it;
        items.swap(buffer);
    }
}

// Bit b of x (b < 21) moved to bit 3b, the others zero: one axis of an
// interleaved key, in five mask steps instead of a loop over the bits.
std::uint64_t spread_bits(std::uint64_t x) {
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

}  // namespace

// Skilling's transform ("Programming the Hilbert curve", 2004): turns the
// coordinates into the transposed Hilbert index in place, then the bits are
// interleaved, most significant level first.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits) {
    std::uint32_t X[3] = {x, y, z};
    const std::uint32_t top = 1u << (bits - 1);
    // Without branches: the bit tested is set or not as often as not, and
    // the mispredictions were most of the transform's time (reordering
    // igea's tetrahedra for the refinement passes).
    for (std::uint32_t q = top; q > 1; q >>= 1) {
        const std::uint32_t p = q - 1;
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t set = 0u - ((X[i] & q) != 0);  // all ones when the bit is set
            // set: invert the low bits of X[0]; clear: exchange the low
            // bits of X[0] and X[i] (nothing for i = 0).
            const std::uint32_t t = (X[0] ^ X[i]) & p & ~set;
            X[0] ^= (p & set) | t;
            X[i] ^= t;
        }
    }
    X[1] ^= X[0];  // Gray encode
    X[2] ^= X[1];
    std::uint32_t t = 0;
    for (std::uint32_t q = top; q > 1; q >>= 1)
        if (X[2] & q) t ^= q - 1;
    for (std::uint32_t& c : X) c ^= t;

    // Bit b of X[0], X[1], X[2] goes to bit 3b + 2, 3b + 1, 3b.
    return spread_bits(X[0]) << 2 | spread_bits(X[1]) << 1 | spread_bits(X[2]);
}

namespace {

// Hilbert keys of the points `ids`, over their common bounding box, in one
// sequential pass over the ids.
KeyedIds hilbert_keys(const double* coords, const mesh::VertexId* first, const mesh::VertexId* last) {
    const std::size_t n = static_cast<std::size_t>(last - first);
    KeyedIds items(n);
    if (n == 0) return items;
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = coords[3 * std::size_t{*first} + k];
    for (const mesh::VertexId* v = first; v != last; ++v)
        for (int k = 0; k < 3; ++k) {
            const double c = coords[3 * std::size_t{*v} + k];
            lo[k] = std::min(lo[k], c);
            hi[k] = std::max(hi[k], c);
        }
    // One scale for all axes keeps the curve's cells cubic. Computed as
    // cells / extent so no intermediate overflows for large coordinates.
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    const double cells = double((1u << kHilbertBits) - 1);
    const double scale = extent > 0 ? cells / extent : 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double* p = coords + 3 * std::size_t{first[i]};
        std::uint32_t q[3];
        for (int k = 0; k < 3; ++k) q[k] = static_cast<std::uint32_t>(std::min(cells, std::max(0.0, (p[k] - lo[k]) * scale)));
        items[i] = {hilbert_index(q[0], q[1], q[2], kHilbertBits), first[i]};
    }
    return items;
}

}  // namespace

std::vector<std::size_t> hilbert_order(const double* xyz, std::size_t n) {
    std::vector<mesh::VertexId> ids(n);
    for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<mesh::VertexId>(i);
    KeyedIds items = hilbert_keys(xyz, ids.data(), ids.data() + n);
    if (items.size() > 1) radix_sort(items, 3 * kHilbertBits);  // stable: ties stay in index order
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = items[i].id;
    return order;
}

void brio_sort(const double* coords, std::vector<mesh::VertexId>& ids, std::uint64_t seed) {
    // Keys first, in the given order (sequential memory access), then the
    // shuffle and the rounds move (key, id) pairs only: no coordinate is
    // read in random order.
    KeyedIds items = hilbert_keys(coords, ids.data(), ids.data() + ids.size());
    // Fisher-Yates with our own generator: the order is the same everywhere.
    std::uint64_t state = seed;
    for (std::size_t i = items.size(); i > 1; --i) {
        const std::size_t j = static_cast<std::size_t>(splitmix64(state) % i);
        std::swap(items[i - 1], items[j]);
    }
    // Rounds: [0, r0) [r0, r1) ... each round kRoundDivisor times the last,
    // each sorted along the curve.
    std::size_t end = items.size();
    KeyedIds round;
    while (end > 0) {
        const std::size_t begin = end > kSmallestRound ? end / kRoundDivisor : 0;
        round.assign(items.begin() + static_cast<std::ptrdiff_t>(begin), items.begin() + static_cast<std::ptrdiff_t>(end));
        if (round.size() > 1) radix_sort(round, 3 * kHilbertBits);
        std::copy(round.begin(), round.end(), items.begin() + static_cast<std::ptrdiff_t>(begin));
        end = begin;
    }
    for (std::size_t i = 0; i < items.size(); ++i) ids[i] = items[i].id;
}

}  // namespace cbr::delaunay
