// Mesh surgery (replace_tets), flips (§5.1 Definition 5.6 Swap23/32/44,
// Definition 5.8 shell transformation / edge removal), ball and shell.
// After every successful operation the whole mesh is checked exactly
// (check_mesh: orientation, symmetric adjacency, closed hull), plus here:
// the hull stays convex, the volume is unchanged, constraint marks are
// symmetric and their set never changes; every refusal leaves the arrays
// bit-identical.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>

#include "delaunay/delaunay.hpp"
#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/flips.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh/slot_pool.hpp"
#include "mesh/surgery.hpp"
#include "mesh_test_util.hpp"
#include "test_util.hpp"

using namespace cbr::mesh;

namespace {

using cbr::test::build_mesh;
using cbr::test::delaunay_mesh;
using cbr::test::face_key;
using cbr::test::Key3;
using cbr::test::Tet;
using Rng = std::mt19937_64;

// --- whole-mesh observations ------------------------------------------------

// Every hull edge convex or flat: the far vertex of the neighbouring hull
// face is not above a ghost's hull face.
bool hull_convex(const TetMesh& m) {
    for (TetId g = 0; g < m.slot_count(); ++g) {
        if (m.is_free(g) || !m.is_ghost(g)) continue;
        for (int f = 0; f < 3; ++f) {
            const FacetRef r = m.neighbor(g, f);
            const double* e = m.point(m.vertex(facet_tet(r), facet_face(r)));
            if (cbr::geom::orient3d(m.point(m.vertex(g, 0)), m.point(m.vertex(g, 1)), m.point(m.vertex(g, 2)), e) > 0)
                return false;
        }
    }
    return true;
}

long double six_volume(const TetMesh& m) {
    long double sum = 0;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t) || m.is_ghost(t)) continue;
        long double e[3][3];
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
                e[i][k] = static_cast<long double>(m.point(m.vertex(t, i + 1))[k]) - m.point(m.vertex(t, 0))[k];
        sum += e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
               e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    }
    return sum;
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

bool has_edge(const TetMesh& m, VertexId u, VertexId v) {
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t) && vertex_index(m, t, u) >= 0 && vertex_index(m, t, v) >= 0) return true;
    return false;
}

// Marked faces by vertex set; `symmetric` false when a mark is one-sided.
std::set<Key3> marked_faces(const TetMesh& m, bool* symmetric = nullptr) {
    std::set<Key3> s;
    if (symmetric) *symmetric = true;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        for (int f = 0; f < 4; ++f) {
            if (!m.is_constrained(t, f)) continue;
            s.insert(face_key(m, t, f));
            const FacetRef r = m.neighbor(t, f);
            if (symmetric && !m.is_constrained(facet_tet(r), facet_face(r))) *symmetric = false;
        }
    }
    return s;
}

void mark_face(TetMesh& m, TetId t, int f) {
    const FacetRef r = m.neighbor(t, f);
    m.set_constrained(t, f, true);
    m.set_constrained(facet_tet(r), facet_face(r), true);
}

using Snapshot = cbr::test::SlotSnapshot;

void require_valid(const TetMesh& m) {
    const CheckReport report = check_mesh(m);
    for (const auto& e : report.errors) MESSAGE(e);
    REQUIRE(report.ok());
    REQUIRE(hull_convex(m));
}

TetId random_live(const TetMesh& m, Rng& rng) {
    for (;;) {
        const TetId t = static_cast<TetId>(rng() % m.slot_count());
        if (!m.is_free(t)) return t;
    }
}

// --- random flips -----------------------------------------------------------

enum Kind { k23, k32, k44, kRemove, kKinds };

struct Tally {
    int done[kKinds] = {};
    int hull_done = 0;      // flips whose region contained a ghost
    int marks_carried = 0;  // flips that created a tetrahedron with a marked face
};

// One random flip of the given kind; `hull`: the region touched the hull.
FlipResult random_flip(TetMesh& m, Rng& rng, Kind kind, bool& hull, std::vector<TetId>& created) {
    const TetId t = random_live(m, rng);
    if (kind == k23) {
        const int f = static_cast<int>(rng() % 4);
        hull = m.is_ghost(t) || m.is_ghost(facet_tet(m.neighbor(t, f)));
        return flip23(m, t, f, {}, &created);
    }
    const int i = static_cast<int>(rng() % 4), j = (i + 1 + static_cast<int>(rng() % 3)) % 4;
    const VertexId u = m.vertex(t, i), v = m.vertex(t, j);
    Shell s;
    REQUIRE(shell(m, u, v, t, s));
    hull = s.has_ghost() || u == kGhostVertex || v == kGhostVertex;
    if (kind == k32) return flip32(m, t, u, v, {}, &created);
    if (kind == k44) return flip44(m, t, u, v, {}, &created);
    return remove_edge(m, t, u, v, {}, &created);
}

bool created_marked(const TetMesh& m, const std::vector<TetId>& created) {
    for (TetId t : created)
        for (int f = 0; f < 4; ++f)
            if (m.is_constrained(t, f)) return true;
    return false;
}

// `attempts` random flips; every success is checked in full, every refusal
// must leave the mesh bit-identical.
Tally random_flips(TetMesh& m, int attempts, std::uint64_t seed) {
    Rng rng(seed);
    Tally tally;
    const long double volume = six_volume(m);
    bool symmetric = false;
    const std::set<Key3> marks = marked_faces(m, &symmetric);
    REQUIRE(symmetric);
    Snapshot before(m);
    std::vector<TetId> created;
    for (int a = 0; a < attempts; ++a) {
        const Kind kind = static_cast<Kind>(rng() % kKinds);
        bool hull = false;
        const FlipResult r = random_flip(m, rng, kind, hull, created);
        if (r != FlipResult::kDone) {
            REQUIRE((Snapshot(m) == before));
            continue;
        }
        ++tally.done[kind];
        tally.hull_done += hull;
        tally.marks_carried += created_marked(m, created);
        require_valid(m);
        REQUIRE(std::fabs(static_cast<double>(six_volume(m) - volume)) <= 1e-9 * static_cast<double>(volume));
        REQUIRE(marked_faces(m, &symmetric) == marks);
        REQUIRE(symmetric);
        before = Snapshot(m);
    }
    return tally;
}

void report(const char* name, const Tally& t) {
    MESSAGE(std::string(name) << ": 2-3 " << t.done[k23] << ", 3-2 " << t.done[k32] << ", 4-4 " << t.done[k44]
                              << ", removal " << t.done[kRemove] << ", on the hull " << t.hull_done
                              << ", marks carried " << t.marks_carried);
}

// Marks about one interior face in `every` as a constraint, both sides.
void mark_random_faces(TetMesh& m, int every, std::uint64_t seed) {
    Rng rng(seed);
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t) || m.is_ghost(t)) continue;
        for (int f = 0; f < 4; ++f)
            if (rng() % static_cast<unsigned>(every) == 0) mark_face(m, t, f);
    }
}

}  // namespace

// ---------------------------------------------------------------------------

TEST_CASE("random flips on Delaunay meshes keep the mesh valid") {
    SUBCASE("random points, some faces constrained") {
        TetMesh m = delaunay_mesh(cbr::test::random_points(300, 17));
        mark_random_faces(m, 40, 3);
        const Tally t = random_flips(m, 12000, 101);
        report("random points", t);
        for (int k : {k23, k32, kRemove}) CHECK(t.done[k] > 0);  // no coplanar quadrilateral: no 4-4
        CHECK(t.marks_carried > 0);
    }
    SUBCASE("grid: coplanar everywhere, flat hull") {
        TetMesh m = delaunay_mesh(cbr::test::grid_points(6));
        mark_random_faces(m, 60, 4);
        const Tally t = random_flips(m, 12000, 202);
        report("grid", t);
        for (int k = 0; k < kKinds; ++k) CHECK(t.done[k] > 0);
        CHECK(t.hull_done > 0);  // 2-2 flips of flat hull quadrilaterals, at least
    }
}

TEST_CASE("flip23 then flip32 on the new edge gives back the same tetrahedra") {
    // A pure grid has almost no valid 2-3 flip (its faces are coplanar with
    // their neighbours'): the second mesh is a grid with random points inside.
    for (int grid = 0; grid < 2; ++grid) {
        std::vector<double> xyz = cbr::test::random_points(200, 5, 0.5, 3.5);
        if (grid) {
            const auto g = cbr::test::grid_points(5);
            xyz.insert(xyz.end(), g.begin(), g.end());
        }
        TetMesh m = delaunay_mesh(xyz);
        mark_random_faces(m, 30, 6);
        Rng rng(7);
        int pairs = 0;
        std::vector<TetId> created;
        // Every pair gives back the same sets: they never change.
        const auto tets = tet_keys(m);
        const auto marks = marked_faces(m);
        for (int a = 0; a < 4000 && pairs < 200; ++a) {
            const TetId t = random_live(m, rng);
            const int f = static_cast<int>(rng() % 4);
            const FacetRef across = m.neighbor(t, f);
            const VertexId d = m.vertex(t, f), e = m.vertex(facet_tet(across), facet_face(across));
            if (flip23(m, t, f, {}, &created) != FlipResult::kDone) continue;
            REQUIRE(created.size() == 3);
            REQUIRE(has_edge(m, d, e));
            REQUIRE(flip32(m, created[0], d, e) == FlipResult::kDone);
            REQUIRE(tet_keys(m) == tets);
            REQUIRE(marked_faces(m) == marks);
            require_valid(m);
            ++pairs;
        }
        CHECK(pairs == 200);
    }
}

