// Input surface validation (recover/surface_check): hand-made cases for each
// defect kind and each legal contact, then every file of the shared data set
// (skipped when CBR_SHARED_DATA_DIR is unset or missing).
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "geom/intersect.hpp"
#include "geom/predicates.hpp"
#include "recover/surface_check.hpp"

namespace {

using cbr::recover::check_surface;
using cbr::recover::Defect;
using cbr::recover::DefectKind;
using cbr::recover::describe;
using cbr::recover::SurfaceCheckResult;
namespace fs = std::filesystem;

struct Mesh {
    std::vector<double> xyz;
    std::vector<std::int64_t> tris;

    std::int64_t add_point(double x, double y, double z) {
        xyz.insert(xyz.end(), {x, y, z});
        return static_cast<std::int64_t>(xyz.size() / 3 - 1);
    }
    void add_tri(std::int64_t a, std::int64_t b, std::int64_t c) {
        tris.insert(tris.end(), {a, b, c});
    }
    std::int64_t points() const { return static_cast<std::int64_t>(xyz.size() / 3); }
    std::int64_t triangles() const { return static_cast<std::int64_t>(tris.size() / 3); }
};

SurfaceCheckResult check(const Mesh& m, cbr::recover::SurfaceCheckOptions opt = {}) {
    return check_surface(m.xyz.data(), m.points(), m.tris.data(), m.triangles(), opt);
}

std::vector<Defect> of_kind(const SurfaceCheckResult& r, DefectKind k) {
    std::vector<Defect> out;
    std::copy_if(r.defects.begin(), r.defects.end(), std::back_inserter(out),
                 [k](const Defect& d) { return d.kind == k; });
    return out;
}

// Axis-aligned box [x0,x1] x [y0,y1] x [z0,z1], 12 outward triangles.
void add_box(Mesh& m, double x0, double y0, double z0, double x1, double y1, double z1) {
    std::int64_t v[8];
    for (int i = 0; i < 8; ++i)
        v[i] = m.add_point(i & 1 ? x1 : x0, i & 2 ? y1 : y0, i & 4 ? z1 : z0);
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.add_tri(v[q[0]], v[q[1]], v[q[2]]);
        m.add_tri(v[q[0]], v[q[2]], v[q[3]]);
    }
}

// A tetrahedron's four faces on points a, b, c, d of m.
void add_tet_faces(Mesh& m, std::int64_t a, std::int64_t b, std::int64_t c, std::int64_t d) {
    m.add_tri(a, c, b);
    m.add_tri(a, b, d);
    m.add_tri(b, c, d);
    m.add_tri(c, a, d);
}

// The pair test of check_surface, spelled out: both triangles must be
// usable (distinct ids, non-zero area) and not the same vertex set; their
// shared vertices go first, in the same order.
bool brute_pair_meets(const Mesh& m, std::int64_t t, std::int64_t u) {
    std::array<std::int64_t, 3> a, b;
    for (int k = 0; k < 3; ++k) {
        a[k] = m.tris[static_cast<std::size_t>(3 * t + k)];
        b[k] = m.tris[static_cast<std::size_t>(3 * u + k)];
    }
    const auto pt = [&m](std::int64_t id) { return m.xyz.data() + 3 * id; };
    for (const auto& v : {a, b})
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] ||
            cbr::geom::collinear(pt(v[0]), pt(v[1]), pt(v[2])))
            return false;
    int shared = 0;
    for (int i = 0; i < 3; ++i) {
        const auto j = std::find(b.begin() + shared, b.end(), a[i]);
        if (j == b.end()) continue;
        std::swap(a[static_cast<std::size_t>(shared)], a[static_cast<std::size_t>(i)]);
        std::iter_swap(b.begin() + shared, j);
        ++shared;
    }
    if (shared == 3) return false;
    const double* pa[3] = {pt(a[0]), pt(a[1]), pt(a[2])};
    const double* pb[3] = {pt(b[0]), pt(b[1]), pt(b[2])};
    return cbr::geom::triangles_meet_illegally(pa, pb, shared);
}

Mesh tetrahedron() {
    Mesh m;
    m.add_point(0, 0, 0);
    m.add_point(1, 0, 0);
    m.add_point(0, 1, 0);
    m.add_point(0, 0, 1);
    add_tet_faces(m, 0, 1, 2, 3);
    return m;
}

}  // namespace

