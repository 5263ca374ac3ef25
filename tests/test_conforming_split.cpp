// Conforming recovery and added-point splitting (§5.2-5.4), step by step:
// polygon triangulation (cap / ball transformations), vertex compaction,
// ConformingRecovery + PointSplitting on small exact cases, the whole
// recover_faces driver on Schonhardt-type inputs, and the nearly_flat rule
// of protected insertion. Every check is exact where it can be (orient2d /
// orient3d, check_mesh); the distance of a rounded point from the surface
// is bounded relatively.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "delaunay/delaunay.hpp"
#include "geom/orient2d.hpp"
#include "geom/point_in_triangle.hpp"
#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/failed_rings.hpp"
#include "mesh/key_table.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh/vertex_compaction.hpp"
#include "recover/conforming.hpp"
#include "recover/failed_searches.hpp"
#include "recover/constraint_faces.hpp"
#include "recover/flip_recovery.hpp"
#include "recover/point_splitting.hpp"
#include "recover/polygon_triangulation.hpp"
#include "recover/protected_insertion.hpp"
#include "recover/recovery.hpp"
#include "recover/surface_points.hpp"
#include "hard_cases.hpp"
#include "test_util.hpp"

using namespace cbr::mesh;
using cbr::geom::orient2d;
using cbr::geom::Projection;
using cbr::recover::ConformingRecovery;
using cbr::recover::ConstraintFaces;
using cbr::recover::PointSplitting;
using cbr::recover::SurfacePoints;
using cbr::recover::Triangle;
using cbr::recover::kMaxOptimalPolygon;
using cbr::recover::chord_is_clear;
using cbr::recover::triangulate_polygon;
using cbr::recover::triangulate_polygon_by_ears;

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------
// Polygon triangulation helpers (2D, z = 0, projection {0, 1}).

using P2 = std::array<double, 3>;

std::vector<const double*> ptrs(const std::vector<P2>& pts) {
    std::vector<const double*> out;
    for (const P2& p : pts) out.push_back(p.data());
    return out;
}

double shoelace(const std::vector<P2>& pts) {
    double s = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const P2& a = pts[i];
        const P2& b = pts[(i + 1) % pts.size()];
        s += a[0] * b[1] - a[1] * b[0];
    }
    return s / 2;
}

double tri_area2d(const P2& a, const P2& b, const P2& c) {
    return ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2;
}

// Open segments cross at one interior point (exact).
bool cross2d(const double* p, const double* q, const double* r, const double* s) {
    const Projection pr{0, 1};
    return orient2d(pr, p, q, r) * orient2d(pr, p, q, s) < 0 && orient2d(pr, r, s, p) * orient2d(pr, r, s, q) < 0;
}

// Everything a triangulation of the simple polygon `pts` (turning with
// `turn`) must satisfy: n - 2 triangles, indices i < j < k, each of sign
// `turn` (exact), no other polygon vertex in a closed triangle, no
// triangle side crossing a polygon edge, each polygon edge used once and
// each diagonal twice, total area = polygon area.
void check_triangulation(const std::vector<P2>& pts, int turn, const std::vector<std::array<int, 3>>& tris) {
    const Projection pr{0, 1};
    const int n = static_cast<int>(pts.size());
    REQUIRE(tris.size() == static_cast<std::size_t>(n - 2));
    double area = 0;
    std::map<std::pair<int, int>, int> uses;
    for (const auto& t : tris) {
        REQUIRE(t[0] >= 0);
        REQUIRE(t[2] < n);
        CHECK(t[0] < t[1]);
        CHECK(t[1] < t[2]);
        const P2 &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]];
        CHECK(orient2d(pr, a.data(), b.data(), c.data()) == turn);
        area += tri_area2d(a, b, c);
        for (int x = 0; x < n; ++x) {
            if (x == t[0] || x == t[1] || x == t[2]) continue;
            const bool inside = turn * orient2d(pr, a.data(), b.data(), pts[x].data()) >= 0 &&
                                turn * orient2d(pr, b.data(), c.data(), pts[x].data()) >= 0 &&
                                turn * orient2d(pr, c.data(), a.data(), pts[x].data()) >= 0;
            CHECK_MESSAGE(!inside, "vertex " << x << " inside triangle " << t[0] << " " << t[1] << " " << t[2]);
        }
        for (int k = 0; k < 3; ++k) {
            const int i = t[k], j = t[(k + 1) % 3];
            ++uses[std::minmax(i, j)];
            for (int e = 0; e < n; ++e) {
                const int f = (e + 1) % n;
                if (e == i || e == j || f == i || f == j) continue;
                CHECK_MESSAGE(!cross2d(pts[i].data(), pts[j].data(), pts[e].data(), pts[f].data()),
                              "side " << i << "-" << j << " crosses polygon edge " << e << "-" << f);
            }
        }
    }
    for (const auto& [e, k] : uses) {
        const bool boundary = e.second == e.first + 1 || (e.first == 0 && e.second == n - 1);
        CHECK(k == (boundary ? 1 : 2));
    }
    const double poly = shoelace(pts);
    CHECK(area == doctest::Approx(poly).epsilon(1e-12));
}

// ---------------------------------------------------------------------------
// Small exact recovery cases.

struct Case {
    std::unique_ptr<cbr::delaunay::Delaunay> d = std::make_unique<cbr::delaunay::Delaunay>();
    std::unique_ptr<ConstraintFaces> faces;
    std::size_t input_count = 0;
    TetMesh& m() { return d->mesh_for_update(); }
};

void build(Case& c, const std::vector<double>& xyz, const std::vector<std::int64_t>& tris) {
    c.input_count = xyz.size() / 3;
    REQUIRE(c.d->insert_points(xyz.data(), c.input_count).ok);
    std::vector<Triangle> t;
    for (std::size_t i = 0; i + 2 < tris.size(); i += 3)
        t.push_back({c.d->internal_id(static_cast<VertexId>(tris[i])), c.d->internal_id(static_cast<VertexId>(tris[i + 1])),
                     c.d->internal_id(static_cast<VertexId>(tris[i + 2]))});
    c.faces = std::make_unique<ConstraintFaces>(std::move(t), std::vector<std::int32_t>{});
}

void require_valid(const TetMesh& m, const char* when) {
    const CheckReport r = check_mesh(m);
    REQUIRE_MESSAGE(r.ok(), when << ": " << (r.errors.empty() ? std::string() : r.errors[0]));
}

// check_mesh, except that exactly `unused` vertices (the added points split
// off so far: they stay in the coordinate array until compaction) are in no
// tetrahedron.
void require_valid_but_unused(const TetMesh& m, std::size_t unused, const char* when) {
    const CheckReport r = check_mesh(m);
    INFO(when << ": " << (r.errors.empty() ? std::string() : r.errors[0]));
    REQUIRE(r.error_count == unused);
    for (const std::string& e : r.errors) REQUIRE(e.find("is in no tetrahedron") != std::string::npos);
}

double dist(const double* a, const double* b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Distance of p from the line ab, and the parameter of its projection.
double line_distance(const double* p, const double* a, const double* b, double* param) {
    double d[3], r[3];
    for (int k = 0; k < 3; ++k) {
        d[k] = b[k] - a[k];
        r[k] = p[k] - a[k];
    }
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double s = (r[0] * d[0] + r[1] * d[1] + r[2] * d[2]) / dd;
    *param = s;
    double e = 0;
    for (int k = 0; k < 3; ++k) e += (r[k] - s * d[k]) * (r[k] - s * d[k]);
    return std::sqrt(e);
}

// Distance of p from the plane of abc and its barycentric coordinates.
double plane_distance(const double* p, const double* a, const double* b, const double* c, double bary[3]) {
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = p[k] - a[k];
    }
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    // Barycentric coordinates of the projection.
    const double uu = dot(u, u), uv = dot(u, v), vv = dot(v, v), wu = dot(w, u), wv = dot(w, v);
    const double den = uu * vv - uv * uv;
    bary[1] = (vv * wu - uv * wv) / den;
    bary[2] = (uu * wv - uv * wu) / den;
    bary[0] = 1 - bary[1] - bary[2];
    return std::fabs(dot(n, w)) / std::sqrt(nn);
}

bool used_by_a_tet(const TetMesh& m, VertexId v) {
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t) && vertex_index(m, t, v) >= 0) return true;
    return false;
}

std::size_t added_now(const SurfacePoints& sp) {
    std::size_t n = 0;
    for (VertexId v : sp.added_in_order()) n += sp.is_added(v);
    return n;
}

// v lies on (the closed) input triangle i (exact).
bool on_some_input_triangle(const TetMesh& m, const ConstraintFaces& faces, VertexId v) {
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const Triangle& t = faces.triangle(i);
        if (cbr::geom::point_in_triangle(m.point(v), m.point(t[0]), m.point(t[1]), m.point(t[2]))) return true;
    }
    return false;
}

struct SplitStats {
    std::size_t edge_points = 0, face_points = 0, steiner = 0;
    std::size_t max_fans = 0;  // input triangles at one edge point
    std::size_t absorbed = 0;  // Steiner points a later split's grown wedge took in
};

// Conforming recovery of every face of `missing`, with its checks, then
// the splitting of every added point (edge points first) with its checks;
// at the end every input triangle is a face.
// What recover_faces promises on success (recovery.hpp), for the case's
// mesh after result r: a valid mesh, every input triangle a face, the
// input points where they were (`input`: their coordinates before), the
// Steiner points after them and none on an input triangle.
void check_recovered_case(Case& c, const cbr::recover::RecoveryResult& r,
                          const cbr::mesh::LargeArray<double>& input) {
    TetMesh& m = c.m();
    require_valid(m, "after recover_faces");
    CHECK(cbr::recover::mark_present_faces(m, *c.faces).empty());
    CHECK(std::equal(input.begin(), input.end(), m.coordinates().begin()));
    CHECK(m.vertex_count() == c.input_count + r.steiner.size());
    for (VertexId v : r.steiner) CHECK_FALSE(on_some_input_triangle(m, *c.faces, v));
}

