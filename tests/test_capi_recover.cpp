// cbr_mesh_recover_faces and its queries, as a caller sees them.
#include <doctest/doctest.h>

#include <cbr/cbr.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <string>

#include "capi_test_util.hpp"
#include "hard_cases.hpp"
#include "recovery_checks.hpp"
#include "test_util.hpp"

namespace {

using cbr::test::contains;
using cbr::test::Handle;
using cbr::test::tets_of;

double stat(const cbr_mesh* m, int key) {
    double v = -1;
    REQUIRE(cbr_mesh_get_stat(m, key, &v) == CBR_OK);
    return v;
}

// The boundary of the Delaunay tetrahedra whose centroid lies within 0.3 of
// the centre, outward: a closed surface made of faces that are present.
std::vector<std::int64_t> ball_surface(const std::vector<double>& xyz, const std::vector<std::int64_t>& tets,
                                       std::size_t* inside_count) {
    const std::size_t n = tets.size() / 4;
    std::vector<char> inside(n);
    *inside_count = 0;
    for (std::size_t t = 0; t < n; ++t) {
        double c[3] = {0, 0, 0};
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 3; ++k) c[k] += xyz[3 * static_cast<std::size_t>(tets[4 * t + i]) + k] / 4;
        inside[t] = (c[0] - .5) * (c[0] - .5) + (c[1] - .5) * (c[1] - .5) + (c[2] - .5) * (c[2] - .5) < 0.09;
        *inside_count += inside[t] ? 1 : 0;
    }
    // A face of exactly one inside tetrahedron and at most one outside one
    // (none on the hull) is on the boundary.
    std::map<std::array<std::int64_t, 3>, std::array<int, 2>> sides;  // tetrahedra inside, outside
    std::map<std::array<std::int64_t, 3>, std::array<std::int64_t, 3>> oriented;
    static const int face[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
    for (std::size_t t = 0; t < n; ++t)
        for (int f = 0; f < 4; ++f) {
            std::array<std::int64_t, 3> v = {tets[4 * t + face[f][0]], tets[4 * t + face[f][2]], tets[4 * t + face[f][1]]};
            std::array<std::int64_t, 3> key = v;
            std::sort(key.begin(), key.end());
            ++sides[key][inside[t] ? 0 : 1];
            if (inside[t]) oriented[key] = v;
        }
    std::vector<std::int64_t> tris;
    for (const auto& [key, count] : sides)
        if (count[0] == 1 && count[1] <= 1) tris.insert(tris.end(), oriented[key].begin(), oriented[key].end());
    return tris;
}

// Reads tests/data/recover/`name` into p, inserts its points into h and
// recovers its faces, which must succeed; returns the number of its points.
std::int64_t recover_fixture(const char* name, cbr::test::OffSurface& p, Handle& h) {
    REQUIRE(cbr::test::read_off(std::string(CBR_TEST_DATA_DIR "/recover/") + name, p));
    const auto n = static_cast<std::int64_t>(p.xyz.size() / 3);
    REQUIRE(cbr_mesh_insert_points(h.m, n, p.xyz.data()) == CBR_OK);
    REQUIRE_MESSAGE(cbr_mesh_recover_faces(h.m, static_cast<std::int64_t>(p.tris.size() / 3), p.tris.data(),
                                           nullptr) == CBR_OK,
                    h.error());
    return n;
}

// Every point of the mesh, the caller's then the Steiner points.
std::vector<double> points_of(const Handle& h) {
    std::vector<double> xyz(3 * static_cast<std::size_t>(cbr_mesh_point_count(h.m)));
    REQUIRE(cbr_mesh_get_points(h.m, xyz.data()) == CBR_OK);
    return xyz;
}

// The smallest box holding the points xyz (x, y, z, x, ...; at least one).
void bounding_box(const std::vector<double>& xyz, double lo[3], double hi[3]) {
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = xyz[static_cast<std::size_t>(k)];
    for (std::size_t i = 0; i < xyz.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], xyz[i]);
        hi[i % 3] = std::max(hi[i % 3], xyz[i]);
    }
}

}  // namespace

