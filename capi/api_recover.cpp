// extern "C" boundary recovery: cbr_mesh_recover_faces and the queries of
// its results (Steiner points, regions, Table I statistics).
#include <cbr/cbr.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "handle.hpp"

using cbr::capi::ApiError;
using cbr::capi::guarded;
using cbr::capi::require;

namespace {

// "triangles 3, 17 and 40 (and 12 more)" in the caller's index base.
std::string name_triangles(const std::vector<std::size_t>& tris, int base) {
    std::string s = tris.size() == 1 ? "triangle " : "triangles ";
    const std::size_t shown = std::min<std::size_t>(tris.size(), 10);
    for (std::size_t i = 0; i < shown; ++i) {
        if (i > 0) s += i + 1 == shown && shown == tris.size() ? " and " : ", ";
        s += std::to_string(tris[i] + static_cast<std::size_t>(base));
    }
    if (tris.size() > shown) s += " (and " + std::to_string(tris.size() - shown) + " more)";
    return s;
}

// The input triangles in internal vertex ids (after the surface check, so
// every id is valid).
cbr::recover::ConstraintFaces constraint_faces(const cbr_mesh& h, std::int64_t count, const std::int64_t* tris,
                                               const std::int32_t* labels) {
    std::vector<cbr::recover::Triangle> internal(static_cast<std::size_t>(count));
    for (std::size_t i = 0; i < internal.size(); ++i)
        for (int k = 0; k < 3; ++k)
            internal[i][k] = h.delaunay.internal_id(static_cast<cbr::mesh::VertexId>(tris[3 * i + k] - h.index_base));
    std::vector<std::int32_t> label_list;
    if (labels) label_list.assign(labels, labels + count);
    return cbr::recover::ConstraintFaces(std::move(internal), std::move(label_list));
}

// One attempt of recovery from the Delaunay mesh as it is now, from the
// flip state `state` (its budget 0: the caller's; another budget also
// tries only the plain unblocking points, kRetryUnblockingTries); a retry
// (`first_present` null) leaves out the last unblocking try
// (kRetryLastUnblockingTries). The first attempt gets the facets the
// surface check found the triangles at, in this very mesh
// (recover_faces' `present`). The flips may run again from the Delaunay
// mesh (recovery.cpp, kFlipRestartShare): rebuild() gives it back, bit
// for bit.
cbr::recover::RecoveryResult attempt(cbr_mesh& mesh, const cbr::recover::ConstraintFaces& faces,
                                     const cbr::recover::FlipState& state,
                                     const std::vector<cbr::mesh::FacetRef>* first_present,
                                     cbr::recover::RecoveryStats& stats) {
    const bool first = first_present != nullptr;
    cbr::recover::RecoveryOptions options = mesh.recovery_options;
    options.nested_order = state.nested;
    options.threads = cbr::capi::thread_count(mesh);
    if (!first) options.unblocking_tries = std::min(options.unblocking_tries, cbr::recover::kRetryLastUnblockingTries);
    if (state.deepest_budget != 0) {
        options.deepest_flip_budget = state.deepest_budget;
        options.unblocking_tries = std::min(options.unblocking_tries, cbr::recover::kRetryUnblockingTries);
    }
    const std::function<void()> delaunay_again = [&mesh] { mesh.delaunay.rebuild(); };
    return cbr::recover::recover_faces(mesh.delaunay.mesh_for_update(), faces, stats, options, delaunay_again,
                                       first_present);
}

// The corners of a cube around every point of m, centred on their
// bounding box, its half side twice the box's largest half side: each
// corner at least that half side beyond the points in every coordinate.
std::vector<double> enclosing_box(const cbr::mesh::TetMesh& m) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = m.point(0)[k];
    for (cbr::mesh::VertexId v = 1; v < m.vertex_count(); ++v)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], m.point(v)[k]);
            hi[k] = std::max(hi[k], m.point(v)[k]);
        }
    double half = 0;
    for (int k = 0; k < 3; ++k) half = std::max(half, (hi[k] - lo[k]) / 2);
    std::vector<double> corners;
    for (int i = 0; i < 8; ++i)
        for (int k = 0; k < 3; ++k) corners.push_back((lo[k] + hi[k]) / 2 + ((i >> k & 1) ? 2 : -2) * half);
    return corners;
}