SplitStats conform_and_split(Case& c, const std::vector<std::size_t>& missing) {
    TetMesh& m = c.m();
    const ConstraintFaces& faces = *c.faces;
    SplitStats st;
    SurfacePoints sp(faces, m.vertex_count());
    ConformingRecovery cr(m, sp);
    for (std::size_t f : missing) {
        INFO("conforming recovery of triangle " << f);
        REQUIRE_MESSAGE(cr.recover_face(f), cr.why());
        require_valid(m, "after recover_face");
    }
    // Every point added is recorded, and only those.
    REQUIRE(sp.added_in_order().size() == m.vertex_count() - c.input_count);
    {
        std::set<VertexId> seen(sp.added_in_order().begin(), sp.added_in_order().end());
        CHECK(seen.size() == sp.added_in_order().size());
        for (VertexId v = static_cast<VertexId>(c.input_count); v < m.vertex_count(); ++v) {
            CHECK(sp.is_added(v));
            CHECK(seen.count(v) == 1);
        }
    }
    const std::vector<TetId> inc = incident_tets(m);
    // Chains: every edge of a missing face, a to b, consecutive vertices
    // joined by mesh edges, inner ones points added on that edge; every edge
    // point is on exactly one chain.
    std::map<VertexId, int> on_chains;
    std::set<std::pair<VertexId, VertexId>> edges_done;
    for (std::size_t f : missing) {
        const Triangle& t = faces.triangle(f);
        for (int k = 0; k < 3; ++k) {
            const VertexId a = t[k], b = t[(k + 1) % 3];
            const std::vector<VertexId> ch = sp.chain(a, b);
            INFO("edge " << a << "-" << b);
            REQUIRE(ch.size() >= 2);
            CHECK(ch.front() == a);
            CHECK(ch.back() == b);
            for (std::size_t i = 0; i + 1 < ch.size(); ++i)
                CHECK_MESSAGE(find_edge_tet(m, ch[i], inc[ch[i]], ch[i + 1]) != kNoTet,
                              "chain link " << ch[i] << "-" << ch[i + 1] << " is not a mesh edge");
            if (!edges_done.insert(std::minmax(a, b)).second) continue;
            for (std::size_t i = 1; i + 1 < ch.size(); ++i) {
                REQUIRE(sp.is_added(ch[i]));
                VertexId x = 0, y = 0;
                REQUIRE(sp.on_edge(ch[i], &x, &y, nullptr));
                CHECK(std::minmax(x, y) == std::minmax(a, b));
                ++on_chains[ch[i]];
            }
        }
    }
    // Each added point is a rounded intersection point: within a few ulps
    // (relative to its edge / face) of the edge or face it was added on, and
    // inside it.
    for (VertexId v : sp.added_in_order()) {
        VertexId a = 0, b = 0;
        std::size_t f = SurfacePoints::npos;
        if (sp.on_edge(v, &a, &b, &f)) {
            ++st.edge_points;
            CHECK(on_chains[v] == 1);
            double s = 0;
            const double e = line_distance(m.point(v), m.point(a), m.point(b), &s);
            CHECK(e <= 1e-13 * dist(m.point(a), m.point(b)));
            CHECK(s > 0);
            CHECK(s < 1);
            st.max_fans = std::max(st.max_fans, sp.faces_of_edge(a, b).size());
        } else {
            ++st.face_points;
            REQUIRE(f < faces.size());
            const Triangle& t = faces.triangle(f);
            double bary[3];
            const double e = plane_distance(m.point(v), m.point(t[0]), m.point(t[1]), m.point(t[2]), bary);
            const double size = std::max({dist(m.point(t[0]), m.point(t[1])), dist(m.point(t[1]), m.point(t[2])),
                                          dist(m.point(t[2]), m.point(t[0]))});
            CHECK(e <= 1e-13 * size);
            for (double x : bary) CHECK(x > -1e-13);
        }
    }

    // Splitting, edge points first.
    PointSplitting ps(m, sp, cr.incident());
    std::vector<VertexId> steiner;
    std::size_t split_off = 0, absorbed = 0;
    const std::vector<VertexId> added = sp.added_in_order();
    for (const bool edges : {true, false}) {
        for (VertexId e : added) {
            if (!sp.is_added(e) || sp.on_edge(e, nullptr, nullptr, nullptr) != edges) continue;
            INFO("splitting added point " << e << (edges ? " (edge)" : " (face)"));
            const std::size_t before = added_now(sp);
            const std::vector<VertexId> steiner_before = steiner;
            const std::size_t vertices_before = m.vertex_count();
            REQUIRE_MESSAGE(ps.split(e, steiner), ps.why());
            ++split_off;
            // Earlier Steiner points a grown wedge took in whole are gone
            // from the list and from every tetrahedron; the others stay, in
            // order, and the new ones follow.
            std::size_t absorbed_now = 0;
            for (VertexId s : steiner_before)
                if (std::find(steiner.begin(), steiner.end(), s) == steiner.end()) {
                    ++absorbed_now;
                    CHECK_FALSE(used_by_a_tet(m, s));
                }
            absorbed += absorbed_now;
            require_valid_but_unused(m, split_off + absorbed, "after split");
            CHECK(added_now(sp) == before - 1);
            CHECK_FALSE(sp.is_added(e));
            CHECK_FALSE(used_by_a_tet(m, e));
            const std::size_t made = m.vertex_count() - vertices_before;
            CHECK(made > 0);
            REQUIRE(steiner.size() == steiner_before.size() - absorbed_now + made);
            for (std::size_t i = steiner.size() - made; i < steiner.size(); ++i) {
                CHECK(steiner[i] == vertices_before + (i - (steiner.size() - made)));
                CHECK_MESSAGE(!on_some_input_triangle(m, faces, steiner[i]), "Steiner point on the surface");
                CHECK(used_by_a_tet(m, steiner[i]));
            }
            // An edge point leaves its chain, which stays a chain of mesh
            // edges.
            if (edges) {
                for (std::size_t f : missing) {
                    const Triangle& t = faces.triangle(f);
                    for (int k = 0; k < 3; ++k) {
                        const std::vector<VertexId> ch = sp.chain(t[k], t[(k + 1) % 3]);
                        CHECK(std::find(ch.begin(), ch.end(), e) == ch.end());
                        const std::vector<TetId> inc2 = incident_tets(m);
                        for (std::size_t i = 0; i + 1 < ch.size(); ++i)
                            CHECK(find_edge_tet(m, ch[i], inc2[ch[i]], ch[i + 1]) != kNoTet);
                    }
                }
            }
        }
    }
    CHECK(added_now(sp) == 0);
    // Every Steiner point is still off the surface (none moved).
    for (VertexId s : steiner) CHECK_FALSE(on_some_input_triangle(m, faces, s));
    CHECK(cbr::recover::mark_present_faces(m, faces).empty());
    require_valid_but_unused(m, split_off + absorbed, "at the end");
    CHECK(ps.made() == steiner.size() + absorbed);
    // Compacted, the mesh is valid as a whole: the split-off and absorbed
    // points were the only unused vertices and the Steiner points are renumbered after the
    // input ones.
    std::vector<VertexId> kept = steiner;
    compact_vertices_from(m, c.input_count, kept);
    require_valid(m, "after compaction");
    CHECK(kept.size() == steiner.size());
    CHECK(m.vertex_count() == c.input_count + steiner.size());
    st.steiner = steiner.size();
    st.absorbed = absorbed;
    return st;
}

// `levels` triangles stacked, the ones between top and bottom faces too.
cbr::test::Polyhedron twisted_stack(int levels, double twist) { return cbr::test::twisted_prisms(levels, twist, true); }

// The prism turned by an arbitrary rotation, scaled and moved: every
// coordinate rounded.
cbr::test::Polyhedron rotated(cbr::test::Polyhedron p, double ax, double ay, double az, double scale,
                              const double shift[3]) {
    const double cx = std::cos(ax), sx = std::sin(ax), cy = std::cos(ay), sy = std::sin(ay), cz = std::cos(az),
                 sz = std::sin(az);
    const double r[3][3] = {{cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
                            {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
                            {-sy, cy * sx, cy * cx}};
    for (std::size_t i = 0; i + 2 < p.xyz.size(); i += 3) {
        const double x[3] = {p.xyz[i], p.xyz[i + 1], p.xyz[i + 2]};
        for (int k = 0; k < 3; ++k)
            p.xyz[i + k] = shift[k] + scale * (r[k][0] * x[0] + r[k][1] * x[1] + r[k][2] * x[2]);
    }
    return p;
}

// Triangle A B C (tilted, integer corners) with pairs of points just above
// and below it at the barycentric positions selected by `mask`; `far` adds
// the corners of a big cube; `closed` adds apex D and the other three faces
// of the tetrahedron ABCD (a closed surface), else the triangle is alone
// (an open surface: its edges have one triangle).
cbr::test::Polyhedron pierced_triangle(int mask, bool far, bool closed, double far_size = 15.0) {
    cbr::test::Polyhedron p;
    p.xyz = {0, 0, 0, 8, 1, 2, 1, 7, -1};
    p.tris = {0, 1, 2};
    if (closed) {
        p.xyz.insert(p.xyz.end(), {3, 3, 9});
        p.tris = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};
    }
    const double u[3] = {8, 1, 2}, v[3] = {1, 7, -1};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double bary[6][2] = {{0.2, 0.3}, {0.5, 0.2}, {0.3, 0.45}, {0.15, 0.15}, {0.6, 0.3}, {0.3, 0.3}};
    for (int i = 0; i < 6; ++i) {
        if (!(mask >> i & 1)) continue;
        for (const double h : {0.21, -0.17}) {
            const double hh = h * (1 + bary[i][0]);
            for (int k = 0; k < 3; ++k) p.xyz.push_back(bary[i][0] * u[k] + bary[i][1] * v[k] + hh * n[k] / nl);
        }
    }
    if (far)
        for (int sx = -1; sx <= 1; sx += 2)
            for (int sy = -1; sy <= 1; sy += 2)
                for (int sz = -1; sz <= 1; sz += 2) p.xyz.insert(p.xyz.end(), {4 + far_size * sx, 4 + far_size * sy, far_size * sz});
    return p;
}

// Minimum over the four corners of 6 |V| / (product of the three edge
// lengths at the corner): the sine-like flatness of a tetrahedron.
double relative_volume(const TetMesh& m, TetId t) {
    const double* p[4] = {m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)), m.point(m.vertex(t, 2)),
                          m.point(m.vertex(t, 3))};
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = p[1][k] - p[0][k];
        v[k] = p[2][k] - p[0][k];
        w[k] = p[3][k] - p[0][k];
    }
    const double six = std::fabs(u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                                 u[2] * (v[0] * w[1] - v[1] * w[0]));
    double worst = INFINITY;
    for (int i = 0; i < 4; ++i) {
        double prod = 1;
        for (int j = 0; j < 4; ++j)
            if (j != i) prod *= dist(p[i], p[j]);
        worst = std::min(worst, six / prod);
    }
    return worst;
}

}  // namespace

// ===========================================================================
// 1. Polygon triangulation

TEST_CASE("triangulate_polygon: convex polygon, counter-clockwise and clockwise") {
    std::vector<P2> pts;
    const int n = 9;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * kPi * i / n + 0.1;
        pts.push_back({3 * std::cos(a) + 0.5, 2 * std::sin(a) - 1, 0.0});
    }
    const auto tris = triangulate_polygon(ptrs(pts), Projection{0, 1}, +1);
    check_triangulation(pts, +1, tris);

    std::vector<P2> cw(pts.rbegin(), pts.rend());
    const auto tris_cw = triangulate_polygon(ptrs(cw), Projection{0, 1}, -1);
    check_triangulation(cw, -1, tris_cw);
    CHECK(shoelace(cw) < 0);

    // The wrong turn has no triangulation.
    CHECK(triangulate_polygon(ptrs(pts), Projection{0, 1}, -1).empty());
    CHECK(triangulate_polygon(ptrs(cw), Projection{0, 1}, +1).empty());
    // A triangle is itself.
    const std::vector<P2> tri = {P2{0, 0, 0}, P2{1, 0, 0}, P2{0, 1, 0}};
    const auto one = triangulate_polygon(ptrs(tri), Projection{0, 1}, +1);
    REQUIRE(one.size() == 1);
    CHECK(one[0] == std::array<int, 3>{0, 1, 2});
}

TEST_CASE("triangulate_polygon: triangles named flat are left out") {
    // A chain of points on one line (collinear but for a rounding-sized
    // dip at vertex 1, which makes 0-1-2 a valid ear) and one point off it:
    // only the fan from the point off the line avoids the chain's own
    // triangles.
    const std::vector<P2> loop = {P2{0, 0, 0}, P2{1, -1e-12, 0}, P2{2, 0, 0}, P2{3, 0, 0}, P2{1.5, 0.001, 0}};
    const auto on_chain = [](int i, int j, int k) { return i < 4 && j < 4 && k < 4; };
    const auto tris = triangulate_polygon(ptrs(loop), Projection{0, 1}, +1, on_chain);
    check_triangulation(loop, +1, tris);
    for (const auto& t : tris) CHECK_FALSE(on_chain(t[0], t[1], t[2]));
    // Every triangle flat: none.
    CHECK(triangulate_polygon(ptrs(loop), Projection{0, 1}, +1, [](int, int, int) { return true; }).empty());
}

