// The recovered mesh as the writers want it (io::VolumeMesh), collected
// from a cbr_mesh through the public C API: points, the tetrahedra
// returned (bounded regions, or all with CBR_PARAM_KEEP_EXTERIOR) and their
// regions, the input triangles with their labels, which points are Steiner.
// The points are those the library returns: without the exterior, the
// input's with their ids and the added points that a returned tetrahedron
// uses, in their order (CBR_PARAM_KEEP_EXTERIOR).
#pragma once

#include <cbr/cbr.h>

#include "io/mesh_types.hpp"

namespace cbr::cli {

// Returns CBR_OK or the status of the C API call that failed.
int collect_volume(const cbr_mesh* m, const io::SurfaceMesh& surface, io::VolumeMesh& out);

}  // namespace cbr::cli