// The attempts of cbr_mesh_recover_faces, until one recovers every face
// (or breaks an invariant, which ends them):
//   1. on the Delaunay mesh of the caller's points, with the options as
//      they are;
//   then, with options.retries,
//   2. inside an enclosing box: the same with the corners of
//      enclosing_box() added, so that every input triangle is interior to
//      the mesh, away from its convex hull;
//   3. on the Delaunay mesh again from other flip states (FlipState), all
//      with the nested removals in ring order: the options' budget (where
//      the options have the blocking vertices first), then each of
//      kRetryFlipBudgets (where the deepest round runs with its default
//      budget: options.deep_flips, no deepest_flip_budget);
//   4. those flip states inside the box.
// The flips decide the mesh that conforming recovery and point splitting
// start from. Where those fail (rounded points between nearly coplanar
// faces of a surface turned in space) they fail in one flip state and not
// in another, with no budget better than the others (turned fan-cap
// prisms and CAD parts: each budget from 5,000 to 80,000 recovers some
// failures and not others). Surfaces with nearly planar faces on the hull
// (a turned CAD cylinder's fanned caps: the flat layer between them and
// the hull leaves no room for the points that split them) recover inside
// the box, and they are most of the first attempt's failures: of the 36
// shared surfaces other than the feeder body, as given and turned by
// rotate_surface.py seeds 1-4, 8 of 180 fail the first attempt; the box
// recovers all 8, the other budgets 1. So the box comes second.
//
// Returns the successful attempt's result, its statistics in `stats`;
// `corners` then lists the box's eight corners if it was used: they follow
// the caller's points and count as Steiner points (outside every bounded
// region). On failure, the first attempt's result and statistics, its
// reason naming the attempts after it; the caller rebuilds the Delaunay
// mesh.
cbr::recover::RecoveryResult recover_in_attempts(cbr_mesh& mesh, const cbr::recover::ConstraintFaces& faces,
                                                 const std::vector<cbr::mesh::FacetRef>& present,
                                                 cbr::recover::RecoveryStats& stats,
                                                 std::vector<cbr::mesh::VertexId>& corners) {
    const cbr::recover::RecoveryOptions& options = mesh.recovery_options;
    // The box around the caller's points (the mesh holds only them now);
    // its corners would follow them.
    const std::vector<double> box = enclosing_box(mesh.delaunay.mesh());
    const auto box_first = static_cast<cbr::mesh::VertexId>(mesh.delaunay.mesh().vertex_count());
    const cbr::recover::FlipState as_given{0, options.nested_order};
    cbr::recover::RecoveryResult first = attempt(mesh, faces, as_given, &present, stats);
    if (first.ok || !first.invalid.empty() || !options.retries) return first;
    std::optional<std::string> boxed_why;  // the first boxed attempt's reason, for the message
    // An attempt that ends the attempts (a success, or a broken invariant)
    // becomes `first`; true then.
    const auto ends = [&](cbr::recover::RecoveryResult& r, const cbr::recover::RecoveryStats& attempt_stats) {
        if (!r.ok && r.invalid.empty()) return false;
        stats = attempt_stats;
        first = std::move(r);
        return true;
    };
    using States = std::vector<cbr::recover::FlipState>;
    // Attempts from `states` on the Delaunay mesh of the caller's points,
    // each from that mesh built anew.
    const auto outside = [&](const States& states) {
        for (const cbr::recover::FlipState& state : states) {
            mesh.delaunay.rebuild();
            cbr::recover::RecoveryStats attempt_stats;
            cbr::recover::RecoveryResult r = attempt(mesh, faces, state, nullptr, attempt_stats);
            if (ends(r, attempt_stats)) return true;
        }
        return false;
    };
    // Attempts from `states` with the box's corners added: the first, when
    // its budget is the options' own, from the mesh they were inserted in,
    // the others from the mesh built anew with them, like every retry. The
    // corners stay for a success and go otherwise.
    const auto inside = [&](const States& states) {
        mesh.delaunay.rebuild();
        if (!mesh.delaunay.insert_points(box.data(), 8).ok) return false;  // restored by insert_points
        bool inserted = true;  // the mesh is the one the corners were inserted in
        for (const cbr::recover::FlipState& state : states) {
            if (!inserted || state.deepest_budget != 0) mesh.delaunay.rebuild();
            inserted = false;
            cbr::recover::RecoveryStats attempt_stats;
            cbr::recover::RecoveryResult r = attempt(mesh, faces, state, nullptr, attempt_stats);
            if (r.ok) {
                ends(r, attempt_stats);
                stats.steiner_generated += 8;
                stats.steiner_remaining += 8;
                for (cbr::mesh::VertexId v = box_first; v < box_first + 8; ++v) corners.push_back(v);
                return true;
            }
            if (!boxed_why) boxed_why = r.why;
            if (ends(r, attempt_stats)) break;  // a broken invariant: the corners go too
        }
        mesh.delaunay.drop_last_batch();
        return !first.invalid.empty();
    };
    // The retries are the flip states of the attempts before session 33,
    // all in ring order (FlipState), after the caller's own state in ring
    // order when it is not.
    constexpr cbr::recover::NestedOrder ring = cbr::recover::NestedOrder::kRing;
    States retry_states;
    if (as_given.nested != ring) retry_states.push_back({0, ring});
    if (options.deep_flips && options.deepest_flip_budget == 0)  // the deepest round runs with its default budget
        for (const int budget : cbr::recover::kRetryFlipBudgets) retry_states.push_back({budget, ring});
    if (inside({as_given}) || outside(retry_states) || (!retry_states.empty() && inside(retry_states))) return first;
    const std::string others =
        retry_states.empty() ? "" : " (and from " + std::to_string(retry_states.size()) + " other flip states)";
    first.why += others;
    if (boxed_why) first.why += " (and inside an enclosing box: " + *boxed_why + others + ")";
    return first;
}

