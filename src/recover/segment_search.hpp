// The tetrahedra that a segment between two mesh vertices meets, found
// from one end's ball outwards: the search under flip recovery's list of
// crossings (SegmentCrossings) and the unblocking points' count of the
// tetrahedra a missing edge meets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/ball_shell.hpp"
#include "mesh/large_array.hpp"
#include "mesh/slot_marks.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::recover {

class SegmentSearch {
public:
    // What the segment does at one face of a searched tetrahedron (two
    // bits per face in FaceBits, face f at bits 2f and 2f + 1).
    // kMeets: the closed segment and the closed face have a common point,
    // other than an end of the segment that is a corner of the face
    // (classify_segment_face neither Disjoint nor EndpointVertex).
    // kCrossesInterior: a proper crossing of the face (CrossInterior).
    static constexpr std::uint8_t kMeets = 1;
    static constexpr std::uint8_t kCrossesInterior = 2;
    using FaceBits = std::uint8_t;
    static std::uint8_t face(FaceBits bits, int f) { return (bits >> (2 * f)) & 3u; }

    struct Limits {
        bool through_constraints;  // whether the search crosses constraint faces
        std::size_t max_tets;      // the search goes on while fewer tetrahedra are known
    };

    // Searches from u's ball (`start`: a tetrahedron at u) across the faces
    // that segment uw meets, and calls visit(t, bits) for each finite
    // tetrahedron searched, in search order (breadth first, neighbours in
    // face order). A face shared by two searched tetrahedra is classified
    // once (classify_segment_face) and read from the other side. False
    // (nothing visited) when u's ball cannot be walked.
    template <typename Visit>
    bool run(const mesh::TetMesh& m, mesh::VertexId u, mesh::TetId start, mesh::VertexId w, Limits limits,
             Visit visit) {
        if (!mesh::ball(m, u, start, near_)) return false;
        marks_.new_round(m.slot_count());
        if (bits_.size() < m.slot_count()) bits_.resize(m.slot_count());
        for (mesh::TetId t : near_) marks_.set(t, kSeen);
        for (std::size_t i = 0; i < near_.size() && near_.size() < limits.max_tets; ++i) {
            const mesh::TetId t = near_[i];
            if (m.is_ghost(t)) continue;
            FaceBits bits = 0;
            for (int f = 0; f < 4; ++f) {
                const std::uint8_t here = face_bits(m, u, w, t, f);
                bits = static_cast<FaceBits>(bits | here << (2 * f));
                if (!(here & kMeets) || (!limits.through_constraints && m.is_constrained(t, f))) continue;
                const mesh::TetId n = mesh::facet_tet(m.neighbor(t, f));
                if (!marks_.has(n, kSeen)) {
                    marks_.set(n, kSeen);
                    near_.push_back(n);
                }
            }
            bits_[t] = bits;
            marks_.set(t, kSearched);
            visit(t, bits);
        }
        return true;
    }

private:
    std::uint8_t face_bits(const mesh::TetMesh& m, mesh::VertexId u, mesh::VertexId w, mesh::TetId t, int f) const;

    std::vector<mesh::TetId> near_;
    // kSeen: in near_; kSearched: its faces are in bits_.
    static constexpr std::uint8_t kSeen = 1, kSearched = 2;
    mesh::SlotMarks marks_;
    mesh::LargeArray<FaceBits> bits_;
};

}  // namespace cbr::recover