TEST_CASE("replace_tets refusals leave the mesh bit-identical") {
    TetMesh m = delaunay_mesh(cbr::test::random_points(150, 9));
    Rng rng(11);
    // A face whose 2-3 flip is valid, and one whose flip inverts a tetrahedron.
    TetId good_t = kNoTet, bad_t = kNoTet;
    int good_f = 0, bad_f = 0;
    while (good_t == kNoTet || bad_t == kNoTet) {
        const TetId t = random_live(m, rng);
        const int f = static_cast<int>(rng() % 4);
        if (m.is_ghost(t) || m.is_ghost(facet_tet(m.neighbor(t, f)))) continue;
        TetMesh copy = m;
        const FlipResult r = flip23(copy, t, f);
        if (r == FlipResult::kDone) good_t = t, good_f = f;
        if (r == FlipResult::kInverted) bad_t = t, bad_f = f;
    }
    // The 2-3 region and fresh set of face f of t.
    auto flip_sets = [&](TetId t, int f, std::vector<TetId>& old, std::vector<Tet>& fresh) {
        const FacetRef across = m.neighbor(t, f);
        const VertexId a = m.vertex(t, kFaceVertices[f][0]), b = m.vertex(t, kFaceVertices[f][1]),
                       c = m.vertex(t, kFaceVertices[f][2]), d = m.vertex(t, f),
                       e = m.vertex(facet_tet(across), facet_face(across));
        old = {t, facet_tet(across)};
        fresh = {{a, b, e, d}, {b, c, e, d}, {c, a, e, d}};
    };
    std::vector<TetId> old;
    std::vector<Tet> fresh;
    const Snapshot before(m);
    auto refused = [&](ReplaceResult expected) {
        CHECK(replace_tets(m, old, fresh) == expected);
        CHECK((Snapshot(m) == before));
    };

    SUBCASE("fresh sets that do not tile the region") {
        flip_sets(good_t, good_f, old, fresh);
        fresh.pop_back();  // a hole
        refused(ReplaceResult::kNotTiling);
        flip_sets(good_t, good_f, old, fresh);
        std::swap(fresh[0][0], fresh[0][1]);  // one tetrahedron turned inside out: faces mismatch
        refused(ReplaceResult::kNotTiling);
        flip_sets(good_t, good_f, old, fresh);
        fresh.push_back(fresh[0]);  // a face shared three times
        refused(ReplaceResult::kNotTiling);
        flip_sets(good_t, good_f, old, fresh);
        old.pop_back();  // the fresh set fills more than the region
        refused(ReplaceResult::kNotTiling);
    }
    SUBCASE("bad input") {
        flip_sets(good_t, good_f, old, fresh);
        old.push_back(old[0]);
        refused(ReplaceResult::kBadInput);
        flip_sets(good_t, good_f, old, fresh);
        fresh[1][2] = static_cast<VertexId>(m.vertex_count());
        refused(ReplaceResult::kBadInput);
        flip_sets(good_t, good_f, old, fresh);
        fresh[1][2] = fresh[1][0];
        refused(ReplaceResult::kBadInput);
        flip_sets(good_t, good_f, old, fresh);
        fresh[1][0] = fresh[1][1] = kGhostVertex;
        refused(ReplaceResult::kBadInput);
        old.clear();
        refused(ReplaceResult::kBadInput);
    }
    SUBCASE("an inverted fresh tetrahedron") {
        flip_sets(bad_t, bad_f, old, fresh);
        refused(ReplaceResult::kInverted);
        CHECK(flip23(m, bad_t, bad_f) == FlipResult::kInverted);
        CHECK((Snapshot(m) == before));
    }
    SUBCASE("a constraint face would disappear") {
        mark_face(m, good_t, good_f);
        const Snapshot marked(m);
        flip_sets(good_t, good_f, old, fresh);
        CHECK(replace_tets(m, old, fresh) == ReplaceResult::kRemovesConstraint);
        CHECK(flip23(m, good_t, good_f) == FlipResult::kRemovesConstraint);
        CHECK((Snapshot(m) == marked));
    }
    SUBCASE("constraint faces on the region's boundary are carried; inside, they block a 3-2") {
        // Mark the other three faces of t: they bound the 2-3 region.
        std::set<Key3> boundary;
        for (int f = 0; f < 4; ++f)
            if (f != good_f) {
                mark_face(m, good_t, f);
                boundary.insert(face_key(m, good_t, f));
            }
        const VertexId d = m.vertex(good_t, good_f);
        const FacetRef across = m.neighbor(good_t, good_f);
        const VertexId e = m.vertex(facet_tet(across), facet_face(across));
        std::vector<TetId> created;
        REQUIRE(flip23(m, good_t, good_f, {}, &created) == FlipResult::kDone);
        require_valid(m);
        std::set<Key3> carried;
        for (TetId t : created)
            for (int f = 0; f < 4; ++f) {
                if (!m.is_constrained(t, f)) continue;
                carried.insert(face_key(m, t, f));
                const FacetRef r = m.neighbor(t, f);
                CHECK(m.is_constrained(facet_tet(r), facet_face(r)));  // the outside side kept its mark
            }
        CHECK(carried == boundary);
        // Now a face around the new edge de is a constraint: the 3-2 flip
        // that would take de away again is refused.
        int f_de = 0;
        while (m.vertex(created[0], f_de) == d || m.vertex(created[0], f_de) == e) ++f_de;
        mark_face(m, created[0], f_de);
        const Snapshot marked(m);
        CHECK(flip32(m, created[0], d, e) == FlipResult::kRemovesConstraint);
        CHECK(remove_edge(m, created[0], d, e) == FlipResult::kRemovesConstraint);
        CHECK((Snapshot(m) == marked));
    }
    SUBCASE("the same flip without the refusals succeeds") {
        flip_sets(good_t, good_f, old, fresh);
        std::vector<TetId> created;
        CHECK(replace_tets(m, old, fresh, &created) == ReplaceResult::kDone);
        CHECK(created[0] == old[0]);  // old slots reused in order
        CHECK(created[1] == old[1]);
        require_valid(m);
    }
}

// ConeReplacer is replace_tets specialised to the star of a new point: on
// random regions (connected, of 1 to 12 tetrahedra, ghosts included, with
// random constraint faces) and points (near or inside a tetrahedron of the
// region, or anywhere around the mesh), both give the same verdict and the
// same mesh, slot for slot.
TEST_CASE("ConeReplacer agrees with replace_tets on cones over random regions") {
    TetMesh base = delaunay_mesh(cbr::test::random_points(120, 21));
    Rng rng(23);
    for (TetId t = 0; t < base.slot_count(); ++t)
        for (int f = 0; f < 4; ++f)
            if (rng() % 40 == 0) mark_face(base, t, f);
    ConeReplacer cones;  // one replacer for every trial: its scratch is reused
    std::map<ReplaceResult, int> verdicts;
    int restores = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        TetMesh m = base;
        // A connected region grown from a random tetrahedron.
        std::vector<TetId> old{random_live(m, rng)};
        const std::size_t size = 1 + rng() % 12;
        for (int tries = 0; old.size() < size && tries < 100; ++tries) {
            const TetId n = facet_tet(m.neighbor(old[rng() % old.size()], static_cast<int>(rng() % 4)));
            if (std::find(old.begin(), old.end(), n) == old.end()) old.push_back(n);
        }
        // The point: the centroid of a finite region tetrahedron, moved a
        // little at random, or a random point around the mesh.
        std::array<double, 3> xyz{};
        const TetId host = old[rng() % old.size()];
        std::uniform_real_distribution<double> jitter(-0.05, 0.05), anywhere(-0.2, 1.2);
        if (!m.is_ghost(host) && rng() % 4 != 0) {
            for (int i = 0; i < 4; ++i)
                for (int k = 0; k < 3; ++k) xyz[k] += 0.25 * m.point(m.vertex(host, i))[k];
            if (rng() % 2)
                for (double& x : xyz) x += jitter(rng);
        } else {
            for (double& x : xyz) x = anywhere(rng);
        }
        const VertexId p = m.add_points(xyz.data(), 1);
        // The cone list replace_tets is given: by region tetrahedron, then face.
        std::vector<Tet> fresh;
        for (TetId t : old)
            for (int f = 0; f < 4; ++f) {
                if (std::find(old.begin(), old.end(), facet_tet(m.neighbor(t, f))) != old.end()) continue;
                Tet c = {m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)};
                c[static_cast<std::size_t>(f)] = p;
                fresh.push_back(c);
            }
        TetMesh by_faces = m;
        std::vector<Tet> region;  // the region as it was, for the undo
        for (TetId t : old) region.push_back({m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)});
        std::vector<TetId> created_by_faces, created_by_cones;
        const ReplaceResult expected = replace_tets(by_faces, old, fresh, &created_by_faces);
        const ReplaceResult got = cones.replace(m, old, p, &created_by_cones);
        REQUIRE(got == expected);
        CHECK((Snapshot(m) == Snapshot(by_faces)));
        CHECK(created_by_cones == created_by_faces);
        ++verdicts[got];
        if (got != ReplaceResult::kDone) {
            CHECK_FALSE(cones.restore_last(m, created_by_cones));  // nothing to undo after a refusal
            continue;
        }
        require_valid(m);
        // The undo against replace_tets putting the region back: the same
        // mesh, slot for slot.
        std::vector<TetId> restored_by_faces, restored;
        REQUIRE(replace_tets(by_faces, created_by_faces, region, &restored_by_faces) == ReplaceResult::kDone);
        REQUIRE(cones.restore_last(m, created_by_cones, &restored));
        CHECK((Snapshot(m) == Snapshot(by_faces)));
        CHECK(restored == restored_by_faces);
        CHECK_FALSE(cones.restore_last(m, created_by_cones));  // once
        ++restores;
    }
    CHECK(restores > 100);
    // The trials reach every verdict a cone can get.
    CHECK(verdicts[ReplaceResult::kDone] > 100);
    CHECK(verdicts[ReplaceResult::kNotTiling] > 0);
    CHECK(verdicts[ReplaceResult::kRemovesConstraint] > 0);
    CHECK(verdicts[ReplaceResult::kInverted] > 100);
    CHECK(verdicts[ReplaceResult::kNotConvex] > 0);
    // Refusals of bad input, as replace_tets: an empty region, a slot listed
    // twice, a point that is a vertex of the region.
    TetMesh m = base;
    const Snapshot before(m);
    const TetId t = random_live(m, rng);
    CHECK(cones.replace(m, {}, 0) == ReplaceResult::kBadInput);
    CHECK(cones.replace(m, {t, t}, 0) == ReplaceResult::kBadInput);
    const VertexId corner = m.vertex(t, 0) == kGhostVertex ? m.vertex(t, 1) : m.vertex(t, 0);
    CHECK(cones.replace(m, {t}, corner) == ReplaceResult::kBadInput);
    CHECK((Snapshot(m) == before));
    // A star that changed since is not undone: the mesh stays as it is.
    const TetId host = m.is_ghost(t) ? facet_tet(m.neighbor(t, 3)) : t;
    std::array<double, 3> centroid{};
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) centroid[k] += 0.25 * m.point(m.vertex(host, i))[k];
    const std::size_t live_before = m.live_count();
    const Tet host_vertices = {m.vertex(host, 0), m.vertex(host, 1), m.vertex(host, 2), m.vertex(host, 3)};
    const VertexId p = m.add_points(centroid.data(), 1);
    std::vector<TetId> star;
    REQUIRE(cones.replace(m, {host}, p, &star) == ReplaceResult::kDone);
    const Snapshot four(m);
    std::vector<TetId> moved = star;
    std::swap(moved[0], moved[1]);  // cone 0 listed where cone 1 is
    CHECK_FALSE(cones.restore_last(m, moved));
    CHECK((Snapshot(m) == four));
    REQUIRE(cones.restore_last(m, star));
    m.truncate_vertices(p);
    require_valid(m);
    CHECK(m.live_count() == live_before);
    for (int i = 0; i < 4; ++i) CHECK(m.vertex(host, i) == host_vertices[static_cast<std::size_t>(i)]);
}