// CBR_STAT_STEINER_INSIDE: the Steiner points that some tetrahedron of a
// bounded region (region > 0) uses (InteriorPoints numbers them); 0
// before recovery.
std::size_t steiner_inside(const cbr_mesh& h) {
    const std::vector<cbr::mesh::VertexId>& steiner = h.recovery.steiner;
    return static_cast<std::size_t>(std::count_if(steiner.begin(), steiner.end(), [&](cbr::mesh::VertexId v) {
        return cbr::capi::interior_id(h, v) >= 0;
    }));
}

}  // namespace

cbr::capi::InteriorPoints cbr::capi::interior_points(const cbr_mesh& h, std::size_t caller,
                                                     const std::vector<std::int32_t>& regions) {
    const cbr::mesh::TetMesh& m = h.delaunay.mesh();
    InteriorPoints p;
    p.caller = caller;
    p.added.assign(m.vertex_count() - caller, -1);
    for (cbr::mesh::TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t) || m.is_ghost(t) || regions[t] <= 0) continue;
        for (int i = 0; i < 4; ++i) {
            const std::size_t id = h.delaunay.external_id(m.vertex(t, i));
            if (id >= caller) p.added[id - caller] = 0;  // used; numbered below
        }
    }
    p.count = caller;
    for (std::int64_t& id : p.added)
        if (id == 0) id = static_cast<std::int64_t>(p.count++);
    return p;
}

