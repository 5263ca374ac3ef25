// extern "C" functions on a cbr_mesh handle: argument checks, then the
// core, inside the exception firewall (handle.hpp).
#include <cbr/cbr.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "handle.hpp"
#include "mesh/tet_mesh.hpp"

using cbr::capi::ApiError;
using cbr::capi::guarded;
using cbr::capi::require;

namespace {

std::string format_point(const double* p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", p[0], p[1], p[2]);
    return buf;
}

// Rejects a NaN, infinite or out-of-range coordinate, naming the point.
void check_coordinates(const double* xyz, std::int64_t count, std::int64_t first_id) {
    static const char axis[] = "xyz";
    for (std::int64_t i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k) {
            const double c = xyz[3 * i + k];
            const double a = std::fabs(c);
            if (!std::isfinite(c)) {
                throw ApiError{CBR_ERR_INVALID_INPUT, "point " + std::to_string(first_id + i) + " has " +
                                                          (std::isnan(c) ? "a NaN " : "an infinite ") + axis[k] +
                                                          " coordinate"};
            }
            if (c != 0 && (a < cbr::geom::kMinMagnitude || a > cbr::geom::kMaxMagnitude)) {
                char buf[64];
                std::snprintf(buf, sizeof buf, "%.17g", c);
                throw ApiError{CBR_ERR_INVALID_INPUT,
                               "point " + std::to_string(first_id + i) + " has " + axis[k] + " = " + buf +
                                   ", outside the supported range (0, or magnitude within [1e-40, 1e+40])"};
            }
        }
}

void require_mesh(const cbr_mesh* mesh) { require(mesh != nullptr, CBR_ERR_INVALID_ARGUMENT, "mesh is NULL"); }

}  // namespace