// A region with more tetrahedra than boundary faces (every triangulation
// of points on two skew lines has (n - 1)^2 tetrahedra and 4n - 4 hull
// faces: 25 and 20 for n = 6), starred from a point inside and put back:
// the region's last tetrahedra return in other slots, linked as
// replace_tets links them.
TEST_CASE("ConeReplacer puts back a region larger than its star") {
    std::vector<double> xyz;
    for (int i = 0; i < 6; ++i) xyz.insert(xyz.end(), {0.2 * i, 0.0, 0.0});
    for (int i = 0; i < 6; ++i) xyz.insert(xyz.end(), {0.5, -0.5 + 0.2 * i, 1.0});
    xyz.insert(xyz.end(), {0.5, 0.0, 0.5});  // the apex, added after the triangulation
    std::vector<double> lines(xyz.begin(), xyz.end() - 3);
    TetMesh m = delaunay_mesh(lines);
    std::vector<TetId> old;
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (cbr::test::live_finite(m, t)) old.push_back(t);
    REQUIRE(old.size() == 25);
    std::vector<Tet> region;
    for (TetId t : old) region.push_back({m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)});
    const VertexId p = m.add_points(&xyz[xyz.size() - 3], 1);
    ConeReplacer cones;
    std::vector<TetId> star, restored, restored_by_faces;
    REQUIRE(cones.replace(m, old, p, &star) == ReplaceResult::kDone);
    REQUIRE(star.size() == 20);
    TetMesh by_faces = m;
    REQUIRE(replace_tets(by_faces, star, region, &restored_by_faces) == ReplaceResult::kDone);
    REQUIRE(cones.restore_last(m, star, &restored));
    CHECK((Snapshot(m) == Snapshot(by_faces)));
    CHECK(restored == restored_by_faces);
    CHECK(restored != old);  // five came back in other slots
    m.truncate_vertices(p);
    require_valid(m);
}

namespace {

// A random triangulation of the ring polygon r_i .. r_j (closed by the
// chord ij), each triangle in ring order, randomly rotated.
void random_ring_triangulation(int i, int j, Rng& rng, std::vector<RingTriangle>& out) {
    if (j - i < 2) return;
    const int k = i + 1 + static_cast<int>(rng() % static_cast<unsigned>(j - i - 1));
    RingTriangle tri = {i, k, j};
    std::rotate(tri.begin(), tri.begin() + static_cast<std::ptrdiff_t>(rng() % 3), tri.end());
    out.push_back(tri);
    random_ring_triangulation(i, k, rng, out);
    random_ring_triangulation(k, j, rng, out);
}

// The cone list replace_tets is given for a shell transformation.
std::vector<Tet> ring_cones(VertexId u, VertexId v, const Shell& s, const std::vector<RingTriangle>& triangles) {
    std::vector<Tet> fresh;
    for (const RingTriangle& t : triangles) {
        const VertexId a = s.ring[static_cast<std::size_t>(t[0])], b = s.ring[static_cast<std::size_t>(t[1])],
                       c = s.ring[static_cast<std::size_t>(t[2])];
        fresh.push_back({a, b, c, v});
        fresh.push_back({a, c, b, u});
    }
    return fresh;
}

// The meshes the replacers are compared on: 80 random points (few
// coplanar configurations) and a 4 x 4 x 3 grid (flat hull faces,
// coplanar rings: the cases of CAD surfaces), each with about one face in
// `one_in` marked as a constraint face.
std::array<TetMesh, 2> replacement_test_meshes(std::uint64_t points_seed, std::uint64_t marks_seed, unsigned one_in) {
    std::vector<double> grid;
    for (int x = 0; x < 4; ++x)
        for (int y = 0; y < 4; ++y)
            for (int z = 0; z < 3; ++z) grid.insert(grid.end(), {double(x), double(y), double(z)});
    std::array<TetMesh, 2> meshes = {delaunay_mesh(cbr::test::random_points(80, points_seed)), delaunay_mesh(grid)};
    for (TetMesh& m : meshes) {
        Rng rng(marks_seed);
        for (TetId t = 0; t < m.slot_count(); ++t)
            for (int f = 0; f < 4; ++f)
                if (!m.is_free(t) && rng() % one_in == 0) mark_face(m, t, f);
    }
    return meshes;
}

// ShellReplacer against replace_tets on random shells of `base` (edges
// with a ghost endpoint or ghosts in the ring included): the best ring
// triangulation (also with the checks it vouches for skipped), random
// triangulations, and broken ones (a triangle reversed or repeated). Same
// verdict, same mesh slot for slot, same created list.
std::map<ReplaceResult, int> compare_shell_replacements(const TetMesh& base, int trials, std::uint64_t seed) {
    Rng rng(seed);
    ShellReplacer shells;  // one replacer for every trial: its scratch is reused
    std::map<ReplaceResult, int> verdicts;
    for (int trial = 0; trial < trials; ++trial) {
        const TetId t = random_live(base, rng);
        const int i = static_cast<int>(rng() % 4), j = (i + 1 + static_cast<int>(rng() % 3)) % 4;
        const VertexId u = base.vertex(t, i), v = base.vertex(t, j);
        Shell s;
        REQUIRE(shell(base, u, v, t, s));
        if (s.size() > 12) continue;
        const int n = static_cast<int>(s.size());
        std::vector<RingTriangle> triangles;
        const int mode = static_cast<int>(rng() % 3);
        if (mode == 0) {
            if (!best_ring_triangulation(base, u, v, s, triangles)) continue;
        } else {
            random_ring_triangulation(0, n - 1, rng, triangles);
            std::shuffle(triangles.begin(), triangles.end(), rng);
            if (mode == 2) {
                RingTriangle& bad = triangles[rng() % triangles.size()];
                if (rng() % 2 || triangles.size() == 1) std::swap(bad[0], bad[1]);
                else bad = triangles[(&bad - triangles.data() + 1) % static_cast<std::ptrdiff_t>(triangles.size())];
            }
        }
        TetMesh expected_mesh = base;
        std::vector<TetId> expected_created, created;
        const ReplaceResult expected =
            replace_tets(expected_mesh, s.tets, ring_cones(u, v, s, triangles), &expected_created);
        const std::vector<ShellGeometry> ways =
            mode == 0 ? std::vector<ShellGeometry>{ShellGeometry::kUnchecked, ShellGeometry::kScoredRing}
                      : std::vector<ShellGeometry>{ShellGeometry::kUnchecked};
        for (ShellGeometry way : ways) {
            CAPTURE(mode);
            CAPTURE(static_cast<int>(way));
            TetMesh m = base;
            const ReplaceResult got = shells.replace(m, u, v, s, triangles, way, &created);
            REQUIRE(got == expected);
            CHECK((Snapshot(m) == Snapshot(expected_mesh)));
            if (got == ReplaceResult::kDone) {
                CHECK(created == expected_created);
                require_valid(m);
            }
        }
        if (mode == 2) CHECK(expected == ReplaceResult::kNotTiling);
        ++verdicts[expected];
    }
    return verdicts;
}

}  // namespace

// ShellReplacer is replace_tets specialised to the shell transformation:
// on random points and on a grid (replacement_test_meshes), it gives the
// same verdicts and meshes.
TEST_CASE("ShellReplacer agrees with replace_tets on random shells") {
    const auto [scattered, flat] = replacement_test_meshes(31, 37, 60);
    std::map<ReplaceResult, int> verdicts = compare_shell_replacements(scattered, 3000, 41);
    for (const auto& [r, count] : compare_shell_replacements(flat, 3000, 43)) verdicts[r] += count;
    for (const auto& [r, count] : verdicts) MESSAGE(std::string(to_string(r)) << ": " << count);
    // The trials reach every verdict a shell transformation can get.
    CHECK(verdicts[ReplaceResult::kDone] > 100);
    CHECK(verdicts[ReplaceResult::kNotTiling] > 100);
    CHECK(verdicts[ReplaceResult::kRemovesConstraint] > 0);
    CHECK(verdicts[ReplaceResult::kInverted] > 100);
    CHECK(verdicts[ReplaceResult::kNotConvex] > 0);
}