TEST_CASE("triangulate_polygon: non-convex star-shaped polygons, every rotation of the loop") {
    // A star: alternate long and short spokes, strongly reflex.
    std::vector<P2> star;
    const int spikes = 6;
    for (int i = 0; i < 2 * spikes; ++i) {
        const double a = kPi * i / spikes;
        const double r = i % 2 ? 0.6 : 3.0;
        star.push_back({r * std::cos(a), r * std::sin(a), 0.0});
    }
    for (int rot = 0; rot < static_cast<int>(star.size()); ++rot) {
        INFO("rotation " << rot);
        std::vector<P2> loop(star.begin() + rot, star.end());
        loop.insert(loop.end(), star.begin(), star.begin() + rot);
        check_triangulation(loop, +1, triangulate_polygon(ptrs(loop), Projection{0, 1}, +1));
        std::vector<P2> rev(loop.rbegin(), loop.rend());
        check_triangulation(rev, -1, triangulate_polygon(ptrs(rev), Projection{0, 1}, -1));
    }
    // Random star-shaped polygons around the origin (the fans of added
    // points look like this), including nearly collinear runs.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int trial = 0; trial < 300; ++trial) {
        const int n = 3 + static_cast<int>(U(rng) * 12);
        std::vector<double> angles;
        for (int i = 0; i < n; ++i) angles.push_back(2 * kPi * U(rng));
        std::sort(angles.begin(), angles.end());
        bool ok = true;  // spokes at least a little apart and no gap of pi or more
        for (int i = 0; i < n; ++i) {
            const double gap = i + 1 < n ? angles[i + 1] - angles[i] : angles[0] + 2 * kPi - angles[i];
            ok = ok && gap > 1e-3 && gap < kPi - 1e-3;
        }
        if (!ok) continue;
        std::vector<P2> loop;
        for (double a : angles) {
            const double r = 0.2 + 3 * U(rng);
            loop.push_back({r * std::cos(a), r * std::sin(a), 0.0});
        }
        INFO("trial " << trial << " n " << n);
        check_triangulation(loop, +1, triangulate_polygon(ptrs(loop), Projection{0, 1}, +1));
    }
}

TEST_CASE("triangulate_polygon: a reflex vertex inside the ear of its neighbours is never covered") {
    // Vertex 2 pokes into the polygon so that triangle (1, 3, 5) would
    // contain it while its sides cross no polygon edge that does not touch
    // them: only the containment test refuses it.
    const std::vector<P2> loop = {P2{0, 0, 0}, P2{4, 0, 0}, P2{2.2, 1.0, 0}, P2{4, 3, 0}, P2{2, 4, 0}, P2{0, 3, 0}};
    const auto tris = triangulate_polygon(ptrs(loop), Projection{0, 1}, +1);
    check_triangulation(loop, +1, tris);
    // Also a dart (arrow head): one reflex vertex at the back.
    const std::vector<P2> dart = {P2{0, 0, 0}, P2{5, 2, 0}, P2{0, 4, 0}, P2{1.5, 2, 0}};
    check_triangulation(dart, +1, triangulate_polygon(ptrs(dart), Projection{0, 1}, +1));
    const std::vector<P2> dart2 = {P2{1.5, 2, 0}, P2{0, 0, 0}, P2{5, 2, 0}, P2{0, 4, 0}};
    check_triangulation(dart2, +1, triangulate_polygon(ptrs(dart2), Projection{0, 1}, +1));
}

TEST_CASE("triangulate_polygon: every simple polygon on a small integer grid (collinear vertices too)") {
    // Random loops of 4-8 points of {-3..3}^2, kept when simple (no contact
    // between non-adjacent edges, no edge folding back) and counter-
    // clockwise: each has a triangulation, and it is valid.
    std::mt19937_64 rng(17);
    std::uniform_int_distribution<int> G(-3, 3);
    std::uniform_int_distribution<int> N(4, 8);
    const Projection pr{0, 1};
    int simple_count = 0;
    for (int trial = 0; trial < 200000 && simple_count < 3000; ++trial) {
        const int n = N(rng);
        std::vector<P2> loop;
        for (int i = 0; i < n; ++i) loop.push_back({double(G(rng)), double(G(rng)), 0.0});
        bool simple = true;
        for (int i = 0; i < n && simple; ++i)
            for (int j = i + 1; j < n && simple; ++j) {
                if (loop[i] == loop[j]) simple = false;
                const int i2 = (i + 1) % n, j2 = (j + 1) % n;
                if (i2 == j || j2 == i) continue;
                const double *a = loop[i].data(), *b = loop[i2].data(), *c = loop[j].data(), *d = loop[j2].data();
                const int o1 = orient2d(pr, a, b, c), o2 = orient2d(pr, a, b, d), o3 = orient2d(pr, c, d, a),
                          o4 = orient2d(pr, c, d, b);
                if (o1 * o2 <= 0 && o3 * o4 <= 0) {
                    if (o1 == 0 && o2 == 0) {
                        bool overlap = true;
                        for (int k = 0; k < 2; ++k)
                            overlap = overlap && std::max(a[k], b[k]) >= std::min(c[k], d[k]) &&
                                      std::max(c[k], d[k]) >= std::min(a[k], b[k]);
                        if (overlap) simple = false;
                    } else {
                        simple = false;
                    }
                }
            }
        for (int i = 0; i < n && simple; ++i) {
            const P2 &a = loop[(i + n - 1) % n], &b = loop[i], &c = loop[(i + 1) % n];
            if (orient2d(pr, a.data(), b.data(), c.data()) == 0 &&
                (a[0] - b[0]) * (c[0] - b[0]) + (a[1] - b[1]) * (c[1] - b[1]) > 0)
                simple = false;
        }
        if (!simple || shoelace(loop) <= 0) continue;
        ++simple_count;
        INFO("trial " << trial);
        check_triangulation(loop, +1, triangulate_polygon(ptrs(loop), pr, +1));
        std::vector<P2> rev(loop.rbegin(), loop.rend());
        check_triangulation(rev, -1, triangulate_polygon(ptrs(rev), pr, -1));
        // Ear clipping (the large polygons' method) on the same polygons.
        check_triangulation(loop, +1, triangulate_polygon_by_ears(ptrs(loop), pr, +1));
        check_triangulation(rev, -1, triangulate_polygon_by_ears(ptrs(rev), pr, -1));
    }
    CHECK(simple_count == 3000);
}

// chord_is_clear against its definition, checked the plain way on small
// integer coordinates (every product exact): no polygon vertex strictly
// inside the chord, no polygon edge away from its ends crossing it at a
// point interior to both. Loops need not be simple; on a 5 x 5 grid many
// vertices lie on chords and many edges touch them at an end. Loops of
// more than kMaxOptimalPolygon vertices too (another buffer).
TEST_CASE("chord_is_clear: no vertex inside the chord, no edge across it") {
    std::mt19937_64 rng(29);
    std::uniform_int_distribution<int> G(-2, 2);
    const Projection pr{0, 1};
    const auto on_open_segment = [](const P2& p, const P2& q, const P2& v) {
        const double cross = (q[0] - p[0]) * (v[1] - p[1]) - (q[1] - p[1]) * (v[0] - p[0]);
        const double along = (v[0] - p[0]) * (q[0] - p[0]) + (v[1] - p[1]) * (q[1] - p[1]);
        const double length2 = (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]);
        return cross == 0 && along > 0 && along < length2;
    };
    int clear = 0, blocked_by_vertex = 0, blocked_by_edge = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const int n = trial % 50 == 0 ? kMaxOptimalPolygon + 6 : 4 + trial % 7;
        std::vector<P2> loop;
        for (int i = 0; i < n; ++i) loop.push_back({double(G(rng)), double(G(rng)), 0.0});
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                if (i == j || (i + 1) % n == j || (j + 1) % n == i || loop[i] == loop[j]) continue;
                bool vertex_inside = false, edge_across = false;
                for (int x = 0; x < n; ++x) {
                    if (x != i && x != j && on_open_segment(loop[i], loop[j], loop[x])) vertex_inside = true;
                    const int y = (x + 1) % n;
                    if (x != i && x != j && y != i && y != j &&
                        cross2d(loop[i].data(), loop[j].data(), loop[x].data(), loop[y].data()))
                        edge_across = true;
                }
                const bool expected = !vertex_inside && !edge_across;
                INFO("trial " << trial << " chord " << i << " " << j);
                CHECK(chord_is_clear(ptrs(loop), pr, i, j) == expected);
                clear += expected;
                blocked_by_vertex += vertex_inside;
                blocked_by_edge += edge_across && !vertex_inside;
            }
    }
    MESSAGE("clear " << clear << ", a vertex inside " << blocked_by_vertex << ", only an edge across "
                     << blocked_by_edge);
    CHECK(clear > 1000);
    CHECK(blocked_by_vertex > 1000);
    CHECK(blocked_by_edge > 1000);
}

TEST_CASE("triangulate_polygon: large fans go to ear clipping, which keeps every condition") {
    // Star-shaped loops around the origin like the fans of the feeder
    // body's added points (up to 922 vertices), with every rotation of the
    // start for a small one; and the flat triangles of a chain left out.
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (const int n : {5, 12, kMaxOptimalPolygon + 1, 200, 900}) {
        std::vector<P2> loop;
        for (int i = 0; i < n; ++i) {
            const double a = 2 * kPi * (i + 0.4 * U(rng)) / n;
            const double r = 0.2 + 3 * U(rng);
            loop.push_back({r * std::cos(a), r * std::sin(a), 0.0});
        }
        INFO("n " << n);
        const int rotations = n <= 12 ? n : 1;
        for (int rot = 0; rot < rotations; ++rot) {
            std::vector<P2> turned(loop.begin() + rot, loop.end());
            turned.insert(turned.end(), loop.begin(), loop.begin() + rot);
            check_triangulation(turned, +1, triangulate_polygon_by_ears(ptrs(turned), Projection{0, 1}, +1));
            std::vector<P2> rev(turned.rbegin(), turned.rend());
            check_triangulation(rev, -1, triangulate_polygon_by_ears(ptrs(rev), Projection{0, 1}, -1));
        }
        check_triangulation(loop, +1, triangulate_polygon(ptrs(loop), Projection{0, 1}, +1));
        CHECK(triangulate_polygon_by_ears(ptrs(loop), Projection{0, 1}, -1).empty());  // the wrong turn
    }
    const std::vector<P2> chain = {P2{0, 0, 0}, P2{1, -1e-12, 0}, P2{2, 0, 0}, P2{3, 0, 0}, P2{1.5, 0.001, 0}};
    const auto on_chain = [](int i, int j, int k) { return i < 4 && j < 4 && k < 4; };
    const auto tris = triangulate_polygon_by_ears(ptrs(chain), Projection{0, 1}, +1, on_chain);
    check_triangulation(chain, +1, tris);
    for (const auto& t : tris) CHECK_FALSE(on_chain(t[0], t[1], t[2]));
    CHECK(triangulate_polygon_by_ears(ptrs(chain), Projection{0, 1}, +1, [](int, int, int) { return true; }).empty());
}

