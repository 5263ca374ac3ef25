// write_volume(): validation, dispatch by extension, exception firewall.
#include "io/write_volume.hpp"

#include <cmath>
#include <exception>
#include <new>

#include "io/file_source.hpp"
#include "io/writers.hpp"

namespace cbr::io {

namespace {

using Writer = Status (*)(const std::string&, const VolumeMesh&);

Writer writer_for(const std::string& ext) {
    if (ext == "mesh") return detail::write_medit;
    if (ext == "vtu") return detail::write_vtu;
    if (ext == "msh") return detail::write_gmsh;
    if (ext.empty() || ext == "node" || ext == "ele" || ext == "face") return detail::write_tetgen;
    return nullptr;
}

Status invalid(const std::string& msg) { return Status::error(ErrorKind::invalid_mesh, "invalid mesh: " + msg); }

Status check_ids(const std::vector<std::int64_t>& ids, std::size_t per, std::int64_t np, const char* what) {
    for (std::size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] < 0 || ids[i] >= np) {
            return invalid(std::string(what) + " " + std::to_string(i / per) + " has point index " +
                           std::to_string(ids[i]) + " (the mesh has " + std::to_string(np) + " points)");
        }
    }
    return {};
}

}  // namespace

Status validate_volume(const VolumeMesh& m) {
    if (m.xyz.size() % 3 != 0) return invalid("xyz size is not a multiple of 3");
    if (m.tets.size() % 4 != 0) return invalid("tets size is not a multiple of 4");
    if (m.tris.size() % 3 != 0) return invalid("tris size is not a multiple of 3");
    if (m.tet_regions.size() != m.num_tets()) return invalid("tet_regions needs one value per tetrahedron");
    if (m.tri_labels.size() != m.num_triangles()) return invalid("tri_labels needs one value per triangle");
    if (!m.is_steiner.empty() && m.is_steiner.size() != m.num_points()) {
        return invalid("is_steiner must be empty or have one flag per point");
    }
    if (!m.tet_quality.empty() && m.tet_quality.size() != m.num_tets()) {
        return invalid("tet_quality must be empty or have one value per tetrahedron");
    }
    for (std::size_t i = 0; i < m.xyz.size(); ++i) {
        if (!std::isfinite(m.xyz[i])) return invalid("point " + std::to_string(i / 3) + " has a non-finite coordinate");
    }
    for (std::size_t t = 0; t < m.tet_quality.size(); ++t) {
        if (!std::isfinite(m.tet_quality[t])) return invalid("tetrahedron " + std::to_string(t) + " has a non-finite quality");
    }
    const auto np = static_cast<std::int64_t>(m.num_points());
    if (auto st = check_ids(m.tets, 4, np, "tetrahedron"); !st) return st;
    return check_ids(m.tris, 3, np, "triangle");
}

bool is_volume_file(const std::string& path) { return writer_for(detail::lower_extension(path)) != nullptr; }

bool volume_file_stores_quality(const std::string& path) { return detail::lower_extension(path) == "vtu"; }

const char* volume_extensions() { return "mesh, vtu, msh, node/ele/face (TetGen)"; }

Status write_volume(const std::string& path, const VolumeMesh& mesh) noexcept {
    try {
        const std::string ext = detail::lower_extension(path);
        const Writer write = writer_for(ext);
        if (write == nullptr) {
            return Status::error(ErrorKind::unknown_extension, path + ": unknown volume mesh extension '" + ext +
                                                                   "' (known: " + volume_extensions() + ")");
        }
        if (auto st = validate_volume(mesh); !st) {
            st.message = path + ": " + st.message;
            return st;
        }
        return write(path, mesh);
    } catch (const std::bad_alloc&) {
        return Status::error(ErrorKind::out_of_memory, path + ": out of memory while writing");
    } catch (const std::exception& e) {
        return Status::error(ErrorKind::write_error, path + ": " + e.what());
    } catch (...) {
        return Status::error(ErrorKind::write_error, path + ": unexpected error while writing");
    }
}

}  // namespace cbr::io
