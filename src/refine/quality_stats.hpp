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

// Over the live finite tetrahedra t with region_of_slot[t] > 0; `steiner`:
// the Steiner points of recovery (internal ids). All zero without any
// tetrahedron.
QualityTable measure_quality(const mesh::TetMesh& m, const std::vector<std::int32_t>& region_of_slot,
                             const std::vector<mesh::VertexId>& steiner);

}  // namespace cbr::refine