extern "C" {

CBR_API int cbr_mesh_create(cbr_mesh** out) {
    if (!out) return CBR_ERR_INVALID_ARGUMENT;
    *out = nullptr;
    try {
        *out = new cbr_mesh();
        return CBR_OK;
    } catch (...) {
        return CBR_ERR_OUT_OF_MEMORY;
    }
}

CBR_API void cbr_mesh_destroy(cbr_mesh* mesh) { delete mesh; }

CBR_API const char* cbr_mesh_last_error(const cbr_mesh* mesh) {
    if (!mesh) return "cbr_mesh_last_error: mesh is NULL";
    return mesh->last_error.c_str();
}

CBR_API int cbr_mesh_set_param(cbr_mesh* mesh, int key, double value) {
    return guarded(mesh, "cbr_mesh_set_param", [&] {
        require_mesh(mesh);
        switch (key) {
            case CBR_PARAM_INDEX_BASE:
                require(value == 0.0 || value == 1.0, CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_INDEX_BASE must be 0 or 1");
                mesh->index_base = static_cast<int>(value);
                return CBR_OK;
            case CBR_PARAM_KEEP_EXTERIOR:
                require(value == 0.0 || value == 1.0, CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_KEEP_EXTERIOR must be 0 or 1");
                mesh->keep_exterior = value != 0.0;
                return CBR_OK;
            case CBR_PARAM_REFINE_SIZE:
                require(value == 0.0 || (std::isfinite(value) && value > 0), CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_REFINE_SIZE must be 0 (from the surface) or finite and > 0");
                mesh->refine_options.target_size = value;
                return CBR_OK;
            case CBR_PARAM_REFINE_GRADING:
                require(value >= 0.01 && value <= 100, CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_REFINE_GRADING must be within [0.01, 100]");
                mesh->refine_options.grading = value;
                return CBR_OK;
            case CBR_PARAM_REFINE_QUALITY_BOUND:
                require(value >= 1 && value <= 1000, CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_REFINE_QUALITY_BOUND must be within [1, 1000]");
                mesh->refine_options.quality_bound = value;
                return CBR_OK;
            case CBR_PARAM_REFINE_PASSES:
                require(value >= 0 && value <= 100 && value == std::floor(value), CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_REFINE_PASSES must be an integer within [0, 100]");
                mesh->refine_options.optimisation_passes = static_cast<int>(value);
                return CBR_OK;
            case CBR_PARAM_REFINE_SIZE_FROM_SURFACE:
                require(value == 0.0 || value == 1.0, CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_REFINE_SIZE_FROM_SURFACE must be 0 or 1");
                mesh->refine_options.size_from_surface = value != 0.0;
                return CBR_OK;
            case CBR_PARAM_REFINE_GROWTH:
                require(value >= 0 && value <= 100, CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_REFINE_GROWTH must be within [0, 100]");
                mesh->refine_options.growth = value;
                return CBR_OK;
            case CBR_PARAM_RECOVERY_DEEP_FLIPS:
                require(value == 0.0 || value == 1.0, CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_RECOVERY_DEEP_FLIPS must be 0 or 1");
                mesh->recovery_options.deep_flips = value != 0.0;
                return CBR_OK;
            case CBR_PARAM_RECOVERY_RETRIES:
                require(value == 0.0 || value == 1.0, CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_RECOVERY_RETRIES must be 0 or 1");
                mesh->recovery_options.retries = value != 0.0;
                return CBR_OK;
            case CBR_PARAM_THREADS:
                require(value >= 0 && value <= cbr::capi::kMaxThreads && value == std::floor(value),
                        CBR_ERR_INVALID_ARGUMENT,
                        "CBR_PARAM_THREADS must be an integer within [0, " + std::to_string(cbr::capi::kMaxThreads) +
                            "] (0: as many as the hardware runs at once)");
                mesh->threads = static_cast<int>(value);
                return CBR_OK;
            default:
                throw ApiError{CBR_ERR_INVALID_ARGUMENT, "unknown parameter key " + std::to_string(key)};
        }
    });
}

CBR_API int cbr_mesh_get_param(const cbr_mesh* mesh, int key, double* value) {
    return guarded(mesh, "cbr_mesh_get_param", [&] {
        require_mesh(mesh);
        require(value != nullptr, CBR_ERR_INVALID_ARGUMENT, "value is NULL");
        switch (key) {
            case CBR_PARAM_INDEX_BASE: *value = mesh->index_base; return CBR_OK;
            case CBR_PARAM_KEEP_EXTERIOR: *value = mesh->keep_exterior ? 1.0 : 0.0; return CBR_OK;
            case CBR_PARAM_REFINE_SIZE: *value = mesh->refine_options.target_size; return CBR_OK;
            case CBR_PARAM_REFINE_GRADING: *value = mesh->refine_options.grading; return CBR_OK;
            case CBR_PARAM_REFINE_QUALITY_BOUND: *value = mesh->refine_options.quality_bound; return CBR_OK;
            case CBR_PARAM_REFINE_PASSES: *value = mesh->refine_options.optimisation_passes; return CBR_OK;
            case CBR_PARAM_REFINE_SIZE_FROM_SURFACE:
                *value = mesh->refine_options.size_from_surface ? 1.0 : 0.0;
                return CBR_OK;
            case CBR_PARAM_REFINE_GROWTH: *value = mesh->refine_options.growth; return CBR_OK;
            case CBR_PARAM_RECOVERY_DEEP_FLIPS: *value = mesh->recovery_options.deep_flips ? 1.0 : 0.0; return CBR_OK;
            case CBR_PARAM_RECOVERY_RETRIES:
                *value = mesh->recovery_options.retries ? 1.0 : 0.0;
                return CBR_OK;
            case CBR_PARAM_THREADS: *value = mesh->threads; return CBR_OK;
            default: throw ApiError{CBR_ERR_INVALID_ARGUMENT, "unknown parameter key " + std::to_string(key)};
        }
    });
}

CBR_API int cbr_mesh_insert_points(cbr_mesh* mesh, int64_t count, const double* xyz) {
    return guarded(mesh, "cbr_mesh_insert_points", [&] {
        require_mesh(mesh);
        require(count >= 0, CBR_ERR_INVALID_ARGUMENT, "count is negative (" + std::to_string(count) + ")");
        if (count == 0) return CBR_OK;
        require(xyz != nullptr, CBR_ERR_INVALID_ARGUMENT, "xyz is NULL");
        require(!mesh->recovery.done, CBR_ERR_INVALID_ARGUMENT,
                "points cannot be added after cbr_mesh_recover_faces (create a new mesh)");
        const auto existing = static_cast<std::int64_t>(mesh->delaunay.mesh().vertex_count());
        require(count <= static_cast<std::int64_t>(cbr::mesh::kMaxVertices) - existing, CBR_ERR_INVALID_ARGUMENT,
                "too many points: a mesh holds at most 2^31 - 2");
        const std::int64_t first_id = existing + mesh->index_base;
        check_coordinates(xyz, count, first_id);
        const auto start = std::chrono::steady_clock::now();
        const auto outcome = mesh->delaunay.insert_points(xyz, static_cast<std::size_t>(count));
        mesh->delaunay_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!outcome.ok) {
            const double* p = xyz + 3 * (std::int64_t{outcome.duplicate_second} - existing);
            throw ApiError{CBR_ERR_INVALID_INPUT,
                           "points " + std::to_string(outcome.duplicate_first + mesh->index_base) + " and " +
                               std::to_string(outcome.duplicate_second + mesh->index_base) + " are identical " +
                               format_point(p)};
        }
        return CBR_OK;
    });
}

CBR_API int64_t cbr_mesh_point_count(const cbr_mesh* mesh) {
    if (!mesh) return -1;
    return static_cast<int64_t>(cbr::capi::returned_point_count(*mesh));
}

CBR_API int64_t cbr_mesh_tet_count(const cbr_mesh* mesh) {
    if (!mesh) return -1;
    if (!mesh->recovery.done) return static_cast<int64_t>(mesh->delaunay.finite_tet_count());
    int64_t n = 0;
    for (cbr::mesh::TetId t = 0; t < mesh->delaunay.mesh().slot_count(); ++t) n += cbr::capi::is_returned(*mesh, t);
    return n;
}

CBR_API int cbr_mesh_get_points(const cbr_mesh* mesh, double* xyz_out) {
    return guarded(mesh, "cbr_mesh_get_points", [&] {
        require_mesh(mesh);
        const cbr::mesh::TetMesh& m = mesh->delaunay.mesh();
        if (cbr::capi::returned_point_count(*mesh) == 0) return CBR_OK;
        require(xyz_out != nullptr, CBR_ERR_INVALID_ARGUMENT, "xyz_out is NULL");
        for (cbr::mesh::VertexId v = 0; v < m.vertex_count(); ++v) {
            const std::int64_t id = cbr::capi::returned_id(*mesh, v);
            if (id >= 0) std::memcpy(xyz_out + 3 * static_cast<std::size_t>(id), m.point(v), 3 * sizeof(double));
        }
        return CBR_OK;
    });
}

CBR_API int cbr_mesh_get_tets(const cbr_mesh* mesh, int64_t* tets_out) {
    return guarded(mesh, "cbr_mesh_get_tets", [&] {
        require_mesh(mesh);
        const cbr::mesh::TetMesh& m = mesh->delaunay.mesh();
        const std::int64_t base = mesh->index_base;
        std::int64_t* out = tets_out;
        for (cbr::mesh::TetId t = 0; t < m.slot_count(); ++t) {
            if (!cbr::capi::is_returned(*mesh, t)) continue;
            require(tets_out != nullptr, CBR_ERR_INVALID_ARGUMENT, "tets_out is NULL");
            const cbr::mesh::VertexId* v = m.vertices(t);
            for (int i = 0; i < 4; ++i) *out++ = cbr::capi::returned_id(*mesh, v[i]) + base;  // returned: never -1
        }
        return CBR_OK;
    });
}

}  // extern "C"
