#include "recover/segment_crossings.hpp"

#include <utility>

#include "geom/intersect.hpp"
#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"

namespace cbr::recover {
namespace {

using mesh::kFaceVertices;
using mesh::TetId;
using mesh::VertexId;

std::uint64_t edge_key(VertexId a, VertexId b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t{a} << 32) | b;
}

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

std::uint8_t SegmentCrossings::face_bits(const mesh::TetMesh& m, VertexId u, VertexId w, TetId t, int f) const {
    // A face whose other side was searched already was classified there:
    // the kind is the segment's and the triangle's, whichever side asks.
    const mesh::FacetRef across = m.neighbor(t, f);
    const TetId n = mesh::facet_tet(across);
    if (marks_.has(n, kSearched)) return (face_bits_[n] >> (2 * mesh::facet_face(across))) & 3u;
    const int* k = kFaceVertices[f];
    const VertexId* v = m.vertices(t);
    const geom::SegTriKind kind = classify_segment_face(m, u, w, v[k[0]], v[k[1]], v[k[2]]);
    if (kind == geom::SegTriKind::Disjoint || kind == geom::SegTriKind::EndpointVertex) return 0;
    return kind == geom::SegTriKind::CrossInterior ? kMeets | kCrossesInterior : kMeets;
}

bool SegmentCrossings::find(const mesh::TetMesh& m, VertexId u, TetId start, VertexId w, std::size_t max_tets) {
    crossings_.clear();
    tried_edges_.clear();
    if (!mesh::ball(m, u, start, near_)) return false;
    marks_.new_round(m.slot_count());
    if (face_bits_.size() < m.slot_count()) face_bits_.resize(m.slot_count());
    for (TetId t : near_) marks_.set(t, kSeen);
    const double* pu = m.point(u);
    const double* pw = m.point(w);
    for (std::size_t i = 0; i < near_.size() && near_.size() < max_tets; ++i) {
        const TetId t = near_[i];
        if (m.is_ghost(t)) continue;
        std::uint8_t bits[4];
        for (int f = 0; f < 4; ++f) {
            bits[f] = face_bits(m, u, w, t, f);
            if (!(bits[f] & kMeets)) continue;
            if (bits[f] & kCrossesInterior) {
                Crossing face{};
                face.kind = Crossing::kFace;
                face.tet = t;
                face.face = f;
                crossings_.push_back(face);
            }
            const TetId n = mesh::facet_tet(m.neighbor(t, f));
            if (!marks_.has(n, kSeen)) {
                marks_.set(n, kSeen);
                near_.push_back(n);
            }
        }
        face_bits_[t] = static_cast<std::uint8_t>(bits[0] | bits[1] << 2 | bits[2] << 4 | bits[3] << 6);
        marks_.set(t, kSearched);
        const VertexId* v = m.vertices(t);
        for (int i0 = 0; i0 < 4; ++i0)
            for (int i1 = i0 + 1; i1 < 4; ++i1) {
                const VertexId x = v[i0], y = v[i1];
                if (x == u || x == w || y == u || y == w) continue;
                // A point of xy interior to uw lies on both faces that hold
                // xy, and is neither u nor w: a face the segment does not
                // meet there rules the edge out, here and in any other
                // tetrahedron, without the exact tests.
                const int* faces = kOtherCorners[i0][i1];
                if (!(bits[faces[0]] & kMeets) || !(bits[faces[1]] & kMeets)) continue;
                bool& tried = tried_edges_[edge_key(x, y)];
                if (tried) continue;
                tried = true;
                if (crosses_in_interior(pu, pw, m.point(x), m.point(y))) {
                    Crossing edge{};
                    edge.kind = Crossing::kEdge;
                    edge.tet = t;
                    edge.x = x;
                    edge.y = y;
                    crossings_.push_back(edge);
                }
            }
    }
    return true;
}

}  // namespace cbr::recover
