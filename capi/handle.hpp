// The object behind the opaque cbr_mesh handle, and the exception firewall
// every extern "C" function runs its body in.
#pragma once

#include <cbr/cbr.h>

#include <algorithm>
#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "delaunay/delaunay.hpp"
#include "mesh/errors.hpp"
#include "recover/constraint_faces.hpp"
#include "recover/recovery.hpp"
#include "recover/regions.hpp"
#include "recover/surface_check.hpp"
#include "refine/quality_stats.hpp"
#include "refine/refine_options.hpp"

namespace cbr::capi {

// The largest CBR_PARAM_THREADS.
constexpr int kMaxThreads = 256;

// How the getters number the points after recovery when the exterior is
// left out (CBR_PARAM_KEEP_EXTERIOR = 0): the caller's points keep their
// ids; of the points added after them (Steiner points, then field
// points), those that a tetrahedron of a bounded region uses follow in
// their order, and those only the exterior used (Steiner points outside
// the domain, the corners of an enclosing box) are left out.
struct InteriorPoints {
    std::size_t caller = 0;           // the caller's points: ids [0, caller)
    std::vector<std::int64_t> added;  // per added point, by external id - caller: its id, or -1 (left out)
    std::size_t count = 0;            // points the getters return
};

// What cbr_mesh_recover_faces leaves behind.
struct RecoveryState {
    bool done = false;
    InteriorPoints interior;  // recomputed by cbr_mesh_refine
    cbr::recover::ConstraintFaces faces;
    cbr::recover::RegionMap regions;
    cbr::recover::RecoveryStats stats;
    double seconds = 0;
    std::vector<cbr::mesh::VertexId> steiner;  // internal ids
};

// What cbr_mesh_refine leaves behind (its options live in the handle).
struct RefineState {
    bool done = false;
    cbr::refine::RefineStats stats;
    cbr::refine::QualityTable quality;
    std::vector<cbr::refine::QualityTable> region_quality;  // by region (0: the exterior, all zero)
    double seconds = 0;
};

// Serves the CBR_STAT_* keys of refinement (api_refine.cpp); false for a
// key that is not one of them.
bool refine_stat(const cbr_mesh& mesh, int key, double& value);

}  // namespace cbr::capi

struct cbr_mesh {
    cbr::delaunay::Delaunay delaunay;
    int index_base = 0;
    bool keep_exterior = false;
    // CBR_PARAM_THREADS as set: 0 = as many as the hardware runs at once
    // (thread_count() resolves it).
    int threads = 1;
    double delaunay_seconds = 0;
    cbr::recover::RecoveryOptions recovery_options;
    cbr::capi::RecoveryState recovery;
    cbr::refine::RefineOptions refine_options;
    cbr::capi::RefineState refine;
    // Report of the last cbr_mesh_check_faces that ran its checks (whatever
    // it found); ids 0-based. A call refused on its arguments keeps it.
    cbr::recover::SurfaceCheckResult last_check;
    // Message of the last failed call; mutable so that const queries can
    // report their own failures.
    mutable std::string last_error;
};

