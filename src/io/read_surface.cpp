// read_surface(): dispatch by extension, file loading, and the firewall that
// turns any exception (out of memory) into a Status.
//
// Why cbr_io parses every format itself instead of using OpenMesh's
// readers -- measured with OpenMesh 9.0 (Debian 9.0-4), reading a
// tetrahedron whose first point is (0.1, 1.0000000000000002, 0.3) into a
// TriMesh whose Point type is Vec3d:
//
//   OFF, OBJ, ASCII STL, ASCII PLY, binary PLY (little and big endian,
//   `property double`): all return 0.10000000149011612, 1, 0.30000001192092896
//   -- every reader parses or converts coordinates through float (Vec3f)
//   before handing them to the importer, even when the file stores doubles.
//   Binary STL is float32 by definition and widens exactly, but the STL
//   reader welds vertices with a tolerance (it merged 1e-40 with 0), not by
//   exact equality.
//
//   The OFF reader also returns success with an EMPTY mesh when the file
//   has a '#' comment line.
//
//   Topology is not kept either: OpenMesh's add_face refuses non-manifold
//   configurations ("complex vertex"/"complex edge") and duplicates vertices
//   to work around them (nonmanifold-edge-two-tets.off: 6 points came back
//   as 18), which would hide exactly the defects `cbr check` must report,
//   and change legal multi-region inputs.
//
// So no OpenMesh reader keeps coordinates bit-exact AND the file's
// connectivity, and each format has its own small exact parser here
// (std::from_chars, correctly rounded). tests/test_io.cpp re-checks the
// OpenMesh behaviour, so a future exact OpenMesh would be noticed.
#include "io/read_surface.hpp"

#include <exception>
#include <new>

#include "io/file_source.hpp"
#include "io/readers.hpp"

namespace cbr::io {

namespace {

using Parser = Status (*)(const std::string&, std::string_view, const ReadOptions&, SurfaceMesh&);

Status read_medit_surface(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh) {
    return detail::read_medit(path, text, opt, mesh, nullptr);
}

Parser parser_for(const std::string& ext) {
    if (ext == "off") return detail::read_off;
    if (ext == "obj") return detail::read_obj;
    if (ext == "stl") return detail::read_stl;
    if (ext == "ply") return detail::read_ply;
    if (ext == "smesh" || ext == "poly") return detail::read_tetgen;
    if (ext == "mesh") return read_medit_surface;
    return nullptr;
}

// Runs `body`, turning exceptions into a Status.
template <class F>
Status guarded(const std::string& path, F&& body) noexcept {
    try {
        return body();
    } catch (const std::bad_alloc&) {
        return Status::error(ErrorKind::out_of_memory, path + ": out of memory while reading");
    } catch (const std::exception& e) {
        return Status::error(ErrorKind::unreadable, path + ": " + e.what());
    } catch (...) {
        return Status::error(ErrorKind::unreadable, path + ": unexpected error while reading");
    }
}

}  // namespace

bool is_surface_file(const std::string& path) { return parser_for(detail::lower_extension(path)) != nullptr; }

const char* surface_extensions() { return "off, obj, stl, ply, smesh, poly, mesh"; }

Status read_surface(const std::string& path, SurfaceMesh& mesh, const ReadOptions& options) noexcept {
    Status st = guarded(path, [&]() -> Status {
        mesh = SurfaceMesh{};
        const std::string ext = detail::lower_extension(path);
        const Parser parse = parser_for(ext);
        if (parse == nullptr) {
            return Status::error(ErrorKind::unknown_extension,
                                 path + ": unknown surface file extension '" + ext + "' (known: " +
                                     surface_extensions() + ")");
        }
        std::string text;
        if (auto s = detail::load_file(path, text); !s) return s;
        return parse(path, text, options, mesh);
    });
    if (!st) mesh = SurfaceMesh{};
    return st;
}

Status read_medit_volume(const std::string& path, VolumeMesh& mesh) noexcept {
    Status st = guarded(path, [&]() -> Status {
        mesh = VolumeMesh{};
        if (detail::lower_extension(path) != "mesh") {
            return Status::error(ErrorKind::unknown_extension, path + ": expected a Medit .mesh file");
        }
        std::string text;
        if (auto s = detail::load_file(path, text); !s) return s;
        SurfaceMesh surface;
        detail::MeditVolumePart part;
        if (auto s = detail::read_medit(path, text, ReadOptions{}, surface, &part); !s) return s;
        mesh.xyz = std::move(surface.xyz);
        mesh.tris = std::move(surface.tris);
        mesh.tri_labels = std::move(surface.labels);
        mesh.tets = std::move(part.tets);
        mesh.tet_regions = std::move(part.tet_refs);
        mesh.is_steiner.reserve(part.vertex_refs.size());
        for (const std::int32_t r : part.vertex_refs) mesh.is_steiner.push_back(r != 0 ? 1 : 0);
        return {};
    });
    if (!st) mesh = VolumeMesh{};
    return st;
}

}  // namespace cbr::io
