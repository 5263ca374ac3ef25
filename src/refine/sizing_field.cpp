#include "refine/sizing_field.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "refine/tet_measures.hpp"

namespace cbr::refine {
namespace {

using mesh::TetId;
using mesh::VertexId;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Mean length of the input edges at each surface vertex (+inf elsewhere);
// each edge counted once per endpoint even when shared by two triangles.
std::vector<double> surface_sizes(const mesh::TetMesh& m, const recover::ConstraintFaces& faces) {
    const std::size_t n = m.vertex_count();
    std::vector<std::pair<VertexId, VertexId>> edges;
    edges.reserve(3 * faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const recover::Triangle& t = faces.triangle(i);
        for (int k = 0; k < 3; ++k) {
            VertexId a = t[k], b = t[(k + 1) % 3];
            if (a > b) std::swap(a, b);
            edges.emplace_back(a, b);
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<double> sum(n, 0);
    std::vector<int> count(n, 0);
    for (const auto& [a, b] : edges) {
        const double l = std::sqrt(squared_distance(m.point(a), m.point(b)));
        sum[a] += l;
        sum[b] += l;
        ++count[a];
        ++count[b];
    }
    std::vector<double> h(n, kInf);
    for (std::size_t v = 0; v < n; ++v)
        if (count[v] > 0) h[v] = sum[v] / count[v];
    return h;
}

// Adjacency of the finite edges of m: vertex v's neighbours are
// ids[offsets[v] .. offsets[v + 1]). Filled in place (each tetrahedron
// lists three neighbours per corner, duplicates then squeezed out), not as
// one growing vector per vertex: on igea those reallocations were most of
// the field's setup. Duplicates go by a mark per vertex (the last vertex
// whose list met it), not by sorting each list (the sorts were 40% of the
// field's setup on igea); grade's result does not depend on the order.
struct EdgeLists {
    std::vector<std::size_t> offsets;
    std::vector<VertexId> ids;
};

EdgeLists edge_lists(const mesh::TetMesh& m) {
    const std::size_t n = m.vertex_count();
    const auto finite = [&](TetId t) { return !m.is_free(t) && !m.is_ghost(t); };
    std::vector<std::size_t> start(n + 1, 0);
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (finite(t))
            for (int i = 0; i < 4; ++i) start[m.vertex(t, i) + 1] += 3;
    for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<VertexId> ids(start[n]);
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (!finite(t)) continue;
        const VertexId* v = m.vertices(t);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                if (j != i) ids[fill[v[i]]++] = v[j];
    }
    EdgeLists out;
    out.offsets.assign(n + 1, 0);
    std::vector<VertexId> listed_by(n, mesh::kGhostVertex);  // no vertex's id
    std::size_t kept = 0;
    for (std::size_t v = 0; v < n; ++v) {
        // Squeezed toward the front: kept <= k, so no entry is overwritten
        // before it is read.
        for (std::size_t k = start[v]; k < start[v + 1]; ++k) {
            const VertexId u = ids[k];
            if (listed_by[u] == v) continue;
            listed_by[u] = static_cast<VertexId>(v);
            ids[kept++] = u;
        }
        out.offsets[v + 1] = kept;
    }
    ids.resize(kept);
    out.ids = std::move(ids);
    return out;
}

// h(v) = min over u of h(u) + g |uv| along mesh edges (Dijkstra). A
// surface vertex is only lowered from another surface vertex: its value is
// the length of the input edges there, which no refinement can change
// (a smaller value could never be met by the tetrahedra on the surface).
void grade(const mesh::TetMesh& m, double g, const std::vector<char>& on_surface, std::vector<double>& h) {
    const EdgeLists adj = edge_lists(m);
    using Item = std::pair<double, VertexId>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (VertexId v = 0; v < h.size(); ++v)
        if (std::isfinite(h[v])) queue.push({h[v], v});
    while (!queue.empty()) {
        const auto [hv, v] = queue.top();
        queue.pop();
        if (hv > h[v]) continue;
        for (std::size_t k = adj.offsets[v]; k < adj.offsets[v + 1]; ++k) {
            const VertexId u = adj.ids[k];
            if (on_surface[u] && !on_surface[v]) continue;
            const double cand = hv + g * std::sqrt(squared_distance(m.point(v), m.point(u)));
            if (cand < h[u]) {
                h[u] = cand;
                queue.push({cand, u});
            }
        }
    }
}

}  // namespace

// §6: "the surface mesh should conform with the sizing field": at a surface
// vertex the field is the surface's own size (mean input-edge length) in
// every mode, since the surface is never split. Elsewhere: the surface
// field carried inside (grading, then interpolation), capped by H when H is
// given; or H alone.
SizingField::SizingField(const mesh::TetMesh& m, const recover::ConstraintFaces& faces, const RefineOptions& options) {
    h_ = surface_sizes(m, faces);
    cap_ = options.target_size > 0 ? options.target_size : kInf;
    constant_ = !options.size_from_surface && options.target_size > 0;
    growth_ = options.growth;
    std::vector<char> on_surface(h_.size(), 0);
    double sum = 0;
    std::size_t known = 0;
    for (std::size_t v = 0; v < h_.size(); ++v) {
        if (!std::isfinite(h_[v])) continue;
        on_surface[v] = 1;
        sum += h_[v];
        ++known;
    }
    grade(m, options.grading, on_surface, h_);
    const double fallback = known > 0 ? sum / static_cast<double>(known) : 1.0;
    for (std::size_t v = 0; v < h_.size(); ++v) {
        if (on_surface[v]) continue;
        if (constant_) h_[v] = cap_;
        else if (!std::isfinite(h_[v])) h_[v] = std::min(fallback, cap_);
        else h_[v] = std::min(h_[v], cap_);
    }
}

double SizingField::for_new_point(const mesh::TetMesh& m, TetId t, const double* p) const {
    const double interpolated = interpolate(m, t, p);
    if (!(growth_ > 0)) return interior(interpolated);
    // Growth away from the surface: the largest value the corners allow
    // under a field that grows by growth_ per unit length (the corners'
    // values are themselves graded, so the field stays growth-Lipschitz
    // along the insertion sequence).
    const VertexId* v = m.vertices(t);
    double grown = kInf;
    for (int i = 0; i < 4; ++i)
        grown = std::min(grown, h_[v[i]] + growth_ * std::sqrt(squared_distance(m.point(v[i]), p)));
    return interior(std::max(interpolated, grown));
}

double SizingField::interpolate(const mesh::TetMesh& m, TetId t, const double* p) const {
    const VertexId* v = m.vertices(t);
    const double* a = m.point(v[0]);
    // Barycentric weights from sub-volumes (double; p is inside or near t).
    auto vol = [](const double* q0, const double* q1, const double* q2, const double* q3) {
        const double u[3] = {q1[0] - q0[0], q1[1] - q0[1], q1[2] - q0[2]};
        const double s[3] = {q2[0] - q0[0], q2[1] - q0[1], q2[2] - q0[2]};
        const double w[3] = {q3[0] - q0[0], q3[1] - q0[1], q3[2] - q0[2]};
        return u[0] * (s[1] * w[2] - s[2] * w[1]) - u[1] * (s[0] * w[2] - s[2] * w[0]) + u[2] * (s[0] * w[1] - s[1] * w[0]);
    };
    const double* q[4] = {a, m.point(v[1]), m.point(v[2]), m.point(v[3])};
    const double total = vol(q[0], q[1], q[2], q[3]);
    double lo = kInf, hi = 0;
    for (int i = 0; i < 4; ++i) lo = std::min(lo, h_[v[i]]), hi = std::max(hi, h_[v[i]]);
    if (!(total > 0)) return lo;
    double value = 0;
    for (int i = 0; i < 4; ++i) {
        const double* r[4] = {q[0], q[1], q[2], q[3]};
        r[i] = p;
        value += vol(r[0], r[1], r[2], r[3]) / total * h_[v[i]];
    }
    return std::clamp(value, lo, hi);
}

}  // namespace cbr::refine