extern "C" {

CBR_API int cbr_mesh_recover_faces(cbr_mesh* mesh, int64_t count, const int64_t* tris, const int32_t* labels) {
    return guarded(mesh, "cbr_mesh_recover_faces", [&] {
        require(mesh != nullptr, CBR_ERR_INVALID_ARGUMENT, "mesh is NULL");
        require(!mesh->recovery.done, CBR_ERR_INVALID_ARGUMENT, "the faces of this mesh were recovered already");
        require(count >= 0, CBR_ERR_INVALID_ARGUMENT, "count is negative (" + std::to_string(count) + ")");
        require(count == 0 || tris != nullptr, CBR_ERR_INVALID_ARGUMENT, "tris is NULL");
        // The same exact checks as cbr_mesh_check_faces, before any change.
        std::vector<cbr::mesh::FacetRef> present;  // per triangle: its facet in the mesh now
        try {
            cbr::capi::check_faces(mesh, count, tris, present);
        } catch (const ApiError& e) {
            throw ApiError{CBR_ERR_INVALID_INPUT, "invalid surface: " + e.message};
        }
        require(mesh->delaunay.finite_tet_count() > 0, CBR_ERR_INVALID_INPUT,
                "there is no volume to recover faces in: the points are all coplanar (or fewer than 4)");
        const auto start = std::chrono::steady_clock::now();
        const std::size_t caller_points = mesh->delaunay.mesh().vertex_count();  // only the caller's, so far
        cbr::capi::RecoveryState state;
        state.faces = constraint_faces(*mesh, count, tris, labels);
        std::vector<cbr::mesh::VertexId> box_corners;
        cbr::recover::RecoveryResult result =
            recover_in_attempts(*mesh, state.faces, present, state.stats, box_corners);
        if (!result.ok) {
            mesh->delaunay.rebuild();  // the mesh stays as it was
            // The statistics of the attempt stay readable (Table I rows).
            mesh->recovery.stats = state.stats;
            mesh->recovery.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (!result.invalid.empty())
                throw ApiError{CBR_ERR_INTERNAL, "recovery left an invalid mesh: " + result.invalid.front()};
            throw ApiError{CBR_ERR_RECOVERY_FAILED,
                           "could not recover " + name_triangles(result.unrecovered, mesh->index_base) + " of " +
                               std::to_string(count) + " (" + std::to_string(state.stats.missing_faces) +
                               " missing after Delaunay): " + result.why};
        }
        // Steiner points follow the caller's points in both numberings.
        mesh->delaunay.adopt_added_vertices();
        state.steiner = box_corners;
        state.steiner.insert(state.steiner.end(), result.steiner.begin(), result.steiner.end());
        state.regions = cbr::recover::classify_regions(mesh->delaunay.mesh(), state.faces);
        state.interior = cbr::capi::interior_points(*mesh, caller_points, state.regions.of_tet);
        state.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        state.done = true;
        mesh->recovery = std::move(state);
        return CBR_OK;
    });
}

CBR_API int64_t cbr_mesh_steiner_count(const cbr_mesh* mesh) {
    if (!mesh) return -1;
    const auto& steiner = mesh->recovery.steiner;
    return std::count_if(steiner.begin(), steiner.end(),
                         [&](cbr::mesh::VertexId v) { return cbr::capi::returned_id(*mesh, v) >= 0; });
}

CBR_API int cbr_mesh_steiner_points(const cbr_mesh* mesh, int64_t* ids_out) {
    return guarded(mesh, "cbr_mesh_steiner_points", [&] {
        require(mesh != nullptr, CBR_ERR_INVALID_ARGUMENT, "mesh is NULL");
        for (cbr::mesh::VertexId v : mesh->recovery.steiner) {
            const std::int64_t id = cbr::capi::returned_id(*mesh, v);
            if (id < 0) continue;  // the exterior's, left out
            require(ids_out != nullptr, CBR_ERR_INVALID_ARGUMENT, "ids_out is NULL");
            *ids_out++ = id + mesh->index_base;
        }
        return CBR_OK;
    });
}

CBR_API int cbr_mesh_get_tet_regions(const cbr_mesh* mesh, int32_t* regions_out) {
    return guarded(mesh, "cbr_mesh_get_tet_regions", [&] {
        require(mesh != nullptr, CBR_ERR_INVALID_ARGUMENT, "mesh is NULL");
        const cbr::mesh::TetMesh& m = mesh->delaunay.mesh();
        for (cbr::mesh::TetId t = 0; t < m.slot_count(); ++t) {
            if (!cbr::capi::is_returned(*mesh, t)) continue;
            require(regions_out != nullptr, CBR_ERR_INVALID_ARGUMENT, "regions_out is NULL");
            *regions_out++ = mesh->recovery.done ? mesh->recovery.regions.of_tet[t] : 0;
        }
        return CBR_OK;
    });
}

CBR_API int cbr_mesh_get_stat(const cbr_mesh* mesh, int key, double* value) {
    return guarded(mesh, "cbr_mesh_get_stat", [&] {
        require(mesh != nullptr, CBR_ERR_INVALID_ARGUMENT, "mesh is NULL");
        require(value != nullptr, CBR_ERR_INVALID_ARGUMENT, "value is NULL");
        const cbr::capi::RecoveryState& r = mesh->recovery;
        const auto count = [](std::size_t n) { return static_cast<double>(n); };
        switch (key) {
            case CBR_STAT_TOTAL_VERTICES: *value = count(mesh->delaunay.mesh().vertex_count()); break;
            case CBR_STAT_BOUNDARY_VERTICES: *value = r.done ? count(r.faces.vertex_count()) : 0.0; break;
            case CBR_STAT_MISSING_FACES: *value = count(r.stats.missing_faces); break;
            case CBR_STAT_FACES_RECOVERED_BY_FLIPS: *value = count(r.stats.recovered_by_flips); break;
            case CBR_STAT_CONFORMING_POINTS: *value = count(r.stats.conforming_points); break;
            case CBR_STAT_STEINER_GENERATED: *value = count(r.stats.steiner_generated); break;
            case CBR_STAT_STEINER_REMAINING: *value = count(r.stats.steiner_remaining); break;
            case CBR_STAT_DELAUNAY_SECONDS: *value = mesh->delaunay_seconds; break;
            case CBR_STAT_RECOVERY_SECONDS: *value = r.seconds; break;
            case CBR_STAT_TOTAL_SECONDS: *value = mesh->delaunay_seconds + r.seconds; break;
            case CBR_STAT_REGION_COUNT: *value = r.done ? r.regions.count : 0; break;
            case CBR_STAT_STEINER_INSIDE: *value = count(steiner_inside(*mesh)); break;
            default:
                if (cbr::capi::refine_stat(*mesh, key, *value)) break;
                throw ApiError{CBR_ERR_INVALID_ARGUMENT, "unknown statistic key " + std::to_string(key)};
        }
        return CBR_OK;
    });
}

}  // extern "C"
