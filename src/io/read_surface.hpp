// Reading a triangulated surface from a file, format chosen by the file's
// extension (case-insensitive):
//
//   .off            OFF (also COFF/NOFF/STOFF headers; extra per-vertex
//                   values ignored)
//   .obj            Wavefront OBJ: `v` and `f` (i, i/t, i//n, i/t/n,
//                   negative = relative); other statements ignored
//   .stl            STL, ASCII or binary (detected); vertices welded by
//                   exact coordinate equality; ASCII: label = index of the
//                   `solid` block
//   .ply            PLY ascii / binary_little_endian / binary_big_endian;
//                   `face` lists (vertex_indices or vertex_index) and
//                   `tristrips`
//   .smesh, .poly   TetGen facets (label = facet boundary marker); a point
//                   count of 0 reads the points from the sibling .node file
//   .mesh           Medit: Vertices, Triangles (label = ref),
//                   Quadrilaterals; other sections skipped
//
// Every coordinate is bit-identical to the number written in the file
// (binary formats: the stored float/double, widened exactly). Faces with
// more than 3 corners are rejected, naming the face, unless
// triangulate_polygons is set. Faces, in messages, are numbered from 0 in
// file order. Geometric and topological defects (duplicate points,
// degenerate or non-manifold faces, holes) are NOT checked here.
//
// Nothing throws: failures come back as a Status (see status.hpp).
#pragma once

#include <string>

#include "io/mesh_types.hpp"
#include "io/status.hpp"

namespace cbr::io {

struct ReadOptions {
    bool triangulate_polygons = false;  // fan-triangulate faces with > 3 corners
};

// Reads `path` into `mesh` (replacing its content). On failure `mesh` is
// left empty.
Status read_surface(const std::string& path, SurfaceMesh& mesh, const ReadOptions& options = {}) noexcept;

// Reads a Medit .mesh volume mesh (Vertices, Tetrahedra, Triangles), as
// written by write_volume: region = tetrahedron ref, label = triangle ref,
// is_steiner = (vertex ref != 0). Used to check written files.
Status read_medit_volume(const std::string& path, VolumeMesh& mesh) noexcept;

// True if read_surface knows the extension of `path`.
bool is_surface_file(const std::string& path);

// "off, obj, stl, ply, smesh, poly, mesh" (for help texts).
const char* surface_extensions();

}  // namespace cbr::io
