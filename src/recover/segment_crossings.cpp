#include "recover/segment_crossings.hpp"

#include "geom/intersect.hpp"
#include "geom/predicates.hpp"

namespace cbr::recover {
namespace {

using mesh::TetId;
using mesh::VertexId;

// Segment xy crosses segment pq at one point interior to both.
bool crosses_in_interior(const double* p, const double* q, const double* x, const double* y) {
    if (geom::orient3d(p, q, x, y) != 0 || geom::collinear(p, q, x) || geom::collinear(p, q, y)) return false;
    return geom::classify_coplanar_segments(p, q, x, y) == geom::SegSegKind::Point;
}

// The two faces of a tetrahedron that hold its edge (i, j): those opposite
// its other two corners.
constexpr int kOtherCorners[4][4][2] = {
    {{-1, -1}, {2, 3}, {1, 3}, {1, 2}},
    {{2, 3}, {-1, -1}, {0, 3}, {0, 2}},
    {{1, 3}, {0, 3}, {-1, -1}, {0, 1}},
    {{1, 2}, {0, 2}, {0, 1}, {-1, -1}},
};

}  // namespace

bool SegmentCrossings::find(const mesh::TetMesh& m, VertexId u, TetId start, VertexId w, std::size_t max_tets) {
    crossings_.clear();
    tried_edges_.clear();
    const SegmentSearch::Limits through_everything{true, max_tets};
    return search_.run(m, u, start, w, through_everything,
                       [&](TetId t, SegmentSearch::FaceBits bits) { add_crossings(m, u, w, t, bits); });
}

void SegmentCrossings::add_crossings(const mesh::TetMesh& m, VertexId u, VertexId w, TetId t,
                                     SegmentSearch::FaceBits bits) {
    for (int f = 0; f < 4; ++f)
        if (SegmentSearch::face(bits, f) & SegmentSearch::kCrossesInterior) {
            Crossing face{};
            face.kind = Crossing::kFace;
            face.tet = t;
            face.face = f;
            crossings_.push_back(face);
        }
    const VertexId* v = m.vertices(t);
    for (int i0 = 0; i0 < 4; ++i0)
        for (int i1 = i0 + 1; i1 < 4; ++i1) {
            const VertexId x = v[i0], y = v[i1];
            if (x == u || x == w || y == u || y == w) continue;
            // A point of xy interior to uw lies on both faces that hold xy,
            // and is neither u nor w: a face the segment does not meet
            // there rules the edge out, here and in any other tetrahedron,
            // without the exact tests.
            const int* faces = kOtherCorners[i0][i1];
            if (!(SegmentSearch::face(bits, faces[0]) & SegmentSearch::kMeets) ||
                !(SegmentSearch::face(bits, faces[1]) & SegmentSearch::kMeets))
                continue;
            bool& tried = tried_edges_[mesh::edge_key(x, y)];
            if (tried) continue;
            tried = true;
            if (crosses_in_interior(m.point(u), m.point(w), m.point(x), m.point(y))) {
                Crossing edge{};
                edge.kind = Crossing::kEdge;
                edge.tet = t;
                edge.x = x;
                edge.y = y;
                crossings_.push_back(edge);
            }
        }
}

}  // namespace cbr::recover