TEST_CASE("recovering a surface whose faces are all present, and reading the regions") {
    Handle h;
    const auto xyz = cbr::test::random_points(2000, 31);
    REQUIRE(cbr_mesh_insert_points(h.m, 2000, xyz.data()) == CBR_OK);
    const auto all = tets_of(h.m);
    std::size_t inside = 0;
    const auto tris = ball_surface(xyz, all, &inside);
    const auto count = static_cast<std::int64_t>(tris.size() / 3);
    REQUIRE(count > 50);
    std::vector<std::int32_t> labels(static_cast<std::size_t>(count), 7);
    REQUIRE(cbr_mesh_recover_faces(h.m, count, tris.data(), labels.data()) == CBR_OK);

    CHECK(stat(h.m, CBR_STAT_MISSING_FACES) == 0);
    CHECK(stat(h.m, CBR_STAT_TOTAL_VERTICES) == 2000);
    CHECK(stat(h.m, CBR_STAT_REGION_COUNT) >= 2);
    CHECK(stat(h.m, CBR_STAT_TOTAL_SECONDS) >= stat(h.m, CBR_STAT_RECOVERY_SECONDS));
    std::set<std::int64_t> boundary(tris.begin(), tris.end());
    CHECK(stat(h.m, CBR_STAT_BOUNDARY_VERTICES) == double(boundary.size()));
    CHECK(cbr_mesh_steiner_count(h.m) == 0);

    // Bounded regions only by default: at least the chosen tetrahedra
    // (pockets they enclose are bounded regions too), never all of them.
    const std::int64_t bounded = cbr_mesh_tet_count(h.m);
    CHECK(bounded >= static_cast<std::int64_t>(inside));
    CHECK(bounded < static_cast<std::int64_t>(all.size() / 4));
    std::vector<std::int32_t> regions(static_cast<std::size_t>(bounded));
    REQUIRE(cbr_mesh_get_tet_regions(h.m, regions.data()) == CBR_OK);
    for (std::int32_t r : regions) CHECK(r > 0);

    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_KEEP_EXTERIOR, 1) == CBR_OK);
    CHECK(cbr_mesh_tet_count(h.m) == static_cast<std::int64_t>(all.size() / 4));
    regions.resize(all.size() / 4);
    REQUIRE(cbr_mesh_get_tet_regions(h.m, regions.data()) == CBR_OK);
    CHECK(std::count(regions.begin(), regions.end(), 0) > 0);

    // Once recovered, the mesh takes no more points and no second recovery.
    CHECK(cbr_mesh_insert_points(h.m, 1, xyz.data()) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "after cbr_mesh_recover_faces"));
    CHECK(cbr_mesh_recover_faces(h.m, count, tris.data(), nullptr) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "recovered already"));
}

TEST_CASE("a face that cannot be recovered is named, and the mesh is unchanged") {
    // A turned fan-cap prism (tests/data/recover/prism-96-fan-caps-h3-r12.off,
    // tests/bench/fan_cap_prism.py 96 10 3, rotate_surface.py seed 12)
    // defeats conforming recovery in the first attempt ("a flat tetrahedron
    // in a face could not be removed"; the enclosing box then recovers it,
    // so the retries are off here); when it stops doing so, pick another
    // failing input for this test (the failure path must stay tested).
    // pierced-62 served until session 17 and pierced-27 until session 33,
    // when they began to recover.
    cbr::test::OffSurface p;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/prism-96-fan-caps-h3-r12.off", p));
    std::vector<std::int64_t> tris = p.tris;
    for (auto& v : tris) ++v;  // 1-based
    Handle h;
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_INDEX_BASE, 1) == CBR_OK);
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_RECOVERY_RETRIES, 0) == CBR_OK);
    REQUIRE(cbr_mesh_insert_points(h.m, static_cast<std::int64_t>(p.xyz.size() / 3), p.xyz.data()) == CBR_OK);
    const auto before = tets_of(h.m);
    double points_before = 0;
    REQUIRE(cbr_mesh_get_stat(h.m, CBR_STAT_TOTAL_VERTICES, &points_before) == CBR_OK);
    CHECK(cbr_mesh_recover_faces(h.m, static_cast<std::int64_t>(tris.size() / 3), tris.data(), nullptr) ==
          CBR_ERR_RECOVERY_FAILED);
    CHECK(contains(h.error(), "could not recover triangle"));
    CHECK(tets_of(h.m) == before);  // bit for bit
    CHECK(cbr_mesh_point_count(h.m) == static_cast<std::int64_t>(p.xyz.size() / 3));  // added points gone
    CHECK(cbr_mesh_steiner_count(h.m) == 0);
    // The statistics of the attempt stay readable.
    double conforming = -1;
    REQUIRE(cbr_mesh_get_stat(h.m, CBR_STAT_CONFORMING_POINTS, &conforming) == CBR_OK);
    CHECK(conforming > 0);
    // Still usable: more points can be inserted.
    const double extra[3] = {1e3, 1e3, 1e3};
    CHECK(cbr_mesh_insert_points(h.m, 1, extra) == CBR_OK);
}

