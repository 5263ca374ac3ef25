// Combinatorial checks of `cbr check` (see surface_topology.hpp).
#include "cli/surface_topology.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace cbr::cli {
namespace {

class UnionFind {
public:
    explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t{0}); }
    std::size_t find(std::size_t a) {
        while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
        return a;
    }
    void unite(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }

private:
    std::vector<std::size_t> parent_;
};

using Tri = std::array<std::int64_t, 3>;

// The triangles whose ids are in range and distinct.
std::vector<Tri> valid_triangles(const std::vector<std::int64_t>& tris, std::int64_t n) {
    std::vector<Tri> out;
    for (std::size_t t = 0; t + 2 < tris.size(); t += 3) {
        const Tri v = {tris[t], tris[t + 1], tris[t + 2]};
        const bool in_range = std::all_of(v.begin(), v.end(), [n](std::int64_t id) { return id >= 0 && id < n; });
        if (in_range && v[0] != v[1] && v[1] != v[2] && v[2] != v[0]) out.push_back(v);
    }
    return out;
}

// An edge as a triangle walks it: u < v, forward when the walk goes u -> v.
struct EdgeUse {
    std::int64_t u, v;
    std::size_t tri;
    bool forward;
    bool operator<(const EdgeUse& o) const { return u != o.u ? u < o.u : (v != o.v ? v < o.v : tri < o.tri); }
    bool same_edge(const EdgeUse& o) const { return u == o.u && v == o.v; }
};

// Every edge of every triangle, sorted: the uses of one edge are adjacent.
std::vector<EdgeUse> edge_uses(const std::vector<Tri>& tris) {
    std::vector<EdgeUse> uses;
    uses.reserve(3 * tris.size());
    for (std::size_t t = 0; t < tris.size(); ++t)
        for (std::size_t i = 0; i < 3; ++i) {
            const std::int64_t a = tris[t][i], b = tris[t][(i + 1) % 3];
            uses.push_back({std::min(a, b), std::max(a, b), t, a < b});
        }
    std::sort(uses.begin(), uses.end());
    return uses;
}

// Calls visit(first, last) for the uses [first, last) of each edge.
template <class Visit>
void for_each_edge(const std::vector<EdgeUse>& uses, Visit&& visit) {
    for (std::size_t i = 0, j = 0; i < uses.size(); i = j) {
        for (j = i + 1; j < uses.size() && uses[j].same_edge(uses[i]); ++j) {
        }
        visit(i, j);
    }
}

// Open edges (one triangle) and misoriented ones: two triangles walking the
// edge the same way, or, for an even number of triangles (several regions
// meeting there), not as many walking it one way as the other.
void check_edges(const std::vector<EdgeUse>& uses, std::size_t max_listed, Topology& topo) {
    for_each_edge(uses, [&](std::size_t first, std::size_t last) {
        const std::size_t n = last - first;
        std::size_t forward = 0;
        for (std::size_t k = first; k < last; ++k) forward += uses[k].forward ? 1 : 0;
        if (n == 1) ++topo.open_edges;
        if (n % 2 == 1 || 2 * forward == n) return;
        if (topo.misoriented_listed.size() < max_listed)
            topo.misoriented_listed.push_back({uses[first].u, uses[first].v});
        ++topo.misoriented_edges;
    });
}

// Shells: triangles joined across the edges that have exactly two (so two
// tetrahedra sharing an edge, or two cones sharing an apex, are two shells).
// A shell is closed when each edge is used an even number of times by its
// triangles. Returns the shell (a root triangle) of each triangle and marks
// the roots of open shells.
std::vector<std::size_t> find_shells(const std::vector<EdgeUse>& uses, std::size_t tri_count,
                                     std::vector<char>& open_root) {
    UnionFind shells(tri_count);
    for_each_edge(uses, [&](std::size_t first, std::size_t last) {
        if (last - first == 2) shells.unite(uses[first].tri, uses[first + 1].tri);
    });
    std::vector<std::size_t> shell_of(tri_count);
    for (std::size_t t = 0; t < tri_count; ++t) shell_of[t] = shells.find(t);
    open_root.assign(tri_count, 0);
    std::vector<std::size_t> roots;
    for_each_edge(uses, [&](std::size_t first, std::size_t last) {
        roots.clear();
        for (std::size_t k = first; k < last; ++k) roots.push_back(shell_of[uses[k].tri]);
        std::sort(roots.begin(), roots.end());
        for (std::size_t a = 0, b = 0; a < roots.size(); a = b) {
            for (b = a + 1; b < roots.size() && roots[b] == roots[a]; ++b) {
            }
            if ((b - a) % 2 == 1) open_root[roots[a]] = 1;
        }
    });
    return shell_of;
}