// ---------------------------------------------------------------------------
// Legal inputs.
// ---------------------------------------------------------------------------

TEST_CASE("legal: empty input, a tetrahedron, a box") {
    CHECK(check(Mesh{}).ok());
    CHECK(check(Mesh{}).defects.empty());
    const SurfaceCheckResult t = check(tetrahedron());
    CHECK(t.ok());
    CHECK(t.defects.empty());
    Mesh box;
    add_box(box, 0, 0, 0, 1, 2, 3);
    const SurfaceCheckResult b = check(box);
    CHECK(b.ok());
    CHECK(b.defects.empty());  // coplanar pairs sharing an edge are legal
    CHECK(cbr::recover::summarize(b) == "no defect");
}

TEST_CASE("legal: a lone triangle is an open surface") {
    Mesh m;
    m.add_point(0, 0, 0);
    m.add_point(1, 0, 0);
    m.add_point(0, 1, 0);
    m.add_tri(0, 1, 2);
    const SurfaceCheckResult r = check(m);
    CHECK(r.ok());
    CHECK(r.count(DefectKind::OpenEdge) == 3);
    REQUIRE(r.defects.size() == 3);
    CHECK(describe(r.defects[0]) == "edge 0-1 is open: used by 1 triangle (triangle 0)");
    CHECK(describe(r.defects[2]) == "edge 1-2 is open: used by 1 triangle (triangle 0)");
    cbr::recover::SurfaceCheckOptions quiet;
    quiet.report_edges = false;
    CHECK(check(m, quiet).defects.empty());
}

TEST_CASE("legal: triangles sharing only a vertex (two tetrahedra tip to tip)") {
    Mesh m = tetrahedron();
    m.add_point(-1, 0, 0);
    m.add_point(0, -1, 0);
    m.add_point(0, 0, -1);
    add_tet_faces(m, 0, 5, 4, 6);  // mirrored through the shared vertex 0
    const SurfaceCheckResult r = check(m);
    CHECK(r.ok());
    CHECK(r.defects.empty());
}

TEST_CASE("legal: non-manifold edge (two tetrahedra sharing an edge, a book of pages)") {
    Mesh m = tetrahedron();
    m.add_point(0, -1, 0);
    m.add_point(0, 0, -1);  // tet (0, 1, 4, 5) shares edge 0-1 with the first
    add_tet_faces(m, 0, 1, 5, 4);
    SurfaceCheckResult r = check(m);
    CHECK(r.ok());
    CHECK(r.count(DefectKind::NonManifoldEdge) == 1);
    CHECK(r.count(DefectKind::OpenEdge) == 0);
    const auto nm = of_kind(r, DefectKind::NonManifoldEdge);
    REQUIRE(nm.size() == 1);
    CHECK(nm[0].value == 4);
    CHECK(describe(nm[0]) == "edge 0-1 is non-manifold: used by 4 triangles (first: triangle 0)");
    // A fifth page through the same edge, in the free quadrant y > 0 > z.
    m.add_point(1, 1, -1);
    m.add_tri(0, 1, 6);
    r = check(m);
    CHECK(r.ok());
    CHECK(of_kind(r, DefectKind::NonManifoldEdge)[0].value == 5);
}

TEST_CASE("legal: two cubes sharing a face, a cube inside a cube") {
    Mesh m;
    add_box(m, 0, 0, 0, 1, 1, 1);
    add_box(m, 1, 0, 0, 2, 1, 1);
    // Weld the second cube's x = 1 corners onto the first cube's and drop
    // its copy of the common face: 3 triangles on each edge of that face.
    for (std::int64_t& id : m.tris) {
        if (id < 8) continue;
        const std::int64_t i = id - 8;
        if ((i & 1) == 0) id = i | 1;  // x0 = 1 corner of cube 2 -> x1 corner of cube 1
    }
    // Cube 2's face x0 was triangles 12 + 8 and 12 + 9 (quad {0, 4, 6, 2}).
    m.tris.erase(m.tris.begin() + 3 * 20, m.tris.begin() + 3 * 22);
    SurfaceCheckResult r = check(m);
    CHECK(r.ok());
    CHECK(r.count(DefectKind::NonManifoldEdge) == 4);
    CHECK(r.count(DefectKind::OpenEdge) == 0);

    Mesh nested;
    add_box(nested, 0, 0, 0, 3, 3, 3);
    add_box(nested, 1, 1, 1, 2, 2, 2);
    r = check(nested);
    CHECK(r.ok());
    CHECK(r.defects.empty());
}

