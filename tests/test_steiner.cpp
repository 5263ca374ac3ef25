// Steiner point suppression and repositioning (§6): recover/
// steiner_suppression and recover/steiner_repositioning.
// After every operation the mesh is checked exactly: check_mesh on a copy
// without the suppressed vertices (they stay in the coordinate array but in
// no tetrahedron), the set of constraint faces (marked on both sides)
// unchanged, protected edges still edges; a refusal leaves the
// tetrahedra unchanged.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "delaunay/delaunay.hpp"
#include "geom/point_in_triangle.hpp"
#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/flips.hpp"
#include "mesh/mesh_check.hpp"
#include "recover/constraint_faces.hpp"
#include "recover/protected_insertion.hpp"
#include "recover/steiner_merging.hpp"
#include "recover/steiner_repositioning.hpp"
#include "recover/steiner_suppression.hpp"
#include "mesh_test_util.hpp"
#include "test_util.hpp"

using namespace cbr::mesh;
using namespace cbr::recover;

namespace {

using cbr::test::build_mesh;
using cbr::test::delaunay_mesh;
using cbr::test::face_key;
using cbr::test::Key3;
using cbr::test::live_finite;
using cbr::test::SlotSnapshot;
using cbr::test::locate;
using cbr::test::Tet;
using Edge = std::array<VertexId, 2>;
constexpr double kInf = std::numeric_limits<double>::infinity();


void mark_face(TetMesh& m, TetId t, int f) {
    const FacetRef r = m.neighbor(t, f);
    m.set_constrained(t, f, true);
    m.set_constrained(facet_tet(r), facet_face(r), true);
}

// Marked faces by vertex set; every mark must be on both sides.
std::set<Key3> marked_faces(const TetMesh& m) {
    std::set<Key3> s;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        for (int f = 0; f < 4; ++f) {
            if (!m.is_constrained(t, f)) continue;
            s.insert(face_key(m, t, f));
            const FacetRef r = m.neighbor(t, f);
            CHECK(m.is_constrained(facet_tet(r), facet_face(r)));
        }
    }
    return s;
}

// Marks every hull face as a constraint (the mesh of a recovered convex
// domain) and returns them as input triangles.
std::vector<Triangle> mark_hull(TetMesh& m) {
    std::vector<Triangle> tris;
    for (TetId g = 0; g < m.slot_count(); ++g) {
        if (m.is_free(g) || !m.is_ghost(g)) continue;
        mark_face(m, g, 3);
        tris.push_back({m.vertex(g, 0), m.vertex(g, 1), m.vertex(g, 2)});
    }
    return tris;
}

ConstraintFaces as_constraints(const std::vector<Triangle>& tris) {
    return ConstraintFaces(tris, std::vector<std::int32_t>(tris.size(), 0));
}

std::set<Tet> tet_keys(const TetMesh& m) {
    std::set<Tet> s;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        Tet v = {m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)};
        std::sort(v.begin(), v.end());
        s.insert(v);
    }
    return s;
}

std::set<Edge> edges(const TetMesh& m) {
    std::set<Edge> s;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (!live_finite(m, t)) continue;
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j)
                s.insert({std::min(m.vertex(t, i), m.vertex(t, j)), std::max(m.vertex(t, i), m.vertex(t, j))});
    }
    return s;
}

std::size_t used_vertex_count(const TetMesh& m) {
    std::set<VertexId> s;
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t))
            for (int i = 0; i < 4; ++i)
                if (m.vertex(t, i) != kGhostVertex) s.insert(m.vertex(t, i));
    return s.size();
}

// check_mesh on a copy without the vertices that are in no tetrahedron
// (suppressed Steiner points): same tetrahedra, links and marks, vertices
// renumbered. Everything else check_mesh proves holds for m itself.
void check_valid(const TetMesh& m) {
    std::vector<VertexId> renumber(m.vertex_count(), kGhostVertex);
    std::vector<double> xyz;
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t))
            for (int i = 0; i < 4; ++i) {
                const VertexId v = m.vertex(t, i);
                if (v == kGhostVertex || v >= m.vertex_count() || renumber[v] != kGhostVertex) continue;
                renumber[v] = static_cast<VertexId>(xyz.size() / 3);
                xyz.insert(xyz.end(), m.point(v), m.point(v) + 3);
            }
    TetMesh c;
    c.add_points(xyz.data(), xyz.size() / 3);
    std::vector<TetId> slot(m.slot_count(), kNoTet);
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t)) slot[t] = c.allocate_tet();
    auto map_v = [&](VertexId v) { return v == kGhostVertex ? v : renumber[v]; };
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        c.set_vertices(slot[t], map_v(m.vertex(t, 0)), map_v(m.vertex(t, 1)), map_v(m.vertex(t, 2)),
                       map_v(m.vertex(t, 3)));
        for (int f = 0; f < 4; ++f) {
            const FacetRef r = m.neighbor(t, f);
            REQUIRE(!m.is_free(facet_tet(r)));
            c.set_neighbor(slot[t], f, make_facet(slot[facet_tet(r)], facet_face(r)));
            c.set_constrained(slot[t], f, m.is_constrained(t, f));
        }
    }
    const CheckReport rep = check_mesh(c);
    REQUIRE_MESSAGE(rep.ok(), (rep.errors.empty() ? std::string() : rep.errors[0]));
}