namespace {

// TwoThreeReplacer against replace_tets on two copies of `base` that
// evolve together: random 2-3 replacements (ghosts included, which take
// replace_tets' own path), with random scratch marks on the region, and
// random 3-2 flips in between, which free slots that later replacements
// take again. Same verdict, same mesh slot for slot (the free list's
// order shows in the slots taken), same created list.
std::map<ReplaceResult, int> compare_two_three_replacements(const TetMesh& base, int trials, std::uint64_t seed) {
    Rng rng(seed);
    TwoThreeReplacer two_three;  // one replacer for every trial: its scratch is reused
    TetMesh m = base, expected_mesh = base;
    std::map<ReplaceResult, int> verdicts;
    for (int trial = 0; trial < trials; ++trial) {
        const TetId t = random_live(m, rng);
        const int f = static_cast<int>(rng() % 4);
        if (rng() % 3 == 0) {  // a 3-2 flip on both copies
            const VertexId u = m.vertex(t, f), v = m.vertex(t, (f + 1) % 4);
            REQUIRE(flip32(m, t, u, v) == flip32(expected_mesh, t, u, v));
            continue;
        }
        if (rng() % 4 == 0)
            for (TetId x : {t, facet_tet(m.neighbor(t, f))}) {
                m.set_mark(x, kFlagMarkA);
                expected_mesh.set_mark(x, kFlagMarkA);
            }
        const VertexId* v = m.vertices(t);
        const VertexId a = v[kFaceVertices[f][0]], b = v[kFaceVertices[f][1]], c = v[kFaceVertices[f][2]];
        const VertexId d = v[f], e = m.vertex(facet_tet(m.neighbor(t, f)), facet_face(m.neighbor(t, f)));
        const std::vector<Tet> fresh = {{a, b, e, d}, {b, c, e, d}, {c, a, e, d}};
        std::vector<TetId> expected_created, created;
        const ReplaceResult expected =
            replace_tets(expected_mesh, {t, facet_tet(m.neighbor(t, f))}, fresh, &expected_created);
        const ReplaceResult got = two_three.replace(m, t, f, &created);
        REQUIRE(got == expected);
        REQUIRE((Snapshot(m) == Snapshot(expected_mesh)));
        if (got == ReplaceResult::kDone) {
            CHECK(created == expected_created);
            require_valid(m);
        }
        ++verdicts[expected];
    }
    return verdicts;
}

}  // namespace

// TwoThreeReplacer is replace_tets specialised to the 2-3 flip: on random
// points and on a grid (replacement_test_meshes), it gives the same
// verdicts and meshes.
TEST_CASE("TwoThreeReplacer agrees with replace_tets on random faces") {
    const auto [scattered, flat] = replacement_test_meshes(47, 53, 30);
    std::map<ReplaceResult, int> verdicts = compare_two_three_replacements(scattered, 3000, 59);
    for (const auto& [r, count] : compare_two_three_replacements(flat, 3000, 61)) verdicts[r] += count;
    for (const auto& [r, count] : verdicts) MESSAGE(std::string(to_string(r)) << ": " << count);
    // The trials reach every verdict a 2-3 flip can get.
    CHECK(verdicts[ReplaceResult::kDone] > 100);
    CHECK(verdicts[ReplaceResult::kRemovesConstraint] > 0);
    CHECK(verdicts[ReplaceResult::kInverted] > 100);
    CHECK(verdicts[ReplaceResult::kNotConvex] > 0);
}

TEST_CASE("flips that would dent the hull are refused") {
    TetMesh m = delaunay_mesh(cbr::test::random_points(100, 13));
    const Snapshot before(m);
    int refused23 = 0, refused32 = 0;
    for (TetId g = 0; g < m.slot_count(); ++g) {
        if (m.is_free(g) || !m.is_ghost(g)) continue;
        // 2-3 between a ghost and the finite tetrahedron under its hull face:
        // the finite tetrahedron would leave the mesh.
        const FlipResult r = flip23(m, g, 3);
        CHECK(r == FlipResult::kNotConvex);
        refused23 += r == FlipResult::kNotConvex;
        // Hull edges with a shell of three (one finite tetrahedron, two ghosts).
        for (int i = 0; i < 3; ++i) {
            Shell s;
            REQUIRE(shell(m, m.vertex(g, i), m.vertex(g, (i + 1) % 3), g, s));
            if (s.size() != 3) continue;
            CHECK(flip32(m, g, m.vertex(g, i), m.vertex(g, (i + 1) % 3)) == FlipResult::kNotConvex);
            ++refused32;
        }
    }
    CHECK(refused23 > 0);
    MESSAGE("hull 3-2 candidates refused: " << refused32);
    CHECK((Snapshot(m) == before));
}

TEST_CASE("replace_tets inserts and removes a vertex (1-4, 4-1, and outside the hull)") {
    TetMesh m = delaunay_mesh(cbr::test::random_points(80, 15));
    const auto tets = tet_keys(m);
    const std::size_t n = m.vertex_count();
    // A star of p over a region: every tetrahedron of the region with one
    // vertex replaced by p, per face of the region's boundary (a 1-k flip).
    auto star = [&](TetId t, VertexId p) {
        std::vector<Tet> fresh;
        for (int i = 0; i < 4; ++i) {
            Tet v = {m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)};
            v[static_cast<std::size_t>(i)] = p;
            fresh.push_back(v);
        }
        return fresh;
    };

    SUBCASE("inside a tetrahedron, then back") {
        TetId t = 0;
        while (m.is_free(t) || m.is_ghost(t)) ++t;
        double c[3] = {0, 0, 0};
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 3; ++k) c[k] += m.point(m.vertex(t, i))[k] / 4;
        const VertexId p = m.add_points(c, 1);
        const Tet original = {m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)};
        std::vector<TetId> created;
        REQUIRE(replace_tets(m, {t}, star(t, p), &created) == ReplaceResult::kDone);
        require_valid(m);
        // Steiner suppression in its simplest form: 4-1.
        REQUIRE(replace_tets(m, created, {original}) == ReplaceResult::kDone);
        m.truncate_vertices(n);
        require_valid(m);
        CHECK(tet_keys(m) == tets);
    }
    SUBCASE("beyond one hull face") {
        TetId g = 0;
        while (m.is_free(g) || !m.is_ghost(g)) ++g;
        double a[3], b[3], c[3];  // copies: adding points moves the coordinates
        for (int k = 0; k < 3; ++k) {
            a[k] = m.point(m.vertex(g, 0))[k];
            b[k] = m.point(m.vertex(g, 1))[k];
            c[k] = m.point(m.vertex(g, 2))[k];
        }
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double normal[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        auto beyond = [&](double distance) {  // centroid + distance * outward normal
            double p[3];
            for (int k = 0; k < 3; ++k) p[k] = (a[k] + b[k] + c[k]) / 3 + distance * normal[k];
            return m.add_points(p, 1);
        };
        const VertexId far = beyond(100.0);
        const Snapshot before(m);
        // Seen from far away the neighbouring hull faces are visible too:
        // the hull would fold. (The region's own vertices are all below the
        // new hull faces: only the neighbours' far vertices show it.)
        CHECK(replace_tets(m, {g}, star(g, far)) == ReplaceResult::kNotConvex);
        CHECK((Snapshot(m) == before));
        m.truncate_vertices(n);
        const VertexId near = beyond(1e-3);
        REQUIRE(replace_tets(m, {g}, star(g, near)) == ReplaceResult::kDone);
        require_valid(m);
    }
}

// --- edge removal on hand-built shells -------------------------------------

namespace {

// Edge uv (u = 0 at z = -1, v = 1 at z = +1) and a ring of n points
// 2..n+1 counter-clockwise around the z axis at radius radius(i), height
// height(i): the shell of n tetrahedra (u, v, r_i, r_i+1).
TetMesh shell_mesh(int n, const std::function<double(int)>& radius, const std::function<double(int)>& height) {
    const double pi = 3.14159265358979323846;
    std::vector<double> xyz = {0, 0, -1, 0, 0, 1};
    std::vector<Tet> tets;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * pi * i / n + 0.1;
        xyz.insert(xyz.end(), {radius(i) * std::cos(a), radius(i) * std::sin(a), height(i)});
        tets.push_back({0, 1, static_cast<VertexId>(2 + i), static_cast<VertexId>(2 + (i + 1) % n)});
    }
    TetMesh m = build_mesh(xyz, tets);
    REQUIRE(check_mesh(m).ok());
    return m;
}

// All triangulations of the n-gon 0..n-1 (Catalan(n-2) of them).
std::vector<std::vector<RingTriangle>> all_triangulations(int n) {
    // Polygon pieces still to triangulate, depth first.
    std::vector<std::vector<RingTriangle>> out;
    std::function<void(std::vector<std::pair<int, int>>, std::vector<RingTriangle>)> rec =
        [&](std::vector<std::pair<int, int>> todo, std::vector<RingTriangle> tris) {
            while (!todo.empty() && todo.back().second - todo.back().first < 2) todo.pop_back();
            if (todo.empty()) {
                out.push_back(tris);
                return;
            }
            const auto [i, j] = todo.back();
            todo.pop_back();
            for (int k = i + 1; k < j; ++k) {
                auto next = todo;
                next.push_back({i, k});
                next.push_back({k, j});
                auto t = tris;
                t.push_back({i, k, j});
                rec(next, t);
            }
        };
    rec({{0, n - 1}}, {});
    return out;
}

double min_quality(const TetMesh& m, const std::vector<TetId>& tets) {
    double q = std::numeric_limits<double>::infinity();
    for (TetId t : tets)
        q = std::min(q, tet_quality(m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)), m.point(m.vertex(t, 2)),
                                    m.point(m.vertex(t, 3))));
    return q;
}

struct Outcome {
    int valid = 0, total = 0;
    double best = -std::numeric_limits<double>::infinity();  // best worst quality over valid ones
};

