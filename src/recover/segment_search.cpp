#include "recover/segment_search.hpp"

#include "geom/intersect.hpp"
#include "recover/segment_walk.hpp"

namespace cbr::recover {

std::uint8_t SegmentSearch::face_bits(const mesh::TetMesh& m, mesh::VertexId u, mesh::VertexId w, mesh::TetId t,
                                      int f) const {
    // A face whose other side was searched already was classified there:
    // the kind is the segment's and the triangle's, whichever side asks.
    const mesh::FacetRef across = m.neighbor(t, f);
    const mesh::TetId n = mesh::facet_tet(across);
    if (marks_.has(n, kSearched)) return face(bits_[n], mesh::facet_face(across));
    const int* k = mesh::kFaceVertices[f];
    const mesh::VertexId* v = m.vertices(t);
    const geom::SegTriKind kind = classify_segment_face(m, u, w, v[k[0]], v[k[1]], v[k[2]]);
    if (kind == geom::SegTriKind::Disjoint || kind == geom::SegTriKind::EndpointVertex) return 0;
    return kind == geom::SegTriKind::CrossInterior ? kMeets | kCrossesInterior : kMeets;
}

}  // namespace cbr::recover
