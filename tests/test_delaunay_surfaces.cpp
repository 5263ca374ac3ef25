// The Delaunay tetrahedralization of the vertices of every real surface in
// ../shared/data/surfaces, checked exactly. Skips (exit 77) without them.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>

#include "delaunay/delaunay.hpp"
#include "mesh/mesh_check.hpp"
#include "test_util.hpp"

TEST_CASE("vertices of every shared surface") {
    for (const std::string& path : cbr::test::shared_surfaces()) {
        CAPTURE(path);
        cbr::test::OffSurface s;
        REQUIRE(cbr::test::read_off(path, s));
        cbr::delaunay::Delaunay d;
        REQUIRE(d.insert_points(s.xyz.data(), s.xyz.size() / 3).ok);
        const auto report = cbr::mesh::check_delaunay(d.mesh());
        for (const auto& e : report.errors) MESSAGE(e);
        CHECK(report.ok());
        CHECK(d.finite_tet_count() > 0);
    }
}

CBR_TEST_MAIN_NEEDING_SHARED_DATA