TEST_CASE("triangulate_polygon: folded, self-crossing and degenerate loops have none") {
    const Projection pr{0, 1};
    // Bow tie.
    const std::vector<P2> bow = {P2{0, 0, 0}, P2{1, 1, 0}, P2{1, 0, 0}, P2{0, 1, 0}};
    CHECK(triangulate_polygon(ptrs(bow), pr, +1).empty());
    CHECK(triangulate_polygon(ptrs(bow), pr, -1).empty());
    // All on a line.
    const std::vector<P2> line = {P2{0, 0, 0}, P2{1, 1, 0}, P2{2, 2, 0}, P2{3, 3, 0}};
    CHECK(triangulate_polygon(ptrs(line), pr, +1).empty());
    CHECK(triangulate_polygon(ptrs(line), pr, -1).empty());
    // A fan that folds over itself (a loop winding twice around a point,
    // as a projection of a too-curved polygon would): every triangle of the
    // right sign exists locally, but no triangulation of the whole.
    std::vector<P2> twice;
    for (int i = 0; i < 7; ++i) {
        const double a = 4 * kPi * i / 7;
        twice.push_back({std::cos(a) * (1 + 0.1 * i), std::sin(a) * (1 + 0.1 * i), 0.0});
    }
    CHECK(triangulate_polygon(ptrs(twice), pr, +1).empty());
    CHECK(triangulate_polygon(ptrs(twice), pr, -1).empty());
    // Self-crossing loops (found by a differential search against builds
    // without the containment test, resp. without the chord test: each of
    // those alone returns triangles for them).
    const std::vector<std::vector<P2>> crossing = {
        {P2{2, -3, 0}, P2{2, 2, 0}, P2{-2, -3, 0}, P2{0, -2, 0}, P2{-1, -2, 0}},
        {P2{-1, 2, 0}, P2{0, -3, 0}, P2{1, 0, 0}, P2{0, -1, 0}, P2{2, -1, 0}},
        {P2{1, 0, 0}, P2{2, 1, 0}, P2{-1, -3, 0}, P2{2, 3, 0}, P2{2, -2, 0}},
        {P2{2, -3, 0}, P2{-2, -3, 0}, P2{-2, 1, 0}, P2{3, -3, 0}, P2{-3, -2, 0}, P2{0, -1, 0}},
        {P2{0, -1, 0}, P2{-3, -1, 0}, P2{3, 2, 0}, P2{1, -2, 0}, P2{-3, 1, 0}, P2{-3, 2, 0}},
        {P2{-3, -3, 0}, P2{3, -1, 0}, P2{-1, 2, 0}, P2{0, 0, 0}, P2{-1, -2, 0}, P2{3, 2, 0}},
    };
    for (std::size_t c = 0; c < crossing.size(); ++c) {
        INFO("self-crossing loop " << c);
        CHECK(triangulate_polygon(ptrs(crossing[c]), pr, +1).empty());
        CHECK(triangulate_polygon(ptrs(crossing[c]), pr, -1).empty());
    }
    // Fewer than three vertices.
    CHECK(triangulate_polygon(ptrs(std::vector<P2>(bow.begin(), bow.begin() + 2)), pr, +1).empty());
    // Degenerate: a vertex on the segment between its neighbours (a
    // triangle with a collinear "corner"): no triangle may be flat.
    const std::vector<P2> flat = {P2{0, 0, 0}, P2{1, 0, 0}, P2{2, 0, 0}};
    CHECK(triangulate_polygon(ptrs(flat), pr, +1).empty());
}

TEST_CASE("triangulate_polygon: maximizes the smallest triangle quality") {
    // A rhombus long in x: the short diagonal (1-3) gives two fat
    // triangles (quality 0.87), the long one (0-2) two flat ones (0.37).
    std::vector<P2> rh = {P2{-3, 0, 0}, P2{0, -1, 0}, P2{3, 0, 0}, P2{0, 1, 0}};
    for (int rot = 0; rot < 4; ++rot) {
        INFO("rotation " << rot);
        const auto tris = triangulate_polygon(ptrs(rh), Projection{0, 1}, +1);
        check_triangulation(rh, +1, tris);
        // The vertices at y = +-1 are joined: both triangles use them.
        for (const auto& t : tris) {
            int fat = 0;
            for (int k : t) fat += std::fabs(rh[k][0]) < 0.5;
            CHECK(fat == 2);
        }
        std::rotate(rh.begin(), rh.begin() + 1, rh.end());
    }
    // A regular hexagon stretched: among the 14 triangulations the best
    // max-min one has no sliver; compare with a brute-force optimum.
    std::vector<P2> hex;
    for (int i = 0; i < 6; ++i) {
        const double a = 2 * kPi * i / 6;
        hex.push_back({4 * std::cos(a), std::sin(a), 0.0});
    }
    const auto quality = [](const P2& a, const P2& b, const P2& c) {
        const double ar = std::fabs(tri_area2d(a, b, c)) * 2;
        double s = 0;
        for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
            s += (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]);
        return 2 * std::sqrt(3.0) * ar / s;
    };
    const auto tris = triangulate_polygon(ptrs(hex), Projection{0, 1}, +1);
    check_triangulation(hex, +1, tris);
    double got = INFINITY;
    for (const auto& t : tris) got = std::min(got, quality(hex[t[0]], hex[t[1]], hex[t[2]]));
    // Brute force: every triangulation of a convex hexagon by recursion.
    std::function<double(int, int)> best = [&](int i, int j) -> double {
        if (j - i < 2) return INFINITY;
        double b = -1;
        for (int k = i + 1; k < j; ++k) b = std::max(b, std::min({quality(hex[i], hex[k], hex[j]), best(i, k), best(k, j)}));
        return b;
    };
    CHECK(got == doctest::Approx(best(0, 5)).epsilon(1e-12));
}

// ===========================================================================
// 2. Vertex compaction

TEST_CASE("compact_vertices_from: drops unused vertices after `first`, renumbers the others in order") {
    const auto xyz = cbr::test::random_points(40, 3);
    cbr::delaunay::Delaunay d;
    REQUIRE(d.insert_points(xyz.data(), 40).ok);
    TetMesh& m = d.mesh_for_update();
    const std::size_t n = m.vertex_count();
    // Append 6 extra points; insert 3 of them (ids n+1, n+3, n+4) with
    // protected insertion, leave n, n+2, n+5 unused.
    const std::vector<double> extra = {0.31, 0.42, 0.53, 0.5, 0.5, 0.5, 0.71, 0.22, 0.63,
                                       0.2,  0.3,  0.4,  0.6, 0.7, 0.35, 0.9, 0.9, 0.1};
    const VertexId first_new = m.add_points(extra.data(), 6);
    REQUIRE(first_new == n);
    std::map<VertexId, std::array<double, 3>> where;
    for (VertexId v : {VertexId(n + 1), VertexId(n + 3), VertexId(n + 4)}) {
        const double* q = m.point(v);
        where[v] = {q[0], q[1], q[2]};
        TetId start = kNoTet;
        for (TetId t = 0; t < m.slot_count() && start == kNoTet; ++t) {
            if (m.is_free(t) || m.is_ghost(t)) continue;
            bool in = true;
            for (int f = 0; f < 4 && in; ++f) {
                const int* k = kFaceVertices[f];
                in = cbr::geom::orient3d(m.point(m.vertex(t, k[0])), m.point(m.vertex(t, k[1])),
                                         m.point(m.vertex(t, k[2])), q) >= 0;
            }
            if (in) start = t;
        }
        REQUIRE(start != kNoTet);
        REQUIRE(cbr::recover::insert_protected(m, v, start).ok);
    }
    // `first` = n - 1: vertex n - 1 (a Delaunay vertex, used) is the first
    // candidate and keeps its id; vertices below it are never touched.
    const std::vector<double> before(m.coordinates().begin(), m.coordinates().begin() + 3 * (n - 1));
    std::map<TetId, std::array<VertexId, 4>> tets_before;
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t)) tets_before[t] = {m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)};
    std::vector<VertexId> keep = {VertexId(n + 5), VertexId(n + 4), VertexId(n - 1), VertexId(n), VertexId(n + 1),
                                  VertexId(n + 3), VertexId(n + 2), 5};
    compact_vertices_from(m, n - 1, keep);

    REQUIRE(m.vertex_count() == n + 3);
    // Below `first`: coordinates identical.
    CHECK(std::equal(before.begin(), before.end(), m.coordinates().begin()));
    // Used ones renumbered in order: n-1 -> n-1, n+1 -> n, n+3 -> n+1, n+4 -> n+2.
    const std::map<VertexId, VertexId> expect = {
        {VertexId(n - 1), VertexId(n - 1)}, {VertexId(n + 1), VertexId(n)}, {VertexId(n + 3), VertexId(n + 1)},
        {VertexId(n + 4), VertexId(n + 2)}};
    for (const auto& [old_id, new_id] : expect) {
        if (old_id >= n) {
            const double* q = m.point(new_id);
            CHECK(q[0] == where[old_id][0]);
            CHECK(q[1] == where[old_id][1]);
            CHECK(q[2] == where[old_id][2]);
        }
    }
    // Tetrahedra remapped (slot by slot), nothing else changed.
    for (const auto& [t, v] : tets_before) {
        REQUIRE_FALSE(m.is_free(t));
        for (int i = 0; i < 4; ++i) {
            const VertexId want = v[i] == kGhostVertex || v[i] < n - 1 ? v[i] : expect.at(v[i]);
            CHECK(m.vertex(t, i) == want);
        }
    }
    // keep list: dropped ones removed, the others mapped, order kept.
    const std::vector<VertexId> want_keep = {VertexId(n + 2), VertexId(n - 1), VertexId(n), VertexId(n + 1), 5};
    CHECK(keep == want_keep);
    require_valid(m, "after compaction");
    // Every vertex is used now.
    for (VertexId v = 0; v < m.vertex_count(); ++v) CHECK(used_by_a_tet(m, v));
    CHECK(m.point(VertexId(n - 1))[0] == xyz[3 * d.external_id(VertexId(n - 1))]);
    // A vertex below `first` is kept even when unused: N (unused), N + 1
    // (inserted), N + 2 (unused), compacted from N + 1.
    const std::size_t N = m.vertex_count();
    const std::vector<double> more = {0.45, 0.55, 0.65, 0.35, 0.25, 0.45, 0.15, 0.85, 0.75};
    m.add_points(more.data(), 3);
    {
        const double* q = m.point(VertexId(N + 1));
        TetId start = kNoTet;
        for (TetId t = 0; t < m.slot_count() && start == kNoTet; ++t) {
            if (m.is_free(t) || m.is_ghost(t)) continue;
            bool in = true;
            for (int f = 0; f < 4 && in; ++f) {
                const int* k = kFaceVertices[f];
                in = cbr::geom::orient3d(m.point(m.vertex(t, k[0])), m.point(m.vertex(t, k[1])),
                                         m.point(m.vertex(t, k[2])), q) >= 0;
            }
            if (in) start = t;
        }
        REQUIRE(start != kNoTet);
        REQUIRE(cbr::recover::insert_protected(m, VertexId(N + 1), start).ok);
    }
    std::vector<VertexId> k3 = {VertexId(N), VertexId(N + 2), VertexId(N + 1)};
    compact_vertices_from(m, N + 1, k3);
    CHECK(m.vertex_count() == N + 2);
    CHECK(m.point(VertexId(N))[0] == more[0]);
    CHECK(m.point(VertexId(N + 1))[0] == more[3]);
    CHECK(k3 == std::vector<VertexId>{VertexId(N), VertexId(N + 1)});
    CHECK_FALSE(used_by_a_tet(m, VertexId(N)));
    CHECK(used_by_a_tet(m, VertexId(N + 1)));
    // first beyond the end: nothing to do.
    std::vector<VertexId> k2 = {1, 2};
    compact_vertices_from(m, m.vertex_count(), k2);
    CHECK(m.vertex_count() == N + 2);
    CHECK(k2 == std::vector<VertexId>{1, 2});
}

// ===========================================================================
// 3. ConformingRecovery + PointSplitting

TEST_CASE("conforming recovery and splitting: the Schonhardt prism") {
    Case c;
    const cbr::test::Polyhedron p = cbr::test::schonhardt_prism();
    build(c, p.xyz, p.tris);
    std::vector<std::size_t> missing = cbr::recover::mark_present_faces(c.m(), *c.faces);
    REQUIRE(!missing.empty());  // lateral triangles on the reflex diagonals
    missing = cbr::recover::recover_by_flips(c.m(), *c.faces, missing);
    REQUIRE_MESSAGE(!missing.empty(), "flips cannot recover the Schonhardt prism");
    require_valid(c.m(), "after flips");
    const SplitStats st = conform_and_split(c, missing);
    MESSAGE("prism: " << st.edge_points << " edge points, " << st.face_points << " face points, " << st.steiner
                      << " Steiner points");
    CHECK(st.edge_points > 0);
    CHECK(st.steiner >= st.edge_points + st.face_points);
}

