// Region classification: tetrahedra connected through faces that are not
// recovered constraint faces form a region.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/constraint_faces.hpp"

namespace cbr::recover {

struct RegionMap {
    std::vector<std::int32_t> of_tet;  // per tetrahedron slot; -1 for free slots
    std::int32_t count = 0;            // number of regions, region 0 included
};

// Region 0 is the one holding the ghost tetrahedra: outside every closed
// part of the surface. The others are numbered 1, 2, ... in the order of
// the smallest (triangle index, side) found on their boundary, where side 0
// is the side the triangle's normal (b-a) x (c-a) points to: the numbering
// depends on the input only, not on how the mesh is stored.
RegionMap classify_regions(const mesh::TetMesh& m, const ConstraintFaces& faces);

}  // namespace cbr::recover