TetId any_tet_of(const TetMesh& m, VertexId v) {
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t) && vertex_index(m, t, v) >= 0) return t;
    return kNoTet;
}

// Inserts the points (protected insertion) and returns their ids; points
// whose insertion is refused are dropped from the mesh again.
std::vector<VertexId> insert_points(TetMesh& m, const std::vector<double>& xyz) {
    std::vector<VertexId> ids;
    for (std::size_t i = 0; i < xyz.size() / 3; ++i) {
        const VertexId p = m.add_points(&xyz[3 * i], 1);
        const TetId t = locate(m, m.point(p));
        REQUIRE(t != kNoTet);
        const ProtectedInsertResult res = insert_protected(m, p, t);
        if (!res.ok) {
            m.truncate_vertices(p);
            continue;
        }
        ids.push_back(p);
    }
    check_valid(m);
    return ids;
}

// Worst quality of the finite tetrahedra incident to v.
double ball_quality(const TetMesh& m, VertexId v) {
    double q = kInf;
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (live_finite(m, t) && vertex_index(m, t, v) >= 0)
            q = std::min(q, tet_quality(m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)), m.point(m.vertex(t, 2)),
                                        m.point(m.vertex(t, 3))));
    return q;
}

// A convex domain: the cube's corners and random points, hull faces marked
// as constraints, and every 13th interior face too (constraints inside the
// domain that suppression must route around).
struct Domain {
    TetMesh m;
    std::vector<Triangle> tris;
};
Domain convex_domain(std::uint64_t seed, std::size_t n, bool interior_constraints) {
    std::vector<double> xyz = cbr::test::random_points(n, seed, 0.02, 0.98);
    for (int c = 0; c < 8; ++c) xyz.insert(xyz.end(), {double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)});
    Domain d{delaunay_mesh(xyz), {}};
    d.tris = mark_hull(d.m);
    if (interior_constraints) {
        std::size_t k = 0;
        for (TetId t = 0; t < d.m.slot_count(); ++t) {
            if (!live_finite(d.m, t)) continue;
            for (int f = 0; f < 4; ++f) {
                const TetId nb = facet_tet(d.m.neighbor(t, f));
                if (nb < t || d.m.is_ghost(nb) || ++k % 13 != 0) continue;
                mark_face(d.m, t, f);
                d.tris.push_back({d.m.vertex(t, kFaceVertices[f][0]), d.m.vertex(t, kFaceVertices[f][1]),
                                  d.m.vertex(t, kFaceVertices[f][2])});
            }
        }
    }
    return d;
}

// Suppresses each point in turn, checking the mesh after each one; returns
// how many went.
std::size_t suppress_each(TetMesh& m, const std::vector<VertexId>& points, const SuppressOptions& options,
                          const EdgeProtect& protect = {}, std::map<SuppressMethod, int>* methods = nullptr) {
    const std::set<Key3> constraints = marked_faces(m);
    std::size_t used = used_vertex_count(m), done = 0;
    for (VertexId v : points) {
        const std::set<Tet> before = tet_keys(m);
        SuppressReport rep;
        const bool ok = suppress_vertex(m, v, any_tet_of(m, v), protect, &rep, options);
        CHECK(ok == (rep.result == SuppressResult::kSuppressed));
        if (rep.flips_undone) MESSAGE("vertex " << v << ": " << rep.flips_undone << " 2-3 flips undone");
        check_valid(m);
        CHECK(marked_faces(m) == constraints);
        if (ok) {
            ++done;
            CHECK(any_tet_of(m, v) == kNoTet);
            CHECK(used_vertex_count(m) == --used);
            CHECK(rep.min_quality > 0);
            if (methods) ++(*methods)[rep.method];
        } else {
            CHECK(tet_keys(m) == before);  // refused: the same tetrahedra
        }
    }
    return done;
}

}  // namespace

TEST_CASE("suppression: every interior point inserted into a recovered convex mesh goes") {
    for (bool inner : {false, true}) {
        for (std::uint64_t seed : {1u, 2u, 3u}) {
            CAPTURE(inner);
            CAPTURE(seed);
            Domain d = convex_domain(seed, 40, inner);
            const std::size_t used = used_vertex_count(d.m);
            const auto pts = insert_points(d.m, cbr::test::random_points(30, 100 + seed, 0.05, 0.95));
            REQUIRE(pts.size() >= 25);
            std::map<SuppressMethod, int> methods;
            const std::size_t done = suppress_each(d.m, pts, SuppressOptions{}, {}, &methods);
            MESSAGE("inner constraints " << inner << " seed " << seed << ": " << done << "/" << pts.size()
                                         << " suppressed (contraction " << methods[SuppressMethod::kContraction]
                                         << ", flips " << methods[SuppressMethod::kFlips] << ")");
            CHECK(done == pts.size());
            CHECK(used_vertex_count(d.m) == used);
        }
    }
}

