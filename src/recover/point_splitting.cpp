#include "recover/point_splitting.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "geom/flat_cone.hpp"
#include "geom/orient2d.hpp"
#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/key_table.hpp"
#include "mesh/surgery.hpp"
#include "recover/polygon_triangulation.hpp"

namespace cbr::recover {

using mesh::kFaceVertices;
using mesh::kGhostVertex;
using mesh::kNoTet;
using mesh::TetId;
using mesh::VertexId;

namespace {

// Halvings of the perturbation before a wedge is given up: 2^-40 of the
// shortest edge is far below any placement that rounding can still tell
// from e.
constexpr int kMaxHalvings = 40;
// Tetrahedra one growth of a wedge may take in beyond the ball
// (grow_wedge): past flat faces, and towards a target point (enough to
// take in the balls of a few earlier Steiner points).
constexpr std::size_t kMaxTakenPastFlat = 64;
constexpr std::size_t kMaxTakenTowardsTarget = 4096;
// A placement nearer to e than this fraction of the ball's shortest edge
// is thin: the wedge is grown instead where it can be (place_by_growing).
constexpr double kThinPlacement = 1e-3;

// A sub-face at e, seen from the wedge on one side: (e, x, y) with its
// normal into the wedge, i.e. the directed polygon edge x -> y.
struct FanFace {
    int wedge;
    std::size_t face;  // the input triangle it belongs to
    VertexId x, y;
};

// One input triangle's fan around e: its polygon (outer vertices in the
// order seen from `wedge`) and the polygon's triangulation.
struct Fan {
    std::size_t face;
    int wedge = -1;       // the wedge the loop is seen from
    int other = -1;       // the wedge on the other side
    std::vector<VertexId> loop;
    std::vector<std::array<int, 3>> triangles;
};

int find_root(std::vector<int>& parent, int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

double distance(const double* p, const double* q) {
    return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

bool sees_all(const mesh::TetMesh& m, const std::vector<std::array<VertexId, 3>>& bounds, const double* s) {
    for (const auto& b : bounds)
        if (geom::orient3d(m.point(b[0]), m.point(b[1]), m.point(b[2]), s) <= 0) return false;
    return true;
}

}  // namespace

// Along the ray e + eps u (u = d / |d|), each boundary face of the wedge
// is seen from an interval of eps: (lo_b, inf) for a face the ray moves
// towards the front of (the fans, which e lies on up to rounding), [0,
// hi_b) for one it approaches from the front (the far faces of the ball).
// The intersection (lo, hi) is estimated in floating point and its middle
// tried first — as far from every face as the ray allows —, then points
// nearer to e; every candidate is tested exactly.
bool PointSplitting::place_in_wedge(const double* pe, const double* d,
                                    const std::vector<std::array<VertexId, 3>>& bounds, double shortest,
                                    std::array<double, 3>& s) const {
    const double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(dl > 0)) return false;
    const double u[3] = {d[0] / dl, d[1] / dl, d[2] / dl};
    double lo = 0, hi = INFINITY;
    for (const auto& b : bounds) {
        const double* a = m_.point(b[0]);
        const double* p = m_.point(b[1]);
        const double* c = m_.point(b[2]);
        const double x[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
        const double y[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double n[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
        const double at_e = n[0] * (pe[0] - a[0]) + n[1] * (pe[1] - a[1]) + n[2] * (pe[2] - a[2]);
        const double slope = n[0] * u[0] + n[1] * u[1] + n[2] * u[2];
        if (slope > 0) lo = std::max(lo, -at_e / slope);
        else if (slope < 0) hi = std::min(hi, at_e / -slope);
    }
    const auto at = [&](double eps) {
        for (int k = 0; k < 3; ++k) s[k] = pe[k] + eps * u[k];
        return !geom::same_point(s.data(), pe) && sees_all(m_, bounds, s.data());
    };
    if (lo < hi && std::isfinite(hi)) {
        for (const double f : {0.5, 0.25, 0.75, 0.1, 0.9, 0.01, 0.99})
            if (at(lo + f * (hi - lo))) return true;
    }
    double eps = 0.25 * shortest;
    for (int h = 0; h <= kMaxHalvings; ++h, eps *= 0.5)
        if (at(eps)) return true;
    return false;
}

// The vertices of far face r (normal into the wedge that lists it).
std::array<VertexId, 3> PointSplitting::face_vertices(mesh::FacetRef r) const {
    const TetId t = mesh::facet_tet(r);
    const int* k = kFaceVertices[mesh::facet_face(r)];
    return {m_.vertex(t, k[0]), m_.vertex(t, k[1]), m_.vertex(t, k[2])};
}

// Point p lies strictly beyond the hull face of ghost g (on the side of
// the ghost vertex).
bool PointSplitting::sees_hull_face(TetId g, const double* p) const {
    const VertexId* v = m_.vertices(g);
    return geom::orient3d(m_.point(v[0]), m_.point(v[1]), m_.point(v[2]), p) > 0;
}

// Far face r of a wedge may stay a boundary face of the cone from p: p
// sees it strictly; for a ghost face, p is not beyond the hull face of the
// ghost across it (the hull stays convex there).
bool PointSplitting::keeps_far_face(mesh::FacetRef r, const double* p) const {
    const TetId t = mesh::facet_tet(r);
    if (m_.is_ghost(t)) return !sees_hull_face(mesh::facet_tet(m_.neighbor(t, mesh::facet_face(r))), p);
    const auto [a, b, c] = face_vertices(r);
    return geom::orient3d(m_.point(a), m_.point(b), m_.point(c), p) > 0;
}

// A vertex a split may take out of the mesh: a Steiner point of an earlier
// split (never an input vertex or an added point).
bool PointSplitting::absorbable(VertexId v) const {
    return v >= points_.first_new_vertex() && !points_.is_added(v);
}

// Grows wedge w past the far faces `cross` selects: the tetrahedron beyond
// such a face joins the wedge (its other faces become far faces, or
// interior ones where they meet the wedge) — unless the face is a
// constraint or a sub-face, or that tetrahedron is in the ball or already
// taken by a wedge, or a ghost while `beyond_hull` is null. At most `limit`
// tetrahedra are taken in. The region stays a set of whole tetrahedra, so
// whatever point sees all its boundary faces can cone it (tested exactly
// by the caller).
//
// With `beyond_hull`, a point the wedge is to be coned from, the wedge may
// also take in the ghosts of the hull faces that point lies beyond (or on:
// `cross` decides for the hull face as for any face): the point then
// becomes a hull vertex, as a Delaunay insertion outside the hull would
// make it. A ghost face (a hull edge and the ghost vertex) is crossed when
// the point lies strictly beyond the hull face of the ghost on its other
// side; coned, a ghost face gives a ghost whose hull face joins the edge
// to the point (replace_tets checks that the hull stays convex).
void PointSplitting::grow_wedge(int w, const TetOwners& ball_wedge, std::vector<mesh::FacetRef>& links,
                                TetOwners& taken, const CrossTest& cross,
                                std::size_t limit, const double* beyond_hull) const {
    const auto in_wedge = [&](TetId t) {
        if (const int* b = ball_wedge.find(t)) return *b == w;
        const int* k = taken.find(t);
        return k != nullptr && *k == w;
    };
    // One pass over a growing list: whether a face may be crossed never
    // changes, except that a tetrahedron once taken is not taken again; a
    // far face that ends up inside the wedge is dropped at the end.
    mesh::KeyTable<bool> inside;
    std::size_t grown = 0;
    for (std::size_t i = 0; i < links.size() && grown < limit; ++i) {
        if (inside.find(links[i])) continue;
        const TetId t = mesh::facet_tet(links[i]);
        const int f = mesh::facet_face(links[i]);
        const mesh::FacetRef across = m_.neighbor(t, f);
        const TetId n = mesh::facet_tet(across);
        if (m_.is_ghost(n) && beyond_hull == nullptr) continue;
        if (m_.is_ghost(t)) {
            // A ghost face: n is a ghost too.
            if (!sees_hull_face(n, beyond_hull)) continue;
        } else {
            const auto [a, b, c] = face_vertices(links[i]);
            if (m_.is_constrained(t, f) || points_.is_subface(a, b, c)) continue;
            if (!cross(m_.point(a), m_.point(b), m_.point(c))) continue;
        }
        if (ball_wedge.contains(n) || taken.contains(n)) continue;
        taken.add(n, w);
        ++grown;
        inside[links[i]] = true;
        for (int g = 0; g < 4; ++g) {
            if (g == mesh::facet_face(across)) continue;
            const mesh::FacetRef beyond = m_.neighbor(n, g);
            if (in_wedge(mesh::facet_tet(beyond))) {
                inside[beyond] = true;  // now between two tetrahedra of the wedge
            } else {
                links.push_back(mesh::make_facet(n, g));
            }
        }
    }
    links.erase(std::remove_if(links.begin(), links.end(), [&](mesh::FacetRef r) { return inside.find(r) != nullptr; }),
                links.end());
}

// Every vertex of the replaced tetrahedra but e is still used — except
// Steiner points of earlier splits that a grown wedge took in whole: the
// new Steiner point replaces them (listed in `absorbed`). Input vertices
// and added points are never lost.
bool PointSplitting::keeps_vertices(const std::vector<TetId>& old, const std::vector<std::array<VertexId, 4>>& fresh,
                                    VertexId e, std::vector<VertexId>& absorbed) const {
    std::set<VertexId> kept, lost;
    for (const auto& t : fresh) kept.insert(t.begin(), t.end());
    for (TetId t : old)
        for (int i = 0; i < 4; ++i) {
            const VertexId v = m_.vertex(t, i);
            if (v == e || v == kGhostVertex || kept.count(v)) continue;
            if (!absorbable(v)) return false;
            lost.insert(v);
        }
    absorbed.assign(lost.begin(), lost.end());
    return true;
}

// Every vertex of the tetrahedra wedge w took in is still on its boundary
// (a far face or a polygon triangle), unless it is a Steiner point of an
// earlier split (absorbed): a growth must not swallow an input vertex or
// an added point (checked again for the whole split by keeps_vertices).
bool PointSplitting::keeps_region_vertices(int w, const std::vector<std::array<VertexId, 3>>& poly,
                                           const std::vector<mesh::FacetRef>& links,
                                           const TetOwners& taken) const {
    std::set<VertexId> boundary;
    for (const auto& b : poly) boundary.insert(b.begin(), b.end());
    for (const mesh::FacetRef r : links)
        for (const VertexId v : face_vertices(r)) boundary.insert(v);
    for (const TetId t : taken.ids()) {
        if (*taken.find(t) != w) continue;
        for (int i = 0; i < 4; ++i) {
            const VertexId v = m_.vertex(t, i);
            if (v != kGhostVertex && boundary.count(v) == 0 && !absorbable(v)) return false;
        }
    }
    return true;
}

// When no point of the wedge sees all of it — far faces of nearly
// coplanar surface points cut it down to a sliver near e — a target s_t
// on the ray e + eps u, in front of every polygon triangle, is chosen,
// and the wedge grows past every far face s_t does not see (the §5.1
// cavity correction, driven by the point instead of by flatness). Targets
// from a quarter of the ball's shortest edge down, until one sees the
// whole grown wedge; the wedge is left as it was otherwise.
bool PointSplitting::place_by_growing(int w, const double* pe, const double* d,
                                      const std::vector<std::array<VertexId, 3>>& poly, double shortest,
                                      const TetOwners& ball_wedge, std::vector<mesh::FacetRef>& links,
                                      TetOwners& taken, std::array<double, 3>& s) const {
    const double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(dl > 0)) return false;
    for (double f = 0.25; f >= kThinPlacement; f *= 0.25) {
        for (int k = 0; k < 3; ++k) s[k] = pe[k] + f * shortest * d[k] / dl;
        if (!sees_all(m_, poly, s.data())) continue;
        std::vector<mesh::FacetRef> grown = links;
        TetOwners grown_taken = taken;
        const double* st = s.data();
        grow_wedge(w, ball_wedge, grown, grown_taken, [st](const double* a, const double* b, const double* c) {
            return geom::orient3d(a, b, c, st) <= 0;
        }, kMaxTakenTowardsTarget, st);
        const bool sees_far = std::all_of(grown.begin(), grown.end(), [&](mesh::FacetRef r) { return keeps_far_face(r, st); });
        if (!sees_far || !keeps_region_vertices(w, poly, grown, grown_taken)) continue;
        links = std::move(grown);
        taken = std::move(grown_taken);
        return true;
    }
    return false;
}

bool PointSplitting::split(VertexId e, std::vector<VertexId>& steiner) {
    std::vector<TetId> ball;
    if (!mesh::ball(m_, e, incident_[e], ball)) return fail("an added point lost its ball");
    const int nb = static_cast<int>(ball.size());
    std::map<TetId, int> index;
    for (int i = 0; i < nb; ++i) index[ball[i]] = i;

    // Wedges: the ball's tetrahedra joined across faces at e that are not
    // sub-faces.
    std::vector<int> parent(nb);
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<FanFace> fan_faces;
    for (int i = 0; i < nb; ++i) {
        const TetId t = ball[i];
        const int ei = mesh::vertex_index(m_, t, e);
        for (int f = 0; f < 4; ++f) {
            if (f == ei) continue;
            const int* k = kFaceVertices[f];
            VertexId v[3] = {m_.vertex(t, k[0]), m_.vertex(t, k[1]), m_.vertex(t, k[2])};
            while (v[0] != e) std::rotate(v, v + 1, v + 3);
            const std::size_t g = points_.common_face(v[0], v[1], v[2]);
            if (g == SurfacePoints::npos) {
                parent[find_root(parent, i)] = find_root(parent, index.at(mesh::facet_tet(m_.neighbor(t, f))));
            } else {
                fan_faces.push_back({i, g, v[1], v[2]});
            }
        }
    }
    std::vector<int> wedge_of(nb);
    std::map<int, int> wedge_id;
    for (int i = 0; i < nb; ++i) {
        const int r = find_root(parent, i);
        if (!wedge_id.count(r)) {
            const int id = static_cast<int>(wedge_id.size());
            wedge_id[r] = id;
        }
        wedge_of[i] = wedge_id[r];
    }
    const int nw = static_cast<int>(wedge_id.size());
    TetOwners ball_wedge;
    for (int i = 0; i < nb; ++i) ball_wedge.add(ball[i], wedge_of[i]);
    for (FanFace& ff : fan_faces) ff.wedge = wedge_of[ff.wedge];
    if (nw < 2) return fail("the sub-faces around an added point do not cut its ball");

    // The fans, their polygons and triangulations.
    std::map<std::size_t, Fan> fans;
    for (const FanFace& ff : fan_faces) {
        Fan& fan = fans[ff.face];
        fan.face = ff.face;
        if (fan.wedge < 0) fan.wedge = ff.wedge;
        else if (ff.wedge != fan.wedge) {
            if (fan.other >= 0 && fan.other != ff.wedge) return fail("a fan borders more than two wedges");
            fan.other = ff.wedge;
        }
    }
    for (auto& [g, fan] : fans) {
        if (fan.other < 0) return fail("a fan has the same wedge on both sides");
        std::map<VertexId, VertexId> next, prev;
        for (const FanFace& ff : fan_faces) {
            if (ff.face != g || ff.wedge != fan.wedge) continue;
            if (!next.emplace(ff.x, ff.y).second || !prev.emplace(ff.y, ff.x).second)
                return fail("the sub-faces around an added point are not a fan");
        }
        VertexId first = next.begin()->first;
        for (const auto& [x, y] : next)
            if (!prev.count(x)) first = x;  // an open fan (edge point) starts where no link ends
        for (VertexId v = first;;) {
            fan.loop.push_back(v);
            const auto it = next.find(v);
            if (it == next.end() || it->second == first) break;
            v = it->second;
            if (fan.loop.size() > next.size() + 1) return fail("the fan around an added point does not close");
        }
        if (fan.loop.size() < next.size()) return fail("the fan around an added point has several pieces");
        const Triangle& tri = points_.faces().triangle(g);
        const double* A = m_.point(tri[0]);
        const double* B = m_.point(tri[1]);
        const double* C = m_.point(tri[2]);
        const double n[3] = {(B[1] - A[1]) * (C[2] - A[2]) - (B[2] - A[2]) * (C[1] - A[1]),
                             (B[2] - A[2]) * (C[0] - A[0]) - (B[0] - A[0]) * (C[2] - A[2]),
                             (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0])};
        const geom::Projection pr = geom::projection_along(n);
        int turn = 0;
        for (const auto& [x, y] : next) {
            const int s = geom::orient2d(pr, m_.point(e), m_.point(x), m_.point(y));
            if (s == 0 || (turn != 0 && s != turn)) return fail("the fan around an added point folds over");
            turn = s;
        }
        std::vector<const double*> coords;
        for (VertexId v : fan.loop) coords.push_back(m_.point(v));
        // Three points of one input edge (its ends or points added on it:
        // a stretch of a chain seen across a thin face) are collinear in
        // exact geometry; the sign of their triangle is rounding and its
        // normal arbitrary, and a cone over it can leave no room in the
        // wedge (the feeder body's thin cylinder facets).
        const std::vector<VertexId>& loop = fan.loop;
        fan.triangles = triangulate_polygon(coords, pr, turn, [&](int i, int j, int k) {
            return points_.on_one_edge(loop[i], loop[j], loop[k]);
        });
        if (fan.triangles.empty()) return fail("the polygon around an added point has no triangulation");
    }

    // Each wedge: the cone from its Steiner point (or from the ghost vertex).
    const double* pe = m_.point(e);
    double shortest = INFINITY;
    for (TetId t : ball)
        for (int i = 0; i < 4; ++i) {
            const VertexId v = m_.vertex(t, i);
            if (v == e || v == kGhostVertex) continue;
            const double* p = m_.point(v);
            shortest = std::min(shortest, std::sqrt((p[0] - pe[0]) * (p[0] - pe[0]) + (p[1] - pe[1]) * (p[1] - pe[1]) +
                                                    (p[2] - pe[2]) * (p[2] - pe[2])));
        }
    std::vector<std::array<VertexId, 4>> fresh;
    std::vector<TetId> extra_old;
    TetOwners taken;  // tetrahedra outside the ball that a wedge took in, and the wedge
    std::vector<std::array<double, 3>> apexes;  // coordinates of the Steiner points, in wedge order
    for (int w = 0; w < nw; ++w) {
        std::vector<mesh::FacetRef> links;  // the wedge's faces opposite e
        int ghosts = 0, finite = 0;
        for (int i = 0; i < nb; ++i) {
            if (wedge_of[i] != w) continue;
            const TetId t = ball[i];
            (m_.is_ghost(t) ? ghosts : finite)++;
            links.push_back(mesh::make_facet(t, mesh::vertex_index(m_, t, e)));
        }
        if (ghosts > 0 && finite > 0) return fail("an added point on the hull has a wedge partly outside it");
        std::vector<std::array<VertexId, 3>> poly;  // polygon triangles, normals into the wedge
        double d[3] = {0, 0, 0};
        for (const auto& [g, fan] : fans) {
            if (fan.wedge != w && fan.other != w) continue;
            const bool reversed = fan.wedge != w;
            for (const auto& tr : fan.triangles) {
                const VertexId a = fan.loop[tr[0]], b = fan.loop[tr[1]], c = fan.loop[tr[2]];
                poly.push_back(reversed ? std::array<VertexId, 3>{c, b, a} : std::array<VertexId, 3>{a, b, c});
            }
            double n[3] = {0, 0, 0};
            for (const FanFace& ff : fan_faces) {
                if (ff.face != g || ff.wedge != w) continue;
                const double* x = m_.point(ff.x);
                const double* y = m_.point(ff.y);
                const double u[3] = {x[0] - pe[0], x[1] - pe[1], x[2] - pe[2]};
                const double v[3] = {y[0] - pe[0], y[1] - pe[1], y[2] - pe[2]};
                n[0] += u[1] * v[2] - u[2] * v[1];
                n[1] += u[2] * v[0] - u[0] * v[2];
                n[2] += u[0] * v[1] - u[1] * v[0];
            }
            const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!(len > 0)) return fail("a fan around an added point has no area");
            for (int k = 0; k < 3; ++k) d[k] += n[k] / len;
        }
        if (ghosts > 0) {
            for (const auto& b : poly) fresh.push_back({b[0], b[1], b[2], kGhostVertex});
            continue;
        }
        // §5.1 cavity correction: a far face that e lies on up to rounding
        // (a flat cone: e and the face's vertices are surface points of
        // nearly coplanar triangles) leaves no room behind it.
        grow_wedge(w, ball_wedge, links, taken, [pe](const double* a, const double* b, const double* c) {
            return geom::flat_cone(a, b, c, pe);
        }, kMaxTakenPastFlat);
        std::vector<std::array<VertexId, 3>> bounds;  // boundary faces, normals into the wedge
        std::vector<TetId> beyond;                     // ghosts across the far faces
        const auto collect_bounds = [&]() {
            bounds.clear();
            beyond.clear();
            for (const mesh::FacetRef r : links) {
                bounds.push_back(face_vertices(r));
                const TetId across = mesh::facet_tet(m_.neighbor(mesh::facet_tet(r), mesh::facet_face(r)));
                if (m_.is_ghost(across)) beyond.push_back(across);
            }
            bounds.insert(bounds.end(), poly.begin(), poly.end());
        };
        collect_bounds();
        const std::size_t far_faces = links.size();
        std::array<double, 3> s{};
        bool placed = place_in_wedge(pe, d, bounds, shortest, s);
        const bool thin = placed && distance(s.data(), pe) < kThinPlacement * shortest;
        if (!placed && beyond.size() == far_faces) {
            // A flat wedge between the fans and hull faces (an added point on
            // a coplanar hull face whose other diagonal the Delaunay mesh
            // has, nudged inside the hull): the wedge and the ghosts beyond
            // it become the ghosts of the polygon triangles, which are then
            // hull faces. replace_tets checks that the hull stays convex.
            extra_old.insert(extra_old.end(), beyond.begin(), beyond.end());
            for (const auto& b : poly) fresh.push_back({b[0], b[1], b[2], kGhostVertex});
            continue;
        }
        // A thin placement would leave a Steiner point next to the surface,
        // where it blocks the splits after it: grow instead where possible.
        if (!placed || thin) {
            std::array<double, 3> grown_s{};
            if (place_by_growing(w, pe, d, poly, shortest, ball_wedge, links, taken, grown_s)) {
                s = grown_s;
                placed = true;
            }
        }
        if (!placed) return fail("no Steiner point position sees the whole wedge of an added point");
        collect_bounds();
        const VertexId id = static_cast<VertexId>(m_.vertex_count() + apexes.size());
        apexes.push_back(s);
        for (const auto& b : bounds) fresh.push_back({b[0], b[1], b[2], id});
    }

    std::vector<TetId> old = ball;
    old.insert(old.end(), extra_old.begin(), extra_old.end());
    for (const TetId t : taken.sorted_ids()) old.push_back(t);
    std::vector<VertexId> absorbed;  // earlier Steiner points a grown wedge took in
    if (!keeps_vertices(old, fresh, e, absorbed)) return fail("the new tetrahedra would lose a vertex");
    const std::size_t before = m_.vertex_count();
    for (const auto& s : apexes) m_.add_points(s.data(), 1);
    std::vector<TetId> created;
    const mesh::ReplaceResult r = mesh::replace_tets(m_, old, fresh, &created);
    if (r != mesh::ReplaceResult::kDone) {
        m_.truncate_vertices(before);
        return fail(std::string("the new tetrahedra were refused: ") + mesh::to_string(r));
    }
    if (incident_.size() < m_.vertex_count()) incident_.resize(m_.vertex_count(), kNoTet);
    for (TetId t : created)
        for (int i = 0; i < 4; ++i)
            if (m_.vertex(t, i) != kGhostVertex) incident_[m_.vertex(t, i)] = t;
    incident_[e] = kNoTet;
    for (VertexId v : absorbed) {
        incident_[v] = kNoTet;
        steiner.erase(std::remove(steiner.begin(), steiner.end(), v), steiner.end());
    }
    if (points_.on_edge(e, nullptr, nullptr, nullptr)) points_.remove_from_chain(e);
    points_.remove(e);
    for (std::size_t v = before; v < m_.vertex_count(); ++v) steiner.push_back(static_cast<VertexId>(v));
    made_ += m_.vertex_count() - before;
    return true;
}

}  // namespace cbr::recover
