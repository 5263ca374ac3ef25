#include "refine/locate.hpp"

#include <cstdint>

#include "geom/predicates.hpp"

namespace cbr::refine {

using mesh::facet_tet;
using mesh::kFaceVertices;
using mesh::TetId;
using mesh::VertexId;

Location locate_in_region(const RefineContext& c, TetId start, const double* p, const HalfClaim* claim) {
    const mesh::TetMesh& m = c.m;
    const std::int32_t region = c.region(start);
    TetId t = start;
    std::uint32_t rng = 0x9E3779B9u ^ start;
    const std::size_t limit = 4 * m.live_count() + 64;
    for (std::size_t step = 0; step < limit; ++step) {
        const VertexId* v = m.vertices(t);
        // Faces in a pseudo-random order: a visibility walk can cycle in a
        // non-Delaunay mesh with a fixed order, not with a random one.
        rng ^= rng << 13;
        rng ^= rng >> 17;
        rng ^= rng << 5;
        const int first = static_cast<int>(rng & 3u);
        int next = -1, zeros = 0;
        bool on_constraint = false;
        for (int k = 0; k < 4; ++k) {
            const int f = (first + k) & 3;
            const int* fv = kFaceVertices[f];
            const int o = geom::orient3d(m.point(v[fv[0]]), m.point(v[fv[1]]), m.point(v[fv[2]]), p);
            if (o < 0) {
                next = f;
                break;
            }
            if (o == 0) {
                ++zeros;
                on_constraint = on_constraint || m.is_constrained(t, f);
            }
        }
        if (next < 0) {
            if (on_constraint) return {Located::kOnSurface, t};
            return {zeros == 0 ? Located::kInside : Located::kOnFace, t};
        }
        if (m.is_constrained(t, next)) return {Located::kBlocked, t};
        const TetId n = facet_tet(m.neighbor(t, next));
        if (m.is_ghost(n) || c.region(n) != region) return {Located::kBlocked, t};
        if (claim && !claim->owns(m, n)) return {Located::kForeign, t};
        t = n;
    }
    return {Located::kLost, t};
}

}  // namespace cbr::refine