TEST_CASE("merging: adjacent interior points go in pairs, constraints and validity kept") {
    std::size_t total = 0;
    for (bool inner : {false, true}) {
        for (std::uint64_t seed : {1u, 2u, 3u}) {
            CAPTURE(inner);
            CAPTURE(seed);
            Domain d = convex_domain(seed, 40, inner);
            const std::set<Key3> constraints = marked_faces(d.m);
            const auto pts = insert_points(d.m, cbr::test::random_points(30, 100 + seed, 0.05, 0.95));
            const std::size_t used = used_vertex_count(d.m);
            std::vector<VertexId> kept = pts;
            const std::size_t merged = merge_steiner_pairs(d.m, kept);
            total += merged;
            check_valid(d.m);
            CHECK(marked_faces(d.m) == constraints);
            CHECK(kept.size() == pts.size() - merged);
            CHECK(used_vertex_count(d.m) == used - merged);
            for (VertexId v : pts) {
                const bool stays = std::find(kept.begin(), kept.end(), v) != kept.end();
                CHECK((any_tet_of(d.m, v) != kNoTet) == stays);
            }
            // Deterministic: the same input merges the same way.
            Domain again = convex_domain(seed, 40, inner);
            const auto pts2 = insert_points(again.m, cbr::test::random_points(30, 100 + seed, 0.05, 0.95));
            std::vector<VertexId> kept2 = pts2;
            CHECK(merge_steiner_pairs(again.m, kept2) == merged);
            CHECK(kept2 == kept);
        }
    }
    MESSAGE(total << " points merged away over 6 domains of 30 interior points");
    CHECK(total > 0);
}

TEST_CASE("suppression by flipping the ball down alone (no contraction)") {
    std::size_t total = 0, done = 0;
    for (std::uint64_t seed : {4u, 5u, 6u}) {
        Domain d = convex_domain(seed, 40, true);
        const auto pts = insert_points(d.m, cbr::test::random_points(30, 200 + seed, 0.05, 0.95));
        std::map<SuppressMethod, int> methods;
        SuppressOptions flips_only;
        flips_only.contraction = false;
        const std::size_t k = suppress_each(d.m, pts, flips_only, {}, &methods);
        CHECK(methods[SuppressMethod::kContraction] == 0);
        CHECK(static_cast<std::size_t>(methods[SuppressMethod::kFlips]) == k);
        total += pts.size();
        done += k;
    }
    MESSAGE("flips only: " << done << "/" << total << " suppressed");
    CHECK(done * 10 >= total * 9);  // at least 90%
}

TEST_CASE("suppression by contraction alone") {
    Domain d = convex_domain(7, 40, true);
    const auto pts = insert_points(d.m, cbr::test::random_points(30, 307, 0.05, 0.95));
    std::map<SuppressMethod, int> methods;
    SuppressOptions contraction_only;
    contraction_only.flips = false;
    const std::size_t k = suppress_each(d.m, pts, contraction_only, {}, &methods);
    MESSAGE("contraction only: " << k << "/" << pts.size() << " suppressed");
    CHECK(methods[SuppressMethod::kFlips] == 0);
    CHECK(k * 4 >= pts.size() * 3);  // at least 75%
}

// The best contraction of v by the definition, every target rated in
// full: over the link vertices x whose contraction (the ball tetrahedra
// without x, v replaced by x) makes tetrahedra that are all valid, the
// largest worst tet_quality; -inf when none is valid.
double best_contraction_quality(const TetMesh& m, VertexId v) {
    std::vector<TetId> ball;
    REQUIRE(cbr::mesh::ball(m, v, any_tet_of(m, v), ball));
    std::set<VertexId> link;
    for (TetId t : ball)
        for (int i = 0; i < 4; ++i)
            if (m.vertex(t, i) != v) link.insert(m.vertex(t, i));
    double best = -kInf;
    for (VertexId x : link) {
        double worst = kInf;
        int made = 0;
        for (TetId t : ball) {
            Tet k = {m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)};
            if (std::find(k.begin(), k.end(), x) != k.end()) continue;
            std::replace(k.begin(), k.end(), v, x);
            worst = std::min(worst, tet_quality(m.point(k[0]), m.point(k[1]), m.point(k[2]), m.point(k[3])));
            ++made;
        }
        if (made > 0 && worst > -kInf) best = std::max(best, worst);
    }
    return best;
}