namespace cbr::capi {

// An error found by an argument or input check: status and message.
struct ApiError {
    int status;
    std::string message;
};

inline int fail(const cbr_mesh* mesh, const char* function, int status, const std::string& message) {
    if (mesh) {
        try {
            mesh->last_error = std::string(function) + ": " + message;
        } catch (...) {
            // No memory even for the message: keep the previous one.
        }
    }
    return status;
}

// Runs body() (returning a status) so that no exception leaves the library.
template <class Body>
int guarded(const cbr_mesh* mesh, const char* function, Body&& body) noexcept {
    try {
        return body();
    } catch (const ApiError& e) {
        return fail(mesh, function, e.status, e.message);
    } catch (const std::bad_alloc&) {
        return fail(mesh, function, CBR_ERR_OUT_OF_MEMORY, "out of memory");
    } catch (const std::length_error& e) {
        return fail(mesh, function, CBR_ERR_OUT_OF_MEMORY, std::string("capacity exceeded: ") + e.what());
    } catch (const cbr::InternalError& e) {
        return fail(mesh, function, CBR_ERR_INTERNAL, std::string("internal error: ") + e.what());
    } catch (const std::exception& e) {
        return fail(mesh, function, CBR_ERR_INTERNAL, std::string("internal error: ") + e.what());
    } catch (...) {
        return fail(mesh, function, CBR_ERR_INTERNAL, "internal error: unknown exception");
    }
}

inline void require(bool condition, int status, const std::string& message) {
    if (!condition) throw ApiError{status, message};
}

// A literal message becomes a std::string only when the check fails: the
// getters check their output pointer once per element they write, and a
// message longer than the short-string buffer cost a heap allocation each
// time (igea after recovery: 240 million instructions in
// cbr_mesh_get_tets and cbr_mesh_get_tet_regions for its 472,739
// tetrahedra).
inline void require(bool condition, int status, const char* message) {
    if (!condition) throw ApiError{status, message};
}

// cbr_mesh_check_faces' checks (api_check.cpp), for it and for
// cbr_mesh_recover_faces: throws ApiError (CBR_ERR_INVALID_INPUT with the
// report's message) when the triangles cannot be recovered, and keeps the
// report in mesh->last_check; `facets` gets, per triangle, the facet of
// the mesh that holds it or recover::kNoFacet (recovery marks those
// without looking for them again).
void check_faces(cbr_mesh* mesh, std::int64_t count, const std::int64_t* tris,
                 std::vector<cbr::mesh::FacetRef>& facets);

// The threads CBR_PARAM_THREADS allows: as set, or for 0 as many as the
// hardware runs at once (at least 1).
inline int thread_count(const cbr_mesh& h) {
    if (h.threads > 0) return h.threads;
    const unsigned hardware = std::thread::hardware_concurrency();
    return hardware > 0 ? static_cast<int>(std::min(hardware, unsigned{kMaxThreads})) : 1;
}

// The numbering above for the mesh as it is, its bounded regions as
// `regions` gives them (api_recover.cpp).
InteriorPoints interior_points(const cbr_mesh& h, std::size_t caller, const std::vector<std::int32_t>& regions);

// Whether the getters leave the exterior out (after recovery, unless
// CBR_PARAM_KEEP_EXTERIOR is set).
inline bool drops_exterior(const cbr_mesh& h) { return h.recovery.done && !h.keep_exterior; }

// After recovery: the id (0-based) of internal vertex v in the numbering
// of InteriorPoints, or -1 when only the exterior uses it.
inline std::int64_t interior_id(const cbr_mesh& h, cbr::mesh::VertexId v) {
    const std::int64_t id = h.delaunay.external_id(v);
    const InteriorPoints& p = h.recovery.interior;
    const auto caller = static_cast<std::int64_t>(p.caller);
    return id < caller ? id : p.added[static_cast<std::size_t>(id - caller)];
}

// The id (0-based) the getters give internal vertex v, or -1 when they
// leave it out.
inline std::int64_t returned_id(const cbr_mesh& h, cbr::mesh::VertexId v) {
    return drops_exterior(h) ? interior_id(h, v) : std::int64_t{h.delaunay.external_id(v)};
}

// How many points the getters return.
inline std::size_t returned_point_count(const cbr_mesh& h) {
    return drops_exterior(h) ? h.recovery.interior.count : h.delaunay.mesh().vertex_count();
}

// The tetrahedra the getters return: finite ones; after recovery only those
// of bounded regions, unless CBR_PARAM_KEEP_EXTERIOR is set.
inline bool is_returned(const cbr_mesh& h, cbr::mesh::TetId t) {
    const cbr::mesh::TetMesh& m = h.delaunay.mesh();
    if (m.is_free(t) || m.is_ghost(t)) return false;
    if (!h.recovery.done || h.keep_exterior) return true;
    return h.recovery.regions.of_tet[t] > 0;
}

}  // namespace cbr::capi