TEST_CASE("a surface that its own Delaunay mesh defeats is recovered inside an enclosing box") {
    // tests/data/recover/prism-96-fan-caps-h3-r12.off, a rotated CAD
    // cylinder with fanned caps (prism-64-fan-caps-h20-q2.off until session
    // 33, when its first attempt began to succeed): recovery fails on the Delaunay mesh of its
    // points (checked when the fixture was made) and succeeds once the
    // eight corners of a box around them are added. The corners follow the
    // caller's points and are Steiner points of the exterior; if the first
    // attempt ever succeeds, they are gone and this test says so.
    cbr::test::OffSurface p;
    Handle h;
    const std::int64_t n = recover_fixture("prism-96-fan-caps-h3-r12.off", p, h);
    double lo[3], hi[3];
    bounding_box(p.xyz, lo, hi);
    const auto outside_box = [&](const std::vector<double>& xyz, std::int64_t v) {
        for (int k = 0; k < 3; ++k) {
            const double x = xyz[3 * static_cast<std::size_t>(v) + static_cast<std::size_t>(k)];
            if (!(x < lo[k] || x > hi[k])) return false;
        }
        return true;
    };
    SUBCASE("with the exterior: the corners are ids n .. n + 7, outside the box, in no bounded tetrahedron") {
        REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_KEEP_EXTERIOR, 1) == CBR_OK);
        const std::int64_t steiner_count = cbr_mesh_steiner_count(h.m);
        CHECK(cbr_mesh_steiner_points(h.m, nullptr) == CBR_ERR_INVALID_ARGUMENT);  // the corners at least
        CHECK(cbr_mesh_point_count(h.m) == n + steiner_count);
        CHECK(stat(h.m, CBR_STAT_STEINER_REMAINING) == static_cast<double>(steiner_count));
        std::vector<std::int64_t> ids(static_cast<std::size_t>(steiner_count));
        REQUIRE(cbr_mesh_steiner_points(h.m, ids.data()) == CBR_OK);
        const std::set<std::int64_t> steiner(ids.begin(), ids.end());
        const std::vector<double> xyz = points_of(h);
        std::set<std::int64_t> corners;
        for (std::int64_t v = n; v < n + 8; ++v) {
            CHECK(steiner.count(v) == 1);
            CHECK(outside_box(xyz, v));
            corners.insert(v);
        }
        const auto tets = tets_of(h.m);
        std::vector<std::int32_t> regions(tets.size() / 4);
        REQUIRE(cbr_mesh_get_tet_regions(h.m, regions.data()) == CBR_OK);
        for (std::size_t t = 0; t < regions.size(); ++t)
            if (regions[t] > 0)
                for (int i = 0; i < 4; ++i) CHECK(corners.count(tets[4 * t + static_cast<std::size_t>(i)]) == 0);
        CHECK(stat(h.m, CBR_STAT_STEINER_INSIDE) <= static_cast<double>(steiner_count - 8));
    }
    SUBCASE("without it (the default): every point after the caller's is used, the corners are gone") {
        const std::int64_t steiner_count = cbr_mesh_steiner_count(h.m);
        const std::int64_t np = cbr_mesh_point_count(h.m);
        CHECK(np == n + steiner_count);
        CHECK(stat(h.m, CBR_STAT_STEINER_INSIDE) == static_cast<double>(steiner_count));
        CHECK(stat(h.m, CBR_STAT_STEINER_REMAINING) >= static_cast<double>(steiner_count + 8));
        // Nothing to write needs no array; something to write does.
        CHECK(cbr_mesh_steiner_points(h.m, nullptr) == (steiner_count == 0 ? CBR_OK : CBR_ERR_INVALID_ARGUMENT));
        std::vector<std::int64_t> ids(static_cast<std::size_t>(steiner_count));
        REQUIRE(cbr_mesh_steiner_points(h.m, ids.data()) == CBR_OK);
        std::vector<std::int64_t> expected(ids.size());
        std::iota(expected.begin(), expected.end(), n);  // the ids after the caller's close up
        CHECK(ids == expected);
        const std::vector<double> xyz = points_of(h);
        std::vector<char> used(static_cast<std::size_t>(np), 0);
        for (std::int64_t v : tets_of(h.m)) used[static_cast<std::size_t>(v)] = 1;
        for (std::int64_t v = n; v < np; ++v) {
            CHECK(used[static_cast<std::size_t>(v)] == 1);
            CHECK_FALSE(outside_box(xyz, v));
        }
    }
    SUBCASE("refined: the same, the field points after the Steiner points the domain kept") {
        REQUIRE_MESSAGE(cbr_mesh_refine(h.m) == CBR_OK, h.error());
        const std::int64_t np = cbr_mesh_point_count(h.m);
        std::vector<char> used(static_cast<std::size_t>(np), 0);
        for (std::int64_t v : tets_of(h.m)) used[static_cast<std::size_t>(v)] = 1;
        CHECK(std::all_of(used.begin() + n, used.end(), [](char u) { return u == 1; }));
        const std::vector<double> xyz = points_of(h);
        for (std::int64_t v = n; v < np; ++v) CHECK_FALSE(outside_box(xyz, v));
        REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_KEEP_EXTERIOR, 1) == CBR_OK);
        CHECK(cbr_mesh_point_count(h.m) >= np + 8);  // the corners (at least) come back
        const std::vector<double> all = points_of(h);
        for (std::int64_t v = n; v < n + 8; ++v) CHECK(outside_box(all, v));
    }
    // The project's exact checks of the recovered mesh.
    cbr::test::check_recovered(h.m, p.xyz, p.tris);
}