TEST_CASE("suppression by contraction takes the best target") {
    // The search rates targets only above the best so far; what it returns
    // must be the full ranking's first.
    std::size_t compared = 0;
    for (std::uint64_t seed : {7u, 8u, 9u}) {
        Domain d = convex_domain(seed, 40, true);
        const auto pts = insert_points(d.m, cbr::test::random_points(30, 400 + seed, 0.05, 0.95));
        SuppressOptions contraction_only;
        contraction_only.flips = false;
        for (VertexId v : pts) {
            const double best = best_contraction_quality(d.m, v);
            SuppressReport rep;
            const bool ok = suppress_vertex(d.m, v, any_tet_of(d.m, v), {}, &rep, contraction_only);
            check_valid(d.m);
            if (!ok) continue;
            CHECK(rep.method == SuppressMethod::kContraction);
            CHECK(rep.min_quality == best);
            ++compared;
        }
    }
    MESSAGE("best contraction checked on " << compared << " points");
    CHECK(compared >= 60);
}

TEST_CASE("a flip-down that gives up is rolled back exactly") {
    Domain d = convex_domain(13, 40, true);
    const auto pts = insert_points(d.m, cbr::test::random_points(20, 813, 0.05, 0.95));
    const std::set<Key3> constraints = marked_faces(d.m);
    SuppressOptions one_step;
    one_step.contraction = false;
    one_step.max_flip_steps = 1;  // one edge removal, then give up
    std::size_t rolled_back = 0;
    for (VertexId v : pts) {
        const SlotSnapshot before(d.m);
        SuppressReport rep;
        const bool ok = suppress_vertex(d.m, v, any_tet_of(d.m, v), {}, &rep, one_step);
        check_valid(d.m);
        CHECK(marked_faces(d.m) == constraints);
        if (ok) continue;  // a ball of four: the 4-1 flip at step 0
        CHECK(rep.result == SuppressResult::kNoRetriangulation);
        // The same tetrahedra in the same slots, links and marks included
        // (the mesh's journal): what suppress_vertices' skipping relies on.
        CHECK(SlotSnapshot(d.m) == before);
        CHECK(rep.created.empty());
        rolled_back += rep.flips > 0;
    }
    MESSAGE("rolled back: " << rolled_back << "/" << pts.size());
    CHECK(rolled_back * 2 >= pts.size());
}

TEST_CASE("suppression: a retetrahedralization the caller refuses is put back exactly") {
    Domain d = convex_domain(17, 40, true);
    const auto pts = insert_points(d.m, cbr::test::random_points(20, 917, 0.05, 0.95));
    REQUIRE(pts.size() >= 15);
    const std::set<Key3> constraints = marked_faces(d.m);
    // Refuses every result: each ball goes back, with its point.
    SuppressOptions never;
    never.accept = [](const TetMesh&, const std::vector<TetId>&) { return false; };
    for (VertexId v : pts) {
        const std::set<Tet> before = tet_keys(d.m);
        SuppressReport rep;
        CHECK_FALSE(suppress_vertex(d.m, v, any_tet_of(d.m, v), {}, &rep, never));
        CHECK(rep.result == SuppressResult::kRefused);
        CHECK(tet_keys(d.m) == before);
        check_valid(d.m);
        CHECK(marked_faces(d.m) == constraints);
    }
    // Refuses tetrahedra with a vertex of a chosen set (three points): the
    // balls next to one are put back, the others go, and no new
    // tetrahedron ever has one.
    const std::set<VertexId> banned(pts.begin(), pts.begin() + 3);
    SuppressOptions not_at_banned;
    not_at_banned.accept = [&](const TetMesh& m, const std::vector<TetId>& created) {
        for (TetId t : created)
            for (int i = 0; i < 4; ++i)
                if (banned.count(m.vertex(t, i))) return false;
        return true;
    };
    std::size_t refused = 0, suppressed = 0;
    for (auto v = pts.begin() + 3; v != pts.end(); ++v) {
        const std::set<Tet> before = tet_keys(d.m);
        SuppressReport rep;
        const bool ok = suppress_vertex(d.m, *v, any_tet_of(d.m, *v), {}, &rep, not_at_banned);
        check_valid(d.m);
        CHECK(marked_faces(d.m) == constraints);
        if (ok) {
            ++suppressed;
            for (TetId t : rep.created)
                for (int i = 0; i < 4; ++i) CHECK(banned.count(d.m.vertex(t, i)) == 0);
        } else {
            CHECK(tet_keys(d.m) == before);
            refused += rep.result == SuppressResult::kRefused;
        }
    }
    MESSAGE("next to a banned point: " << refused << " refused, " << suppressed << " suppressed of "
                                       << pts.size() - 3);
    CHECK(refused > 0);
    CHECK(suppressed > 0);
}

TEST_CASE("suppress_vertices: passes, list shrinks, deterministic") {
    auto run = [](std::vector<VertexId>& pts, SuppressStats& st) {
        Domain d = convex_domain(8, 60, true);
        pts = insert_points(d.m, cbr::test::random_points(40, 408, 0.05, 0.95));
        const std::size_t n = pts.size();
        const std::size_t k = suppress_vertices(d.m, pts, {}, &st);
        check_valid(d.m);
        CHECK(k + pts.size() == n);
        CHECK(st.suppressed == k);
        CHECK(st.by_contraction + st.by_flips == k);
        return tet_keys(d.m);
    };
    std::vector<VertexId> a, b;
    SuppressStats sa, sb;
    const auto ta = run(a, sa), tb = run(b, sb);
    CHECK(a.empty());
    CHECK(ta == tb);
    CHECK(a == b);
    CHECK(sa.passes >= 1);
}