// ---------------------------------------------------------------------------
// Each defect kind.
// ---------------------------------------------------------------------------

TEST_CASE("error: vertex id out of range") {
    Mesh m = tetrahedron();
    m.add_tri(0, 1, 4);
    m.add_tri(-1, 1, 2);
    const SurfaceCheckResult r = check(m);
    CHECK_FALSE(r.ok());
    CHECK(r.count(DefectKind::IdOutOfRange) == 2);
    CHECK(r.error_count() == 2);
    REQUIRE(r.defects.size() >= 2);
    CHECK(describe(r.defects[0]) ==
          "triangle 4 uses vertex id 4, out of range (valid ids are 0 to 3)");
    CHECK(describe(r.defects[1]) ==
          "triangle 5 uses vertex id -1, out of range (valid ids are 0 to 3)");
    CHECK(describe(r.defects[0], 1) ==
          "triangle 5 uses vertex id 5, out of range (valid ids are 1 to 4)");
    // Out-of-range triangles take no further part (no open edge to id 4).
    CHECK(r.count(DefectKind::OpenEdge) == 0);

    Mesh none;
    none.add_tri(0, 1, 2);
    CHECK(describe(check(none).defects[0]) ==
          "triangle 0 uses vertex ids 0, 1, 2, out of range (there are no points)");
}

TEST_CASE("error: repeated vertex id") {
    Mesh m = tetrahedron();
    m.add_tri(2, 3, 2);
    const SurfaceCheckResult r = check(m);
    CHECK(r.count(DefectKind::RepeatedId) == 1);
    CHECK(r.error_count() == 1);
    CHECK(describe(r.defects[0]) == "triangle 4 repeats a vertex id (vertices 2, 3, 2)");
}

TEST_CASE("error: zero-area triangle") {
    Mesh m = tetrahedron();
    m.add_point(0.5, 0.5, 0);  // 4: on edge 1-2, exactly
    m.add_point(0, 0, 0);      // 5: same coordinates as 0
    m.add_tri(1, 4, 2);        // collinear
    m.add_tri(5, 0, 3);        // two ids at one point
    const SurfaceCheckResult r = check(m);
    CHECK(r.count(DefectKind::ZeroArea) == 2);
    const auto z = of_kind(r, DefectKind::ZeroArea);
    REQUIRE(z.size() == 2);
    CHECK(describe(z[0]) == "triangle 4 has zero area (vertices 1, 4, 2 are collinear)");
    CHECK(z[1].tri[0] == 5);
    // Nearly collinear is not zero area: exact test.
    Mesh n = tetrahedron();
    n.add_point(0.5, 0.5, 1e-40);
    n.add_tri(1, 4, 2);
    CHECK(check(n).count(DefectKind::ZeroArea) == 0);
}

TEST_CASE("error: the same triangle twice") {
    Mesh m = tetrahedron();
    m.add_tri(0, 2, 1);  // = triangle 0 (0, 2, 1), same order
    m.add_tri(1, 0, 2);  // = triangle 0, rotated and flipped
    m.add_tri(3, 1, 0);  // = triangle 1 (0, 1, 3), flipped
    const SurfaceCheckResult r = check(m);
    CHECK(r.count(DefectKind::DuplicateTriangle) == 3);
    CHECK(r.count(DefectKind::Intersection) == 0);  // not reported twice
    const auto d = of_kind(r, DefectKind::DuplicateTriangle);
    REQUIRE(d.size() == 3);
    CHECK(d[0].tri == std::array<std::int64_t, 2>{0, 4});
    CHECK(d[1].tri == std::array<std::int64_t, 2>{0, 5});
    CHECK(d[2].tri == std::array<std::int64_t, 2>{1, 6});
    CHECK(describe(d[1]) == "triangles 0 and 5 are the same triangle (vertices 1, 0, 2)");
}

