// extern "C" surface checks (cbr.h, "Surface checks"): cbr_mesh_check_faces
// runs recover::check_surface on the caller's triangles over the points of
// the mesh and keeps the report in the handle; the other three read it.
//
// The report is stored with 0-based ids and converted to the index base in
// force when it is read, so that ids in messages and outputs are always the
// caller's. (A caller id of INT64_MIN under base 1 cannot be shifted to
// 0-based; it is kept as INT64_MIN, and read back as INT64_MIN + 1.)
#include <cbr/cbr.h>

#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "handle.hpp"
#include "mesh/huge_pages.hpp"
#include "recover/constraint_faces.hpp"
#include "recover/surface_check.hpp"

using cbr::capi::ApiError;
using cbr::capi::guarded;
using cbr::capi::require;
using cbr::recover::Defect;
using cbr::recover::DefectKind;
using cbr::recover::SurfaceCheckResult;

namespace {

// The CBR_DEFECT_* key of the header for each internal kind (and back).
std::optional<DefectKind> kind_of(int key) {
    switch (key) {
        case CBR_DEFECT_ID_OUT_OF_RANGE: return DefectKind::IdOutOfRange;
        case CBR_DEFECT_REPEATED_ID: return DefectKind::RepeatedId;
        case CBR_DEFECT_ZERO_AREA: return DefectKind::ZeroArea;
        case CBR_DEFECT_DUPLICATE_TRIANGLE: return DefectKind::DuplicateTriangle;
        case CBR_DEFECT_INTERSECTION: return DefectKind::Intersection;
        case CBR_DEFECT_OPEN_EDGE: return DefectKind::OpenEdge;
        case CBR_DEFECT_NONMANIFOLD_EDGE: return DefectKind::NonManifoldEdge;
        default: return std::nullopt;
    }
}

// Caller id -> 0-based id, saturating instead of overflowing.
std::int64_t to_zero_based(std::int64_t id, int base) {
    if (id < std::numeric_limits<std::int64_t>::min() + base) return std::numeric_limits<std::int64_t>::min();
    return id - base;
}

// 0-based id -> caller id, saturating instead of overflowing.
std::int64_t to_caller(std::int64_t id, int base) {
    if (id > std::numeric_limits<std::int64_t>::max() - base) return std::numeric_limits<std::int64_t>::max();
    return id + base;
}

// The mesh's points in external (caller) order, 3 doubles each.
std::vector<double> points_in_caller_order(const cbr::delaunay::Delaunay& d) {
    const std::size_t n = d.mesh().vertex_count();
    std::vector<double> xyz;
    cbr::mesh::resize_huge(xyz, 3 * n);
    for (cbr::mesh::VertexId v = 0; v < n; ++v)
        std::memcpy(xyz.data() + 3 * std::size_t{d.external_id(v)}, d.mesh().point(v), 3 * sizeof(double));
    return xyz;
}

// Per triangle (0-based caller ids, unchecked): the facet of the handle's
// mesh that holds it, or kNoFacet (recover::facets_of_mesh). The mesh is
// always a valid tetrahedralization of its points (the Delaunay mesh, or
// the mesh recovery or refinement left), so that check_surface skips the
// pairs of two such faces (SurfaceCheckOptions::known_faces). Empty when
// the mesh has no tetrahedron.
std::vector<cbr::mesh::FacetRef> facets_of_the_mesh(const cbr_mesh& h, const std::vector<std::int64_t>& ids) {
    if (h.delaunay.finite_tet_count() == 0) return {};
    const auto points = static_cast<std::int64_t>(h.delaunay.mesh().vertex_count());
    std::vector<cbr::recover::Triangle> tris(ids.size() / 3);
    for (std::size_t i = 0; i < tris.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const std::int64_t id = ids[3 * i + static_cast<std::size_t>(k)];
            tris[i][k] = id >= 0 && id < points ? h.delaunay.internal_id(static_cast<cbr::mesh::VertexId>(id))
                                                : cbr::mesh::kGhostVertex;  // never a face's
        }
    return cbr::recover::facets_of_mesh(h.delaunay.mesh(), tris, cbr::capi::thread_count(h));
}

// The message of a check that found errors: the counts and the first error
// (summarize), then the next two listed errors.
std::string error_message(const SurfaceCheckResult& r, int base) {
    std::vector<std::string> next;
    bool first = true;
    for (const Defect& d : r.defects) {
        if (!cbr::recover::is_error(d.kind)) continue;
        if (!first && next.size() < 2) next.push_back(cbr::recover::describe(d, base));
        first = false;
    }
    std::string message = cbr::recover::summarize(r, base);
    for (std::size_t j = 0; j < next.size(); ++j) message += (j == 0 ? "; then: " : "; ") + next[j];
    return message;
}

// How many of a defect's three point slots hold ids (the rest are unused);
// an out-of-range id may be negative, so -1 cannot tell by itself.
int used_points(const Defect& d) {
    switch (d.kind) {
        case DefectKind::OpenEdge:
        case DefectKind::NonManifoldEdge: return 2;
        case DefectKind::Intersection: {
            int n = 0;
            while (n < 3 && d.vert[static_cast<std::size_t>(n)] >= 0) ++n;  // shared ids first
            return n;
        }
        default: return 3;
    }
}

bool has_second_triangle(DefectKind kind) {
    return kind == DefectKind::DuplicateTriangle || kind == DefectKind::Intersection;
}

// The i-th listed defect of `kind`, or nullptr.
const Defect* listed_defect(const SurfaceCheckResult& r, DefectKind kind, std::int64_t i) {
    std::int64_t seen = 0;
    for (const Defect& d : r.defects)
        if (d.kind == kind && seen++ == i) return &d;
    return nullptr;
}

std::int64_t listed_count(const SurfaceCheckResult& r, DefectKind kind) {
    std::int64_t n = 0;
    for (const Defect& d : r.defects) n += d.kind == kind ? 1 : 0;
    return n;
}

}  // namespace