void count_components(const std::vector<Tri>& tris, std::size_t n, Topology& topo) {
    UnionFind sets(n);
    std::vector<char> used(n, 0);
    for (const Tri& t : tris) {
        sets.unite(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]));
        sets.unite(static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2]));
        for (const std::int64_t v : t) used[static_cast<std::size_t>(v)] = 1;
    }
    for (std::size_t v = 0; v < n; ++v) {
        if (!used[v]) continue;
        ++topo.used_points;
        if (sets.find(v) == v) ++topo.components;
    }
}

// Triangles around each vertex, as offsets into one array (CSR).
struct Incidence {
    std::vector<std::size_t> begin;  // n + 1
    std::vector<std::size_t> tris;
};

Incidence incidence(const std::vector<Tri>& tris, std::size_t n) {
    Incidence inc;
    inc.begin.assign(n + 1, 0);
    for (const Tri& t : tris)
        for (const std::int64_t v : t) ++inc.begin[static_cast<std::size_t>(v) + 1];
    std::partial_sum(inc.begin.begin(), inc.begin.end(), inc.begin.begin());
    inc.tris.resize(inc.begin[n]);
    std::vector<std::size_t> next(inc.begin.begin(), inc.begin.end() - 1);
    for (std::size_t t = 0; t < tris.size(); ++t)
        for (const std::int64_t v : tris[t]) inc.tris[next[static_cast<std::size_t>(v)]++] = t;
    return inc;
}

// True when the triangles around v, joined through the edges at v, form
// more than one group (e.g. two cones touching at their apex).
bool fan_is_split(const std::vector<Tri>& tris, const Incidence& inc, std::int64_t v,
                  std::vector<std::pair<std::int64_t, std::size_t>>& spokes) {
    const auto vi = static_cast<std::size_t>(v);
    const std::size_t first = inc.begin[vi], count = inc.begin[vi + 1] - first;
    spokes.clear();  // (other end of an edge at v, local triangle index)
    for (std::size_t k = 0; k < count; ++k)
        for (const std::int64_t w : tris[inc.tris[first + k]])
            if (w != v) spokes.emplace_back(w, k);
    std::sort(spokes.begin(), spokes.end());
    UnionFind fan(count);
    std::size_t groups = count;
    for (std::size_t s = 1; s < spokes.size(); ++s)
        if (spokes[s].first == spokes[s - 1].first && fan.find(spokes[s].second) != fan.find(spokes[s - 1].second)) {
            fan.unite(spokes[s].second, spokes[s - 1].second);
            --groups;
        }
    return groups > 1;
}

void find_nonmanifold_vertices(const std::vector<Tri>& tris, std::size_t n, std::size_t max_listed, Topology& topo) {
    const Incidence inc = incidence(tris, n);
    std::vector<std::pair<std::int64_t, std::size_t>> spokes;
    for (std::size_t v = 0; v < n; ++v) {
        if (!fan_is_split(tris, inc, static_cast<std::int64_t>(v), spokes)) continue;
        if (topo.nonmanifold_listed.size() < max_listed)
            topo.nonmanifold_listed.push_back(static_cast<std::int64_t>(v));
        ++topo.nonmanifold_vertices;
    }
}

// Six times the signed volume of the tetrahedron (o, a, b, c) of triangle
// abc, o the centre of the bounding box (less cancellation than the origin).
double six_volume(const std::vector<double>& xyz, const Tri& t, const std::array<double, 3>& o) {
    std::array<std::array<double, 3>, 3> p;
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t k = 0; k < 3; ++k) p[i][k] = xyz[3 * static_cast<std::size_t>(t[i]) + k] - o[k];
    return p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
           p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
}