TEST_CASE("conforming recovery and splitting: rotated and stacked Schonhardt prisms") {
    const double shift[3] = {0.3, -1.25, 2.5};
    struct Variant {
        const char* name;
        cbr::test::Polyhedron p;
    };
    const std::vector<Variant> variants = {
        {"twist 25, rotated", rotated(twisted_stack(2, 25 * kPi / 180), 0.3, 1.1, -0.7, 3.7, shift)},
        {"twist 45, rotated", rotated(twisted_stack(2, 45 * kPi / 180), -1.2, 0.4, 2.2, 0.013, shift)},
        {"stack of three", twisted_stack(4, kPi / 6)},
        {"stack of three, rotated", rotated(twisted_stack(4, kPi / 6), 0.9, -0.35, 0.15, 11.0, shift)},
    };
    for (const Variant& v : variants) {
        INFO(std::string(v.name));
        Case c;
        build(c, v.p.xyz, v.p.tris);
        std::vector<std::size_t> missing = cbr::recover::mark_present_faces(c.m(), *c.faces);
        missing = cbr::recover::recover_by_flips(c.m(), *c.faces, missing);
        REQUIRE(!missing.empty());
        const SplitStats st = conform_and_split(c, missing);
        MESSAGE(std::string(v.name) << ": " << missing.size() << " faces after flips, " << st.edge_points << " edge points, "
                       << st.face_points << " face points, " << st.steiner << " Steiner points");
        CHECK(st.edge_points + st.face_points > 0);
    }
}

TEST_CASE("conforming recovery and splitting: points inside a face (ball transformation)") {
    // The closed surface of a tetrahedron; its face 0 (a tilted triangle) is
    // pierced by short edges between points just above and just below it.
    // Conforming recovery (no flips first) puts points inside the face,
    // with several points per face their balls overlap.
    std::size_t total_face_points = 0, most = 0, total_absorbed = 0;
    for (int mask = 1; mask < 64; ++mask)
        for (const double far : {0.0, 15.0, 25.0}) {
            INFO("mask " << mask << ", far points at " << far);
            const cbr::test::Polyhedron p = pierced_triangle(mask, far > 0, true, far);
            Case c;
            build(c, p.xyz, p.tris);
            const std::vector<std::size_t> missing = cbr::recover::mark_present_faces(c.m(), *c.faces);
            REQUIRE(!missing.empty());
            const SplitStats st = conform_and_split(c, missing);
            total_face_points += st.face_points;
            most = std::max(most, st.face_points);
            total_absorbed += st.absorbed;
        }
    MESSAGE("pierced tetrahedron surfaces: " << total_face_points << " face points, up to " << most
                                              << " in one case; " << total_absorbed << " Steiner points absorbed");
    CHECK(total_face_points > 50);
    CHECK(most >= 8);
    // Crowded faces leave wedges no point near e sees whole: they grow
    // towards a target and take in earlier Steiner points.
    CHECK(total_absorbed > 0);
}

TEST_CASE("conforming recovery and splitting: a non-manifold edge (three triangles)") {
    // Edge AB (the z axis) with three fins; a small triangle of points
    // around its middle crosses AB and the fins, so AB is not a Delaunay
    // edge and its added point has three fans (three wedges).
    std::vector<double> xyz = {0, 0, -2, 0, 0, 2};
    std::vector<std::int64_t> tris;
    for (int k = 0; k < 3; ++k) {
        const double a = 2 * kPi * k / 3;
        xyz.insert(xyz.end(), {3 * std::cos(a), 3 * std::sin(a), 0.3 * k - 0.2});
        tris.insert(tris.end(), {0, 1, 2 + k});
    }
    for (int k = 0; k < 3; ++k) {
        const double a = 2 * kPi * k / 3 + kPi / 3;
        xyz.insert(xyz.end(), {0.3 * std::cos(a), 0.3 * std::sin(a), 0.1 + 0.05 * k});
    }
    for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2)
            for (int sz = -1; sz <= 1; sz += 2) xyz.insert(xyz.end(), {10.0 * sx, 10.0 * sy + 0.5, 10.0 * sz});
    Case c;
    build(c, xyz, tris);
    const std::vector<std::size_t> missing = cbr::recover::mark_present_faces(c.m(), *c.faces);
    REQUIRE(missing.size() == 3);
    const SplitStats st = conform_and_split(c, missing);
    MESSAGE("fins: " << st.edge_points << " edge points, " << st.face_points << " face points, " << st.steiner
                     << " Steiner points, up to " << st.max_fans << " triangles at an edge point");
    CHECK(st.max_fans == 3);
    CHECK(st.edge_points > 0);
}

// ===========================================================================
// 4. The driver

TEST_CASE("recover_faces: Schonhardt prism, stack and rotated variants") {
    const double shift[3] = {-0.7, 0.2, 1.5};
    struct Variant {
        const char* name;
        cbr::test::Polyhedron p;
        bool needs_steiner;
    };
    const std::vector<Variant> variants = {
        {"prism", cbr::test::schonhardt_prism(), true},
        {"stack of three", twisted_stack(4, kPi / 6), true},
        {"rotated, twist 25", rotated(twisted_stack(2, 25 * kPi / 180), 0.3, 1.1, -0.7, 3.7, shift), true},
        {"rotated stack", rotated(twisted_stack(4, kPi / 6), 0.9, -0.35, 0.15, 11.0, shift), true},
    };
    for (const Variant& v : variants) {
        INFO(std::string(v.name));
        Case c;
        build(c, v.p.xyz, v.p.tris);
        TetMesh& m = c.m();
        const auto input = m.coordinates();
        cbr::recover::RecoveryStats stats;
        const cbr::recover::RecoveryResult r = cbr::recover::recover_faces(m, *c.faces, stats);
        REQUIRE_MESSAGE(r.ok, r.why << (r.invalid.empty() ? std::string() : " / " + r.invalid[0]));
        CHECK(r.unrecovered.empty());
        CHECK(r.invalid.empty());
        require_valid(m, "after recover_faces");
        CHECK(cbr::recover::mark_present_faces(m, *c.faces).empty());
        // Input points unchanged, bit for bit.
        CHECK(std::equal(input.begin(), input.end(), m.coordinates().begin()));
        if (v.needs_steiner) CHECK(!r.steiner.empty());
        // Steiner ids are exactly [input count, vertex count), in order.
        REQUIRE(r.steiner.size() == m.vertex_count() - c.input_count);
        for (std::size_t i = 0; i < r.steiner.size(); ++i) CHECK(r.steiner[i] == c.input_count + i);
        for (VertexId s : r.steiner) CHECK_FALSE(on_some_input_triangle(m, *c.faces, s));
        for (VertexId x = 0; x < m.vertex_count(); ++x) CHECK(used_by_a_tet(m, x));
        CHECK(stats.missing_faces > 0);
        // Points off the surface, from the unblocking step or from splitting
        // conforming recovery's added points.
        CHECK(stats.steiner_generated > 0);
        CHECK(stats.steiner_generated >= stats.steiner_remaining);
        CHECK(stats.steiner_remaining == r.steiner.size());
        MESSAGE(std::string(v.name) << ": missing " << stats.missing_faces << ", by flips " << stats.recovered_by_flips
                       << ", conforming " << stats.conforming_points << ", Steiner " << stats.steiner_generated << " -> "
                       << stats.steiner_remaining);
    }
}

// ===========================================================================
// 5. Protected insertion: the nearly_flat rule

TEST_CASE("protected insertion: the rounded crossing of a planar quad's diagonals makes no sliver") {
    // Integer points exactly on the tilted plane x + 2y + 3z = 6, a convex
    // quad around c; far points on both sides. The quad is small and the
    // other points far, so both quad triangles are Delaunay faces and one
    // diagonal is an edge. p = the rounded crossing of the diagonals lies
    // a rounding error off the plane; inserted with the half of the
    // diagonal's shell on p's side as initial cavity, the in-plane faces
    // are boundary faces seen from p at a flat angle: without the
    // nearly_flat rule the cones over them are slivers.
    const double c[3] = {2, 2, 0};  // 2 + 4 + 0 = 6
    const double U[3] = {2, -1, 0}, W[3] = {3, 0, -1};
    const double N[3] = {1, 2, 3};
    std::mt19937_64 rng(11);
    std::uniform_int_distribution<int> big(3, 9), small(-1, 1);
    int variants = 0, off_plane = 0, took_in = 0;
    double worst = INFINITY;
    for (int trial = 0; trial < 40; ++trial) {
        const int qa[4][2] = {{big(rng), small(rng)}, {small(rng), big(rng)}, {-big(rng), small(rng)}, {small(rng), -big(rng)}};
        std::vector<double> xyz;
        for (const auto& q : qa)
            for (int k = 0; k < 3; ++k) xyz.push_back(c[k] + q[0] * U[k] + q[1] * W[k]);
        for (int s = -1; s <= 1; s += 2)
            for (int i = -1; i <= 1; ++i)
                for (int j = -1; j <= 1; ++j)
                    for (int k = 0; k < 3; ++k) xyz.push_back(c[k] + s * 40 * N[k] + 60 * i * U[k] + 60 * j * W[k] + (i == 0 && j == 0 ? 7 : 0));
        cbr::delaunay::Delaunay d;
        REQUIRE(d.insert_points(xyz.data(), xyz.size() / 3).ok);
        TetMesh& m = d.mesh_for_update();
        VertexId q[4];
        for (int i = 0; i < 4; ++i) q[i] = d.internal_id(static_cast<VertexId>(i));
        for (int i = 0; i < 4; ++i) REQUIRE(cbr::geom::orient3d(m.point(q[0]), m.point(q[1]), m.point(q[2]), m.point(q[3])) == 0);
        const std::vector<TetId> inc = incident_tets(m);
        // The diagonal present: (d0, d2); the other (d1, d3).
        VertexId d0 = q[0], d1 = q[1], d2 = q[2], d3 = q[3];
        TetId et = find_edge_tet(m, q[0], inc[q[0]], q[2]);
        if (et == kNoTet) {
            d0 = q[1], d1 = q[2], d2 = q[3], d3 = q[0];
            et = find_edge_tet(m, q[1], inc[q[1]], q[3]);
        }
        if (et == kNoTet) continue;  // neither diagonal (should not happen)
        // Rounded crossing: the point of d0 d2 nearest to line d1 d3.
        const double *P0 = m.point(d0), *P2 = m.point(d2), *P1 = m.point(d1), *P3 = m.point(d3);
        double e1[3], e2[3], r[3];
        for (int k = 0; k < 3; ++k) {
            e1[k] = P2[k] - P0[k];
            e2[k] = P3[k] - P1[k];
            r[k] = P0[k] - P1[k];
        }
        const auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
        const double a = dot(e1, e1), e = dot(e2, e2), b = dot(e1, e2), cc = dot(e1, r), f = dot(e2, r);
        const double s = (b * f - cc * e) / (a * e - b * b);
        double p[3];
        for (int k = 0; k < 3; ++k) p[k] = P0[k] + s * e1[k];
        const int side = cbr::geom::orient3d(P0, P1, P2, p);
        ++variants;
        if (side != 0) ++off_plane;
        // Initial cavity: the tetrahedra of the diagonal's shell on p's side
        // (all of them when p is exactly on the plane would also do; then
        // take the + side).
        Shell sh;
        REQUIRE(shell(m, d0, d2, et, sh));
        const int want = side == 0 ? 1 : side;
        std::vector<TetId> cavity;
        for (std::size_t i = 0; i < sh.size(); ++i) {
            const VertexId x = sh.ring[i], y = sh.ring[(i + 1) % sh.size()];
            const int ox = cbr::geom::orient3d(P0, P1, P2, m.point(x)), oy = cbr::geom::orient3d(P0, P1, P2, m.point(y));
            if (ox * want >= 0 && oy * want >= 0) cavity.push_back(sh.tets[i]);
        }
        REQUIRE(!cavity.empty());
        REQUIRE(cavity.size() < sh.size());
        TetId start = kNoTet;
        for (TetId t : cavity) {
            bool in = true;
            for (int g = 0; g < 4 && in; ++g) {
                const int* k = kFaceVertices[g];
                in = cbr::geom::orient3d(m.point(m.vertex(t, k[0])), m.point(m.vertex(t, k[1])),
                                         m.point(m.vertex(t, k[2])), p) >= 0;
            }
            if (in) start = t;
        }
        if (start == kNoTet) continue;  // p rounded off the diagonal's half shell
        const VertexId pv = m.add_points(p, 1);
        const cbr::recover::ProtectedInsertResult res = cbr::recover::insert_protected_in_cavity(m, pv, start, cavity);
        REQUIRE_MESSAGE(res.ok, res.why);
        require_valid(m, "after the insertion");
        took_in += res.added > 0;
        for (TetId t : res.created) {
            if (m.is_ghost(t)) continue;
            const double rv = relative_volume(m, t);
            worst = std::min(worst, rv);
            CHECK_MESSAGE(rv > 1e-12, "trial " << trial << ": a new tetrahedron flat to " << rv << " (p off the plane by "
                                               << side << ")");
        }
    }
    MESSAGE(variants << " quads, " << off_plane << " crossings rounded off the plane, " << took_in
                     << " cavities grew across the plane; flattest new tetrahedron " << worst);
    CHECK(variants >= 20);
    CHECK(off_plane >= 5);  // else this test does not test the rule
}