namespace {

// The tetrahedron and a fifth triangle (4) piercing its face 1 (0, 1, 3;
// y = 0) through the interior.
Mesh pierced_tetrahedron() {
    Mesh m = tetrahedron();
    const auto a = m.add_point(0.2, -1, 0.2);
    const auto b = m.add_point(0.2, 1, 0.2);
    const auto c = m.add_point(0.3, 0.5, 5);
    m.add_tri(a, b, c);
    return m;
}

}  // namespace

TEST_CASE("error: crossing triangles") {
    const Mesh m = pierced_tetrahedron();
    const SurfaceCheckResult r = check(m);
    CHECK_FALSE(r.ok());
    const auto x = of_kind(r, DefectKind::Intersection);
    REQUIRE(!x.empty());
    // Edge ab crosses face 1 (y = 0) at (0.2, 0, 0.2) and face 2
    // (x + y + z = 1) at (0.2, 0.6, 0.2); the triangle stays off faces 0 and 3.
    REQUIRE(x.size() == 2);
    CHECK(x[0].tri == std::array<std::int64_t, 2>{1, 4});
    CHECK(x[1].tri == std::array<std::int64_t, 2>{2, 4});
    CHECK(describe(x[0]) == "triangles 1 and 4 intersect (not in a shared vertex or edge)");
    const std::string s = cbr::recover::summarize(r);
    CHECK(s.rfind("2 errors: 2 intersecting triangle pairs; first: triangles 1 and 4", 0) == 0);
}

TEST_CASE("error: illegal contacts at shared vertices and edges") {
    SUBCASE("T-junction: a vertex on another triangle's edge") {
        Mesh m;
        m.add_point(0, 0, 0);
        m.add_point(2, 0, 0);
        m.add_point(0, 2, 0);
        m.add_point(1, 0, 0);  // on edge 0-1
        m.add_point(1, -1, 1);
        m.add_tri(0, 1, 2);
        m.add_tri(3, 4, 0);  // shares vertex 0; edge 3-0 lies along edge 0-1
        const SurfaceCheckResult r = check(m);
        CHECK(r.count(DefectKind::Intersection) == 1);
        CHECK(of_kind(r, DefectKind::Intersection)[0].vert[0] == 0);  // the shared vertex
    }
    SUBCASE("an edge through the other triangle, one shared vertex") {
        Mesh m;
        m.add_point(0, 0, 0);
        m.add_point(4, 0, 0);
        m.add_point(0, 4, 0);
        m.add_point(1, 1, -3);
        m.add_point(1, 1, 3);
        m.add_tri(0, 1, 2);
        m.add_tri(0, 3, 4);
        CHECK(check(m).count(DefectKind::Intersection) == 1);
    }
    SUBCASE("shared edge folded onto itself") {
        Mesh m;
        m.add_point(0, 0, 0);
        m.add_point(4, 0, 0);
        m.add_point(0, 4, 0);
        m.add_point(3, 1, 0);
        m.add_tri(0, 1, 2);
        m.add_tri(1, 0, 3);
        const SurfaceCheckResult r = check(m);
        CHECK(r.count(DefectKind::Intersection) == 1);
        CHECK(of_kind(r, DefectKind::Intersection)[0].vert ==
              std::array<std::int64_t, 3>{0, 1, -1});
    }
    SUBCASE("distinct vertices at the same point") {
        Mesh m = tetrahedron();
        m.add_point(1, 0, 0);  // 4: a second vertex at point 1
        m.add_point(2, 0, 1);
        m.add_point(2, 1, 0);
        m.add_tri(4, 5, 6);
        const SurfaceCheckResult r = check(m);
        CHECK(r.count(DefectKind::Intersection) == 3);  // the 3 faces at vertex 1
    }
}

