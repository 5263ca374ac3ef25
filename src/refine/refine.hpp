// Full 3D mesh generation after constrained boundary recovery: Du & Wang
// 2004, §6, steps (d) and (e). The driver: sizing field, field points,
// then the optimisation passes (quality flips, smoothing).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/constraint_faces.hpp"
#include "refine/refine_options.hpp"

namespace cbr::refine {

// Refines the bounded regions of m (a recovered mesh: `faces` marked as
// constraint faces, `region_of_slot` from recover::classify_regions).
// `steiner`: recovery's Steiner points (internal ids, after every input
// point), which smoothing and relocation may move; no input point ever
// moves. A Steiner point that keeps a bad tetrahedron may be suppressed
// (steiner_removal.hpp): it is erased from `steiner`, and the vertices
// after the input points are then renumbered without it (Steiner points
// first, then the field points, each in id order; `steiner` holds the new
// ids). New points are appended to m's coordinates. The exterior (region
// 0) and the surface are not changed. The caller classifies the regions
// again afterwards (slots changed). `vertex_sizes` (optional) receives the
// sizing field at every vertex.
RefineStats refine_mesh(mesh::TetMesh& m, const recover::ConstraintFaces& faces,
                        const std::vector<std::int32_t>& region_of_slot, std::vector<mesh::VertexId>& steiner,
                        const RefineOptions& options, std::vector<double>* vertex_sizes = nullptr);

}  // namespace cbr::refine