// ===========================================================================
// Known failures (found while writing these tests; reported). may_fail: they
// are reported without failing the run; drop the decorator once fixed.

// Through the driver: flips run first and leave meshes that conforming
// recovery or splitting may then refuse. None of the 189 is refused any
// more. Mask 57 recovers since the interior is searched again after flat
// tetrahedra are removed, mask 62 since the crossing point is tried again
// a hair along the edge (session 17), and mask 27 with far points at 25
// since the flips try the blocking ring vertices first (session 33; in
// ring order it still fails: "cavity correction would remove a
// tetrahedron of the crossing the point splits", the kept shell of the
// crossing edge holding a flat tetrahedron, two pierce pairs on parallel
// verticals, with the rounded crossing point behind one of its faces).
namespace {

void recover_pierced(int mask, double far) {
    INFO("mask " << mask << ", far points at " << far);
    const cbr::test::Polyhedron p = pierced_triangle(mask, far > 0, true, far > 0 ? far : 15.0);
    Case c;
    build(c, p.xyz, p.tris);
    cbr::recover::RecoveryStats stats;
    const cbr::recover::RecoveryResult r = cbr::recover::recover_faces(c.m(), *c.faces, stats);
    CHECK_MESSAGE(r.ok, r.why);
}

}  // namespace

TEST_CASE("recover_faces: the feeder body from another flip state (deepest round's budget 10,000)") {
    // With a quarter of the default budget, the flips leave the feeder
    // body a mesh on which three steps used to fail in turn: a face
    // crossing that rounded onto its chain end (conforming recovery: "p
    // coincides with a vertex of the mesh"), the suppression around stalled
    // splits rebuilding balls with flat tetrahedra of one triangle ("a fan
    // borders more than two wedges"), and the splits after it starting from
    // stale incident tetrahedra. About 25 s (Release).
    const std::string dir = cbr::test::shared_data_dir();
    if (dir.empty()) {
        MESSAGE("no ../shared data: skipped");
        return;
    }
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(dir + "/surfaces/thingiverse-feeder-body.off", s));
    Case c;
    build(c, s.xyz, s.tris);
    TetMesh& m = c.m();
    cbr::recover::RecoveryOptions options;
    options.deepest_flip_budget = 10000;
    cbr::recover::RecoveryStats stats;
    const cbr::recover::RecoveryResult r = cbr::recover::recover_faces(m, *c.faces, stats, options);
    REQUIRE_MESSAGE(r.ok, r.why << (r.invalid.empty() ? std::string() : " / " + r.invalid[0]));
    require_valid(m, "after recover_faces");
    CHECK(cbr::recover::mark_present_faces(m, *c.faces).empty());
    for (VertexId v : r.steiner) CHECK_FALSE(on_some_input_triangle(m, *c.faces, v));
    CHECK(stats.conforming_points > 0);  // the path through conforming recovery and splitting
    MESSAGE("feeder body, budget 10,000: missing " << stats.missing_faces << ", by flips " << stats.recovered_by_flips
                                                   << ", conforming " << stats.conforming_points << ", Steiner "
                                                   << stats.steiner_generated << " -> " << stats.steiner_remaining);
}

namespace {

// The options with the flips' nested edge removals in ring order
// (NestedOrder::kRing), the flip state in which the fixtures below were
// chosen: with the blocking ring vertices first (the default since
// session 33) the flips recover enough of their faces that the steps
// these tests show are not reached.
cbr::recover::RecoveryOptions in_ring_order(cbr::recover::RecoveryOptions options = {}) {
    options.nested_order = cbr::recover::NestedOrder::kRing;
    return options;
}

}  // namespace

TEST_CASE("recover_faces: a turned CAD cylinder recovers in another order of the faces") {
    // tests/data/recover/cylinder-turned-r3.off: its fanned caps are nearly
    // planar after the turn, and conforming recovery fails in the order the
    // flips leave the faces in (the first order alone must fail: if it ever
    // succeeds, the retry is no longer what this test shows, and it says
    // so). recovery.cpp then restores the flips' mesh and tries other orders.
    // The retry with unblocking points of any star recovers this cylinder
    // too, with no conforming point: it is off here, so that this test
    // keeps showing the orders (the next test shows that retry).
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/cylinder-turned-r3.off", s));
    cbr::recover::RecoveryOptions orders_only = in_ring_order();
    orders_only.unblocking_tries = 1;
    {
        Case c;
        build(c, s.xyz, s.tris);
        cbr::recover::RecoveryOptions one_order = orders_only;
        one_order.face_orders = 1;
        cbr::recover::RecoveryStats stats;
        const cbr::recover::RecoveryResult r = cbr::recover::recover_faces(c.m(), *c.faces, stats, one_order);
        CHECK_FALSE(r.ok);
        CHECK(stats.conforming_points > 0);
        CHECK(r.why.find("conforming recovery of triangle") != std::string::npos);
        CHECK(r.why.find("other orders") == std::string::npos);
    }
    Case c;
    build(c, s.xyz, s.tris);
    TetMesh& m = c.m();
    cbr::recover::RecoveryStats stats;
    const cbr::recover::RecoveryResult r = cbr::recover::recover_faces(m, *c.faces, stats, orders_only);
    REQUIRE_MESSAGE(r.ok, r.why << (r.invalid.empty() ? std::string() : " / " + r.invalid[0]));
    require_valid(m, "after recover_faces");
    CHECK(cbr::recover::mark_present_faces(m, *c.faces).empty());
    CHECK(stats.conforming_points > 0);
    CHECK(m.vertex_count() == c.input_count + r.steiner.size());
    for (VertexId v : r.steiner) CHECK_FALSE(on_some_input_triangle(m, *c.faces, v));
}

namespace {

// recover_faces with `options` on the Delaunay mesh of surface s, built
// afresh; the result (the mesh is dropped).
cbr::recover::RecoveryResult recover_fresh(const cbr::test::OffSurface& s, const cbr::recover::RecoveryOptions& options) {
    Case c;
    build(c, s.xyz, s.tris);
    cbr::recover::RecoveryStats stats;
    return cbr::recover::recover_faces(c.m(), *c.faces, stats, options);
}

// recover_faces with `options` on the Delaunay mesh of surface s, built
// afresh: required to succeed, checked (check_recovered_case); its
// statistics.
cbr::recover::RecoveryStats recover_checked(const cbr::test::OffSurface& s,
                                            const cbr::recover::RecoveryOptions& options = {}) {
    Case c;
    build(c, s.xyz, s.tris);
    const auto input = c.m().coordinates();
    cbr::recover::RecoveryStats stats;
    const cbr::recover::RecoveryResult r = cbr::recover::recover_faces(c.m(), *c.faces, stats, options);
    REQUIRE_MESSAGE(r.ok, r.why << (r.invalid.empty() ? std::string() : " / " + r.invalid[0]));
    check_recovered_case(c, r, input);
    return stats;
}

}  // namespace

TEST_CASE("recover_faces: a turned fan-cap prism recovers with unblocking points of any star") {
    // tests/data/recover/prism-96-fan-caps-q1.off: a 96-gon prism, both caps
    // fanned from one rim vertex, turned in space. The points that would
    // unblock the flips on its nearly flat caps see most of a cap; their
    // stars are over the limit (kUnblockingMaxStar), and without them
    // conforming recovery fails in every order of the faces. recovery.cpp
    // then starts again from the mesh the flips left, with no limit.
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/prism-96-fan-caps-q1.off", s));
    {
        cbr::recover::RecoveryOptions limited = in_ring_order();
        limited.unblocking_tries = 1;
        const cbr::recover::RecoveryResult r = recover_fresh(s, limited);
        CHECK_FALSE(r.ok);  // if the first try ever succeeds, this test no longer shows the retry
        CHECK_FALSE(r.unrecovered.empty());
        CHECK(r.why.find("other placements of unblocking points") == std::string::npos);
    }
    const cbr::recover::RecoveryStats stats = recover_checked(s, in_ring_order());
    // The retry's points made the flips enough: no point on the surface
    // was needed, and the Steiner points it made went again (§6).
    CHECK(stats.steiner_generated > 0);
    CHECK(stats.conforming_points == 0);
}

TEST_CASE("recover_faces: a turned fan-cap prism recovers with denser unblocking points nearer the faces") {
    // tests/data/recover/prism-96-fan-caps-h1-r32.off: a 96-gon prism of
    // radius 10 and height 1, both caps fanned from one rim vertex, turned
    // in space (fan_cap_prism.py 96 10 1, rotate_surface.py seed 32). With
    // the default unblocking points, and again with points of any star,
    // conforming recovery fails in every order of the faces (and it failed
    // in every retry of cbr_mesh_recover_faces before the denser points
    // came). recovery.cpp's third try puts a point every 4 crossed
    // tetrahedra instead of 8, down to 0.05 of the face's shortest edge
    // from it instead of 0.1 (kDenseUnblocking).
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/prism-96-fan-caps-h1-r32.off", s));
    {
        cbr::recover::RecoveryOptions default_points = in_ring_order();
        default_points.unblocking_tries = 2;  // the default points, then of any star
        const cbr::recover::RecoveryResult r = recover_fresh(s, default_points);
        CHECK_FALSE(r.ok);  // if this ever succeeds, the test no longer shows the denser points
        CHECK_FALSE(r.unrecovered.empty());
        CHECK(r.why.find("the sub-faces of a face do not form a disk") != std::string::npos);
    }
    CHECK(recover_checked(s, in_ring_order()).steiner_generated > 0);
}

// recovery.cpp's unblocking tries before the dense points kept where they
// do not cut (the fifth try; the sixth keeps the densest points so).
constexpr int kTriesBeforeKeptDense = 4;

// The turned copy in `path` fails in every attempt with only the first
// `tries_before` of recovery.cpp's unblocking tries (the reason containing
// `why`) and recovers with them all, passing recover_checked's checks: its
// statistics.
cbr::recover::RecoveryStats recovered_by_later_try(const char* path, int tries_before, const char* why) {
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(path, s));
    cbr::recover::RecoveryOptions without = {};
    without.unblocking_tries = tries_before;
    const cbr::recover::RecoveryResult r = recover_fresh(s, without);
    CHECK_FALSE(r.ok);  // if this ever succeeds, the test no longer shows the last try
    CHECK_FALSE(r.unrecovered.empty());
    CHECK_MESSAGE(r.why.find(why) != std::string::npos, r.why);
    const cbr::recover::RecoveryStats stats = recover_checked(s, {});
    MESSAGE("Steiner points generated " << stats.steiner_generated << ", remaining " << stats.steiner_remaining
                                        << ", conforming points " << stats.conforming_points);
    return stats;
}

TEST_CASE("recover_faces: a turned CAD plate recovers with the dense unblocking points kept where they do not cut") {
    // tests/data/recover/guide-arm-r41.off: the shared
    // thingiverse-feeder-guide-arm turned in space (rotate_surface.py seed
    // 41). Six of its triangles lie in a plate of 444 input triangles that
    // the turn makes nearly coplanar. The earlier unblocking tries turn
    // nearly all their points away there (few make a missing edge meet
    // fewer tetrahedra), and conforming recovery then breaks a face's disk in
    // every order of the faces (TetGen recovers the copy). recovery.cpp's
    // last try keeps the dense points each target first gets inserted
    // (UnblockingOptions::keep_first).
    const cbr::recover::RecoveryStats stats = recovered_by_later_try(CBR_TEST_DATA_DIR "/recover/guide-arm-r41.off",
                                                                     kTriesBeforeKeptDense,
                                                                     "the sub-faces of a face do not form a disk");
    CHECK(stats.steiner_generated > 0);
}

