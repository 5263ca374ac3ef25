#include "refine/refine_context.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "delaunay/spatial_sort.hpp"
#include "refine/tet_measures.hpp"

namespace cbr::refine {

RefineContext::RefineContext(mesh::TetMesh& mesh, const recover::ConstraintFaces& faces,
                             std::vector<std::int32_t> region, const std::vector<mesh::VertexId>& movable,
                             const RefineOptions& opts)
    : m(mesh), options(opts), size(mesh, faces, opts), faces_(faces), region_(std::move(region)) {
    surface_vertex_.assign(m.vertex_count(), 0);
    movable_.assign(m.vertex_count(), 0);
    for (mesh::VertexId v : movable)
        if (v < movable_.size()) movable_[v] = 1;
    reach_.assign(m.vertex_count(), 0);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const recover::Triangle& t = faces.triangle(i);
        Point centre;
        double r2 = 0;
        const double r = triangle_circumsphere(m.point(t[0]), m.point(t[1]), m.point(t[2]), centre, r2)
                             ? std::sqrt(r2) : 0;
        for (int k = 0; k < 3; ++k) {
            surface_vertex_[t[k]] = 1;
            reach_[t[k]] = std::max(reach_[t[k]], r);
        }
    }
}

void RefineContext::reorder_tets() {
    std::vector<mesh::TetId> live;
    std::vector<double> centroids;
    live.reserve(m.live_count());
    centroids.reserve(3 * m.live_count());
    for (mesh::TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        const int corners = m.is_ghost(t) ? 3 : 4;
        for (int k = 0; k < 3; ++k) {
            double sum = 0;
            for (int i = 0; i < corners; ++i) sum += m.point(m.vertex(t, i))[k];
            centroids.push_back(sum / corners);
        }
        live.push_back(t);
    }
    std::vector<mesh::TetId> order(live.size());
    std::vector<std::int32_t> region(live.size());
    std::vector<std::uint32_t> stamp(live.size());
    const std::vector<std::size_t> along = delaunay::hilbert_order(centroids.data(), live.size());
    for (std::size_t i = 0; i < along.size(); ++i) {
        const mesh::TetId t = live[along[i]];
        order[i] = t;
        region[i] = this->region(t);
        stamp[i] = t < stamp_.size() ? stamp_[t] : 0;
    }
    m.reorder_tets(order);
    region_.swap(region);
    stamp_.swap(stamp);
}

void RefineContext::set_region(mesh::TetId t, std::int32_t r) {
    if (t >= region_.size()) region_.resize(std::max<std::size_t>(t + 1, region_.size() * 3 / 2), -1);
    region_[t] = r;
    touch(t);
}

bool RefineContext::changed_near_since(mesh::TetId t, std::uint32_t pass) const {
    if (changed_since(t, pass)) return true;
    for (int f = 0; f < 4; ++f)
        if (changed_since(mesh::facet_tet(m.neighbor(t, f)), pass)) return true;
    return false;
}

void RefineContext::touch(mesh::TetId t) {
    if (t >= stamp_.size()) stamp_.resize(std::max<std::size_t>(t + 1, stamp_.size() * 3 / 2), 0);
    stamp_[t] = pass_;
}

bool RefineContext::is_surface_edge(mesh::VertexId a, mesh::VertexId b) const { return faces_.has_edge(a, b); }

double RefineContext::edge_size(mesh::VertexId a, mesh::VertexId b) const {
    const double mean = 0.5 * (size.at(a) + size.at(b));
    const bool sa = is_surface_vertex(a), sb = is_surface_vertex(b);
    // An edge between two surface vertices that is not an input edge
    // crosses the interior: the interior rule applies along it (H caps it),
    // and it can always be split (its midpoint is inside the region).
    if (sa && sb) return size.interior(mean);
    // An edge from a surface vertex u into the interior: no point can be
    // closer to all three corners of an input triangle than its
    // circumradius, so the bound never asks less than that (the surface is
    // never split; §6, "the surface mesh should conform with the sizing
    // field").
    if (sa) return std::max(mean, kSurfaceReach * reach_[a] / kEdgeFactor);
    if (sb) return std::max(mean, kSurfaceReach * reach_[b] / kEdgeFactor);
    return mean;
}

bool RefineContext::edge_within_size(mesh::VertexId a, mesh::VertexId b) const {
    const double bound = kEdgeFactor * edge_size(a, b);
    if (squared_distance(m.point(a), m.point(b)) <= bound * bound) return true;
    return is_surface_edge(a, b);
}

bool RefineContext::edge_within_size(mesh::VertexId a, mesh::VertexId b, double limit2) const {
    return edge_within_size(a, b) || squared_distance(m.point(a), m.point(b)) <= limit2;
}

bool RefineContext::tet_within_size(mesh::TetId t) const {
    const mesh::VertexId* v = m.vertices(t);
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
            if (!edge_within_size(v[i], v[j])) return false;
    return true;
}

}  // namespace cbr::refine