// Every triangulation of the ring through transform_shell, on copies.
Outcome brute_force(const TetMesh& m, int n) {
    Outcome o;
    Shell s;
    REQUIRE(shell(m, 0, 1, 0, s));
    for (const auto& tris : all_triangulations(n)) {
        TetMesh copy = m;
        std::vector<TetId> created;
        ++o.total;
        const FlipResult r = transform_shell(copy, 0, 1, s, tris, &created);
        if (r != FlipResult::kDone) {
            CHECK(r == FlipResult::kInverted);
            continue;
        }
        ++o.valid;
        REQUIRE(check_mesh(copy).ok());
        o.best = std::max(o.best, min_quality(copy, created));
    }
    return o;
}

}  // namespace

TEST_CASE("edge removal on hand-built shells of 3 to 8 tetrahedra") {
    // (Subcases hold the loops: doctest enters a subcase once per run.)
    SUBCASE("convex planar ring: every triangulation valid, the best one chosen") {
        const int catalan[] = {1, 1, 2, 5, 14, 42, 132};
        for (int n = 3; n <= 8; ++n) {
            CAPTURE(n);
            TetMesh m = shell_mesh(n, [](int) { return 1.0; }, [](int) { return 0.0; });
            const Outcome o = brute_force(m, n);
            CHECK(o.total == catalan[n - 2]);
            CHECK(o.valid == o.total);
            std::vector<TetId> created;
            REQUIRE(remove_edge(m, 0, 0, 1, {}, &created) == FlipResult::kDone);
            CHECK(created.size() == static_cast<std::size_t>(2 * (n - 2)));
            CHECK(min_quality(m, created) == o.best);
            CHECK_FALSE(has_edge(m, 0, 1));
            REQUIRE(check_mesh(m).ok());
        }
    }
    SUBCASE("shells over kMaxRemovalShell are not tried") {
        // A convex planar ring of kMaxRemovalShell vertices is removed; one
        // more and remove_edge leaves it alone (the O(n^3) search of a
        // CAD fan's shell was 93% of a recovery and never succeeded).
        const int n = static_cast<int>(cbr::mesh::kMaxRemovalShell);
        TetMesh at_cap = shell_mesh(n, [](int) { return 1.0; }, [](int) { return 0.0; });
        CHECK(remove_edge(at_cap, 0, 0, 1) == FlipResult::kDone);
        REQUIRE(check_mesh(at_cap).ok());
        TetMesh over = shell_mesh(n + 1, [](int) { return 1.0; }, [](int) { return 0.0; });
        const Snapshot before(over);
        CHECK(remove_edge(over, 0, 0, 1) == FlipResult::kNotApplicable);
        CHECK((Snapshot(over) == before));
    }
    SUBCASE("ring lifted above v: no triangulation valid") {
        for (int n = 3; n <= 8; ++n) {
            CAPTURE(n);
            TetMesh m = shell_mesh(n, [](int) { return 1.0; }, [](int) { return 3.0; });
            CHECK(brute_force(m, n).valid == 0);
            const Snapshot before(m);
            CHECK(remove_edge(m, 0, 0, 1) == FlipResult::kNoValidTriangulation);
            if (n == 3) CHECK(flip32(m, 0, 0, 1) == FlipResult::kInverted);
            CHECK((Snapshot(m) == before));
        }
    }
    SUBCASE("protected edge") {
        const EdgeProtect protect = [](VertexId a, VertexId b) { return std::min(a, b) == 0 && std::max(a, b) == 1; };
        for (int n = 3; n <= 8; ++n) {
            TetMesh m = shell_mesh(n, [](int) { return 1.0; }, [](int) { return 0.0; });
            const Snapshot before(m);
            CHECK(remove_edge(m, 0, 0, 1, protect) == FlipResult::kProtectedEdge);
            CHECK(remove_edge(m, 0, 1, 0, protect) == FlipResult::kProtectedEdge);
            if (n == 3) CHECK(flip32(m, 0, 0, 1, protect) == FlipResult::kProtectedEdge);
            CHECK((Snapshot(m) == before));
        }
    }
    SUBCASE("non-convex star rings: only some triangulations valid") {
        for (int n : {6, 8}) {
            CAPTURE(n);
            TetMesh m = shell_mesh(n, [](int i) { return i % 2 ? 0.35 : 1.0; }, [](int) { return 0.0; });
            const Outcome o = brute_force(m, n);
            MESSAGE("n = " << n << ": " << o.valid << " of " << o.total << " triangulations valid");
            CHECK(o.valid > 0);
            CHECK(o.valid < o.total);
            std::vector<TetId> created;
            REQUIRE(remove_edge(m, 0, 0, 1, {}, &created) == FlipResult::kDone);
            CHECK(min_quality(m, created) == o.best);
            REQUIRE(check_mesh(m).ok());
        }
    }
    SUBCASE("non-planar rings: edge removal finds the best valid triangulation, or reports none") {
        // Ring heights random in [-0.9, 0.9] (u, v at -1, +1): depending on
        // them every, some or no triangulation of the ring is valid.
        int none = 0, some = 0, all = 0;
        for (int n = 4; n <= 8; ++n) {
            for (std::uint64_t seed = 0; seed < 12; ++seed) {
                CAPTURE(n);
                CAPTURE(seed);
                const auto h = cbr::test::random_points(3, seed, -0.9, 0.9);
                auto height = [&](int i) { return h[static_cast<std::size_t>(i)]; };
                TetMesh m = shell_mesh(n, [](int) { return 1.0; }, height);
                const Outcome o = brute_force(m, n);
                none += o.valid == 0;
                some += o.valid > 0 && o.valid < o.total;
                all += o.valid == o.total;
                std::vector<TetId> created;
                const Snapshot before(m);
                const FlipResult r = remove_edge(m, 0, 0, 1, {}, &created);
                if (o.valid == 0) {
                    CHECK(r == FlipResult::kNoValidTriangulation);
                    CHECK((Snapshot(m) == before));
                } else {
                    REQUIRE(r == FlipResult::kDone);
                    CHECK(min_quality(m, created) == o.best);
                    REQUIRE(check_mesh(m).ok());
                }
            }
        }
        MESSAGE("non-planar rings: " << none << " with no valid triangulation, " << some << " with some, " << all
                                     << " with all");
        CHECK(none > 0);
        CHECK(some > 0);
        CHECK(all > 0);
    }
    SUBCASE("flip44: octahedron (u, v, r0, r2 coplanar), and a quadrilateral with no such pair") {
        TetMesh oct = build_mesh({0, 0, -1, 0, 0, 1, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0},
                                 {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 5}, {0, 1, 5, 2}});
        std::vector<TetId> created;
        REQUIRE(flip44(oct, 0, 0, 1, {}, &created) == FlipResult::kDone);
        CHECK(created.size() == 4);
        CHECK_FALSE(has_edge(oct, 0, 1));
        CHECK(has_edge(oct, 2, 4));
        REQUIRE(check_mesh(oct).ok());
        TetMesh skew = build_mesh({0, 0, -1, 0, 0, 1, 1, 0.1, 0, 0, 1, 0, -1, 0.3, 0, 0.2, -1, 0},
                                  {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 5}, {0, 1, 5, 2}});
        CHECK(flip44(skew, 0, 0, 1) == FlipResult::kNotApplicable);
        CHECK(remove_edge(skew, 0, 0, 1) == FlipResult::kDone);
        CHECK(flip32(oct, 0, 2, 4) == FlipResult::kNotApplicable);  // the new edge's shell has four
    }
}

namespace {

// A measure unlike tet_quality, for the objective test: shortest over
// longest edge, -inf when abcd is not positively oriented.
double edge_ratio(const double* a, const double* b, const double* c, const double* d) {
    if (cbr::geom::orient3d(a, b, c, d) <= 0) return -std::numeric_limits<double>::infinity();
    const double* p[4] = {a, b, c, d};
    double shortest = std::numeric_limits<double>::infinity(), longest = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            double l2 = 0;
            for (int k = 0; k < 3; ++k) l2 += (p[i][k] - p[j][k]) * (p[i][k] - p[j][k]);
            shortest = std::min(shortest, l2);
            longest = std::max(longest, l2);
        }
    return std::sqrt(shortest / longest);
}

// The worst `measure` over the tetrahedra a ring triangulation of shell_mesh's
// edge (u = 0, v = 1) cones: (a, b, c, v) and (a, c, b, u) per triangle.
double cone_minimum(const TetMesh& m, const Shell& s, const std::vector<RingTriangle>& tris,
                    double (*measure)(const double*, const double*, const double*, const double*)) {
    double q = std::numeric_limits<double>::infinity();
    for (const RingTriangle& t : tris) {
        const double* a = m.point(s.ring[static_cast<std::size_t>(t[0])]);
        const double* b = m.point(s.ring[static_cast<std::size_t>(t[1])]);
        const double* c = m.point(s.ring[static_cast<std::size_t>(t[2])]);
        q = std::min({q, measure(a, b, c, m.point(1)), measure(a, c, b, m.point(0))});
    }
    return q;
}

}  // namespace