TEST_CASE("recover_faces: a turned CAD plate recovers with unblocking points across recovered faces, in rounds") {
    // tests/data/recover/guide-arm-r51.off: the same part turned by
    // rotate_surface.py seed 51, its plate of 444 input triangles nearly
    // coplanar again (TetGen recovers the copy, with 55 Steiner points).
    // The last unblocking try as it was for seed 41 (one round, the walk
    // to a point stopped at recovered faces) left two faces of the plate
    // whose missing edge no point could be walked to, and splitting then
    // found no position for a Steiner point in every attempt. With the
    // walk free to pass recovered faces and a second round of points and
    // flips (recovery.cpp, kUnblockingTries), the flips recover every face:
    // no conforming point, 5 Steiner points left.
    const cbr::recover::RecoveryStats stats = recovered_by_later_try(
        CBR_TEST_DATA_DIR "/recover/guide-arm-r51.off", kTriesBeforeKeptDense, "no Steiner point position sees");
    CHECK(stats.steiner_generated > 0);
    CHECK(stats.conforming_points == 0);
}

TEST_CASE("recover_faces: CAD plates that the dense kept points fail recover with the densest ones") {
    // tests/data/recover/guide-arm-r91.off: the same part turned by
    // rotate_surface.py seed 91 (TetGen recovers it, with 52 Steiner
    // points). With the tries up to the dense points kept where they do
    // not cut, it fails in every attempt: the failure is reported as the
    // first try's (conforming recovery breaks a face's disk), and the
    // dense kept points leave two faces of its plate whose added points
    // splitting cannot place (no position sees the whole wedge).
    // recovery.cpp's last try keeps twice as many points in the same way,
    // and recovers it.
    CHECK(recovered_by_later_try(CBR_TEST_DATA_DIR "/recover/guide-arm-r91.off", kTriesBeforeKeptDense + 1,
                                 "the sub-faces of a face do not form a disk")
              .steiner_generated > 0);
    // tests/data/recover/guide-arm-jittered-s44.off: the part as exported
    // with every point moved a little (run_mutation_sweep.py seed 44, case
    // 298), its plates no longer planar (tetgen -pYQ exits 0 with 4 input
    // triangles missing and 24 tetrahedra crossing the surface). The same.
    CHECK(recovered_by_later_try(CBR_TEST_DATA_DIR "/recover/guide-arm-jittered-s44.off", kTriesBeforeKeptDense + 1,
                                 "no Steiner point position sees the whole wedge")
              .steiner_generated > 0);
}

TEST_CASE("recover_faces: a turned prism that fails in the default flip state recovers in another") {
    // tests/data/recover/prism-96-fan-caps-h1-r22.off: a 96-gon prism of
    // radius 10 and height 1, both caps fanned from one rim vertex, turned
    // in space (tests/bench/fan_cap_prism.py 96 10 1, rotate_surface.py
    // seed 22; seed 4 served until session 17, when it began to recover in
    // the default flip state). In ring order with the deepest flip
    // round's default budget, conforming recovery fails in every order of
    // the faces and with unblocking points of any star; the flips with
    // another budget leave a mesh from which it succeeds.
    // cbr_mesh_recover_faces tries those budgets (kRetryFlipBudgets, in
    // ring order) after a failure, once the enclosing box has failed too
    // (test_capi_recover checks that order on another prism). Since
    // session 33 the default order (the blocking ring vertices first)
    // recovers it in the first attempt, and since session 37 so does ring
    // order with the deepest round's two stages (flip_recovery.cpp,
    // kSearches); the failing state is now ring order with one deepest
    // round of 40,000 removals a face, the default until then. If it ever
    // succeeds, this test no longer shows why the retry is there, and
    // says so.
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/prism-96-fan-caps-h1-r22.off", s));
    {
        cbr::recover::RecoveryOptions one_deepest_round = in_ring_order();
        one_deepest_round.deepest_flip_budget = 40000;
        const cbr::recover::RecoveryResult r = recover_fresh(s, one_deepest_round);
        CHECK_FALSE(r.ok);
        CHECK(r.invalid.empty());
        CHECK_FALSE(r.unrecovered.empty());
    }
    int recovered_in = 0;
    for (const int budget : cbr::recover::kRetryFlipBudgets) {
        Case c;
        build(c, s.xyz, s.tris);
        const auto input = c.m().coordinates();
        cbr::recover::RecoveryOptions other = in_ring_order();
        other.deepest_flip_budget = budget;
        cbr::recover::RecoveryStats stats;
        const cbr::recover::RecoveryResult r = cbr::recover::recover_faces(c.m(), *c.faces, stats, other);
        CHECK(r.invalid.empty());
        if (!r.ok) continue;
        ++recovered_in;
        check_recovered_case(c, r, input);
    }
    CHECK(recovered_in > 0);
}

TEST_CASE("recover_faces: a turned CSG part that fails with the blocking vertices first recovers in ring order") {
    // tests/data/recover/csg-x-r19.off: the shared wildmeshing-csg-x
    // turned by rotate_surface.py seed 19. With the flips' nested removals
    // taking the blocking ring vertices first (the default), recovery
    // fails in every order of the faces and with every unblocking point
    // ("a rounded intersection point fell outside the tetrahedra it was
    // meant to split"); in ring order, the first attempts' order before
    // session 33, it recovers. cbr_mesh_recover_faces retries in that
    // order (FlipState; test_capi_recover checks the retry). (Until
    // session 39 this test used thingicsg-openscad-example012 turned by
    // seed 11, which the last unblocking try now recovers in the default
    // order.)
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/csg-x-r19.off", s));
    {
        const cbr::recover::RecoveryResult r = recover_fresh(s, {});
        CHECK_FALSE(r.ok);  // if this ever succeeds, the test no longer shows why the retry is there
        CHECK(r.invalid.empty());
        CHECK_FALSE(r.unrecovered.empty());
    }
    recover_checked(s, in_ring_order());
}

TEST_CASE("recover_faces: a face-interior crossing rounded behind its shell is tried again along the edge") {
    // tests/data/recover/prism-200-fan-caps-radius30-h1-r20.off: a 200-gon
    // prism of radius 30 and height 1, caps fanned from one rim vertex,
    // turned in space (tests/bench/fan_cap_prism.py 200 30 1,
    // rotate_surface.py seed 20). Where a mesh edge crosses the interior of
    // triangle 387, the rounded intersection point lands behind a face of
    // the edge's thin shell, which must go whole: conforming recovery
    // failed in every order of the faces, flip state and enclosing box.
    // The same crossing a hair further along the edge goes in
    // (ConformingRecovery::insert_on_crossing).
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/prism-200-fan-caps-radius30-h1-r20.off", s));
    Case c;
    build(c, s.xyz, s.tris);
    const auto input = c.m().coordinates();
    cbr::recover::RecoveryStats stats;
    const cbr::recover::RecoveryResult r = cbr::recover::recover_faces(c.m(), *c.faces, stats, in_ring_order());
    REQUIRE_MESSAGE(r.ok, r.why);
    check_recovered_case(c, r, input);
    CHECK(stats.conforming_points > 0);
    // prism-96-fan-caps-h1-r4.off (seed 4) failed the same way in the
    // default flip state and needed another; now the first attempt does.
    cbr::test::OffSurface s4;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/prism-96-fan-caps-h1-r4.off", s4));
    const cbr::recover::RecoveryResult r4 = recover_fresh(s4, {});
    CHECK_MESSAGE(r4.ok, r4.why);
}

TEST_CASE("recover_faces: a tetrahedron surface pierced near one face (flips, then conforming)") {
    // Same inputs as the ball transformation test above. Before the
    // crossing's tetrahedra were kept whole by the cavity correction,
    // grown wedges kept their vertices and flips searched deeper, 7 of the
    // 62 with masks under 32 failed; all of those recover now.
    for (int mask = 1; mask < 64; ++mask)
        for (const double far : {0.0, 15.0, 25.0}) recover_pierced(mask, far);
}

TEST_CASE("splitting: an added point on an open edge (one triangle)" * doctest::may_fail()) {
    // Open surfaces are legal (cbr.h). A lone triangle whose edge BC is
    // crossed: its added point has one fan, which does not cut its ball
    // into two wedges, and split() refuses ("the sub-faces around an added
    // point do not cut its ball").
    const cbr::test::Polyhedron p = pierced_triangle(16, true, false);
    Case c;
    build(c, p.xyz, p.tris);
    const std::vector<std::size_t> missing = cbr::recover::mark_present_faces(c.m(), *c.faces);
    REQUIRE(missing.size() == 1);
    const SplitStats st = conform_and_split(c, missing);
    CHECK(st.edge_points > 0);
}

TEST_CASE("triangulate_polygon: a self-crossing loop gets no triangulation" * doctest::may_fail()) {
    // Edges 2-3 and 4-5 cross at (-1, 1.5); the loop is not simple, yet
    // triangles (0 1 5) (1 3 5) (3 4 5) (1 2 3) come back for turn +1 (they
    // overlap: their areas do not add up to the loop's). The header promises
    // an empty result when the projection folds the polygon. (In split() the
    // fans are checked not to fold first, so this needs a loop that the fan
    // check lets through.)
    const std::vector<P2> loop = {P2{2, -2, 0}, P2{1, 2, 0}, P2{-1, 3, 0}, P2{-1, 1, 0}, P2{0, 3, 0}, P2{-2, 0, 0}};
    CHECK(triangulate_polygon(ptrs(loop), Projection{0, 1}, +1).empty());
}

// ===========================================================================
// 4. Flip recovery's memo of failed searches (FailedRings, FailedSearches)

TEST_CASE("failed rings: one key for every way of walking the same shell") {
    Shell s;
    s.ring = {7, 3, 9, 4, 12};
    const std::uint64_t k = FailedRings::key(5, 8, s);
    Shell rotated = s;
    std::rotate(rotated.ring.begin(), rotated.ring.begin() + 2, rotated.ring.end());
    CHECK(FailedRings::key(5, 8, rotated) == k);
    Shell reversed = s;  // the shell of vu walks the ring the other way
    std::reverse(reversed.ring.begin(), reversed.ring.end());
    CHECK(FailedRings::key(8, 5, reversed) == k);
    std::rotate(reversed.ring.begin(), reversed.ring.begin() + 3, reversed.ring.end());
    CHECK(FailedRings::key(8, 5, reversed) == k);
    // Another shell: the ring in the other direction, another vertex, other ends.
    CHECK(FailedRings::key(5, 8, reversed) != k);
    Shell other = s;
    other.ring[2] = 10;
    CHECK(FailedRings::key(5, 8, other) != k);
    CHECK(FailedRings::key(5, 6, s) != k);
    Shell swapped = s;  // same vertices, another cyclic order
    std::swap(swapped.ring[1], swapped.ring[2]);
    CHECK(FailedRings::key(5, 8, swapped) != k);
}

TEST_CASE("key table: finds what it holds through growth") {
    KeyTable<int> table;
    CHECK(table.find(42) == nullptr);
    for (std::uint64_t k = 0; k < 5000; ++k) table[k * 1000003u + 7] = static_cast<int>(k);
    REQUIRE(table.size() == 5000);
    for (std::uint64_t k = 0; k < 5000; ++k) {
        const int* v = table.find(k * 1000003u + 7);
        REQUIRE(v != nullptr);
        CHECK(*v == static_cast<int>(k));
    }
    CHECK(table.find(8) == nullptr);
    table[7] = -1;  // an existing key keeps one entry
    CHECK(table.size() == 5000);
    CHECK(*table.find(7) == -1);
}

