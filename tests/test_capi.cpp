// The C API as a caller sees it: status codes, messages naming the culprit,
// failed calls changing nothing, index base, independent handles.
#include <doctest/doctest.h>

#include <cbr/cbr.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <thread>

#include "capi_test_util.hpp"
#include "test_util.hpp"

namespace {

using cbr::test::contains;
using cbr::test::Handle;
using cbr::test::tets_of;

const std::vector<double> kCubeAndCentre = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1,
                                            1, 0, 1, 0, 1, 1, 1, 1, 1, 0.5, 0.5, 0.5};

}  // namespace

TEST_CASE("version and status strings") {
    const std::string expected = std::to_string(CBR_VERSION_MAJOR) + "." + std::to_string(CBR_VERSION_MINOR) + "." +
                                 std::to_string(CBR_VERSION_PATCH);
    CHECK(std::string(cbr_version()) == expected);
    std::set<std::string> seen;
    for (int s : {CBR_OK, CBR_ERR_INVALID_ARGUMENT, CBR_ERR_INVALID_INPUT, CBR_ERR_OUT_OF_MEMORY,
                  CBR_ERR_RECOVERY_FAILED, CBR_ERR_IO, CBR_ERR_INTERNAL}) {
        seen.insert(cbr_status_string(s));
        if (s != CBR_OK) CHECK(s < 0);
    }
    CHECK(seen.size() == 7);  // distinct codes, distinct descriptions
    CHECK(std::string(cbr_status_string(12345)) == "unknown status");
}