// The objective of best_ring_triangulation (refinement's quality flips use
// the radius ratio, the bar a flip must beat as the floor, and the size
// bound on chords): against every triangulation of non-planar rings, it
// finds the best worst value of the measure it is given, among the
// triangulations whose chords it allows, and reports none exactly when no
// such triangulation is strictly above the floor.
TEST_CASE("best_ring_triangulation maximizes the objective's measure, only above its floor, with allowed chords") {
    const auto by_edge_ratio = [](double floor) {
        RingObjective o;
        o.measure = edge_ratio;
        o.floor = floor;
        return o;
    };
    const double none = -std::numeric_limits<double>::infinity();
    int differs_from_default = 0, above = 0, chord_mattered = 0;
    for (int n = 4; n <= 8; ++n)
        for (std::uint64_t seed = 0; seed < 12; ++seed) {
            CAPTURE(n);
            CAPTURE(seed);
            const auto h = cbr::test::random_points(3, seed + 100, -0.9, 0.9);
            const TetMesh m = shell_mesh(n, [](int) { return 1.0; }, [&](int i) { return h[static_cast<std::size_t>(i)]; });
            Shell s;
            REQUIRE(shell(m, 0, 1, 0, s));
            double best = none;
            for (const auto& tris : all_triangulations(n)) best = std::max(best, cone_minimum(m, s, tris, edge_ratio));
            std::vector<RingTriangle> tris;
            double got = 0;
            const bool found = best_ring_triangulation(m, 0, 1, s, tris, &got, by_edge_ratio(none));
            CHECK(found == (best > none));
            CHECK(got == best);
            if (!found) continue;
            CHECK(cone_minimum(m, s, tris, edge_ratio) == best);
            std::vector<RingTriangle> by_default;
            REQUIRE(best_ring_triangulation(m, 0, 1, s, by_default));
            differs_from_default += cone_minimum(m, s, by_default, edge_ratio) < best;
            // Floors just below, at, and above the best.
            CHECK(best_ring_triangulation(m, 0, 1, s, tris, &got, by_edge_ratio(std::nextafter(best, 0.0))));
            CHECK(got == best);
            CHECK(cone_minimum(m, s, tris, edge_ratio) == best);
            const std::vector<RingTriangle> best_tris = tris;
            ++above;
            for (const double floor : {best, 2 * best}) {
                CHECK_FALSE(best_ring_triangulation(m, 0, 1, s, tris, &got, by_edge_ratio(floor)));
                CHECK(tris.empty());
                CHECK(got == none);
            }
            // A predicate that refuses the ring's sides changes nothing: they
            // are edges already, not chords.
            RingObjective sides_refused = by_edge_ratio(none);
            sides_refused.chord_allowed = [&](VertexId x, VertexId y) {
                for (int k = 0; k < n; ++k)
                    if (std::minmax(x, y) == std::minmax(s.ring[static_cast<std::size_t>(k)],
                                                         s.ring[static_cast<std::size_t>((k + 1) % n)]))
                        return false;
                return true;
            };
            CHECK(best_ring_triangulation(m, 0, 1, s, tris, &got, sides_refused));
            CHECK(got == best);
            // Each chord of the best triangulation refused in turn: the best
            // of the triangulations without it (or none).
            for (const RingTriangle& t : best_tris)
                for (int e = 0; e < 3; ++e) {
                    const int i = std::min(t[e], t[(e + 1) % 3]), j = std::max(t[e], t[(e + 1) % 3]);
                    if (j - i == 1 || (i == 0 && j == n - 1)) continue;  // a side of the ring
                    const VertexId a = s.ring[static_cast<std::size_t>(i)], b = s.ring[static_cast<std::size_t>(j)];
                    const auto uses_chord = [&](const std::vector<RingTriangle>& candidate) {
                        for (const RingTriangle& x : candidate)
                            for (int k = 0; k < 3; ++k)
                                if (std::minmax(x[k], x[(k + 1) % 3]) == std::minmax(i, j)) return true;
                        return false;
                    };
                    double best_without = none;
                    for (const auto& candidate : all_triangulations(n))
                        if (!uses_chord(candidate)) best_without = std::max(best_without, cone_minimum(m, s, candidate, edge_ratio));
                    RingObjective refusing = by_edge_ratio(none);
                    refusing.chord_allowed = [&](VertexId x, VertexId y) { return std::minmax(x, y) != std::minmax(a, b); };
                    std::vector<RingTriangle> without;
                    CHECK(best_ring_triangulation(m, 0, 1, s, without, &got, refusing) == (best_without > none));
                    CHECK(got == best_without);
                    CHECK_FALSE(uses_chord(without));
                    if (!without.empty()) CHECK(cone_minimum(m, s, without, edge_ratio) == best_without);
                    chord_mattered += best_without < best;
                }
        }
    MESSAGE(above << " rings with a valid triangulation; the default measure's choice is worse in edge ratio on "
                  << differs_from_default << "; a refused chord lowered the best " << chord_mattered << " times");
    CHECK(above > 10);
    CHECK(differs_from_default > 0);
    CHECK(chord_mattered > 0);
}

// --- Schönhardt -------------------------------------------------------------

namespace {

// Schönhardt's twisted prism: bottom triangle 0-2 at z = 0, top 3-5 at
// z = 1 turned by 30 degrees.
std::vector<double> twisted_prism() {
    const double pi = 3.14159265358979323846;
    std::vector<double> xyz;
    for (int level = 0; level < 2; ++level)
        for (int i = 0; i < 3; ++i) {
            const double a = 2 * pi * i / 3 + (level ? pi / 6 : 0);
            xyz.insert(xyz.end(), {std::cos(a), std::sin(a), double(level)});
        }
    return xyz;
}

// Every triangulation reachable from m by the flips of this module.
std::vector<TetMesh> reachable(const TetMesh& start, const EdgeProtect& protect) {
    std::vector<TetMesh> states = {start};
    std::set<std::set<Tet>> seen = {tet_keys(start)};
    for (std::size_t next = 0; next < states.size(); ++next) {
        const TetMesh m = states[next];
        for (TetId t = 0; t < m.slot_count(); ++t) {
            if (m.is_free(t)) continue;
            std::vector<std::function<FlipResult(TetMesh&)>> flips;
            for (int f = 0; f < 4; ++f) flips.push_back([=](TetMesh& c) { return flip23(c, t, f, protect); });
            for (int i = 0; i < 4; ++i)
                for (int j = i + 1; j < 4; ++j) {
                    const VertexId u = m.vertex(t, i), v = m.vertex(t, j);
                    flips.push_back([=](TetMesh& c) { return flip32(c, t, u, v, protect); });
                    flips.push_back([=](TetMesh& c) { return flip44(c, t, u, v, protect); });
                    flips.push_back([=](TetMesh& c) { return remove_edge(c, t, u, v, protect); });
                }
            for (const auto& flip : flips) {
                TetMesh copy = m;
                if (flip(copy) != FlipResult::kDone) continue;
                require_valid(copy);
                if (seen.insert(tet_keys(copy)).second) states.push_back(copy);
            }
        }
    }
    return states;
}

}  // namespace

namespace {

// Every triangulation of the polygon i..j of a ring (closed by chord ij),
// as triangle lists, written out one by one.
void all_ring_triangulations(int i, int j, std::vector<std::vector<RingTriangle>>& out) {
    out.clear();
    if (j - i < 2) {
        out.push_back({});
        return;
    }
    for (int k = i + 1; k < j; ++k) {
        std::vector<std::vector<RingTriangle>> left, right;
        all_ring_triangulations(i, k, left);
        all_ring_triangulations(k, j, right);
        for (const auto& l : left)
            for (const auto& r : right) {
                std::vector<RingTriangle> t = l;
                t.insert(t.end(), r.begin(), r.end());
                t.push_back({i, k, j});
                out.push_back(t);
            }
    }
}

// How many triangulations of the shell's ring cone only positively
// oriented tetrahedra (exact), counted one by one (finite rings only).
int valid_ring_triangulations(const TetMesh& m, VertexId u, VertexId v, const Shell& s) {
    std::vector<std::vector<RingTriangle>> all;
    all_ring_triangulations(0, static_cast<int>(s.size()) - 1, all);
    int valid = 0;
    for (const auto& t : all) {
        bool ok = true;
        for (const RingTriangle& r : t) {
            const double* a = m.point(s.ring[static_cast<std::size_t>(r[0])]);
            const double* b = m.point(s.ring[static_cast<std::size_t>(r[1])]);
            const double* c = m.point(s.ring[static_cast<std::size_t>(r[2])]);
            ok = ok && cbr::geom::orient3d(a, b, c, m.point(v)) > 0 && cbr::geom::orient3d(a, c, b, m.point(u)) > 0;
        }
        valid += ok;
    }
    return valid;
}

}  // namespace

// A ring with exactly one valid triangulation gets it without a ranking
// (best_ring_triangulation's shortcut, taken when no minimum quality is
// asked for): on random shells of a scattered and a grid mesh, the
// triangles must be those of the ranked search (asked for its minimum, so
// it ranks), in the same order, whether the ring has no valid
// triangulation, one, or several (counted one by one).
TEST_CASE("best_ring_triangulation: a ring's only triangulation, taken unranked, is the ranked one") {
    const auto [scattered, flat] = replacement_test_meshes(31, 37, 1000000);
    Rng rng(59);
    std::map<int, int> by_count;  // valid triangulations (2: two or more) -> shells
    for (const TetMesh* m : {&scattered, &flat}) {
        for (int trial = 0; trial < 4000; ++trial) {
            const TetId t = random_live(*m, rng);
            const int i = static_cast<int>(rng() % 4), j = (i + 1 + static_cast<int>(rng() % 3)) % 4;
            const VertexId u = m->vertex(t, i), v = m->vertex(t, j);
            if (u == kGhostVertex || v == kGhostVertex) continue;
            Shell s;
            REQUIRE(shell(*m, u, v, t, s));
            if (s.size() < 3 || s.size() > 9 ||
                std::find(s.ring.begin(), s.ring.end(), kGhostVertex) != s.ring.end())
                continue;
            std::vector<RingTriangle> unranked, ranked;
            double q = 0;
            const bool found = best_ring_triangulation(*m, u, v, s, unranked);
            const bool found_ranked = best_ring_triangulation(*m, u, v, s, ranked, &q);
            CAPTURE(trial);
            CHECK(found == found_ranked);
            CHECK(unranked == ranked);
            const int valid = valid_ring_triangulations(*m, u, v, s);
            CHECK(found == (valid > 0));
            ++by_count[std::min(valid, 2)];
        }
    }
    MESSAGE("shells with no valid triangulation " << by_count[0] << ", one " << by_count[1] << ", several "
                                                 << by_count[2]);
    CHECK(by_count[0] > 100);
    CHECK(by_count[1] > 100);
    CHECK(by_count[2] > 100);
}

