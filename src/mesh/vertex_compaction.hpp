// Dropping vertices that no tetrahedron uses any more (an added point once
// it is split off the surface, a suppressed Steiner point), so that every
// returned point is a vertex of the mesh.
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::mesh {

// Renumbers the vertices with ids >= `first` that some live tetrahedron
// uses to first, first + 1, ... (keeping their order) and drops the
// others. Vertices below `first` keep their ids (used or not). Ids in
// `keep_in_step` are mapped too (and removed if dropped). `kept_old_ids`
// (optional) receives the old ids of the vertices kept from `first` on, in
// their new order (new id first + i had old id (*kept_old_ids)[i]).
void compact_vertices_from(TetMesh& m, std::size_t first, std::vector<VertexId>& keep_in_step,
                           std::vector<VertexId>* kept_old_ids = nullptr);

}  // namespace cbr::mesh