TEST_CASE("suppress_vertices: skipping the points whose ball is unchanged changes nothing but the work") {
    // Flip-downs cut after one step fail often, after a flip that is rolled
    // back; a suppression frees its neighbours, so later passes run and
    // meet unchanged balls.
    SuppressOptions one_step;
    one_step.max_flip_steps = 1;
    auto run = [&](bool skip, std::vector<VertexId>& pts, SuppressStats& st) {
        Domain d = convex_domain(8, 60, true);
        pts = insert_points(d.m, cbr::test::random_points(60, 4211, 0.05, 0.95));
        SuppressOptions options = one_step;
        options.skip_unchanged_balls = skip;
        suppress_vertices(d.m, pts, {}, &st, options);
        check_valid(d.m);
        return SlotSnapshot(d.m);
    };
    std::vector<VertexId> with, without;
    SuppressStats sw, so;
    const auto mesh_with = run(true, with, sw);
    const auto mesh_without = run(false, without, so);
    MESSAGE("passes " << sw.passes << ", kept " << with.size() << ", skipped " << sw.skipped);
    CHECK(sw.passes >= 2);
    CHECK(sw.skipped > 0);
    CHECK(so.skipped == 0);
    CHECK(with == without);
    CHECK(mesh_with == mesh_without);
    CHECK(sw.suppressed == so.suppressed);
    CHECK(sw.passes == so.passes);
    CHECK(sw.kept_no_retriangulation == so.kept_no_retriangulation);
}

namespace {

// Schönhardt's twisted prism with a point c at its centre: the 8 cones
// (prism face, c) and the 3 "pocket" tetrahedra between the prism's reflex
// sides and its convex hull; the prism faces are marked as constraints.
struct Prism {
    TetMesh m;
    VertexId centre;
    std::vector<Triangle> tris;
};
Prism schonhardt_with_centre() {
    const cbr::test::Polyhedron p = cbr::test::schonhardt_prism();
    std::vector<double> xyz = p.xyz;
    xyz.insert(xyz.end(), {0.0, 0.0, 0.5});
    std::vector<Tet> tets;
    auto oriented = [&](Tet t) {
        const int s = cbr::geom::orient3d(&xyz[3 * t[0]], &xyz[3 * t[1]], &xyz[3 * t[2]], &xyz[3 * t[3]]);
        REQUIRE(s != 0);
        if (s < 0) std::swap(t[0], t[1]);
        return t;
    };
    Prism out;
    out.centre = 6;
    for (std::size_t i = 0; i < p.tris.size(); i += 3) {
        const Triangle tri = {VertexId(p.tris[i]), VertexId(p.tris[i + 1]), VertexId(p.tris[i + 2])};
        out.tris.push_back(tri);
        tets.push_back(oriented({tri[0], tri[1], tri[2], 6}));
    }
    for (VertexId i = 0; i < 3; ++i) {
        const VertexId j = (i + 1) % 3;
        tets.push_back(oriented({i, j, 3 + j, 3 + i}));
    }
    out.m = build_mesh(xyz, tets);
    return out;
}

}  // namespace

TEST_CASE("Schönhardt's prism keeps its Steiner point, mesh unchanged") {
    Prism p = schonhardt_with_centre();
    check_valid(p.m);
    const ConstraintFaces cf = as_constraints(p.tris);
    CHECK(mark_present_faces(p.m, cf).empty());
    CHECK(marked_faces(p.m).size() == 8);
    const std::set<Tet> before = tet_keys(p.m);
    const auto coords = p.m.coordinates();
    for (const bool contraction : {true, false})
        for (const bool flips : {true, false}) {
            SuppressOptions opt;
            opt.contraction = contraction;
            opt.flips = flips;
            SuppressReport rep;
            CHECK_FALSE(suppress_vertex(p.m, p.centre, any_tet_of(p.m, p.centre), {}, &rep, opt));
            CHECK(rep.result == SuppressResult::kNoRetriangulation);
            MESSAGE("Schönhardt, contraction " << contraction << " flips " << flips << ": " << rep.flips
                                               << " flips tried and undone");
            CHECK(tet_keys(p.m) == before);
            CHECK(p.m.coordinates() == coords);
            check_valid(p.m);
            CHECK(marked_faces(p.m).size() == 8);
        }
    std::vector<VertexId> steiner = {p.centre};
    SuppressStats st;
    CHECK(suppress_vertices(p.m, steiner, {}, &st) == 0);
    CHECK(steiner == std::vector<VertexId>{p.centre});
    CHECK(st.kept_no_retriangulation == 1);
    CHECK(tet_keys(p.m) == before);

    // Repositioning never lowers its quality (at the symmetric centre it
    // is already at a local optimum) and keeps every cone valid: the prism
    // stays recovered.
    const double q0 = ball_quality(p.m, p.centre);
    const RepositionStats rs = reposition_steiner_points(p.m, steiner, cf);
    MESSAGE("Schönhardt centre: quality " << rs.min_quality_before << " -> " << rs.min_quality_after);
    check_valid(p.m);
    CHECK(rs.min_quality_after >= rs.min_quality_before);
    CHECK(ball_quality(p.m, p.centre) >= q0);
    CHECK(mark_present_faces(p.m, cf).empty());
}

