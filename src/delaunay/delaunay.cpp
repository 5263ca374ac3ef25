#include "delaunay/delaunay.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "delaunay/spatial_sort.hpp"
#include "mesh/huge_pages.hpp"
#include "mesh/large_array.hpp"

namespace cbr::delaunay {

using mesh::kGhostVertex;
using mesh::VertexId;

namespace {

// Expected tetrahedra per point of a 3D Delaunay tetrahedralization of
// uniformly distributed points is about 6.7; reserving a little more keeps
// reallocation (and its transient doubling of memory) rare.
constexpr std::size_t kTetsPerPointReserve = 7;

// Among points [0, n), which have no tetrahedron yet, two with identical
// coordinates, found by sorting; outcome is left alone if there are none.
void find_duplicate(const mesh::TetMesh& m, std::size_t n, InsertOutcome& outcome) {
    std::vector<VertexId> ids(n);
    std::iota(ids.begin(), ids.end(), VertexId{0});
    std::sort(ids.begin(), ids.end(), [&](VertexId a, VertexId b) {
        const int c = geom::lexicographic_compare(m.point(a), m.point(b));
        return c < 0 || (c == 0 && a < b);
    });
    for (std::size_t i = 1; i < ids.size(); ++i)
        if (geom::same_point(m.point(ids[i - 1]), m.point(ids[i]))) {
            outcome = {false, std::min(ids[i - 1], ids[i]), std::max(ids[i - 1], ids[i])};
            return;
        }
}

}  // namespace

Delaunay::Delaunay() : kernel_(mesh_, &counters_) {}

std::size_t Delaunay::finite_tet_count() const {
    std::size_t n = 0;
    for (mesh::TetId t = 0; t < mesh_.slot_count(); ++t)
        if (!mesh_.is_free(t) && !mesh_.is_ghost(t)) ++n;
    return n;
}

InsertOutcome Delaunay::insert_points(const double* xyz, std::size_t count) {
    const std::size_t before = mesh_.vertex_count();
    InsertOutcome outcome;
    try {
        store_batch(xyz, count);
        outcome = insert_batch(static_cast<VertexId>(before), mesh_.vertex_count());
    } catch (...) {
        discard_vertices_from(before);
        rebuild();
        throw;
    }
    if (!outcome.ok) {
        const VertexId a = external_of_[outcome.duplicate_first], b = external_of_[outcome.duplicate_second];
        outcome.duplicate_first = std::min(a, b);
        outcome.duplicate_second = std::max(a, b);
        discard_vertices_from(before);
        rebuild();
        return outcome;
    }
    if (count > 0) batch_ends_.push_back(mesh_.vertex_count());
    return outcome;
}

void Delaunay::store_batch(const double* xyz, std::size_t count) {
    const std::size_t before = mesh_.vertex_count();
    if (count > mesh::kMaxVertices - before) throw std::length_error("too many points");
    std::vector<VertexId> order;
    mesh::resize_huge(order, count);
    std::iota(order.begin(), order.end(), VertexId{0});
    brio_sort(xyz, order, 0xC0FFEEull + count);
    mesh::LargeArray<double> sorted(3 * count);
    for (std::size_t k = 0; k < count; ++k)
        for (int c = 0; c < 3; ++c) sorted[3 * k + c] = xyz[3 * std::size_t{order[k]} + c];
    external_of_.reserve(before + count);
    internal_of_.resize(before + count);
    mesh_.add_points(sorted.data(), count);
    for (std::size_t k = 0; k < count; ++k) {
        const auto external = static_cast<VertexId>(before + order[k]);
        external_of_.push_back(external);
        internal_of_[external] = static_cast<VertexId>(before + k);
    }
}

void Delaunay::discard_vertices_from(std::size_t count) {
    mesh_.truncate_vertices(count);
    if (external_of_.size() > count) external_of_.resize(count);
    if (internal_of_.size() > count) internal_of_.resize(count);
}

bool Delaunay::start_triangulation(std::size_t n, std::vector<VertexId>& rest, InsertOutcome& outcome) {
    // i0 = 0; i1: first point distinct from it; i2: first not on their
    // line; i3: first not in their plane. Skipped points are inserted later.
    VertexId pick[4] = {0, 0, 0, 0};
    std::size_t found = n > 0 ? 1 : 0;
    for (VertexId v = 1; v < n && found < 4; ++v) {
        const double* p = mesh_.point(v);
        bool independent = false;
        if (found == 1) independent = !geom::same_point(mesh_.point(pick[0]), p);
        if (found == 2) independent = !geom::collinear(mesh_.point(pick[0]), mesh_.point(pick[1]), p);
        if (found == 3)
            independent = geom::orient3d(mesh_.point(pick[0]), mesh_.point(pick[1]), mesh_.point(pick[2]), p) != 0;
        if (independent) pick[found++] = v;
    }
    if (found < 4) {
        // No tetrahedron yet (fewer than 4 points, or all coplanar); the
        // points wait for a later batch, but duplicates are reported now.
        find_duplicate(mesh_, n, outcome);
        return false;
    }
    if (geom::orient3d(mesh_.point(pick[0]), mesh_.point(pick[1]), mesh_.point(pick[2]), mesh_.point(pick[3])) < 0)
        std::swap(pick[0], pick[1]);
    kernel_.build_first_tet(pick[0], pick[1], pick[2], pick[3]);
    rest.clear();
    for (VertexId v = 0; v < n; ++v)
        if (v != pick[0] && v != pick[1] && v != pick[2] && v != pick[3]) rest.push_back(v);
    return true;
}

InsertOutcome Delaunay::insert_batch(VertexId first, std::size_t end) {
    InsertOutcome outcome;
    std::vector<VertexId> order;
    if (mesh_.live_count() == 0) {
        if (!start_triangulation(end, order, outcome)) return outcome;
    } else {
        order.resize(end - first);
        std::iota(order.begin(), order.end(), first);
    }
    mesh_.reserve_tets(kTetsPerPointReserve * end + 64);
    // The seed depends on the batch only, so a replay draws the same walk.
    kernel_.set_seed(0x9E3779B97F4A7C15ull ^ (std::uint64_t{first} << 20) ^ order.size());
    // Internal ids already follow the BRIO order (store_batch).
    for (VertexId v : order) {
        const VertexId twin = kernel_.insert(v);
        if (twin != kGhostVertex) return {false, std::min(v, twin), std::max(v, twin)};
    }
    return outcome;
}

void Delaunay::adopt_added_vertices() {
    const std::size_t n = mesh_.vertex_count();
    // Added points may also have been dropped since (a Steiner point
    // suppressed by refinement, the ids after it closed up): the
    // numberings end where the mesh's points end. The caller's points
    // (before the last batch end) are never dropped.
    const std::size_t first_added = batch_ends_.empty() ? 0 : batch_ends_.back();
    if (n >= first_added && external_of_.size() > n) {
        external_of_.resize(n);
        internal_of_.resize(n);
    }
    for (std::size_t v = external_of_.size(); v < n; ++v) {
        external_of_.push_back(static_cast<VertexId>(v));
        internal_of_.push_back(static_cast<VertexId>(v));
    }
}

void Delaunay::drop_last_batch() {
    if (!batch_ends_.empty()) batch_ends_.pop_back();
    rebuild();
}

void Delaunay::rebuild() {
    discard_vertices_from(batch_ends_.empty() ? 0 : batch_ends_.back());
    mesh_.clear_tets();
    kernel_.set_hint(0);
    std::size_t first = 0;
    for (std::size_t end : batch_ends_) {
        insert_batch(static_cast<VertexId>(first), end);
        first = end;
    }
}

}  // namespace cbr::delaunay