TEST_CASE("Schonhardt's twisted prism: no flip sequence recovers its three reflex diagonals") {
    // The convex hull of the six points has 12 edges; the three other pairs
    // are the diagonals i - (3 + (i+1) mod 3) of the lateral quadrilaterals
    // that Schönhardt's polyhedron uses. Every triangulation of the six
    // points has 3 + (interior edges) tetrahedra, its interior edges among
    // these three diagonals: at least one is present. Having all three
    // would triangulate the Schönhardt polyhedron (plus three outer
    // tetrahedra), which is impossible: a Steiner point is needed.
    const TetMesh m = delaunay_mesh(twisted_prism());
    // The pairs that no hull face (ghost) holds.
    std::vector<std::pair<VertexId, VertexId>> diagonals;
    for (VertexId a = 0; a < 6; ++a)
        for (VertexId b = a + 1; b < 6; ++b) {
            bool hull = false;
            for (TetId g = 0; g < m.slot_count(); ++g)
                hull |= !m.is_free(g) && m.is_ghost(g) && vertex_index(m, g, a) >= 0 && vertex_index(m, g, b) >= 0;
            if (!hull) diagonals.push_back({a, b});
        }
    REQUIRE(diagonals.size() == 3);
    for (const auto& [a, b] : diagonals) MESSAGE("reflex diagonal " << a << "-" << b);
    auto present = [&](const TetMesh& s) {
        int count = 0;
        for (const auto& [a, b] : diagonals) count += has_edge(s, a, b);
        return count;
    };

    SUBCASE("free flips: every reachable triangulation misses a diagonal") {
        const auto states = reachable(m, {});
        int with[4] = {0, 0, 0, 0};
        for (const TetMesh& s : states) ++with[present(s)];
        MESSAGE(states.size() << " triangulations reachable from the Delaunay one (" << present(m)
                              << " diagonals): " << with[1] << " with one diagonal, " << with[2] << " with two");
        CHECK(states.size() > 1);
        CHECK(with[0] == 0);  // Euler: at least one interior edge
        CHECK(with[3] == 0);  // Schönhardt: never all three
    }
    SUBCASE("diagonals already present protected: the missing one never appears") {
        const int start = present(m);
        REQUIRE(start < 3);
        const EdgeProtect protect = [&](VertexId a, VertexId b) {
            for (const auto& [p, q] : diagonals)
                if (((a == p && b == q) || (a == q && b == p)) && has_edge(m, p, q)) return true;
            return false;
        };
        for (const TetMesh& s : reachable(m, protect)) {
            for (const auto& [a, b] : diagonals)
                if (has_edge(m, a, b)) CHECK(has_edge(s, a, b));
            CHECK(present(s) < 3);
        }
    }
}

// --- ball and shell -----------------------------------------------------------

TEST_CASE("ball, shell and incident_tets agree with brute-force scans") {
    TetMesh m = delaunay_mesh(cbr::test::random_points(200, 23));
    random_flips(m, 1500, 29);  // not Delaunay any more: the walks do not rely on it
    Rng rng(31);
    const std::vector<TetId> inc = incident_tets(m);
    REQUIRE(inc.size() == m.vertex_count());
    for (VertexId v = 0; v < m.vertex_count(); ++v) {
        REQUIRE(inc[v] != kNoTet);
        REQUIRE(vertex_index(m, inc[v], v) >= 0);
        CHECK_FALSE(m.is_ghost(inc[v]));  // every vertex has a finite tetrahedron
        std::vector<TetId> b;
        REQUIRE(ball(m, v, inc[v], b));
        std::set<TetId> expected;
        for (TetId t = 0; t < m.slot_count(); ++t)
            if (!m.is_free(t) && vertex_index(m, t, v) >= 0) expected.insert(t);
        CHECK(std::set<TetId>(b.begin(), b.end()) == expected);
        CHECK(b.size() == expected.size());
    }
    std::vector<TetId> ghosts;
    TetId g = 0;
    while (m.is_free(g) || !m.is_ghost(g)) ++g;
    REQUIRE(ball(m, kGhostVertex, g, ghosts));
    std::size_t ghost_count = 0;
    for (TetId t = 0; t < m.slot_count(); ++t) ghost_count += !m.is_free(t) && m.is_ghost(t);
    CHECK(ghosts.size() == ghost_count);
    VertexId stranger = 0;
    while (vertex_index(m, g, stranger) >= 0) ++stranger;
    std::vector<TetId> none = {g};
    CHECK_FALSE(ball(m, stranger, g, none));  // g does not contain it
    CHECK(none.empty());

    for (int trial = 0; trial < 2000; ++trial) {
        const TetId t = random_live(m, rng);
        const int i = static_cast<int>(rng() % 4), j = (i + 1 + static_cast<int>(rng() % 3)) % 4;
        const VertexId u = m.vertex(t, i), v = m.vertex(t, j);
        Shell s;
        REQUIRE(shell(m, u, v, t, s));
        CHECK(s.tets[0] == t);
        std::set<TetId> expected;
        for (TetId x = 0; x < m.slot_count(); ++x)
            if (!m.is_free(x) && vertex_index(m, x, u) >= 0 && vertex_index(m, x, v) >= 0) expected.insert(x);
        REQUIRE(std::set<TetId>(s.tets.begin(), s.tets.end()) == expected);
        REQUIRE(s.tets.size() == expected.size());
        const std::size_t n = s.size();
        for (std::size_t k = 0; k < n; ++k) {
            const TetId x = s.tets[k];
            const VertexId a = s.ring[k], b = s.ring[(k + 1) % n];
            REQUIRE(vertex_index(m, x, a) >= 0);
            REQUIRE(vertex_index(m, x, b) >= 0);
            // (u, v, a, b) positively oriented: for a ghost, the same
            // permutation parity as its stored order.
            const Tet order = {u, v, a, b};
            if (std::find(order.begin(), order.end(), kGhostVertex) == order.end()) {
                CHECK(cbr::geom::orient3d(m.point(u), m.point(v), m.point(a), m.point(b)) > 0);
            } else {
                int p[4], inversions = 0;
                for (int q = 0; q < 4; ++q) p[q] = vertex_index(m, x, order[static_cast<std::size_t>(q)]);
                for (int q = 0; q < 4; ++q)
                    for (int r = q + 1; r < 4; ++r) inversions += p[q] > p[r];
                CHECK(inversions % 2 == 0);
            }
        }
        const TetId e = find_edge_tet(m, u, t, v);
        CHECK(expected.count(e) == 1);
        // A size limit: the same shell when it fits, else false and empty.
        Shell limited;
        REQUIRE(shell(m, u, v, t, limited, n));
        CHECK(limited.tets == s.tets);
        CHECK(limited.ring == s.ring);
        CHECK_FALSE(shell(m, u, v, t, limited, n - 1));
        CHECK(limited.tets.empty());
        CHECK(limited.ring.empty());
    }
}

TEST_CASE("VertexBalls lists each vertex's ball as ball() finds it, by slot") {
    TetMesh m = delaunay_mesh(cbr::test::random_points(200, 43));
    random_flips(m, 1500, 47);  // free slots and scattered ones
    const double far[3] = {10, 10, 10};
    const VertexId unused = m.add_points(far, 1);  // in no tetrahedron
    const VertexBalls balls(m);
    const std::vector<TetId> inc = incident_tets(m);
    std::vector<TetId> listed, walked;
    for (VertexId v = 0; v < unused; ++v) {
        REQUIRE(ball(m, v, inc[v], walked));
        std::sort(walked.begin(), walked.end());
        balls.get(v, listed);
        CHECK(listed == walked);  // ghosts included, ascending
        CHECK_FALSE(balls.empty(v));
    }
    CHECK(balls.empty(unused));
    balls.get(unused, listed);
    CHECK(listed.empty());
}

TEST_CASE("reorder_tets keeps every tetrahedron, its flags and its neighbours") {
    TetMesh m = delaunay_mesh(cbr::test::random_points(200, 53));
    random_flips(m, 1500, 59);
    const TetId spare[3] = {m.allocate_tet(), m.allocate_tet(), m.allocate_tet()};
    for (TetId t : spare) m.release_tet(t);  // free slots: they go
    Rng rng(61);
    std::vector<TetId> order;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        order.push_back(t);
        if (rng() % 5 == 0) m.set_mark(t, kFlagMarkA);
        if (rng() % 7 == 0) {  // a constraint face, on both sides
            const int f = static_cast<int>(rng() % 4);
            const FacetRef across = m.neighbor(t, f);
            m.set_constrained(t, f, true);
            m.set_constrained(facet_tet(across), facet_face(across), true);
        }
    }
    REQUIRE(m.free_count() > 0);
    std::shuffle(order.begin(), order.end(), rng);
    const TetMesh before = m;
    m.reorder_tets(order);
    REQUIRE(m.slot_count() == order.size());
    CHECK(m.free_count() == 0);
    REQUIRE(check_mesh(m).ok());
    std::vector<TetId> new_id(before.slot_count(), kNoTet);
    for (TetId i = 0; i < order.size(); ++i) new_id[order[i]] = i;
    for (TetId i = 0; i < order.size(); ++i) {
        const TetId old = order[i];
        CHECK(m.flags(i) == before.flags(old));
        for (int k = 0; k < 4; ++k) {
            CHECK(m.vertex(i, k) == before.vertex(old, k));
            const FacetRef was = before.neighbor(old, k);
            CHECK(m.neighbor(i, k) == make_facet(new_id[facet_tet(was)], facet_face(was)));
        }
    }
}

// The order in which the free list hands out slots (then new ones).
std::vector<TetId> allocation_order(TetMesh m) {
    std::vector<TetId> order;
    for (std::size_t k = m.free_count() + 2; k > 0; --k) order.push_back(m.allocate_tet());
    return order;
}