TEST_CASE("listing is capped, counts are complete, order is deterministic") {
    Mesh m;
    for (int i = 0; i < 30; ++i) {
        const auto a = m.add_point(i, 0, 0);
        const auto b = m.add_point(i + 1, 0, 0);
        const auto c = m.add_point(i + 2, 0, 0);
        m.add_tri(a, b, c);
    }
    SurfaceCheckResult r = check(m);
    CHECK(r.count(DefectKind::ZeroArea) == 30);
    const auto z = of_kind(r, DefectKind::ZeroArea);
    REQUIRE(z.size() == 20);
    for (std::size_t i = 0; i < z.size(); ++i) CHECK(z[i].tri[0] == static_cast<std::int64_t>(i));
    cbr::recover::SurfaceCheckOptions few;
    few.max_listed_per_kind = 3;
    r = check(m, few);
    CHECK(of_kind(r, DefectKind::ZeroArea).size() == 3);
    CHECK(r.error_count() == 30);
    CHECK(cbr::recover::summarize(r).rfind("30 errors: 30 zero-area triangles; first: ", 0) == 0);
    few.max_listed_per_kind = 0;
    r = check(m, few);
    CHECK(r.defects.empty());
    CHECK(r.error_count() == 30);
    CHECK(cbr::recover::summarize(r) == "30 errors: 30 zero-area triangles");
    r = check(m, cbr::recover::SurfaceCheckOptions{});
    // Defects come grouped by kind in enum order.
    for (std::size_t i = 1; i < r.defects.size(); ++i)
        CHECK(r.defects[i - 1].kind <= r.defects[i].kind);
}

TEST_CASE("intersecting pairs agree with an all-pairs search on random soups") {
    // Small triangles of integer points in a cube whose side grows with the
    // round (dense to sparse soups). Equal points mostly share an id, so
    // shared vertices and edges, coplanar contacts, crossings, distinct ids
    // at one point and degenerate triangles all occur.
    std::mt19937_64 rng(4242);
    const auto pick = [&rng](int lo, int hi) {
        const auto span = static_cast<unsigned>(hi - lo + 1);
        return static_cast<double>(lo + static_cast<int>(rng() % span));
    };
    for (int round = 0; round < 20; ++round) {
        const int side = 3 + 2 * round;
        const bool flat = round % 3 == 0;
        Mesh m;
        std::map<std::array<double, 3>, std::int64_t> ids;
        const auto vertex = [&](double x, double y, double z) {
            const std::array<double, 3> key = {x, y, flat ? 0.0 : z};
            const auto it = ids.find(key);
            if (it != ids.end() && rng() % 8 != 0) return it->second;
            return ids[key] = m.add_point(key[0], key[1], key[2]);
        };
        for (int i = 0; i < 200; ++i) {
            const double x = pick(0, side), y = pick(0, side), z = pick(0, side);
            m.add_tri(vertex(x, y, z), vertex(x + pick(-2, 2), y + pick(-2, 2), z + pick(-2, 2)),
                      vertex(x + pick(-2, 2), y + pick(-2, 2), z + pick(-2, 2)));
        }
        // Brute force over the public pair test.
        std::vector<std::array<std::int64_t, 2>> pairs;
        for (std::int64_t t = 0; t < m.triangles(); ++t)
            for (std::int64_t u = t + 1; u < m.triangles(); ++u)
                if (brute_pair_meets(m, t, u)) pairs.push_back({t, u});
        const SurfaceCheckResult r = check(m);
        CAPTURE(round);
        CHECK(r.count(DefectKind::Intersection) == static_cast<std::int64_t>(pairs.size()));
        const auto listed = of_kind(r, DefectKind::Intersection);
        REQUIRE(listed.size() == std::min<std::size_t>(20, pairs.size()));
        for (std::size_t i = 0; i < listed.size(); ++i) CHECK(listed[i].tri == pairs[i]);
    }
}