TEST_CASE("suppression refuses a hull vertex and a vertex of a constraint face") {
    Domain d = convex_domain(9, 30, false);
    SuppressReport rep;
    // A cube corner: on the hull.
    VertexId corner = kGhostVertex;
    for (VertexId v = 0; v < d.m.vertex_count(); ++v)
        if (d.m.point(v)[0] == 0 && d.m.point(v)[1] == 0 && d.m.point(v)[2] == 0) corner = v;
    REQUIRE(corner != kGhostVertex);
    CHECK_FALSE(suppress_vertex(d.m, corner, any_tet_of(d.m, corner), {}, &rep));
    CHECK(rep.result == SuppressResult::kHullVertex);
    // An interior vertex with a marked face.
    VertexId inner = kGhostVertex;
    for (TetId t = 0; t < d.m.slot_count() && inner == kGhostVertex; ++t) {
        if (!live_finite(d.m, t)) continue;
        std::vector<TetId> b;
        for (int i = 0; i < 4 && inner == kGhostVertex; ++i) {
            const VertexId v = d.m.vertex(t, i);
            REQUIRE(ball(d.m, v, t, b));
            if (std::none_of(b.begin(), b.end(), [&](TetId k) { return d.m.is_ghost(k); })) {
                inner = v;
                mark_face(d.m, t, i == 0 ? 1 : 0);
            }
        }
    }
    REQUIRE(inner != kGhostVertex);
    const std::set<Tet> before = tet_keys(d.m);
    CHECK_FALSE(suppress_vertex(d.m, inner, any_tet_of(d.m, inner), {}, &rep));
    CHECK(rep.result == SuppressResult::kOnConstraint);
    CHECK_FALSE(suppress_vertex(d.m, inner, kNoTet, {}, &rep));
    CHECK(rep.result == SuppressResult::kBadInput);
    CHECK(tet_keys(d.m) == before);
    // Repositioning leaves both where they are.
    const ConstraintFaces cf = as_constraints(d.tris);
    const auto coords = d.m.coordinates();
    CHECK_FALSE(reposition_vertex(d.m, corner, any_tet_of(d.m, corner), cf));
    CHECK_FALSE(reposition_vertex(d.m, inner, any_tet_of(d.m, inner), cf));
    const RepositionStats st = reposition_steiner_points(d.m, {corner, inner}, cf);
    CHECK(st.skipped == 2);
    CHECK(st.moved == 0);
    CHECK(d.m.coordinates() == coords);
}

TEST_CASE("protected edges are never destroyed") {
    for (const bool contraction : {true, false}) {
        CAPTURE(contraction);
        Domain d = convex_domain(10, 40, true);
        const auto pts = insert_points(d.m, cbr::test::random_points(30, 510, 0.05, 0.95));
        // Every edge not at a Steiner point is protected.
        const std::set<VertexId> steiner(pts.begin(), pts.end());
        std::set<Edge> kept;
        for (const Edge& e : edges(d.m))
            if (!steiner.count(e[0]) && !steiner.count(e[1])) kept.insert(e);
        std::size_t asked_about_kept = 0;
        const EdgeProtect protect = [&](VertexId a, VertexId b) {
            const bool p = kept.count({std::min(a, b), std::max(a, b)}) != 0;
            asked_about_kept += p;
            return p;
        };
        SuppressOptions opt;
        opt.contraction = contraction;
        const std::set<Key3> constraints = marked_faces(d.m);
        for (VertexId v : pts) {
            suppress_vertex(d.m, v, any_tet_of(d.m, v), protect, nullptr, opt);
            const std::set<Edge> now = edges(d.m);
            CHECK(std::includes(now.begin(), now.end(), kept.begin(), kept.end()));
        }
        CHECK(asked_about_kept == 0);  // only edges at the suppressed point disappear
        check_valid(d.m);
        CHECK(marked_faces(d.m) == constraints);
    }
    // Protecting an edge at the point itself keeps the point.
    Domain d = convex_domain(11, 40, false);
    const auto pts = insert_points(d.m, cbr::test::random_points(5, 611, 0.2, 0.8));
    REQUIRE(!pts.empty());
    const VertexId v = pts[0];
    std::vector<TetId> b;
    REQUIRE(ball(d.m, v, any_tet_of(d.m, v), b));
    const VertexId x = d.m.vertex(b[0], d.m.vertex(b[0], 0) == v ? 1 : 0);
    const EdgeProtect protect = [&](VertexId a, VertexId c) { return (a == v && c == x) || (a == x && c == v); };
    const std::set<Tet> before = tet_keys(d.m);
    SuppressReport rep;
    CHECK_FALSE(suppress_vertex(d.m, v, any_tet_of(d.m, v), protect, &rep));
    CHECK(rep.result == SuppressResult::kProtectedEdge);
    CHECK(tet_keys(d.m) == before);
    std::vector<VertexId> list = pts;
    SuppressStats st;
    suppress_vertices(d.m, list, protect, &st);
    CHECK(list == std::vector<VertexId>{v});
    CHECK(st.kept_protected == 1);
    const auto e = edges(d.m);
    CHECK(e.count({std::min(v, x), std::max(v, x)}) == 1);
    check_valid(d.m);
}