TEST_CASE("the undo journal puts back every slot, flag and the free list") {
    TetMesh m = delaunay_mesh(cbr::test::random_points(200, 41));
    mark_random_faces(m, 30, 43);
    random_flips(m, 600, 47);
    // A free list to take from and push onto (flips alone reuse their slots).
    std::vector<TetId> spare;
    for (int k = 0; k < 12; ++k) spare.push_back(m.allocate_tet());
    for (TetId t : spare) m.release_tet(t);
    Rng rng(53);
    std::vector<TetId> created;
    int changed_runs = 0;
    m.open_journal();
    for (int run = 0; run < 20; ++run) {
        const Snapshot before(m);
        const std::vector<TetId> order = allocation_order(m);
        // Flips of every kind (slots taken off the free list, appended,
        // released), marks set and cleared.
        int done = 0;
        for (int a = 0; a < 200; ++a) {
            bool hull = false;
            done += random_flip(m, rng, static_cast<Kind>(rng() % kKinds), hull, created) == FlipResult::kDone;
        }
        const TetId t = random_live(m, rng);
        m.set_constrained(t, 0, !m.is_constrained(t, 0));
        changed_runs += done > 0 && !(Snapshot(m) == before);
        m.undo_journal();
        REQUIRE((Snapshot(m) == before));
        REQUIRE(allocation_order(m) == order);
        require_valid(m);
    }
    CHECK(changed_runs == 20);
    // Closed, the journal keeps what was done.
    m.close_journal();
    const Snapshot before(m);
    int done = 0;
    for (int a = 0; a < 200; ++a) {
        bool hull = false;
        done += random_flip(m, rng, static_cast<Kind>(rng() % kKinds), hull, created) == FlipResult::kDone;
    }
    REQUIRE(done > 0);
    CHECK_FALSE((Snapshot(m) == before));
    require_valid(m);
}

// A thread's slot pool (mesh/slot_pool.hpp): it takes the free list's
// last slots, then new ones; while in use, replacements on that thread
// take and give back only its slots, and the mesh's free list and size
// stay as they are; left over, its slots go back to the free list.
TEST_CASE("a slot pool takes, hands out and gives back free slots; the mesh's list is untouched meanwhile") {
    TetMesh m = delaunay_mesh(cbr::test::random_points(200, 73));
    std::vector<TetId> spare;
    for (int k = 0; k < 6; ++k) spare.push_back(m.allocate_tet());
    for (TetId t : spare) m.release_tet(t);  // the free list ends with spare, in order
    const std::size_t slots = m.slot_count(), listed = m.free_count();
    REQUIRE(listed < 40);
    const std::size_t added = 40 - listed;  // new slots the pool appends
    Rng rng(79);
    std::vector<TetId> given;
    {
        SlotPool pool(m, 40);
        CHECK(m.free_count() == 0);
        CHECK(m.slot_count() == slots + added);
        given = pool.slots();
        REQUIRE(given.size() == 40);
        CHECK(std::vector<TetId>(given.begin(), given.begin() + 6) ==
              std::vector<TetId>(spare.rbegin(), spare.rend()));
        for (TetId t : given) CHECK(m.is_free(t));
        std::set<TetId> pool_slots(given.begin(), given.end());
        std::size_t done = 0, outside = 0;
        {
            const SlotPool::Use use(pool);
            CHECK(SlotPool::in_use(m) == &pool);
            std::vector<TetId> created;
            for (int a = 0; a < 300 && pool.size() >= 4; ++a) {
                const std::vector<TetId> before_live = [&] {
                    std::vector<TetId> live;
                    for (TetId t = 0; t < m.slot_count(); ++t)
                        if (!m.is_free(t)) live.push_back(t);
                    return live;
                }();
                bool hull = false;
                created.clear();
                if (random_flip(m, rng, static_cast<Kind>(rng() % kKinds), hull, created) != FlipResult::kDone) continue;
                ++done;
                const std::set<TetId> was_live(before_live.begin(), before_live.end());
                for (TetId t : created) outside += !was_live.count(t) && !pool_slots.count(t);
                for (TetId t : before_live)
                    if (m.is_free(t)) pool_slots.insert(t);  // released: the pool's now
            }
            CHECK(m.free_count() == 0);
            CHECK(m.slot_count() == slots + added);
            require_valid(m);
        }
        CHECK(done > 50);
        CHECK(outside == 0);  // every fresh slot came from the pool (or was released to it)
        CHECK(SlotPool::in_use(m) == nullptr);
        // Not in use here: allocation is the mesh's (a new slot).
        const TetId t = m.allocate_tet();
        CHECK(t == slots + added);
        m.release_tet(t);
        CHECK(m.free_count() == 1);
        given = pool.slots();
        // An empty pool refuses; and none is taken while the journal is open.
        SlotPool empty(m, 0);
        const SlotPool::Use use(empty);
        CHECK_THROWS_AS(m.allocate_tet(), std::logic_error);
        m.open_journal();
        CHECK_THROWS_AS(SlotPool(m, 1), std::logic_error);
        m.close_journal();
    }
    // The pool's slots left, back on the free list after the mesh's own one.
    REQUIRE(m.free_count() == 1 + given.size());
    std::vector<TetId> order = allocation_order(m);
    order.resize(given.size());
    CHECK(order == std::vector<TetId>(given.rbegin(), given.rend()));
}

// set_tet, with which every replacement writes its fresh slots: the whole
// record, only the given faces constrained, no other flag left; the
// neighbours' links back untouched; journaled like any change.
TEST_CASE("set_tet writes a slot whole and is undone by the journal") {
    TetMesh m = delaunay_mesh(cbr::test::random_points(40, 67));
    Rng rng(71);
    const TetId t = random_live(m, rng);
    m.set_mark(t, kFlagMarkA | kFlagMarkB);
    m.set_constrained(t, 1, true);
    m.set_constrained(t, 3, true);
    const FacetRef across = m.neighbor(t, 0);
    const Snapshot before(m);
    m.open_journal();
    const VertexId v[4] = {m.vertex(t, 1), m.vertex(t, 0), m.vertex(t, 2), m.vertex(t, 3)};
    const FacetRef n[4] = {m.neighbor(t, 1), m.neighbor(t, 0), make_facet(t, 2), m.neighbor(t, 3)};
    m.set_tet(t, v, n, 0b0101);
    for (int i = 0; i < 4; ++i) {
        CHECK(m.vertex(t, i) == v[i]);
        CHECK(m.neighbor(t, i) == n[i]);
    }
    CHECK(m.is_constrained(t, 0));
    CHECK_FALSE(m.is_constrained(t, 1));
    CHECK(m.is_constrained(t, 2));
    CHECK_FALSE(m.is_constrained(t, 3));
    CHECK(m.flags(t) == static_cast<std::uint8_t>(kFlagConstraintFace0 | (kFlagConstraintFace0 << 2)));
    CHECK(m.neighbor(facet_tet(across), facet_face(across)) == make_facet(t, 0));  // the link back as it was
    m.undo_journal();
    m.close_journal();
    CHECK((Snapshot(m) == before));
}

TEST_CASE("ring_positions_blocking_first: the ears that cone an inverted tetrahedron first, each group in ring order; two separate valid ears needed") {
    // Checked on every interior edge of a Delaunay mesh of random points
    // against orient3d directly: the ear (r[i-1], r[i], r[i+1]) is valid
    // when it cones (.., v) and (.., u) with positive orientation.
    const TetMesh m = delaunay_mesh(cbr::test::random_points(200, 33));
    std::size_t edges = 0, blocking = 0, reordered = 0, ruled_out = 0, without_triangulation = 0;
    Shell s;
    std::vector<std::size_t> order;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t) || m.is_ghost(t)) continue;
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) {
                const VertexId u = m.vertex(t, a), v = m.vertex(t, b);
                if (u > v) continue;  // each edge from a few tetrahedra at most; once per direction is enough
                REQUIRE(shell(m, u, v, t, s));
                if (s.has_ghost()) continue;
                ++edges;
                const std::size_t returned = ring_positions_blocking_first(m, u, v, s, order);
                const std::size_t n = s.size();
                REQUIRE(order.size() == n);
                std::vector<std::size_t> sorted = order;
                std::sort(sorted.begin(), sorted.end());
                for (std::size_t i = 0; i < n; ++i) REQUIRE(sorted[i] == i);
                const auto ear_valid = [&](std::size_t i) {
                    const double* p = m.point(s.ring[(i + n - 1) % n]);
                    const double* q = m.point(s.ring[i]);
                    const double* r = m.point(s.ring[(i + 1) % n]);
                    return cbr::geom::orient3d(p, q, r, m.point(v)) > 0 && cbr::geom::orient3d(p, r, q, m.point(u)) > 0;
                };
                std::size_t first_valid = n;
                for (std::size_t k = 0; k < n; ++k)
                    if (ear_valid(order[k])) {
                        first_valid = k;
                        break;
                    }
                for (std::size_t k = first_valid; k < n; ++k) CHECK(ear_valid(order[k]));
                for (std::size_t k = 1; k < n; ++k)
                    if (k != first_valid) CHECK(order[k - 1] < order[k]);
                CHECK(returned == first_valid);
                // ring_may_be_triangulated: two valid ears at ring positions
                // that are not neighbours (any pair), and never false for a
                // ring that has a valid triangulation.
                bool separate_ears = n < 4;
                for (std::size_t i = 0; i < n; ++i)
                    for (std::size_t j = i + 2; j < n; ++j)
                        if (!(i == 0 && j == n - 1) && ear_valid(i) && ear_valid(j)) separate_ears = true;
                const bool may = ring_may_be_triangulated(order, returned);
                CHECK(may == separate_ears);
                std::vector<cbr::mesh::RingTriangle> triangles;
                const bool triangulated = best_ring_triangulation(m, u, v, s, triangles, nullptr);
                if (triangulated) CHECK(may);
                ruled_out += !may;
                without_triangulation += !triangulated;
                blocking += first_valid;
                for (std::size_t k = 0; k < n; ++k) reordered += order[k] != k;
            }
    }
    MESSAGE(edges << " interior edges, " << blocking << " blocking ring vertices; " << without_triangulation
                  << " rings without a valid triangulation, " << ruled_out << " of them ruled out by their ears");
    CHECK(edges > 100);
    CHECK(blocking > 0);
    CHECK(reordered > 0);
    CHECK(ruled_out > 0);
}