void cbr::capi::check_faces(cbr_mesh* mesh, std::int64_t count, const std::int64_t* tris,
                            std::vector<cbr::mesh::FacetRef>& facets) {
    require(mesh != nullptr, CBR_ERR_INVALID_ARGUMENT, "mesh is NULL");
    require(count >= 0, CBR_ERR_INVALID_ARGUMENT, "count is negative (" + std::to_string(count) + ")");
    require(count == 0 || tris != nullptr, CBR_ERR_INVALID_ARGUMENT, "tris is NULL");
    require(count <= std::numeric_limits<std::int64_t>::max() / 3, CBR_ERR_INVALID_ARGUMENT,
            "count is too large (" + std::to_string(count) + ")");
    const int base = mesh->index_base;
    std::vector<std::int64_t> ids;
    cbr::mesh::resize_huge(ids, 3 * static_cast<std::size_t>(count));
    for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = to_zero_based(tris[k], base);
    const std::vector<double> xyz = points_in_caller_order(mesh->delaunay);
    cbr::recover::SurfaceCheckOptions options;
    facets = facets_of_the_mesh(*mesh, ids);
    std::vector<char> known(facets.size());
    for (std::size_t i = 0; i < facets.size(); ++i) known[i] = facets[i] != cbr::recover::kNoFacet;
    if (!known.empty()) options.known_faces = &known;
    SurfaceCheckResult report = cbr::recover::check_surface(
        xyz.data(), static_cast<std::int64_t>(xyz.size() / 3), ids.data(), count, options);
    std::string message = report.ok() ? std::string() : error_message(report, base);
    mesh->last_check = std::move(report);
    if (!message.empty()) throw ApiError{CBR_ERR_INVALID_INPUT, std::move(message)};
}

extern "C" {

CBR_API int cbr_mesh_check_faces(cbr_mesh* mesh, int64_t count, const int64_t* tris) {
    return guarded(mesh, "cbr_mesh_check_faces", [&] {
        std::vector<cbr::mesh::FacetRef> facets;
        cbr::capi::check_faces(mesh, count, tris, facets);
        return CBR_OK;
    });
}

CBR_API int64_t cbr_mesh_defect_count(const cbr_mesh* mesh, int kind) {
    const std::optional<DefectKind> k = kind_of(kind);
    if (!mesh || !k) return -1;
    return mesh->last_check.count(*k);
}

CBR_API int64_t cbr_mesh_defect_listed(const cbr_mesh* mesh, int kind) {
    const std::optional<DefectKind> k = kind_of(kind);
    if (!mesh || !k) return -1;
    return listed_count(mesh->last_check, *k);
}

CBR_API int cbr_mesh_get_defect(const cbr_mesh* mesh, int kind, int64_t i, int64_t* triangles_out,
                                int64_t* points_out) {
    return guarded(mesh, "cbr_mesh_get_defect", [&] {
        require(mesh != nullptr, CBR_ERR_INVALID_ARGUMENT, "mesh is NULL");
        const std::optional<DefectKind> k = kind_of(kind);
        require(k.has_value(), CBR_ERR_INVALID_ARGUMENT, "unknown defect kind " + std::to_string(kind));
        const Defect* d = i >= 0 ? listed_defect(mesh->last_check, *k, i) : nullptr;
        require(d != nullptr, CBR_ERR_INVALID_ARGUMENT,
                "defect index " + std::to_string(i) + " is out of range (" +
                    std::to_string(listed_count(mesh->last_check, *k)) + " listed of this kind)");
        const int base = mesh->index_base;
        if (triangles_out) {
            triangles_out[0] = to_caller(d->tri[0], base);
            triangles_out[1] = has_second_triangle(d->kind) ? to_caller(d->tri[1], base) : -1;
        }
        if (points_out) {
            const int used = used_points(*d);
            for (int j = 0; j < 3; ++j) {
                const std::int64_t id = d->vert[static_cast<std::size_t>(j)];
                points_out[j] = j < used ? to_caller(id, base) : -1;
            }
        }
        return CBR_OK;
    });
}

}  // extern "C"