namespace {

// The shared wildmeshing-upsampled-box turned as tests/bench/rotate_surface.py
// turns it with seed 3 (cbr::test::turn: the same doubles).
cbr::test::OffSurface upsampled_box_turned_r3(const std::string& dir) {
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(dir + "/surfaces/wildmeshing-upsampled-box.off", s));
    cbr::test::turn(s.xyz, cbr::test::kRotateSurfaceSeed3);
    return s;
}

}  // namespace

TEST_CASE("the turned upsampled box recovers (shortcuts along chains, grazing crossings)") {
    // The shared upsampled box turned by seed 3: its six planar sides, each
    // a fine grid, are only nearly planar after the turn. Conforming
    // recovery failed on them in every order of the faces, flip state and
    // enclosing box. With two changes to it (ConformingRecovery) it
    // recovered inside the enclosing box (since session 33 the flips, the
    // blocking ring vertices first, recover its faces in the first attempt): a flat tetrahedron may lose an
    // edge that skips points of a chain even where the edge borders a
    // neighbour's "sub-face" (it cannot be one: it lies along the chain),
    // and a segment that meets a flat tetrahedron's face at a grazing angle
    // is also tried with a point where it passes the face's edge.
    const std::string dir = cbr::test::shared_data_dir();
    if (dir.empty()) {
        MESSAGE("no ../shared data: skipped");
        return;
    }
    const cbr::test::OffSurface p = upsampled_box_turned_r3(dir);
    const auto n = static_cast<std::int64_t>(p.xyz.size() / 3);
    Handle h;
    REQUIRE(cbr_mesh_insert_points(h.m, n, p.xyz.data()) == CBR_OK);
    REQUIRE_MESSAGE(cbr_mesh_recover_faces(h.m, static_cast<std::int64_t>(p.tris.size() / 3), p.tris.data(),
                                           nullptr) == CBR_OK,
                    h.error());
    cbr::test::check_recovered(h.m, p.xyz, p.tris);
}