TEST_CASE("key table: clear empties it, and it fills and grows again") {
    KeyTable<int> table;
    for (std::uint64_t k = 0; k < 3000; ++k) table[k * 7919u + 1] = static_cast<int>(k) + 1;
    table.clear();
    CHECK(table.size() == 0);
    for (std::uint64_t k = 0; k < 3000; ++k) REQUIRE(table.find(k * 7919u + 1) == nullptr);
    // A key held before the clear comes back value-initialised.
    CHECK(table[1] == 0);
    CHECK(table.size() == 1);
    // Past the old size, through growth: only what was put in since.
    for (std::uint64_t k = 0; k < 6000; ++k) table[k * 104729u + 3] = -static_cast<int>(k);
    CHECK(table.size() == 6001);
    for (std::uint64_t k = 0; k < 6000; ++k) {
        const int* v = table.find(k * 104729u + 3);
        REQUIRE(v != nullptr);
        CHECK(*v == -static_cast<int>(k));
    }
    CHECK(table.find(7919u + 1) == nullptr);  // the second key before the clear
    CHECK(*table.find(1) == 0);
}

TEST_CASE("failed searches: known only in the state they failed in") {
    cbr::recover::FailedSearches memo;
    memo.set_state(3);
    CHECK(memo.spent(1, 2, 4) == -1);
    memo.failed(1, 2, 4, 17);
    CHECK(memo.spent(1, 2, 4) == 17);
    CHECK(memo.spent(1, 2, 3) == -1);  // another depth is another search
    CHECK(memo.spent(2, 1, 4) == -1);  // and so is the other direction
    memo.set_state(4);
    CHECK(memo.spent(1, 2, 4) == -1);
    memo.failed(1, 2, 2, 5);
    memo.set_state(3);  // a rollback to state 3: its failures hold again
    CHECK(memo.spent(1, 2, 4) == -1);  // the entry now belongs to state 4
    memo.set_state(4);
    CHECK(memo.spent(1, 2, 2) == 5);
}

namespace {

bool same_mesh(const TetMesh& a, const TetMesh& b) {
    if (a.slot_count() != b.slot_count() || a.vertex_count() != b.vertex_count()) return false;
    for (TetId t = 0; t < a.slot_count(); ++t) {
        if (a.is_free(t) != b.is_free(t)) return false;
        if (a.is_free(t)) continue;
        for (int i = 0; i < 4; ++i) {
            if (a.vertex(t, i) != b.vertex(t, i)) return false;
            if (a.is_constrained(t, i) != b.is_constrained(t, i)) return false;
        }
    }
    return true;
}

// Flip recovery of `p` with and without the memo: the same faces left and
// the same mesh, slot by slot (skipping a search must change nothing).
void require_memo_changes_nothing(const std::string& name, const std::vector<double>& xyz,
                                  const std::vector<std::int64_t>& tris) {
    INFO(name);
    Case on, off;
    build(on, xyz, tris);
    build(off, xyz, tris);
    const std::vector<std::size_t> missing = cbr::recover::mark_present_faces(on.m(), *on.faces);
    REQUIRE(missing == cbr::recover::mark_present_faces(off.m(), *off.faces));
    const auto left_on = cbr::recover::recover_by_flips(on.m(), *on.faces, missing, cbr::recover::FlipMemo::kOn);
    const auto left_off = cbr::recover::recover_by_flips(off.m(), *off.faces, missing, cbr::recover::FlipMemo::kOff);
    MESSAGE(name << ": " << missing.size() << " missing, " << left_on.size() << " left after flips");
    CHECK(left_on == left_off);
    CHECK(same_mesh(on.m(), off.m()));
    require_valid(on.m(), name.c_str());
    // Every face not left is marked on both sides (a rollback must never
    // take back the mark of a face recovered before it).
    std::set<std::array<VertexId, 3>> marked;
    const TetMesh& m = on.m();
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        for (int f = 0; f < 4; ++f) {
            if (!m.is_constrained(t, f)) continue;
            const FacetRef across = m.neighbor(t, f);
            if (!m.is_constrained(facet_tet(across), facet_face(across))) continue;
            std::array<VertexId, 3> v = {m.vertex(t, kFaceVertices[f][0]), m.vertex(t, kFaceVertices[f][1]),
                                         m.vertex(t, kFaceVertices[f][2])};
            std::sort(v.begin(), v.end());
            marked.insert(v);
        }
    }
    std::size_t unmarked = 0;
    for (std::size_t i = 0; i < on.faces->size(); ++i) {
        if (std::binary_search(left_on.begin(), left_on.end(), i)) continue;
        std::array<VertexId, 3> v = on.faces->triangle(i);
        std::sort(v.begin(), v.end());
        unmarked += marked.count(v) == 0;
    }
    CHECK(unmarked == 0);
}

}  // namespace

TEST_CASE("flip recovery: skipping searches known to fail changes nothing") {
    const cbr::test::Polyhedron chazelle = cbr::test::chazelle_polyhedron();
    require_memo_changes_nothing("chazelle", chazelle.xyz, chazelle.tris);
    const cbr::test::Polyhedron stack = twisted_stack(4, kPi / 6);
    require_memo_changes_nothing("schonhardt stack", stack.xyz, stack.tris);
    cbr::test::OffSurface pierced;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/io/pierced-62.off", pierced));
    require_memo_changes_nothing("pierced-62", pierced.xyz, pierced.tris);
    // Shared surfaces whose deep searches repeat most (when present).
    const std::string dir = cbr::test::shared_data_dir();
    if (dir.empty()) return;
    for (const char* name : {"thingiverse-mouth", "thingiverse-feeder-guide-arm", "cgal-dino"}) {
        cbr::test::OffSurface s;
        REQUIRE(cbr::test::read_off(dir + "/surfaces/" + name + ".off", s));
        require_memo_changes_nothing(name, s.xyz, s.tris);
    }
}

namespace {

// Faces left by flip recovery of `xyz, tris` with every round, and without
// the deepest (the nested removals in `order`); both meshes valid.
std::pair<std::size_t, std::size_t> left_with_and_without_deepest(
    const std::string& name, const std::vector<double>& xyz, const std::vector<std::int64_t>& tris,
    cbr::recover::NestedOrder order = cbr::recover::NestedOrder::kBlockingFirst) {
    INFO(name);
    Case all, shallow;
    build(all, xyz, tris);
    build(shallow, xyz, tris);
    const std::vector<std::size_t> missing = cbr::recover::mark_present_faces(all.m(), *all.faces);
    const auto left_all =
        cbr::recover::recover_by_flips(all.m(), *all.faces, missing, cbr::recover::FlipMemo::kOn,
                                       cbr::recover::FlipRounds::kAll, 0, cbr::recover::FlipDirection::kAsGiven, order);
    const auto left_shallow = cbr::recover::recover_by_flips(
        shallow.m(), *shallow.faces, missing, cbr::recover::FlipMemo::kOn, cbr::recover::FlipRounds::kWithoutDeepest,
        0, cbr::recover::FlipDirection::kAsGiven, order);
    require_valid(all.m(), name.c_str());
    require_valid(shallow.m(), name.c_str());
    MESSAGE(name << ": " << missing.size() << " missing, left " << left_all.size() << " with the deepest round, "
                 << left_shallow.size() << " without");
    return {left_all.size(), left_shallow.size()};
}

}  // namespace

TEST_CASE("flip recovery: the deepest round recovers faces the others leave") {
    // The Chazelle polyhedron with the nested removals in ring order: the
    // rounds up to 5 levels leave 6 of its 96 missing faces (measured), the
    // deepest round none; what CBR_PARAM_RECOVERY_DEEP_FLIPS = 0 gives up.
    const cbr::test::Polyhedron chazelle = cbr::test::chazelle_polyhedron();
    const auto [with_deepest, without] = left_with_and_without_deepest("chazelle, ring order", chazelle.xyz,
                                                                       chazelle.tris, cbr::recover::NestedOrder::kRing);
    CHECK(with_deepest == 0);
    CHECK(without > 0);
}

TEST_CASE("flip recovery: the blocking ring vertices first recover what the deepest round did") {
    // The same polyhedron with the default order (ring vertices where the
    // ring is not convex as seen from the edge's ends first,
    // mesh::ring_positions_blocking_first): the rounds up to 5 levels
    // already recover every face.
    const cbr::test::Polyhedron chazelle = cbr::test::chazelle_polyhedron();
    const auto [with_deepest, without] = left_with_and_without_deepest("chazelle", chazelle.xyz, chazelle.tris);
    CHECK(with_deepest == 0);
    CHECK(without == 0);
}

namespace {

// Flip recovery of `xyz, tris` with every round, the nested removals in
// ring order and the deepest round as `deepest_budget` says (0: its two
// stages); the faces left, and in `spent` what each round did.
std::vector<std::size_t> flips_in_ring_order(const std::string& name, const std::vector<double>& xyz,
                                             const std::vector<std::int64_t>& tris, int deepest_budget,
                                             std::vector<cbr::recover::FlipRoundReport>& spent) {
    INFO(name);
    Case c;
    build(c, xyz, tris);
    const std::vector<std::size_t> missing = cbr::recover::mark_present_faces(c.m(), *c.faces);
    const std::vector<std::size_t> left = cbr::recover::recover_by_flips(
        c.m(), *c.faces, missing, cbr::recover::FlipMemo::kOn, cbr::recover::FlipRounds::kAll, deepest_budget,
        cbr::recover::FlipDirection::kAsGiven, cbr::recover::NestedOrder::kRing, &spent);
    require_valid(c.m(), name.c_str());
    std::string rounds;
    for (const cbr::recover::FlipRoundReport& r : spent)
        rounds += " " + std::to_string(r.removals) + " (" + std::to_string(r.attempts) + " attempts at " +
                  std::to_string(r.faces) + " faces)";
    MESSAGE(name << ", deepest budget " << deepest_budget << ": " << missing.size() << " missing, " << left.size()
                 << " left; removals per round" << rounds);
    return left;
}

}  // namespace

TEST_CASE("flip recovery: the deepest round's second stage, within its allowance") {
    // flip_recovery.cpp, kSearches: the deepest round gives every face
    // 1,500 edge removals, then the faces left 40,000 each while the
    // stage has spent less than 80,000 in all.
    std::vector<cbr::recover::FlipRoundReport> spent;
    // Faces that need more than the first stage: the Chazelle polyhedron
    // in ring order, whose deepest round recovers 6 faces (above).
    const cbr::test::Polyhedron chazelle = cbr::test::chazelle_polyhedron();
    CHECK(flips_in_ring_order("chazelle", chazelle.xyz, chazelle.tris, 0, spent).empty());
    REQUIRE(spent.size() == 5);
    CHECK(spent[4].removals > 0);  // the second stage ran, and recovered what the first left
    CHECK_FALSE(flips_in_ring_order("chazelle", chazelle.xyz, chazelle.tris, 1500, spent).empty());
    REQUIRE(spent.size() == 4);  // one deepest round in place of the two stages
    // Faces that no search recovers spend their whole budget: a turned
    // prism with fanned caps (the caps need Steiner points). One round of
    // 40,000 a face spends many budgets; the second stage at most two.
    cbr::test::OffSurface prism;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/prism-96-fan-caps-h1-r22.off", prism));
    const std::size_t left_single = flips_in_ring_order("prism", prism.xyz, prism.tris, 40000, spent).size();
    REQUIRE(spent.size() == 4);
    CHECK(spent[3].removals > 2 * 40000);
    const std::size_t left_staged = flips_in_ring_order("prism", prism.xyz, prism.tris, 0, spent).size();
    REQUIRE(spent.size() == 5);
    CHECK(spent[4].removals > 0);
    CHECK(spent[4].removals <= 2 * 40000);
    CHECK(left_staged > 0);
    // Once the allowance is spent, the faces left are not attempted at
    // all (with no budget a face could still be attempted, and its 2-3
    // flips, which spend none, would still change the mesh).
    CHECK(spent[4].attempts < spent[4].faces);
    CHECK(spent[4].attempts >= 2);  // each face it cannot recover spends 40,000
    MESSAGE("prism: " << left_single << " faces left with one deepest round, " << left_staged << " with two stages");
}