TEST_CASE("NULL arguments are errors, not crashes") {
    CHECK(cbr_mesh_create(nullptr) == CBR_ERR_INVALID_ARGUMENT);
    cbr_mesh_destroy(nullptr);
    CHECK(std::strlen(cbr_mesh_last_error(nullptr)) > 0);
    CHECK(cbr_mesh_insert_points(nullptr, 1, kCubeAndCentre.data()) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(cbr_mesh_point_count(nullptr) == -1);
    CHECK(cbr_mesh_tet_count(nullptr) == -1);
    double v = 0;
    CHECK(cbr_mesh_get_param(nullptr, CBR_PARAM_INDEX_BASE, &v) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(cbr_mesh_set_param(nullptr, CBR_PARAM_INDEX_BASE, 1) == CBR_ERR_INVALID_ARGUMENT);

    Handle h;
    CHECK(h.error().empty());
    CHECK(cbr_mesh_insert_points(h.m, 3, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "xyz is NULL"));
    CHECK(cbr_mesh_insert_points(h.m, -2, kCubeAndCentre.data()) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "negative"));
    CHECK(cbr_mesh_insert_points(h.m, 0, nullptr) == CBR_OK);
    CHECK(cbr_mesh_get_param(h.m, CBR_PARAM_INDEX_BASE, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    REQUIRE(cbr_mesh_insert_points(h.m, 9, kCubeAndCentre.data()) == CBR_OK);
    CHECK(cbr_mesh_get_tets(h.m, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(cbr_mesh_get_points(h.m, nullptr) == CBR_ERR_INVALID_ARGUMENT);
}

TEST_CASE("a cube and its centre") {
    Handle h;
    REQUIRE(cbr_mesh_insert_points(h.m, 9, kCubeAndCentre.data()) == CBR_OK);
    CHECK(cbr_mesh_point_count(h.m) == 9);
    REQUIRE(cbr_mesh_tet_count(h.m) == 12);
    for (std::int64_t v : tets_of(h.m)) CHECK((v >= 0 && v < 9));
    std::vector<double> back(27);
    REQUIRE(cbr_mesh_get_points(h.m, back.data()) == CBR_OK);
    CHECK(std::memcmp(back.data(), kCubeAndCentre.data(), 27 * sizeof(double)) == 0);
}

TEST_CASE("bad coordinates are rejected with the point's id, and nothing changes") {
    Handle h;
    REQUIRE(cbr_mesh_insert_points(h.m, 9, kCubeAndCentre.data()) == CBR_OK);
    const auto tets_before = tets_of(h.m);
    std::vector<double> batch = cbr::test::random_points(10, 3);

    SUBCASE("NaN") {
        batch[3 * 4 + 1] = std::numeric_limits<double>::quiet_NaN();
        CHECK(cbr_mesh_insert_points(h.m, 10, batch.data()) == CBR_ERR_INVALID_INPUT);
        CHECK(contains(h.error(), "point 13 has a NaN y coordinate"));
    }
    SUBCASE("infinity") {
        batch[3 * 7 + 2] = -std::numeric_limits<double>::infinity();
        CHECK(cbr_mesh_insert_points(h.m, 10, batch.data()) == CBR_ERR_INVALID_INPUT);
        CHECK(contains(h.error(), "point 16 has an infinite z coordinate"));
    }
    SUBCASE("out of the exact range") {
        batch[0] = 1e300;
        CHECK(cbr_mesh_insert_points(h.m, 10, batch.data()) == CBR_ERR_INVALID_INPUT);
        CHECK(contains(h.error(), "point 9 has x = 1.0000000000000001e+300"));
        batch[0] = 1e-300;
        CHECK(cbr_mesh_insert_points(h.m, 10, batch.data()) == CBR_ERR_INVALID_INPUT);
    }
    SUBCASE("identical points") {
        for (int k = 0; k < 3; ++k) batch[3 * 6 + k] = kCubeAndCentre[3 * 8 + k];
        CHECK(cbr_mesh_insert_points(h.m, 10, batch.data()) == CBR_ERR_INVALID_INPUT);
        CHECK(contains(h.error(), "points 8 and 15 are identical (0.5, 0.5, 0.5)"));
    }
    CHECK(cbr_mesh_point_count(h.m) == 9);
    CHECK(tets_of(h.m) == tets_before);
    // The handle stays usable.
    CHECK(cbr_mesh_insert_points(h.m, 10, cbr::test::random_points(10, 3).data()) == CBR_OK);
    CHECK(cbr_mesh_point_count(h.m) == 19);
}

TEST_CASE("parameters") {
    Handle h;
    double v = -1;
    REQUIRE(cbr_mesh_get_param(h.m, CBR_PARAM_INDEX_BASE, &v) == CBR_OK);
    CHECK(v == 0);
    CHECK(cbr_mesh_set_param(h.m, CBR_PARAM_INDEX_BASE, 2) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "CBR_PARAM_INDEX_BASE"));
    CHECK(cbr_mesh_set_param(h.m, 999, 0) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "unknown parameter key 999"));
    CHECK(cbr_mesh_get_param(h.m, 999, &v) == CBR_ERR_INVALID_ARGUMENT);
    REQUIRE(cbr_mesh_get_param(h.m, CBR_PARAM_INDEX_BASE, &v) == CBR_OK);
    CHECK(v == 0);  // the failed set changed nothing
}

TEST_CASE("1-based ids for Fortran") {
    Handle h;
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_INDEX_BASE, 1) == CBR_OK);
    REQUIRE(cbr_mesh_insert_points(h.m, 9, kCubeAndCentre.data()) == CBR_OK);
    std::set<std::int64_t> ids;
    for (std::int64_t v : tets_of(h.m)) ids.insert(v);
    CHECK(*ids.begin() == 1);
    CHECK(*ids.rbegin() == 9);
    std::vector<double> dup = {0.5, 0.5, 0.5};
    CHECK(cbr_mesh_insert_points(h.m, 1, dup.data()) == CBR_ERR_INVALID_INPUT);
    CHECK(contains(h.error(), "points 9 and 10 are identical"));
    dup[0] = std::nan("");
    CHECK(cbr_mesh_insert_points(h.m, 1, dup.data()) == CBR_ERR_INVALID_INPUT);
    CHECK(contains(h.error(), "point 10 has a NaN x coordinate"));
}

TEST_CASE("two handles in two threads do not interfere") {
    const auto a = cbr::test::random_points(20000, 1);
    const auto b = cbr::test::grid_points(14);
    auto reference = [](const std::vector<double>& xyz) {
        Handle h;
        REQUIRE(cbr_mesh_insert_points(h.m, static_cast<std::int64_t>(xyz.size() / 3), xyz.data()) == CBR_OK);
        return tets_of(h.m);
    };
    const auto ref_a = reference(a), ref_b = reference(b);
    std::vector<std::int64_t> got_a, got_b;
    auto run = [](const std::vector<double>* xyz, std::vector<std::int64_t>* out) {
        cbr_mesh* m = nullptr;
        if (cbr_mesh_create(&m) != CBR_OK) return;
        if (cbr_mesh_insert_points(m, static_cast<std::int64_t>(xyz->size() / 3), xyz->data()) == CBR_OK) {
            out->resize(4 * static_cast<std::size_t>(cbr_mesh_tet_count(m)));
            cbr_mesh_get_tets(m, out->data());
        }
        cbr_mesh_destroy(m);
    };
    std::thread ta(run, &a, &got_a), tb(run, &b, &got_b);
    ta.join();
    tb.join();
    CHECK(got_a == ref_a);  // bit-identical: deterministic and independent
    CHECK(got_b == ref_b);
}

// ---------------------------------------------------------------------------
// Surface checks: cbr_mesh_check_faces and the defect report.
// ---------------------------------------------------------------------------
namespace {

// A tetrahedron (points 0-3, outward faces), then extra points: 4 on the
// line through 0 and 1, 5 and 6 piercing face 0-1-2 (z = 0) through its
// interior, 7 off the x axis for a third page on edge 0-1.
const std::vector<double> kCheckPoints = {0,   0,   0,  2,   0,   0, 0,   2,  0, 0, 0, 2,
                                          3,   0,   0,  0.5, 0.5, -1, 0.5, 0.5, 1, 1, -1, -1};
const std::vector<std::int64_t> kTetFaces = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

std::vector<std::int64_t> shifted(std::vector<std::int64_t> ids, std::int64_t by) {
    for (std::int64_t& v : ids) v += by;
    return ids;
}

struct CheckHandle : Handle {
    explicit CheckHandle(int base = 0) {
        REQUIRE(cbr_mesh_set_param(m, CBR_PARAM_INDEX_BASE, base) == CBR_OK);
        REQUIRE(cbr_mesh_insert_points(m, 8, kCheckPoints.data()) == CBR_OK);
    }
    int check(const std::vector<std::int64_t>& tris) const {
        return cbr_mesh_check_faces(m, static_cast<std::int64_t>(tris.size() / 3), tris.data());
    }
    std::int64_t count(int kind) const { return cbr_mesh_defect_count(m, kind); }
    std::int64_t listed(int kind) const { return cbr_mesh_defect_listed(m, kind); }
    // {triangle, triangle, point, point, point} of the i-th listed defect.
    std::vector<std::int64_t> defect(int kind, std::int64_t i) const {
        std::vector<std::int64_t> t(2, -7), p(3, -7);
        REQUIRE(cbr_mesh_get_defect(m, kind, i, t.data(), p.data()) == CBR_OK);
        return {t[0], t[1], p[0], p[1], p[2]};
    }
};

const int kAllDefectKinds[] = {CBR_DEFECT_ID_OUT_OF_RANGE, CBR_DEFECT_REPEATED_ID,   CBR_DEFECT_ZERO_AREA,
                               CBR_DEFECT_DUPLICATE_TRIANGLE, CBR_DEFECT_INTERSECTION, CBR_DEFECT_OPEN_EDGE,
                               CBR_DEFECT_NONMANIFOLD_EDGE};

}  // namespace

TEST_CASE("check faces: a closed tetrahedron has no defect") {
    CheckHandle h;
    for (int kind : kAllDefectKinds) CHECK(h.count(kind) == 0);  // before any check
    CHECK(h.check(kTetFaces) == CBR_OK);
    for (int kind : kAllDefectKinds) {
        CHECK(h.count(kind) == 0);
        CHECK(h.listed(kind) == 0);
    }
    CHECK(cbr_mesh_check_faces(h.m, 0, nullptr) == CBR_OK);  // nothing to check
}

TEST_CASE("check faces: each error kind, with its message and its ids") {
    CheckHandle h;
    SUBCASE("id out of range") {
        CHECK(h.check({0, 1, 2, 0, 1, 8}) == CBR_ERR_INVALID_INPUT);
        CHECK(contains(h.error(), "triangle 1 uses vertex id 8, out of range (valid ids are 0 to 7)"));
        CHECK(h.count(CBR_DEFECT_ID_OUT_OF_RANGE) == 1);
        CHECK(h.defect(CBR_DEFECT_ID_OUT_OF_RANGE, 0) == std::vector<std::int64_t>{1, -1, 0, 1, 8});
    }
    SUBCASE("repeated id") {
        CHECK(h.check({0, 1, 2, 3, 1, 3}) == CBR_ERR_INVALID_INPUT);
        CHECK(contains(h.error(), "triangle 1 repeats a vertex id (vertices 3, 1, 3)"));
        CHECK(h.defect(CBR_DEFECT_REPEATED_ID, 0) == std::vector<std::int64_t>{1, -1, 3, 1, 3});
    }
    SUBCASE("zero area") {
        CHECK(h.check({0, 1, 4, 0, 2, 3}) == CBR_ERR_INVALID_INPUT);
        CHECK(contains(h.error(), "triangle 0 has zero area (vertices 0, 1, 4 are collinear)"));
        CHECK(h.defect(CBR_DEFECT_ZERO_AREA, 0) == std::vector<std::int64_t>{0, -1, 0, 1, 4});
    }
    SUBCASE("duplicate triangle") {
        auto tris = kTetFaces;
        tris.insert(tris.end(), {1, 3, 2});
        CHECK(h.check(tris) == CBR_ERR_INVALID_INPUT);
        CHECK(contains(h.error(), "triangles 3 and 4 are the same triangle"));
        CHECK(h.defect(CBR_DEFECT_DUPLICATE_TRIANGLE, 0) == std::vector<std::int64_t>{3, 4, 1, 3, 2});
    }
    SUBCASE("intersection") {
        CHECK(h.check({0, 1, 2, 5, 6, 3}) == CBR_ERR_INVALID_INPUT);
        CHECK(contains(h.error(), "triangles 0 and 1 intersect (not in a shared vertex or edge)"));
        CHECK(h.count(CBR_DEFECT_INTERSECTION) == 1);
        CHECK(h.defect(CBR_DEFECT_INTERSECTION, 0) == std::vector<std::int64_t>{0, 1, -1, -1, -1});
    }
    CHECK(contains(h.error(), "cbr_mesh_check_faces: 1 error: "));
}

TEST_CASE("check faces: open and non-manifold edges are information, not errors") {
    CheckHandle h;
    SUBCASE("open") {
        CHECK(h.check({0, 2, 1, 0, 1, 3, 0, 3, 2}) == CBR_OK);  // the tetrahedron less a face
        CHECK(h.count(CBR_DEFECT_OPEN_EDGE) == 3);
        CHECK(h.listed(CBR_DEFECT_OPEN_EDGE) == 3);
        CHECK(h.defect(CBR_DEFECT_OPEN_EDGE, 0) == std::vector<std::int64_t>{0, -1, 1, 2, -1});
        CHECK(h.defect(CBR_DEFECT_OPEN_EDGE, 2) == std::vector<std::int64_t>{2, -1, 2, 3, -1});
    }
    SUBCASE("non-manifold") {
        CHECK(h.check({0, 1, 2, 0, 1, 3, 0, 1, 7}) == CBR_OK);  // three pages on edge 0-1
        CHECK(h.count(CBR_DEFECT_NONMANIFOLD_EDGE) == 1);
        CHECK(h.defect(CBR_DEFECT_NONMANIFOLD_EDGE, 0) == std::vector<std::int64_t>{0, -1, 0, 1, -1});
        CHECK(h.count(CBR_DEFECT_OPEN_EDGE) == 6);
    }
    for (int kind : kAllDefectKinds)
        if (kind != CBR_DEFECT_OPEN_EDGE && kind != CBR_DEFECT_NONMANIFOLD_EDGE) CHECK(h.count(kind) == 0);
}

TEST_CASE("check faces: index base 1 in, in messages and out") {
    CheckHandle h(1);
    CHECK(h.check(shifted(kTetFaces, 1)) == CBR_OK);
    CHECK(h.check({1, 2, 3, 1, 2, 0, 6, 7, 4}) == CBR_ERR_INVALID_INPUT);
    CHECK(contains(h.error(), "triangle 2 uses vertex id 0, out of range (valid ids are 1 to 8)"));
    CHECK(contains(h.error(), "then: triangles 1 and 3 intersect"));
    CHECK(h.defect(CBR_DEFECT_ID_OUT_OF_RANGE, 0) == std::vector<std::int64_t>{2, -1, 1, 2, 0});
    CHECK(h.defect(CBR_DEFECT_INTERSECTION, 0) == std::vector<std::int64_t>{1, 3, -1, -1, -1});
    CHECK(h.defect(CBR_DEFECT_OPEN_EDGE, 0) == std::vector<std::int64_t>{1, -1, 1, 2, -1});
    // The report is kept 0-based: switching the base changes what is read.
    REQUIRE(cbr_mesh_set_param(h.m, CBR_PARAM_INDEX_BASE, 0) == CBR_OK);
    CHECK(h.defect(CBR_DEFECT_ID_OUT_OF_RANGE, 0) == std::vector<std::int64_t>{1, -1, 0, 1, -1});
}

TEST_CASE("check faces: counts are complete, listing stops at 20") {
    CheckHandle h;
    std::vector<std::int64_t> tris;
    for (int t = 0; t < 30; ++t) tris.insert(tris.end(), {0, 1, 100 + t});
    CHECK(h.check(tris) == CBR_ERR_INVALID_INPUT);
    CHECK(contains(h.error(), "30 errors: 30 triangles with ids out of range"));
    CHECK(h.count(CBR_DEFECT_ID_OUT_OF_RANGE) == 30);
    CHECK(h.listed(CBR_DEFECT_ID_OUT_OF_RANGE) == 20);
    for (std::int64_t i = 0; i < 20; ++i) CHECK(h.defect(CBR_DEFECT_ID_OUT_OF_RANGE, i)[0] == i);
    CHECK(cbr_mesh_get_defect(h.m, CBR_DEFECT_ID_OUT_OF_RANGE, 20, nullptr, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "defect index 20 is out of range (20 listed of this kind)"));
    CHECK(cbr_mesh_get_defect(h.m, CBR_DEFECT_ID_OUT_OF_RANGE, 3, nullptr, nullptr) == CBR_OK);
}

TEST_CASE("check faces: bad arguments are refused and leave the report as it was") {
    CheckHandle h;
    REQUIRE(h.check({0, 1, 2, 0, 1, 9}) == CBR_ERR_INVALID_INPUT);
    auto unchanged = [&] {
        CHECK(h.count(CBR_DEFECT_ID_OUT_OF_RANGE) == 1);
        CHECK(h.count(CBR_DEFECT_OPEN_EDGE) == 3);  // the invalid triangle has no edges
    };
    CHECK(cbr_mesh_check_faces(h.m, 2, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "tris is NULL"));
    unchanged();
    CHECK(cbr_mesh_check_faces(h.m, -1, kTetFaces.data()) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(contains(h.error(), "count is negative (-1)"));
    unchanged();
    CHECK(cbr_mesh_check_faces(nullptr, 4, kTetFaces.data()) == CBR_ERR_INVALID_ARGUMENT);
    for (int kind : {0, 8, -1}) {
        CHECK(cbr_mesh_defect_count(h.m, kind) == -1);
        CHECK(cbr_mesh_defect_listed(h.m, kind) == -1);
        CHECK(cbr_mesh_get_defect(h.m, kind, 0, nullptr, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    }
    CHECK(contains(h.error(), "unknown defect kind -1"));
    CHECK(cbr_mesh_defect_count(nullptr, CBR_DEFECT_OPEN_EDGE) == -1);
    CHECK(cbr_mesh_defect_listed(nullptr, CBR_DEFECT_OPEN_EDGE) == -1);
    CHECK(cbr_mesh_get_defect(nullptr, CBR_DEFECT_OPEN_EDGE, 0, nullptr, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    CHECK(cbr_mesh_get_defect(h.m, CBR_DEFECT_OPEN_EDGE, -1, nullptr, nullptr) == CBR_ERR_INVALID_ARGUMENT);
    unchanged();
    // A later check replaces the report.
    CHECK(h.check(kTetFaces) == CBR_OK);
    for (int kind : kAllDefectKinds) CHECK(h.count(kind) == 0);
    CHECK(cbr_mesh_get_defect(h.m, CBR_DEFECT_OPEN_EDGE, 0, nullptr, nullptr) == CBR_ERR_INVALID_ARGUMENT);
}

TEST_CASE("check faces: no points yet, every id is out of range") {
    Handle h;
    const std::vector<std::int64_t> tris = {0, 1, 2};
    CHECK(cbr_mesh_check_faces(h.m, 1, tris.data()) == CBR_ERR_INVALID_INPUT);
    CHECK(contains(h.error(), "there are no points"));
    CHECK(cbr_mesh_defect_count(h.m, CBR_DEFECT_ID_OUT_OF_RANGE) == 1);
}

TEST_CASE("check faces: extreme ids do not overflow") {
    CheckHandle h(1);
    const std::int64_t lo = std::numeric_limits<std::int64_t>::min();
    const std::int64_t hi = std::numeric_limits<std::int64_t>::max();
    CHECK(h.check({1, 2, hi, lo + 1, 2, 3}) == CBR_ERR_INVALID_INPUT);
    CHECK(h.defect(CBR_DEFECT_ID_OUT_OF_RANGE, 0) == std::vector<std::int64_t>{1, -1, 1, 2, hi});
    CHECK(h.defect(CBR_DEFECT_ID_OUT_OF_RANGE, 1) == std::vector<std::int64_t>{2, -1, lo + 1, 2, 3});
    CHECK(h.check({lo, 2, 3}) == CBR_ERR_INVALID_INPUT);  // saturates, see api_check.cpp
    CHECK(h.count(CBR_DEFECT_ID_OUT_OF_RANGE) == 1);
}
