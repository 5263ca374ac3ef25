// The splitting of every added point (§5.3-5.4), in passes. A split that
// finds no placement leaves the mesh unchanged and the splits may run in
// any order (point_splitting.hpp), so such a point waits for the next
// pass, when the splits around it have changed its ball. When a pass
// splits nothing, the Steiner points of earlier splits in the ball of each
// waiting point are suppressed (§6; they can lie so near the surface that
// no point near e sees past them), with every sub-face marked as a
// constraint face and every chain link protected so the surface being
// recovered stays as it is; then the passes go on. Fails when that
// suppresses nothing either.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/surface_points.hpp"

namespace cbr::recover {

// Splits every point of `added` that is still an added point, those on
// edges first; appends the Steiner points made to `steiner` and erases
// from it the ones suppressed. `incident`: one tetrahedron per vertex,
// kept up to date. `made`: Steiner points made by the splits. False with
// `why` when some point could not be split.
bool split_added_points(mesh::TetMesh& m, SurfacePoints& points, std::vector<mesh::TetId>& incident,
                        const std::vector<mesh::VertexId>& added, std::vector<mesh::VertexId>& steiner,
                        std::size_t& made, std::string& why);

}  // namespace cbr::recover
