// The per-format surface parsers behind read_surface(). Each gets the whole
// file content, fills an empty `mesh` and returns a Status; the caller
// handles file loading, dispatch and out-of-memory.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/mesh_types.hpp"
#include "io/read_surface.hpp"
#include "io/status.hpp"

namespace cbr::io::detail {

Status read_off(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh);
Status read_obj(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh);
Status read_stl(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh);
Status read_ply(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh);
// .smesh and .poly (chosen by the extension of `path`).
Status read_tetgen(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh);

// Medit .mesh: the surface part, plus vertex refs and tetrahedra when
// `volume` is given.
struct MeditVolumePart {
    std::vector<std::int32_t> vertex_refs;
    std::vector<std::int64_t> tets;
    std::vector<std::int32_t> tet_refs;
};
Status read_medit(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh,
                  MeditVolumePart* volume);

}  // namespace cbr::io::detail