TEST_CASE("known faces: only pairs of two of them are left untested") {
    // SurfaceCheckOptions::known_faces: the caller vouches that those
    // triangles are faces of one valid tetrahedralization, so no two of
    // them meet illegally. On random soups, triangles picked so that no two
    // of them meet illegally (as the faces of a mesh): the same defects,
    // listed and counted, as without the flags; the pairs of a known and
    // an unknown triangle are still tested.
    std::mt19937_64 rng(5151);
    const auto pick = [&rng](int lo, int hi) {
        const auto span = static_cast<unsigned>(hi - lo + 1);
        return static_cast<double>(lo + static_cast<int>(rng() % span));
    };
    std::int64_t crossings_with_known = 0;
    for (int round = 0; round < 10; ++round) {
        const int side = 4 + 2 * round;
        Mesh m;
        for (int i = 0; i < 150; ++i) {
            const double x = pick(0, side), y = pick(0, side), z = pick(0, side);
            const auto a = m.add_point(x, y, z);
            const auto b = m.add_point(x + pick(-2, 2), y + pick(-2, 2), z + pick(-2, 2));
            const auto c = m.add_point(x + pick(-2, 2), y + pick(-2, 2), z + pick(-2, 2));
            m.add_tri(a, b, c);
        }
        std::vector<char> known(static_cast<std::size_t>(m.triangles()), 0);
        for (std::int64_t t = 0; t < m.triangles(); ++t) {
            bool clear = rng() % 2 == 0;
            for (std::int64_t u = 0; u < t && clear; ++u)
                if (known[static_cast<std::size_t>(u)] && brute_pair_meets(m, u, t)) clear = false;
            known[static_cast<std::size_t>(t)] = clear ? 1 : 0;
        }
        for (std::int64_t t = 0; t < m.triangles(); ++t)
            for (std::int64_t u = t + 1; u < m.triangles(); ++u)
                if ((known[static_cast<std::size_t>(t)] || known[static_cast<std::size_t>(u)]) &&
                    brute_pair_meets(m, t, u))
                    ++crossings_with_known;
        cbr::recover::SurfaceCheckOptions vouched;
        vouched.known_faces = &known;
        const SurfaceCheckResult all = check(m), fewer = check(m, vouched);
        CAPTURE(round);
        CHECK(fewer.counts == all.counts);
        REQUIRE(fewer.defects.size() == all.defects.size());
        for (std::size_t i = 0; i < all.defects.size(); ++i) {
            CHECK(fewer.defects[i].kind == all.defects[i].kind);
            CHECK(fewer.defects[i].tri == all.defects[i].tri);
        }
    }
    CHECK(crossings_with_known > 0);  // the soups test the known-unknown pairs
}

TEST_CASE("known faces: a crossing pair vouched for is not tested") {
    // The promise is trusted: a caller must vouch only for faces of a mesh.
    const Mesh m = pierced_tetrahedron();
    std::vector<char> known = {0, 1, 0, 0, 1};  // triangles 1 and 4 cross, 2 and 4 too
    cbr::recover::SurfaceCheckOptions vouched;
    vouched.known_faces = &known;
    const auto x = of_kind(check(m, vouched), DefectKind::Intersection);
    REQUIRE(x.size() == 1);
    CHECK(x[0].tri == std::array<std::int64_t, 2>{2, 4});
}

// ---------------------------------------------------------------------------
// The shared data set.
// ---------------------------------------------------------------------------
namespace {

// Minimal OFF reader for the data set's format: "OFF", "nv nf 0", nv lines
// "x y z", nf lines "3 i j k" (0-based), no comments.
bool read_off(const fs::path& path, Mesh& m) {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const char* p = text.c_str();
    char* end = nullptr;
    while (*p == ' ' || *p == '\n' || *p == '\r') ++p;
    if (text.compare(static_cast<std::size_t>(p - text.c_str()), 3, "OFF") != 0) return false;
    p += 3;
    const long long nv = std::strtoll(p, &end, 10);
    const long long nf = std::strtoll(p = end, &end, 10);
    std::strtoll(p = end, &end, 10);  // edge count, unused
    m.xyz.resize(static_cast<std::size_t>(3 * nv));
    m.tris.resize(static_cast<std::size_t>(3 * nf));
    for (double& x : m.xyz) x = std::strtod(p = end, &end);
    for (long long f = 0; f < nf; ++f) {
        if (std::strtoll(p = end, &end, 10) != 3) return false;
        for (int k = 0; k < 3; ++k)
            m.tris[static_cast<std::size_t>(3 * f + k)] = std::strtoll(p = end, &end, 10);
    }
    return end != p;
}

// The data directory, or empty (after saying why) when tests must skip.
fs::path shared_data(const char* sub) {
    const char* dir = std::getenv("CBR_SHARED_DATA_DIR");
    if (dir == nullptr || !fs::is_directory(fs::path(dir) / sub)) {
        const std::string why =
            "CBR_SHARED_DATA_DIR unset or without " + std::string(sub) + "/: test skipped";
        MESSAGE(why);
        return {};
    }
    return fs::path(dir) / sub;
}

std::vector<fs::path> off_files(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().extension() == ".off") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

struct Timed {
    SurfaceCheckResult result;
    double seconds;
};

Timed timed_check(const Mesh& m) {
    const auto t0 = std::chrono::steady_clock::now();
    SurfaceCheckResult r = check(m);
    const std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
    return {std::move(r), dt.count()};
}

std::string counts_line(const SurfaceCheckResult& r) {
    const char* names[] = {"out-of-range", "repeated-id", "zero-area", "duplicate",
                           "intersection", "open-edge",   "non-manifold-edge"};
    std::string s;
    for (std::size_t k = 0; k < cbr::recover::kDefectKindCount; ++k)
        if (r.counts[k] > 0) s += std::string(" ") + names[k] + "=" + std::to_string(r.counts[k]);
    return s.empty() ? " none" : s;
}

}  // namespace

