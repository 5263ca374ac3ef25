// Element quality of the bounded regions: the rows of Du & Wang 2004,
// Table II (radius ratio q = 3 r_in / r_circ), as cbr_mesh_get_stat serves
// them after cbr_mesh_refine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::refine {

struct QualityTable {
    std::size_t tets = 0;
    double average = 0, minimum = 0;       // of q
    double percent_above_0_4 = 0, percent_below_0_1 = 0;
    std::size_t bad_touching_steiner = 0;  // q < 0.1 with a Steiner corner
    double dihedral_min_deg = 0, dihedral_max_deg = 0;
};

// One flag per vertex of m: 1 for the ids in `steiner` (recovery's Steiner
// points), 0 for the others.
std::vector<char> steiner_flags(const mesh::TetMesh& m, const std::vector<mesh::VertexId>& steiner);

// Whether live finite tetrahedron t has a corner flagged in `flags` (one
// per vertex, as steiner_flags gives them; a vertex added after the flags
// were made counts as unflagged).
inline bool has_flagged_corner(const mesh::TetMesh& m, mesh::TetId t, const std::vector<char>& flags) {
    const mesh::VertexId* w = m.vertices(t);
    for (int i = 0; i < 4; ++i)
        if (w[i] < flags.size() && flags[w[i]]) return true;
    return false;
}

// Over the live finite tetrahedra t with region_of_slot[t] > 0; `steiner`:
// the Steiner points of recovery (internal ids). All zero without any
// tetrahedron. `threads`: how many threads may share the measures
// (mesh/chunks.hpp); the table is the same, bit for bit, with any number.
// With `by_region`, also the table of each region r over its tetrahedra
// alone in (*by_region)[r], for r from 0 to the largest region (entry 0,
// the exterior, and the entries of regions without a tetrahedron all
// zero); each is the table of a pass over that region's tetrahedra, bit
// for bit.
QualityTable measure_quality(const mesh::TetMesh& m, const std::vector<std::int32_t>& region_of_slot,
                             const std::vector<mesh::VertexId>& steiner, int threads = 1,
                             std::vector<QualityTable>* by_region = nullptr);

}  // namespace cbr::refine
