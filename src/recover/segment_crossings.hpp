// Every place where a missing edge crosses the mesh: the faces it passes
// through and the edges it cuts, searched from one end's ball outwards.
// Flip recovery tries them in this order when the crossings at the ends
// cannot be flipped away (FlipRecovery::remove_any_crossing).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/key_table.hpp"
#include "mesh/large_array.hpp"
#include "mesh/slot_marks.hpp"
#include "mesh/tet_mesh.hpp"
#include "recover/segment_walk.hpp"

namespace cbr::recover {

class SegmentCrossings {
public:
    // The crossings of segment uw (two mesh vertices; `start` a tetrahedron
    // at u) in the tetrahedra the closed segment meets, searched from u's
    // ball outwards across the faces it meets (a face met only at u or w
    // is not crossed), while fewer than `max_tets` tetrahedra are known.
    // For each finite tetrahedron in search order: its faces crossed in
    // their interior (kFace; a face shared by two tetrahedra found
    // appears from both sides), then its edges cut at a point interior to
    // both segments (kEdge; each edge once, with the first tetrahedron
    // found at it). False (no crossing) when u's ball cannot be walked.
    bool find(const mesh::TetMesh& m, mesh::VertexId u, mesh::TetId start, mesh::VertexId w, std::size_t max_tets);

    const std::vector<Crossing>& crossings() const { return crossings_; }

private:
    // Per face of a searched tetrahedron: whether the segment meets it
    // other than at u or w, and whether it crosses its interior.
    static constexpr std::uint8_t kMeets = 1, kCrossesInterior = 2;
    std::uint8_t face_bits(const mesh::TetMesh& m, mesh::VertexId u, mesh::VertexId w, mesh::TetId t, int f) const;

    std::vector<mesh::TetId> near_;
    std::vector<Crossing> crossings_;
    // kSeen: in near_; kSearched: its faces are in face_bits_ (two bits per
    // face, face f at bits 2f and 2f + 1).
    static constexpr std::uint8_t kSeen = 1, kSearched = 2;
    mesh::SlotMarks marks_;
    mesh::LargeArray<std::uint8_t> face_bits_;
    mesh::KeyTable<bool> tried_edges_;
};

}  // namespace cbr::recover
