// Every place where a missing edge crosses the mesh: the faces it passes
// through and the edges it cuts, searched from one end's ball outwards.
// Flip recovery tries them in this order when the crossings at the ends
// cannot be flipped away (FlipRecovery::remove_any_crossing).
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/key_table.hpp"
#include "mesh/tet_mesh.hpp"
#include "recover/segment_search.hpp"
#include "recover/segment_walk.hpp"

namespace cbr::recover {

class SegmentCrossings {
public:
    // The crossings of segment uw (two mesh vertices; `start` a tetrahedron
    // at u) in the tetrahedra SegmentSearch finds (across constraint faces
    // too, while fewer than `max_tets` are known). For each finite
    // tetrahedron in search order: its faces crossed in their interior
    // (kFace; a face shared by two tetrahedra found appears from both
    // sides), then its edges cut at a point interior to both segments
    // (kEdge; each edge once, with the first tetrahedron found at it).
    // False (no crossing) when u's ball cannot be walked.
    bool find(const mesh::TetMesh& m, mesh::VertexId u, mesh::TetId start, mesh::VertexId w, std::size_t max_tets);

    const std::vector<Crossing>& crossings() const { return crossings_; }

private:
    void add_crossings(const mesh::TetMesh& m, mesh::VertexId u, mesh::VertexId w, mesh::TetId t,
                       SegmentSearch::FaceBits bits);

    SegmentSearch search_;
    std::vector<Crossing> crossings_;
    mesh::KeyTable<bool> tried_edges_;
};

}  // namespace cbr::recover
