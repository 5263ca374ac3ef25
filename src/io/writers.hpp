// The per-format writers behind write_volume(). Each receives a mesh that
// validate_volume() accepted, and writes through TextWriter (temporary file,
// then rename).
#pragma once

#include <string>

#include "io/mesh_types.hpp"
#include "io/status.hpp"

namespace cbr::io::detail {

Status write_medit(const std::string& path, const VolumeMesh& mesh);
Status write_vtu(const std::string& path, const VolumeMesh& mesh);
Status write_gmsh(const std::string& path, const VolumeMesh& mesh);
// `path` is base.node, base.ele, base.face or base: writes all three.
Status write_tetgen(const std::string& path, const VolumeMesh& mesh);

}  // namespace cbr::io::detail
