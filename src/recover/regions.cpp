#include "recover/regions.hpp"

#include <algorithm>
#include <limits>

namespace cbr::recover {
namespace {

using mesh::TetId;
using mesh::VertexId;

constexpr std::uint64_t kNoKey = std::numeric_limits<std::uint64_t>::max();

// The side of input triangle i on which tetrahedron t lies, read from how
// t lists the face: kFaceVertices order has its normal pointing into t, so
// an even permutation of the input order means t is on the normal's side.
int side_of(const mesh::TetMesh& m, TetId t, int f, const Triangle& tri) {
    const VertexId* v = m.vertices(t);
    const VertexId x = v[mesh::kFaceVertices[f][0]], y = v[mesh::kFaceVertices[f][1]];
    // (x, y, z) is a rotation of (a, b, c) exactly when x -> y follows the
    // input's cyclic order.
    for (int k = 0; k < 3; ++k)
        if (tri[k] == x) return tri[(k + 1) % 3] == y ? 0 : 1;
    return 0;  // unreachable for a face of triangle tri
}

struct Component {
    bool outside = false;
    std::uint64_t key = kNoKey;  // smallest 2 * triangle + side on the boundary
};

}  // namespace

RegionMap classify_regions(const mesh::TetMesh& m, const ConstraintFaces& faces) {
    RegionMap map;
    map.of_tet.assign(m.slot_count(), -1);
    std::vector<Component> components;
    std::vector<TetId> stack;
    for (TetId seed = 0; seed < m.slot_count(); ++seed) {
        if (m.is_free(seed) || map.of_tet[seed] >= 0) continue;
        const auto id = static_cast<std::int32_t>(components.size());
        components.emplace_back();
        map.of_tet[seed] = id;
        stack.assign(1, seed);
        while (!stack.empty()) {
            const TetId t = stack.back();
            stack.pop_back();
            Component& c = components[static_cast<std::size_t>(id)];
            if (m.is_ghost(t)) c.outside = true;
            for (int f = 0; f < 4; ++f) {
                if (m.is_constrained(t, f)) {
                    const VertexId* v = m.vertices(t);
                    const std::size_t tri = faces.find(v[mesh::kFaceVertices[f][0]], v[mesh::kFaceVertices[f][1]],
                                                       v[mesh::kFaceVertices[f][2]]);
                    if (tri != ConstraintFaces::npos)
                        c.key = std::min<std::uint64_t>(c.key, 2 * tri + side_of(m, t, f, faces.triangle(tri)));
                    continue;
                }
                const TetId n = mesh::facet_tet(m.neighbor(t, f));
                if (map.of_tet[n] < 0) {
                    map.of_tet[n] = id;
                    stack.push_back(n);
                }
            }
        }
    }
    // Outside first, then by key.
    std::vector<std::int32_t> order(components.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::int32_t>(i);
    std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
        const Component &ca = components[static_cast<std::size_t>(a)], &cb = components[static_cast<std::size_t>(b)];
        if (ca.outside != cb.outside) return ca.outside;
        return ca.key < cb.key;
    });
    std::vector<std::int32_t> number(components.size());
    for (std::size_t rank = 0; rank < order.size(); ++rank) number[static_cast<std::size_t>(order[rank])] = static_cast<std::int32_t>(rank);
    for (std::int32_t& r : map.of_tet)
        if (r >= 0) r = number[static_cast<std::size_t>(r)];
    map.count = static_cast<std::int32_t>(components.size());
    return map;
}

}  // namespace cbr::recover