TEST_CASE("after a failed first attempt the enclosing box comes before the other flip states") {
    // tests/data/recover/prism-96-fan-caps-h3-r12.off: a turned fan-cap
    // prism on which the first attempt fails and the enclosing box
    // recovers (prism-96-fan-caps-h1-r22.off until session 33, when its
    // first attempt began to succeed). cbr_mesh_recover_faces tries the
    // box second, before the other flip states (api_recover.cpp,
    // recover_in_attempts: on turned CAD parts the box recovers most first
    // failures): the result has the box's eight corners, ids n .. n + 7,
    // beyond the points' bounding box. Were the other flip states tried
    // first and one of them recovered it, it would have none.
    cbr::test::OffSurface p;
    Handle h;
    const std::int64_t n = recover_fixture("prism-96-fan-caps-h3-r12.off", p, h);
    // The corners are in the exterior alone: the getters return them with it.
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_KEEP_EXTERIOR, 1) == CBR_OK);
    const std::int64_t steiner_count = cbr_mesh_steiner_count(h.m);
    CHECK(cbr_mesh_point_count(h.m) == n + steiner_count);
    REQUIRE(steiner_count >= 8);
    const std::vector<double> xyz = points_of(h);
    double lo[3], hi[3];
    bounding_box(p.xyz, lo, hi);
    for (std::size_t v = static_cast<std::size_t>(n); v < static_cast<std::size_t>(n) + 8; ++v)
        for (std::size_t k = 0; k < 3; ++k) CHECK((xyz[3 * v + k] < lo[k] || xyz[3 * v + k] > hi[k]));
    cbr::test::check_recovered(h.m, p.xyz, p.tris);
}

TEST_CASE("after the enclosing box, the flips in ring order") {
    // tests/data/recover/csg-x-r19.off, a turned CSG part:
    // without the deepest flip round (so that the retries with other
    // budgets are out), the first attempt (the flips take the blocking ring
    // vertices first) and the enclosing box fail; from the flips in ring
    // order (the other retry of api_recover.cpp's recover_in_attempts,
    // FlipState) it recovers (test_conforming_split checks both halves on
    // the core, with the deepest round). So the result has no box corner:
    // every Steiner point, if any, is inside the points' bounding box.
    cbr::test::OffSurface p;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/csg-x-r19.off", p));
    const auto n = static_cast<std::int64_t>(p.xyz.size() / 3);
    Handle h;
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_RECOVERY_DEEP_FLIPS, 0) == CBR_OK);
    REQUIRE(cbr_mesh_insert_points(h.m, n, p.xyz.data()) == CBR_OK);
    REQUIRE_MESSAGE(cbr_mesh_recover_faces(h.m, static_cast<std::int64_t>(p.tris.size() / 3), p.tris.data(),
                                           nullptr) == CBR_OK,
                    h.error());
    // The exterior's points too: a box corner would be there alone.
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_KEEP_EXTERIOR, 1) == CBR_OK);
    const std::int64_t steiner_count = cbr_mesh_steiner_count(h.m);
    CHECK(steiner_count < 8);
    const std::vector<double> xyz = points_of(h);
    double lo[3], hi[3];
    bounding_box(p.xyz, lo, hi);
    for (std::size_t v = static_cast<std::size_t>(n); v < static_cast<std::size_t>(n + steiner_count); ++v)
        for (std::size_t k = 0; k < 3; ++k) CHECK((xyz[3 * v + k] >= lo[k] && xyz[3 * v + k] <= hi[k]));
    cbr::test::check_recovered(h.m, p.xyz, p.tris);
}

TEST_CASE("CBR_PARAM_RECOVERY_RETRIES: on by default; off, the first attempt's failure is reported at once") {
    // The fixture of the test above fails in the first attempt and recovers
    // in a later one.
    cbr::test::OffSurface p;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/prism-96-fan-caps-h3-r12.off", p));
    const auto n = static_cast<std::int64_t>(p.xyz.size() / 3);
    const auto count = static_cast<std::int64_t>(p.tris.size() / 3);
    Handle h;
    double v = -1;
    CHECK(cbr_mesh_get_param(h.m, CBR_PARAM_RECOVERY_RETRIES, &v) == CBR_OK);
    CHECK(v == 1);
    CHECK(cbr_mesh_set_param(h.m, CBR_PARAM_RECOVERY_RETRIES, 2) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "CBR_PARAM_RECOVERY_RETRIES must be 0 or 1"));
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_RECOVERY_RETRIES, 0) == CBR_OK);
    CHECK(cbr_mesh_get_param(h.m, CBR_PARAM_RECOVERY_RETRIES, &v) == CBR_OK);
    CHECK(v == 0);
    REQUIRE(cbr_mesh_insert_points(h.m, n, p.xyz.data()) == CBR_OK);
    const auto delaunay = tets_of(h.m);
    CHECK(cbr_mesh_recover_faces(h.m, count, p.tris.data(), nullptr) == CBR_ERR_RECOVERY_FAILED);
    const std::string why = h.error();
    CHECK(contains(why, "could not recover"));
    CHECK_FALSE(contains(why, "other flip states"));
    CHECK_FALSE(contains(why, "enclosing box"));
    CHECK(tets_of(h.m) == delaunay);  // the mesh is as it was
    CHECK(cbr_mesh_point_count(h.m) == n);
    // On again, the same handle recovers the surface.
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_RECOVERY_RETRIES, 1) == CBR_OK);
    REQUIRE_MESSAGE(cbr_mesh_recover_faces(h.m, count, p.tris.data(), nullptr) == CBR_OK, h.error());
    cbr::test::check_recovered(h.m, p.xyz, p.tris);
}