namespace {

// Some vertex of `points` on some triangle of `tris` (exact).
bool on_any(const TetMesh& m, const std::vector<VertexId>& points, const std::vector<Triangle>& tris) {
    for (VertexId v : points)
        for (const Triangle& t : tris)
            if (cbr::geom::point_in_triangle(m.point(v), m.point(t[0]), m.point(t[1]), m.point(t[2]))) return true;
    return false;
}

}  // namespace

TEST_CASE("point_in_triangle is exact on the closed triangle") {
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    const double in[3] = {0.25, 0.25, 0}, edge[3] = {0.5, 0.5, 0}, vertex[3] = {1, 0, 0};
    const double out[3] = {0.5, 0.5000000000000001, 0}, above[3] = {0.25, 0.25, 1e-300};
    CHECK(cbr::geom::point_in_triangle(in, a, b, c));
    CHECK(cbr::geom::point_in_triangle(edge, a, b, c));
    CHECK(cbr::geom::point_in_triangle(vertex, a, b, c));
    CHECK_FALSE(cbr::geom::point_in_triangle(out, a, b, c));
    CHECK_FALSE(cbr::geom::point_in_triangle(above, a, b, c));
    // A tilted triangle, exactly representable points on it.
    const double p[3] = {1, 0, 1}, q[3] = {0, 1, 1}, r[3] = {0, 0, 2};
    const double mid[3] = {0.5, 0.5, 1}, centroidish[3] = {0.25, 0.25, 1.5}, beyond[3] = {1.5, -0.5, 1};
    CHECK(cbr::geom::point_in_triangle(mid, p, q, r));
    CHECK(cbr::geom::point_in_triangle(centroidish, p, q, r));
    CHECK_FALSE(cbr::geom::point_in_triangle(beyond, p, q, r));
}

TEST_CASE("repositioning: a point almost on a constraint face moves away, strictly better") {
    // Two unit boxes stacked, the middle square (z = 1) and the hull
    // marked: the point sits 1e-6 above the middle square.
    std::vector<double> xyz;
    for (int z = 0; z < 3; ++z)
        for (int c = 0; c < 4; ++c) xyz.insert(xyz.end(), {double(c & 1), double(c >> 1), double(z)});
    Domain d{delaunay_mesh(xyz), {}};
    d.tris = mark_hull(d.m);
    for (TetId t = 0; t < d.m.slot_count(); ++t) {
        if (!live_finite(d.m, t)) continue;
        for (int f = 0; f < 4; ++f) {
            const Key3 k = face_key(d.m, t, f);
            if (d.m.point(k[0])[2] == 1 && d.m.point(k[1])[2] == 1 && d.m.point(k[2])[2] == 1 &&
                facet_tet(d.m.neighbor(t, f)) > t) {
                mark_face(d.m, t, f);
                d.tris.push_back({k[0], k[1], k[2]});
            }
        }
    }
    REQUIRE(d.tris.size() == 10 * 2 + 2);
    const ConstraintFaces cf = as_constraints(d.tris);
    const auto pts = insert_points(d.m, {0.37, 0.41, 1 + 1e-6, 0.6, 0.45, 1.999999});
    REQUIRE(pts.size() == 2);
    const std::set<Key3> constraints = marked_faces(d.m);
    const std::set<Tet> topology = tet_keys(d.m);
    const double mid_a[3] = {0, 0, 1}, mid_b[3] = {1, 0, 1}, mid_c[3] = {0, 1, 1};
    const int side = cbr::geom::orient3d(mid_a, mid_b, mid_c, d.m.point(pts[0]));
    REQUIRE(side != 0);
    std::vector<double> before;
    for (VertexId v : pts) before.push_back(ball_quality(d.m, v));
    const RepositionStats st = reposition_steiner_points(d.m, pts, cf);
    MESSAGE("near-face points: min quality " << st.min_quality_before << " -> " << st.min_quality_after << ", moved "
                                             << st.moved << "/" << st.points);
    CHECK(st.points == 2);
    CHECK(st.moved == 2);
    CHECK(st.skipped == 0);
    CHECK(st.min_quality_after > st.min_quality_before);
    for (std::size_t i = 0; i < pts.size(); ++i) CHECK(ball_quality(d.m, pts[i]) > before[i]);
    CHECK(st.min_quality_after > 100 * st.min_quality_before);
    check_valid(d.m);  // every tetrahedron positively oriented (exact)
    CHECK(tet_keys(d.m) == topology);
    CHECK(marked_faces(d.m) == constraints);
    CHECK_FALSE(on_any(d.m, pts, d.tris));
    CHECK(cbr::geom::orient3d(mid_a, mid_b, mid_c, d.m.point(pts[0])) == side);
    // A second run starts from the improved positions: never worse.
    const RepositionStats again = reposition_steiner_points(d.m, pts, cf);
    CHECK(again.min_quality_after >= again.min_quality_before);
    CHECK(again.min_quality_before == st.min_quality_after);
    check_valid(d.m);
}

