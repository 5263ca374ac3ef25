// Full mesh generation (cbr_mesh_refine, Du & Wang 2004 §6) on every real
// surface of ../shared/data/surfaces, through the C API with its defaults
// (what `cbr mesh` runs), proved with the project's own exact checks
// (recovery_checks.hpp) on the refined mesh: every input triangle still a
// face with different regions on its two sides, every tetrahedron
// positively oriented, the input points unmoved, no point recovery or
// refinement added on an input triangle, the bounded regions' volume equal
// to the enclosed volume and their number kept; and the counts the library
// reports (the tetrahedra of the bounded regions, those left over the size
// bound) against the mesh it returns. test_refine.cpp checks the size
// bound itself, tetrahedron by tetrahedron, on the surfaces small enough
// for its sanitizer run.
// Skips (exit 77) without the shared data.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cbr/cbr.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "recovery_checks.hpp"
#include "test_util.hpp"

TEST_CASE("cbr_mesh_refine on every shared surface") {
    std::size_t meshed = 0;
    for (const std::string& path : cbr::test::shared_surfaces()) {
        const std::string name = std::filesystem::path(path).stem().string();
        CAPTURE(name);
        cbr::test::OffSurface s;
        REQUIRE(cbr::test::read_off(path, s));
        const auto n = static_cast<std::int64_t>(s.xyz.size() / 3);
        cbr_mesh* m = nullptr;
        REQUIRE(cbr_mesh_create(&m) == CBR_OK);
        REQUIRE(cbr_mesh_insert_points(m, n, s.xyz.data()) == CBR_OK);
        REQUIRE(cbr_mesh_recover_faces(m, static_cast<std::int64_t>(s.tris.size() / 3), s.tris.data(), nullptr) ==
                CBR_OK);
        double regions_before = 0;
        REQUIRE(cbr_mesh_get_stat(m, CBR_STAT_REGION_COUNT, &regions_before) == CBR_OK);
        const int status = cbr_mesh_refine(m);
        CHECK(status == CBR_OK);
        if (status != CBR_OK) {
            MESSAGE(cbr_mesh_last_error(m));
            cbr_mesh_destroy(m);
            continue;
        }
        ++meshed;
        double regions_after = 0, tets = 0, oversize = -1;
        REQUIRE(cbr_mesh_get_stat(m, CBR_STAT_REGION_COUNT, &regions_after) == CBR_OK);
        REQUIRE(cbr_mesh_get_stat(m, CBR_STAT_REFINE_TETS, &tets) == CBR_OK);
        REQUIRE(cbr_mesh_get_stat(m, CBR_STAT_REFINE_OVERSIZE_TETS, &oversize) == CBR_OK);
        CHECK(regions_after == regions_before);
        // The bounded regions' tetrahedra, as returned without the exterior.
        CHECK(tets == static_cast<double>(cbr_mesh_tet_count(m)));
        CHECK(0 <= oversize);
        CHECK(oversize <= tets);
        // Faces, orientation, regions apart, volume, and every added point
        // (Steiner and field points) off the input triangles.
        cbr::test::check_recovered(m, s.xyz, s.tris);
        cbr_mesh_destroy(m);
    }
    CHECK(meshed == cbr::test::shared_surfaces().size());
}

CBR_TEST_MAIN_NEEDING_SHARED_DATA
