// Boundary recovery on every real surface of ../shared/data/surfaces,
// through the C API, proved with the project's own exact checks: every
// input triangle a face, every tetrahedron positively oriented, no Steiner
// point on an input triangle, the bounded regions' volume equal to the
// enclosed volume, regions that differ across every input triangle.
// Surfaces not recovered yet must fail cleanly: named faces, mesh unchanged.
// Skips (exit 77) without the shared data.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cbr/cbr.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "geom/predicates.hpp"
#include "test_util.hpp"

namespace {

// Recovered completely today; a regression on any of them fails the test.
// Grow this list as conforming recovery and point splitting land.
const std::set<std::string> kRecovered = {
    "cgal-cheese-box", "cgal-cube-shuffled", "cgal-cube", "cgal-tetrahedron-inward",
    "common3d-rocker-arm", "common3d-spot", "nonmanifold-edge-two-tets", "nonmanifold-vertex-hourglass",
    "thingi10k-37322", "thingicsg-openscad-example016", "thingiverse-bird", "wildmeshing-csg-ball",
    "wildmeshing-sphere"};

using Face = std::array<std::int64_t, 3>;
Face sorted(std::int64_t a, std::int64_t b, std::int64_t c) {
    Face f = {a, b, c};
    std::sort(f.begin(), f.end());
    return f;
}

const int kFace[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};

long double six_volume(const double* a, const double* b, const double* c, const double* d) {
    long double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = (long double)b[k] - a[k];
        v[k] = (long double)c[k] - a[k];
        w[k] = (long double)d[k] - a[k];
    }
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// p in the closed triangle abc (exact): coplanar, and on the inner side of
// the three edge planes through a point d off the plane.
bool on_triangle(const double* p, const double* a, const double* b, const double* c) {
    if (cbr::geom::orient3d(a, b, c, p) != 0) return false;
    double d[3];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; ++k) d[k] = a[k] + n[k];
    const int side = cbr::geom::orient3d(a, b, c, d);
    if (side == 0) return false;  // cannot happen for a valid (non-degenerate) triangle
    return cbr::geom::orient3d(a, b, d, p) * side >= 0 && cbr::geom::orient3d(b, c, d, p) * side >= 0 &&
           cbr::geom::orient3d(c, a, d, p) * side >= 0;
}

// The enclosed volume when every edge is used once in each direction
// (consistently oriented closed surface); 0 otherwise.
long double enclosed_volume(const cbr::test::OffSurface& s) {
    std::map<std::pair<std::int64_t, std::int64_t>, int> directed;
    long double sum = 0;
    const double origin[3] = {0, 0, 0};
    for (std::size_t i = 0; i < s.tris.size(); i += 3) {
        const double* p[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = &s.xyz[3 * static_cast<std::size_t>(s.tris[i + k])];
            ++directed[{s.tris[i + k], s.tris[i + (k + 1) % 3]}];
        }
        sum += six_volume(origin, p[0], p[1], p[2]);
    }
    for (const auto& [edge, count] : directed)
        if (count != 1 || directed.count({edge.second, edge.first}) == 0) return 0;
    return sum < 0 ? -sum : sum;
}

void check_recovered(cbr_mesh* m, const cbr::test::OffSurface& s) {
    REQUIRE(cbr_mesh_set_param(m, CBR_PARAM_KEEP_EXTERIOR, 1) == CBR_OK);
    const std::int64_t nt = cbr_mesh_tet_count(m), np = cbr_mesh_point_count(m);
    std::vector<std::int64_t> tets(4 * static_cast<std::size_t>(nt));
    std::vector<std::int32_t> regions(static_cast<std::size_t>(nt));
    std::vector<double> xyz(3 * static_cast<std::size_t>(np));
    REQUIRE(cbr_mesh_get_tets(m, tets.data()) == CBR_OK);
    REQUIRE(cbr_mesh_get_tet_regions(m, regions.data()) == CBR_OK);
    REQUIRE(cbr_mesh_get_points(m, xyz.data()) == CBR_OK);
    auto P = [&](std::int64_t v) { return &xyz[3 * static_cast<std::size_t>(v)]; };

    // Input points unchanged, bit for bit.
    CHECK(std::equal(s.xyz.begin(), s.xyz.end(), xyz.begin()));
    // Orientation, faces, regions on both sides of each face.
    std::map<Face, std::vector<std::int32_t>> face_regions;
    long double bounded = 0;
    std::size_t inverted = 0;
    for (std::size_t t = 0; t < static_cast<std::size_t>(nt); ++t) {
        const std::int64_t* v = &tets[4 * t];
        if (cbr::geom::orient3d(P(v[0]), P(v[1]), P(v[2]), P(v[3])) <= 0) ++inverted;
        if (regions[t] > 0) bounded += six_volume(P(v[0]), P(v[1]), P(v[2]), P(v[3]));
        for (const auto& f : kFace) face_regions[sorted(v[f[0]], v[f[1]], v[f[2]])].push_back(regions[t]);
    }
    CHECK(inverted == 0);
    std::size_t missing = 0, same_region = 0;
    for (std::size_t i = 0; i < s.tris.size(); i += 3) {
        const auto it = face_regions.find(sorted(s.tris[i], s.tris[i + 1], s.tris[i + 2]));
        if (it == face_regions.end()) {
            ++missing;
            continue;
        }
        if (it->second.size() == 2 && it->second[0] == it->second[1]) ++same_region;
    }
    CHECK(missing == 0);
    CHECK(same_region == 0);
    // Steiner points: none on any input triangle (exact).
    std::vector<std::int64_t> steiner(static_cast<std::size_t>(cbr_mesh_steiner_count(m)));
    REQUIRE(cbr_mesh_steiner_points(m, steiner.data()) == CBR_OK);
    std::size_t on_surface = 0;
    for (std::int64_t sp : steiner)
        for (std::size_t i = 0; i < s.tris.size(); i += 3)
            on_surface += on_triangle(P(sp), P(s.tris[i]), P(s.tris[i + 1]), P(s.tris[i + 2]));
    CHECK(on_surface == 0);
    // Volume of the bounded regions = volume the surface encloses.
    const long double enclosed = enclosed_volume(s);
    if (enclosed > 0) CHECK(static_cast<double>(bounded / enclosed) == doctest::Approx(1.0).epsilon(1e-9));
}

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
            if (status == CBR_OK) check_recovered(m, s);
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

int main(int argc, char** argv) {
    if (cbr::test::shared_data_dir().empty()) {
        std::puts("skipped: ../shared/data/surfaces not found (set CBR_SHARED_DATA_DIR)");
        return 77;
    }
    doctest::Context context(argc, argv);
    return context.run();
}
