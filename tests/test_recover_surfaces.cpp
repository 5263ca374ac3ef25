// Boundary recovery on every real surface of ../shared/data/surfaces,
// through the C API, proved with the project's own exact checks
// (recovery_checks.hpp): every input triangle a face, every tetrahedron
// positively oriented, no Steiner point on an input triangle, the bounded
// regions' volume equal to the enclosed volume, regions that differ across
// every input triangle.
// Surfaces not recovered yet must fail cleanly: named faces, mesh unchanged.
// Skips (exit 77) without the shared data.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cbr/cbr.h>

#include <cstdio>
#include <filesystem>
#include <set>
#include <string>

#include "recovery_checks.hpp"
#include "test_util.hpp"

namespace {

// Recovered completely today; a regression on any of them fails the test,
// and so does a surface that starts to recover without being listed.
const std::set<std::string> kRecovered = {
    "cgal-armadillo", "cgal-cheese-box", "cgal-cube-shuffled", "cgal-cube", "cgal-dino", "cgal-tetrahedron-inward",
    "common3d-cheburashka", "common3d-fandisk", "common3d-homer", "common3d-igea", "common3d-nefertiti",
    "common3d-rocker-arm", "common3d-spot", "nonmanifold-edge-two-tets", "nonmanifold-vertex-hourglass",
    "thingi10k-100071", "thingi10k-37322", "thingicsg-openscad-example012", "thingicsg-openscad-example016",
    "thingicsg-cylinder", "thingicsg-sprocket-small", "thingicsg-sprocket", "thingicsg-t1-torus-quads",
    "thingiverse-bird", "thingiverse-chain-link", "thingiverse-feeder-body", "thingiverse-feeder-guide-arm",
    "thingiverse-golf-ball",
    "thingiverse-mouth", "wildmeshing-armadillo", "wildmeshing-blub", "wildmeshing-csg-ball", "wildmeshing-csg-x", "wildmeshing-octocat",
    "wildmeshing-sphere", "wildmeshing-supershape", "wildmeshing-upsampled-box"};

}  // namespace

TEST_CASE("recovery on every shared surface") {
    std::size_t recovered = 0;
    for (const std::string& path : cbr::test::shared_surfaces()) {
        const std::string name = std::filesystem::path(path).stem().string();
        CAPTURE(name);
        cbr::test::OffSurface s;
        REQUIRE(cbr::test::read_off(path, s));
        cbr_mesh* m = nullptr;
        REQUIRE(cbr_mesh_create(&m) == CBR_OK);
        REQUIRE(cbr_mesh_insert_points(m, static_cast<std::int64_t>(s.xyz.size() / 3), s.xyz.data()) == CBR_OK);
        const std::int64_t delaunay_tets = cbr_mesh_tet_count(m);
        const int status = cbr_mesh_recover_faces(m, static_cast<std::int64_t>(s.tris.size() / 3), s.tris.data(), nullptr);
        double missing = -1, flips = -1;
        REQUIRE(cbr_mesh_get_stat(m, CBR_STAT_MISSING_FACES, &missing) == CBR_OK);
        REQUIRE(cbr_mesh_get_stat(m, CBR_STAT_FACES_RECOVERED_BY_FLIPS, &flips) == CBR_OK);
        CHECK(flips <= missing);
        if (kRecovered.count(name)) {
            CHECK(status == CBR_OK);
            if (status == CBR_OK) cbr::test::check_recovered(m, s.xyz, s.tris);
            ++recovered;
        } else {
            // Not yet: a clean failure that names faces and changes nothing.
            CHECK(status == CBR_ERR_RECOVERY_FAILED);
            CHECK(std::string(cbr_mesh_last_error(m)).find("could not recover triangle") != std::string::npos);
            CHECK(cbr_mesh_tet_count(m) == delaunay_tets);
            CHECK(flips < missing);
            if (status == CBR_OK) MESSAGE("now recovered: add it to kRecovered");
        }
        cbr_mesh_destroy(m);
    }
    CHECK(recovered == kRecovered.size());
}

// The CAD cylinder turned, scaled and shifted as tests/bench/rotate_surface.py
// does with seed 1 (cbr::test::turn: the same doubles): its fanned
// caps are then only nearly planar, and the first intersection point that
// conforming recovery rounds on one of its missing edges cannot be joined
// to the chain it extends; another point of the crossing can
// (ConformingRecovery::other_crossing_points).
TEST_CASE("recovery of the CAD cylinder turned in space") {
    std::string path;
    for (const std::string& p : cbr::test::shared_surfaces())
        if (std::filesystem::path(p).stem() == "thingicsg-cylinder") path = p;
    REQUIRE(!path.empty());
    cbr::test::OffSurface s;
    REQUIRE(cbr::test::read_off(path, s));
    cbr::test::turn(s.xyz, cbr::test::kRotateSurfaceSeed1);
    cbr_mesh* m = nullptr;
    REQUIRE(cbr_mesh_create(&m) == CBR_OK);
    REQUIRE(cbr_mesh_insert_points(m, static_cast<std::int64_t>(s.xyz.size() / 3), s.xyz.data()) == CBR_OK);
    const int status = cbr_mesh_recover_faces(m, static_cast<std::int64_t>(s.tris.size() / 3), s.tris.data(), nullptr);
    CHECK(status == CBR_OK);
    if (status != CBR_OK) MESSAGE(cbr_mesh_last_error(m));
    if (status == CBR_OK) cbr::test::check_recovered(m, s.xyz, s.tris);
    cbr_mesh_destroy(m);
}

CBR_TEST_MAIN_NEEDING_SHARED_DATA