TEST_CASE("repositioning: random near-surface points in a convex domain") {
    Domain d = convex_domain(12, 50, true);
    const ConstraintFaces cf = as_constraints(d.tris);
    // Points 1e-7 inside the hull's faces and near interior constraints.
    std::vector<double> xyz = cbr::test::random_points(20, 712, 0.1, 0.9);
    for (std::size_t i = 0; i < 20; ++i) xyz[3 * i + i % 3] = (i % 2) ? 1e-7 : 1 - 1e-7;
    auto pts = insert_points(d.m, xyz);
    REQUIRE(pts.size() >= 15);
    const std::set<Key3> constraints = marked_faces(d.m);
    const std::set<Tet> topology = tet_keys(d.m);
    std::vector<double> before;
    for (VertexId v : pts) before.push_back(ball_quality(d.m, v));
    double q_before = kInf, q_after = kInf;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        double b = 0, a = 0;
        const double q0 = ball_quality(d.m, pts[i]);
        const bool moved = reposition_vertex(d.m, pts[i], any_tet_of(d.m, pts[i]), cf, {}, &b, &a);
        // Same tetrahedra, vertices listed in another order: rounding differs.
        CHECK(b == doctest::Approx(q0).epsilon(1e-9));
        CHECK(ball_quality(d.m, pts[i]) == doctest::Approx(a).epsilon(1e-9));
        if (moved) CHECK(a > b);
        else CHECK(a == b);
        q_before = std::min(q_before, b);
        q_after = std::min(q_after, a);
        check_valid(d.m);
    }
    MESSAGE("near-hull points: worst ball quality " << q_before << " -> " << q_after);
    CHECK(q_after > q_before);
    CHECK(tet_keys(d.m) == topology);
    CHECK(marked_faces(d.m) == constraints);
    CHECK_FALSE(on_any(d.m, pts, d.tris));
    // Then they can all be suppressed from their new places.
    const std::size_t n = pts.size();
    CHECK(suppress_vertices(d.m, pts) == n);
    check_valid(d.m);
}

TEST_CASE("suppression at scale: 2000 points, both mechanisms and flips alone") {
    // 20 domains of 108 points with interior constraints, 100 points
    // inserted in each; every attempt checked (refusals leave the
    // tetrahedra as they were). Exercises the 2-3 look-ahead and its undo.
    for (const bool contraction : {true, false}) {
        std::size_t total = 0, done = 0, link_flips = 0, undone = 0, removals = 0, later = 0, left = 0;
        for (std::uint64_t seed = 20; seed < 40; ++seed) {
            Domain d = convex_domain(seed, 100, true);
            const auto pts = insert_points(d.m, cbr::test::random_points(100, 900 + seed, 0.05, 0.95));
            const std::set<Key3> constraints = marked_faces(d.m);
            SuppressOptions opt;
            opt.contraction = contraction;
            std::vector<VertexId> kept;
            for (VertexId v : pts) {
                const std::set<Tet> before = tet_keys(d.m);
                SuppressReport rep;
                const bool ok = suppress_vertex(d.m, v, any_tet_of(d.m, v), {}, &rep, opt);
                done += ok;
                if (!ok) {
                    CHECK(tet_keys(d.m) == before);
                    kept.push_back(v);
                }
                link_flips += rep.link_flips;
                undone += rep.flips_undone;
                removals += rep.edge_removals;
            }
            // The ones left go in later passes, once their neighbours went.
            const std::size_t n_kept = kept.size();
            const std::size_t k = suppress_vertices(d.m, kept, {}, nullptr, opt);
            CHECK(k + kept.size() == n_kept);
            later += k;
            left += kept.size();
            total += pts.size();
            check_valid(d.m);
            CHECK(marked_faces(d.m) == constraints);
        }
        MESSAGE("contraction " << contraction << ": " << done << "/" << total << " suppressed at once, " << later
                               << " more in later passes, " << left << " left; edge removals " << removals
                               << ", 2-3 flips kept " << link_flips << ", undone " << undone);
        CHECK(done * 100 >= total * 99);
        if (contraction) CHECK(left == 0);
        if (!contraction) CHECK(undone > 0);
    }
}
