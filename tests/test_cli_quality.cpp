// The command's Table II measures (src/cli/quality.cpp): the dihedral range
// of a tetrahedron against the angle at every edge, as the header defines
// it, on random, needle, flat and degenerate tetrahedra.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "cli/quality.hpp"

namespace {

using Point = std::array<double, 3>;

constexpr double kPi = 3.14159265358979323846;

// Every edge's angle atan2(|n1 x n2|, n1 . n2), in degrees: smallest and
// largest (the definition in quality.hpp, unscaled).
std::array<double, 2> range_by_definition(const std::array<Point, 4>& p) {
    static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                         {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    const auto sub = [](const Point& a, const Point& b) { return Point{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
    const auto cross = [](const Point& a, const Point& b) {
        return Point{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    };
    const auto dot = [](const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    std::array<double, 2> range = {180, 0};
    for (const auto& e : kEdges) {
        const Point edge = sub(p[e[1]], p[e[0]]);
        const Point n1 = cross(edge, sub(p[e[2]], p[e[0]])), n2 = cross(edge, sub(p[e[3]], p[e[0]]));
        const double deg = std::atan2(std::sqrt(dot(cross(n1, n2), cross(n1, n2))), dot(n1, n2)) * 180 / kPi;
        range[0] = std::min(range[0], deg);
        range[1] = std::max(range[1], deg);
    }
    return range;
}

void check_range(const std::array<Point, 4>& p) {
    double lo = -1, hi = -1;
    cbr::cli::tet_dihedral_range(p[0].data(), p[1].data(), p[2].data(), p[3].data(), lo, hi);
    const std::array<double, 2> expected = range_by_definition(p);
    CHECK(lo == doctest::Approx(expected[0]).epsilon(1e-9));
    CHECK(hi == doctest::Approx(expected[1]).epsilon(1e-9));
}

}  // namespace

TEST_CASE("dihedral range: the smallest and largest of the six angles") {
    std::mt19937_64 rng(2024);
    std::uniform_real_distribution<double> coordinate(-1, 1);
    for (int i = 0; i < 2000; ++i) {
        std::array<Point, 4> p;
        for (Point& q : p)
            for (double& x : q) x = coordinate(rng);
        // Every fourth: the last corner pulled onto the plane of the others
        // (angles near 0 and 180 degrees).
        if (i % 4 == 3)
            for (int k = 0; k < 3; ++k) p[3][k] = (p[0][k] + p[1][k] + p[2][k]) / 3 + 1e-9 * p[3][k];
        CAPTURE(i);
        check_range(p);
    }
}

TEST_CASE("dihedral range: regular, flat and degenerate tetrahedra") {
    double lo = 0, hi = 0;
    const Point a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
    cbr::cli::tet_dihedral_range(a.data(), b.data(), c.data(), d.data(), lo, hi);
    CHECK(lo == doctest::Approx(std::acos(1 / std::sqrt(3.0)) * 180 / kPi));
    CHECK(hi == doctest::Approx(90));
    // A square: four coplanar corners, angles of 0 and 180 degrees.
    check_range({Point{0, 0, 0}, Point{1, 0, 0}, Point{1, 1, 0}, Point{0, 1, 0}});
    cbr::cli::tet_dihedral_range(a.data(), b.data(), Point{1, 1, 0}.data(), c.data(), lo, hi);
    CHECK(lo == 0);
    CHECK(hi == 180);
    // Three collinear corners: some edges' normals vanish (angle 0).
    check_range({Point{0, 0, 0}, Point{1, 0, 0}, Point{2, 0, 0}, Point{0, 1, 0}});
    check_range({Point{0, 0, 0}, Point{0, 1, 0}, Point{1, 0, 0}, Point{2, 0, 0}});
}

TEST_CASE("Table II of a mesh: the extremes of its tetrahedra, overall and per region") {
    // 300 random tetrahedra with their own corners (every third nearly
    // flat), in three regions interleaved, so that the smallest and largest
    // angles come from different tetrahedra and regions.
    std::mt19937_64 rng(48);
    std::uniform_real_distribution<double> coordinate(-1, 1);
    cbr::io::VolumeMesh mesh;
    for (std::int64_t t = 0; t < 300; ++t) {
        std::array<Point, 4> p;
        for (Point& q : p)
            for (double& x : q) x = coordinate(rng);
        if (t % 3 == 2)
            for (int k = 0; k < 3; ++k) p[3][k] = (p[0][k] + p[1][k] + p[2][k]) / 3 + 1e-6 * p[3][k];
        for (int i = 0; i < 4; ++i) {
            mesh.tets.push_back(4 * t + i);
            mesh.xyz.insert(mesh.xyz.end(), p[static_cast<std::size_t>(i)].begin(),
                            p[static_cast<std::size_t>(i)].end());
        }
        mesh.tet_regions.push_back(static_cast<std::int32_t>(1 + (t / 7) % 3));
    }
    const cbr::cli::QualityReport report = cbr::cli::measure_quality(mesh);
    REQUIRE(report.regions.size() == 3);
    const auto expect = [&](const cbr::cli::QualityStats& s, std::int32_t region) {
        double lo = 180, hi = 0;
        std::int64_t n = 0;
        for (std::size_t t = 0; t < mesh.num_tets(); ++t) {
            if (region != 0 && mesh.tet_regions[t] != region) continue;
            const double* c[4];
            for (std::size_t i = 0; i < 4; ++i) c[i] = &mesh.xyz[3 * static_cast<std::size_t>(mesh.tets[4 * t + i])];
            double a = 0, b = 0;
            cbr::cli::tet_dihedral_range(c[0], c[1], c[2], c[3], a, b);
            lo = std::min(lo, a);
            hi = std::max(hi, b);
            ++n;
        }
        CAPTURE(region);
        CHECK(s.tets == n);
        CHECK(s.dihedral_min_deg == lo);
        CHECK(s.dihedral_max_deg == hi);
    };
    expect(report.all, 0);
    for (const cbr::cli::RegionQuality& r : report.regions) expect(r.stats, r.region);
}
