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

// The root of t's set: the smallest slot in it (unions always hang the
// larger root under the smaller), with the path halved on the way.
TetId root_of(std::vector<TetId>& parent, TetId t) {
    while (parent[t] != t) {
        parent[t] = parent[parent[t]];
        t = parent[t];
    }
    return t;
}

}  // namespace

RegionMap classify_regions(const mesh::TetMesh& m, const ConstraintFaces& faces) {
    RegionMap map;
    map.of_tet.assign(m.slot_count(), -1);
    // The components, as sets joined across every face that is not a
    // constraint face, in one pass over the tetrahedra in storage order
    // (a search from each tetrahedron jumped across memory: igea's 800,000
    // tetrahedra took 0.1 s). Component k is the one with the k-th
    // smallest root, as a search from each slot in turn would number them.
    std::vector<TetId> parent(m.slot_count());
    for (TetId t = 0; t < m.slot_count(); ++t) parent[t] = t;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        for (int f = 0; f < 4; ++f) {
            if (m.is_constrained(t, f)) continue;
            const TetId n = mesh::facet_tet(m.neighbor(t, f));
            if (n < t) continue;  // each face once
            const TetId a = root_of(parent, t), b = root_of(parent, n);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
    }
    std::vector<Component> components;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        const TetId r = root_of(parent, t);
        if (r == t) {
            map.of_tet[t] = static_cast<std::int32_t>(components.size());
            components.emplace_back();
        } else {
            map.of_tet[t] = map.of_tet[r];  // r < t: numbered already
        }
        Component& c = components[static_cast<std::size_t>(map.of_tet[t])];
        if (m.is_ghost(t)) c.outside = true;
        for (int f = 0; f < 4; ++f) {
            if (!m.is_constrained(t, f)) continue;
            const VertexId* v = m.vertices(t);
            const std::size_t tri =
                faces.find(v[mesh::kFaceVertices[f][0]], v[mesh::kFaceVertices[f][1]], v[mesh::kFaceVertices[f][2]]);
            if (tri != ConstraintFaces::npos)
                c.key = std::min<std::uint64_t>(c.key, 2 * tri + side_of(m, t, f, faces.triangle(tri)));
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
