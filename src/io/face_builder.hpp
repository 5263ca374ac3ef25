// Turning the faces of a file into triangles, the same way for every format.
// A face with more than 3 corners is a polygon: rejected (the caller reports
// it, naming the face) unless ReadOptions::triangulate_polygons is set, in
// which case it is fan-triangulated from its first corner: (v0, vi, vi+1).
// A fan is only a valid triangulation of a convex planar polygon; anything
// else is left to the geometric checks that follow reading.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "io/mesh_types.hpp"

namespace cbr::io::detail {

// Appends face ids[0..n) (0-based, already validated, n >= 3) with `label`.
// Returns false, appending nothing, if n > 3 and !triangulate.
bool append_face(SurfaceMesh& mesh, const std::int64_t* ids, std::size_t n, std::int32_t label,
                 bool triangulate);

// "has 4 corners: only triangles are accepted (--triangulate splits a
// polygon into a fan of triangles)" -- the tail of the caller's message,
// naming the option of every cbr command that reads a surface (the readers
// serve the command alone; ReadOptions::triangulate_polygons is that option).
std::string polygon_rejected(std::size_t corners);

}  // namespace cbr::io::detail
