// Writing a tetrahedral mesh, format chosen by the extension of the output
// path (case-insensitive):
//
//   .mesh   Medit (MeshVersionFormatted 2): Vertices with ref = is_steiner,
//           Tetrahedra with ref = region, Triangles with ref = label; 1-based
//   .vtu    VTK XML unstructured grid, ASCII: cell data "region" and
//           "quality" (if given), point data "is_steiner"; for ParaView
//   .msh    Gmsh 4.1 ASCII: one volume entity and physical group (dim 3)
//           per region, one surface entity and physical group (dim 2) per
//           triangle label
//   .node, .ele, .face, or no extension
//           TetGen: base.node, base.ele (region attribute), base.face
//           (label as boundary marker), numbered from 1
//
// Doubles are written in the shortest form that reads back to the same
// bits (std::to_chars). Output goes to a temporary file in the same
// directory, renamed over the target only once complete, so a failure
// never leaves a partial file under the output name.
//
// Nothing throws: failures come back as a Status (see status.hpp).
#pragma once

#include <string>

#include "io/mesh_types.hpp"
#include "io/status.hpp"

namespace cbr::io {

Status write_volume(const std::string& path, const VolumeMesh& mesh) noexcept;

// The checks write_volume() makes first: array sizes agree, every index is
// a point, coordinates and qualities are finite. invalid_mesh otherwise.
Status validate_volume(const VolumeMesh& mesh);

// True if write_volume knows the extension of `path`.
bool is_volume_file(const std::string& path);

// True if the format of `path` stores VolumeMesh::tet_quality (.vtu): the
// others never read it, so it may be filled while they write.
bool volume_file_stores_quality(const std::string& path);

// "mesh, vtu, msh, node/ele/face" (for help texts).
const char* volume_extensions();

}  // namespace cbr::io