TEST_CASE("shared data: every valid surface passes") {
    const fs::path dir = shared_data("surfaces");
    if (dir.empty()) return;
    const auto files = off_files(dir);
    CHECK(files.size() >= 30);
    for (const auto& f : files) {
        Mesh m;
        REQUIRE(read_off(f, m));
        const Timed t = timed_check(m);
        const std::string name = f.stem().string();
        CAPTURE(name);
        CHECK_MESSAGE(t.result.ok(), cbr::recover::summarize(t.result));
        CHECK(t.result.count(DefectKind::OpenEdge) == 0);  // all are closed
        if (name.rfind("nonmanifold-edge", 0) != 0)
            CHECK(t.result.count(DefectKind::NonManifoldEdge) == 0);
        if (m.triangles() > 90000)
            MESSAGE(name << ": " << m.triangles() << " triangles checked in " << t.seconds
                         << " s");
    }
}

TEST_CASE("shared data: every geometrically defective file is caught") {
    const fs::path dir = shared_data("invalid");
    if (dir.empty()) return;
    // Expected counts per kind; error kinds not listed must be 0 (the open
    // surfaces are legal). The intersection counts agree with a brute-force
    // all-pairs run of an independent exact rational construction, and
    // elk's and cones' with the data set's README (CGAL). The dragon's 803
    // non-manifold edges come from its 502 repeated triangles.
    using K = DefectKind;
    const std::map<std::string, std::map<DefectKind, std::int64_t>> expected = {
        {"open-cube", {{K::OpenEdge, 4}}},
        {"open-blub", {{K::OpenEdge, 64}}},
        {"degenerate-sliding-triangles", {{K::ZeroArea, 4}, {K::Intersection, 3}}},
        {"duplicate-vertices-oblong", {{K::Intersection, 20}, {K::OpenEdge, 6}}},
        {"nonmanifold-edges-beetle", {{K::Intersection, 59}, {K::NonManifoldEdge, 47}}},
        {"selfintersect-elk", {{K::Intersection, 7}}},
        {"selfintersect-cones", {{K::Intersection, 5}}},
        {"nonmanifold-selfintersect-dragon",
         {{K::DuplicateTriangle, 502}, {K::Intersection, 34}, {K::NonManifoldEdge, 803}}},
        {"degenerate-zero-area-sphere", {{K::ZeroArea, 1}, {K::Intersection, 2}}},
    };
    for (const auto& f : off_files(dir)) {
        const std::string name = f.stem().string();
        CAPTURE(name);
        Mesh m;
        REQUIRE(read_off(f, m));
        const Timed t = timed_check(m);
        const SurfaceCheckResult& r = t.result;
        MESSAGE(name << ":" << counts_line(r) << " -> " << cbr::recover::summarize(r));
        const auto it = expected.find(name);
        REQUIRE_MESSAGE(it != expected.end(), "no expectation for this file");
        for (std::size_t k = 0; k < cbr::recover::kDefectKindCount; ++k) {
            const auto kind = static_cast<DefectKind>(k);
            const auto want = it->second.find(kind);
            CAPTURE(k);
            if (want != it->second.end())
                CHECK(r.count(kind) == want->second);
            else if (cbr::recover::is_error(kind))
                CHECK(r.count(kind) == 0);
        }
        if (name == "selfintersect-elk") {  // the first pairs, in order
            const auto x = of_kind(r, DefectKind::Intersection);
            REQUIRE(x.size() == 7);
            CHECK(x[0].tri == std::array<std::int64_t, 2>{669, 2877});
            CHECK(x[1].tri == std::array<std::int64_t, 2>{669, 2883});
            CHECK(x[2].tri == std::array<std::int64_t, 2>{669, 2885});
        }
    }
}