TEST_CASE("recover_faces rejects bad arguments and invalid surfaces before any change") {
    Handle h;
    CHECK(cbr_mesh_recover_faces(nullptr, 0, nullptr, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 0};
    const std::vector<std::int64_t> tri = {0, 1, 2};
    CHECK(cbr_mesh_recover_faces(h.m, 1, tri.data(), nullptr) == CBR_ERR_INVALID_INPUT);
    CHECK(contains(h.error(), "invalid surface"));  // the surface is checked first: ids out of range
    REQUIRE(cbr_mesh_insert_points(h.m, 3, xyz.data()) == CBR_OK);
    CHECK(cbr_mesh_recover_faces(h.m, 1, tri.data(), nullptr) == CBR_ERR_INVALID_INPUT);
    CHECK(contains(h.error(), "no volume"));
    REQUIRE(cbr_mesh_insert_points(h.m, 2, xyz.data() + 9) == CBR_OK);
    const auto before = tets_of(h.m);
    CHECK(cbr_mesh_recover_faces(h.m, -1, tri.data(), nullptr) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(cbr_mesh_recover_faces(h.m, 1, nullptr, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    const std::vector<std::int64_t> flat = {0, 1, 4};  // collinear: zero area
    CHECK(cbr_mesh_recover_faces(h.m, 1, flat.data(), nullptr) == CBR_ERR_INVALID_INPUT);
    CHECK(contains(h.error(), "invalid surface"));
    CHECK(contains(h.error(), "zero area"));
    const std::vector<std::int64_t> out_of_range = {0, 1, 9};
    CHECK(cbr_mesh_recover_faces(h.m, 1, out_of_range.data(), nullptr) == CBR_ERR_INVALID_INPUT);
    CHECK(tets_of(h.m) == before);
    double v = 0;
    CHECK(cbr_mesh_get_stat(h.m, 999, &v) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(cbr_mesh_get_stat(h.m, CBR_STAT_MISSING_FACES, nullptr) == CBR_ERR_INVALID_ARGUMENT);
}

TEST_CASE("CBR_STAT_STEINER_INSIDE counts the Steiner points of the bounded regions") {
    // Schonhardt's prism needs a Steiner point; those of the exterior are
    // dropped with it, so only the ones the caller's mesh uses count.
    const cbr::test::Polyhedron p = cbr::test::schonhardt_prism();
    Handle h;
    REQUIRE(cbr_mesh_insert_points(h.m, static_cast<std::int64_t>(p.xyz.size() / 3), p.xyz.data()) == CBR_OK);
    CHECK(stat(h.m, CBR_STAT_STEINER_INSIDE) == 0);  // before recovery
    REQUIRE(cbr_mesh_recover_faces(h.m, static_cast<std::int64_t>(p.tris.size() / 3), p.tris.data(), nullptr) ==
            CBR_OK);
    const double inside = stat(h.m, CBR_STAT_STEINER_INSIDE);
    CHECK(inside >= 1);
    CHECK(inside <= stat(h.m, CBR_STAT_STEINER_REMAINING));

    std::vector<std::int64_t> ids(static_cast<std::size_t>(cbr_mesh_steiner_count(h.m)));
    REQUIRE(cbr_mesh_steiner_points(h.m, ids.data()) == CBR_OK);
    const std::set<std::int64_t> steiner(ids.begin(), ids.end());
    // Distinct Steiner ids among the tetrahedra (those of regions > 0 only
    // when bounded_only).
    const auto used = [&](const std::vector<std::int64_t>& tets, const std::vector<std::int32_t>& regions,
                          bool bounded_only) {
        std::set<std::int64_t> seen;
        for (std::size_t t = 0; t < regions.size(); ++t) {
            if (bounded_only && regions[t] <= 0) continue;
            for (std::size_t i = 4 * t; i < 4 * t + 4; ++i)
                if (steiner.count(tets[i])) seen.insert(tets[i]);
        }
        return static_cast<double>(seen.size());
    };
    const auto regions_of = [&] {
        std::vector<std::int32_t> r(static_cast<std::size_t>(cbr_mesh_tet_count(h.m)));
        REQUIRE(cbr_mesh_get_tet_regions(h.m, r.data()) == CBR_OK);
        return r;
    };

    // By default cbr_mesh_get_tets returns the bounded regions only.
    const auto bounded = tets_of(h.m);
    CHECK(used(bounded, regions_of(), false) == inside);

    // With the exterior kept: the tetrahedra of regions > 0 give the same.
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_KEEP_EXTERIOR, 1) == CBR_OK);
    const auto all = tets_of(h.m);
    const auto regions = regions_of();
    REQUIRE(all.size() / 4 == regions.size());
    CHECK(used(all, regions, true) == inside);
    CHECK(stat(h.m, CBR_STAT_STEINER_INSIDE) == inside);  // independent of the parameter
}

TEST_CASE("CBR_PARAM_RECOVERY_DEEP_FLIPS: on by default; off, flips leave what the deepest round recovers") {
    // A turned fan-cap prism (tests/data/recover/prism-48-fan-caps-q4.off):
    // without the deepest round the flips leave 2 of its 107 missing faces,
    // with it none. (The Chazelle polyhedron served until session 33, when
    // the shallower rounds began to recover all of its faces.)
    cbr::test::OffSurface prism;
    REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/prism-48-fan-caps-q4.off", prism));
    const auto left_by_flips = [&](int deep) {
        Handle h;
        double v = -1;
        CHECK(cbr_mesh_get_param(h.m, CBR_PARAM_RECOVERY_DEEP_FLIPS, &v) == CBR_OK);
        CHECK(v == 1);
        CHECK(cbr_mesh_set_param(h.m, CBR_PARAM_RECOVERY_DEEP_FLIPS, 0.5) == CBR_ERR_INVALID_ARGUMENT);
        CHECK(contains(h.error(), "CBR_PARAM_RECOVERY_DEEP_FLIPS must be 0 or 1"));
        REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_RECOVERY_DEEP_FLIPS, deep) == CBR_OK);
        CHECK(cbr_mesh_get_param(h.m, CBR_PARAM_RECOVERY_DEEP_FLIPS, &v) == CBR_OK);
        CHECK(v == deep);
        REQUIRE(cbr_mesh_insert_points(h.m, static_cast<std::int64_t>(prism.xyz.size() / 3), prism.xyz.data()) ==
                CBR_OK);
        // Recovered either way.
        REQUIRE(cbr_mesh_recover_faces(h.m, static_cast<std::int64_t>(prism.tris.size() / 3), prism.tris.data(),
                                       nullptr) == CBR_OK);
        double missing = 0, flips = 0;
        CHECK(cbr_mesh_get_stat(h.m, CBR_STAT_MISSING_FACES, &missing) == CBR_OK);
        CHECK(cbr_mesh_get_stat(h.m, CBR_STAT_FACES_RECOVERED_BY_FLIPS, &flips) == CBR_OK);
        return missing - flips;  // faces flips alone left
    };
    CHECK(left_by_flips(1) == 0);
    CHECK(left_by_flips(0) > 0);
}

TEST_CASE("flips that leave most faces one way run again from the Delaunay mesh the other way") {
    // A CAD cylinder mirrored (tests/data/recover/cylinder-mirrored.off):
    // walking each triangle as given, the flips recover 206 of its 596
    // missing faces, and recovery then took two minutes for 95 Steiner
    // points; walking each reversed, 594.
    cbr::test::OffSurface p;
    Handle h;
    recover_fixture("cylinder-mirrored.off", p, h);
    cbr::test::check_recovered(h.m, p.xyz, p.tris);
    const double missing = stat(h.m, CBR_STAT_MISSING_FACES);
    const double by_flips = stat(h.m, CBR_STAT_FACES_RECOVERED_BY_FLIPS);
    const double inside = stat(h.m, CBR_STAT_STEINER_INSIDE);
    MESSAGE("missing after Delaunay " << missing << ", recovered by flips " << by_flips << ", Steiner points inside "
                                      << inside);
    CHECK(missing == 596);
    CHECK(by_flips >= 590);
    CHECK(inside <= 2);
}