// The signed volume of the whole surface and of each closed shell.
void measure_volumes(const std::vector<double>& xyz, const std::vector<Tri>& tris,
                     const std::vector<EdgeUse>& uses, Topology& topo) {
    const BoundingBox box = bounding_box(xyz);
    std::array<double, 3> o = {0, 0, 0};
    if (!box.empty)
        for (std::size_t k = 0; k < 3; ++k) o[k] = 0.5 * (box.lo[k] + box.hi[k]);
    std::vector<char> open_root;
    const std::vector<std::size_t> shell_of = find_shells(uses, tris.size(), open_root);
    std::vector<double> volume(tris.size(), 0.0);  // six times, per shell root
    double total = 0;
    for (std::size_t t = 0; t < tris.size(); ++t) {
        const double v = six_volume(xyz, tris[t], o);
        volume[shell_of[t]] += v;
        total += v;
    }
    topo.signed_volume = total / 6;
    for (std::size_t t = 0; t < tris.size(); ++t) {
        if (shell_of[t] != t) continue;
        ++topo.shells;
        if (open_root[t]) ++topo.open_shells;
        else if (volume[t] > 0) ++topo.outward_shells;
        else if (volume[t] < 0) ++topo.inward_shells;
    }
}

bool finite_point(const double* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

}  // namespace

DuplicatePoints find_duplicate_points(const std::vector<double>& xyz, std::size_t max_listed) {
    const std::size_t n = xyz.size() / 3;
    DuplicatePoints d;
    d.first_of.resize(n);
    std::iota(d.first_of.begin(), d.first_of.end(), std::int64_t{0});
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < n; ++i)
        if (finite_point(&xyz[3 * i])) order.push_back(i);
    const auto same = [&](std::size_t a, std::size_t b) {
        return xyz[3 * a] == xyz[3 * b] && xyz[3 * a + 1] == xyz[3 * b + 1] && xyz[3 * a + 2] == xyz[3 * b + 2];
    };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        for (std::size_t k = 0; k < 3; ++k)
            if (xyz[3 * a + k] != xyz[3 * b + k]) return xyz[3 * a + k] < xyz[3 * b + k];
        return a < b;
    });
    std::vector<IdPair> pairs;
    for (std::size_t i = 1; i < order.size(); ++i)
        if (same(order[i], order[i - 1])) {
            const std::int64_t first = d.first_of[order[i - 1]];
            d.first_of[order[i]] = first;
            pairs.push_back({first, static_cast<std::int64_t>(order[i])});
        }
    d.count = static_cast<std::int64_t>(pairs.size());
    std::sort(pairs.begin(), pairs.end(), [](const IdPair& a, const IdPair& b) { return a[1] < b[1]; });
    pairs.resize(std::min(pairs.size(), max_listed));
    d.listed = std::move(pairs);
    return d;
}

Topology analyse_topology(const std::vector<double>& xyz, const std::vector<std::int64_t>& tris,
                          std::size_t max_listed) {
    const std::size_t n = xyz.size() / 3;
    const std::vector<Tri> valid = valid_triangles(tris, static_cast<std::int64_t>(n));
    const std::vector<EdgeUse> uses = edge_uses(valid);
    Topology topo;
    check_edges(uses, max_listed, topo);
    count_components(valid, n, topo);
    find_nonmanifold_vertices(valid, n, max_listed, topo);
    measure_volumes(xyz, valid, uses, topo);
    return topo;
}

BoundingBox bounding_box(const std::vector<double>& xyz) {
    BoundingBox box;
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
        if (!finite_point(&xyz[i])) continue;
        for (std::size_t k = 0; k < 3; ++k) {
            box.lo[k] = box.empty ? xyz[i + k] : std::min(box.lo[k], xyz[i + k]);
            box.hi[k] = box.empty ? xyz[i + k] : std::max(box.hi[k], xyz[i + k]);
        }
        box.empty = false;
    }
    return box;
}

}  // namespace cbr::cli
