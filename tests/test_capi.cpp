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

#include "test_util.hpp"

namespace {

struct Handle {
    cbr_mesh* m = nullptr;
    Handle() { REQUIRE(cbr_mesh_create(&m) == CBR_OK); }
    ~Handle() { cbr_mesh_destroy(m); }
    std::string error() const { return cbr_mesh_last_error(m); }
};

std::vector<std::int64_t> tets_of(const cbr_mesh* m) {
    std::vector<std::int64_t> t(4 * static_cast<std::size_t>(cbr_mesh_tet_count(m)));
    REQUIRE(cbr_mesh_get_tets(m, t.data()) == CBR_OK);
    return t;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

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
