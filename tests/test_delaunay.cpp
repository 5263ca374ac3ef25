// Incremental Delaunay: after every construction the whole mesh is checked
// exactly (adjacency, orientation, closed hull, every face locally Delaunay
// under the perturbation, which proves the mesh Delaunay).
#include <doctest/doctest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <string>

#include "delaunay/delaunay.hpp"
#include "delaunay/spatial_sort.hpp"
#include "mesh/huge_pages.hpp"
#include "mesh/large_array.hpp"
#include "mesh/mesh_check.hpp"
#include "test_util.hpp"

using cbr::delaunay::Delaunay;
using cbr::mesh::TetMesh;

namespace {

void require_delaunay(const Delaunay& d) {
    const auto report = cbr::mesh::check_delaunay(d.mesh());
    for (const auto& e : report.errors) MESSAGE(e);
    REQUIRE(report.ok());
}

// Finite tetrahedra in the callers' (external) ids.
std::vector<std::int64_t> finite_tets(const Delaunay& d) {
    const TetMesh& m = d.mesh();
    std::vector<std::int64_t> out;
    for (cbr::mesh::TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t) && !m.is_ghost(t))
            for (int i = 0; i < 4; ++i) out.push_back(d.external_id(m.vertex(t, i)));
    return out;
}

// Sum of tetrahedron volumes (6x, in long double): the hull's volume.
long double six_volume(const TetMesh& m) {
    long double sum = 0;
    for (cbr::mesh::TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t) || m.is_ghost(t)) continue;
        const double* a = m.point(m.vertex(t, 0));
        long double u[3], v[3], w[3];
        for (int k = 0; k < 3; ++k) {
            u[k] = (long double)m.point(m.vertex(t, 1))[k] - a[k];
            v[k] = (long double)m.point(m.vertex(t, 2))[k] - a[k];
            w[k] = (long double)m.point(m.vertex(t, 3))[k] - a[k];
        }
        sum += u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
               u[2] * (v[0] * w[1] - v[1] * w[0]);
    }
    return sum;
}

Delaunay& build(Delaunay& d, const std::vector<double>& xyz) {
    const auto outcome = d.insert_points(xyz.data(), xyz.size() / 3);
    REQUIRE(outcome.ok);
    return d;
}

}  // namespace

TEST_CASE("a cube and its centre give 12 tetrahedra") {
    std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1, 0.5, 0.5, 0.5};
    Delaunay d;
    build(d, xyz);
    require_delaunay(d);
    CHECK(d.finite_tet_count() == 12);
    CHECK(six_volume(d.mesh()) == doctest::Approx(6.0));
}

TEST_CASE("fewer than four points, or all coplanar, give no tetrahedra") {
    Delaunay d;
    build(d, {0, 0, 0, 1, 0, 2, 0, 1, -1});
    CHECK(d.finite_tet_count() == 0);
    // 1000 points exactly in the tilted plane z = 2x - y (x, y multiples of
    // 2^-10, so z is exact): still none.
    std::vector<double> plane;
    auto r = cbr::test::random_points(1000, 7);
    for (std::size_t i = 0; i < r.size(); i += 3) {
        const double x = std::floor(r[i] * 1024) / 1024, y = std::floor(r[i + 1] * 1024) / 1024;
        plane.insert(plane.end(), {x, y, 2 * x - y});
    }
    build(d, plane);
    CHECK(d.finite_tet_count() == 0);
    REQUIRE(d.mesh().vertex_count() == 1003);
    // One point off the plane: every point becomes a vertex of a valid mesh.
    build(d, {0.5, 0.5, 3.0});
    CHECK(d.finite_tet_count() > 0);
    require_delaunay(d);
}

TEST_CASE("uniform random points") {
    for (std::size_t n : {5u, 50u, 2000u, 20000u}) {
        CAPTURE(n);
        Delaunay d;
        build(d, cbr::test::random_points(n, 42 + n));
        require_delaunay(d);
        if (n >= 2000) CHECK(d.finite_tet_count() > 6 * n);  // about 6.7 n for large n
    }
}

TEST_CASE("20 x 20 x 20 grid: every cube cospherical") {
    Delaunay d;
    build(d, cbr::test::grid_points(20));
    require_delaunay(d);
    // The tetrahedra tile the hull exactly: volume 19^3.
    CHECK(six_volume(d.mesh()) == 6.0L * 19 * 19 * 19);
}

TEST_CASE("points exactly on one sphere: every insphere test is degenerate") {
    const auto xyz = cbr::test::integer_sphere_points(11 * 11 * 3);  // 363 = 11^2 + 11^2 + 11^2
    REQUIRE(xyz.size() / 3 > 50);
    Delaunay d;
    build(d, xyz);
    require_delaunay(d);
    CHECK(d.counters().insphere_perturbed > 0);  // the perturbation decided
}

TEST_CASE("the triangulation depends only on the point set") {
    const auto xyz = cbr::test::grid_points(6, 0.25);  // degenerate everywhere
    const std::size_t n = xyz.size() / 3;
    Delaunay one;
    build(one, xyz);
    const auto reference = cbr::test::canonical(finite_tets(one));

    SUBCASE("several insert calls versus one") {
        Delaunay several;
        for (std::size_t first = 0; first < n; first += 37) {
            const std::size_t count = std::min<std::size_t>(37, n - first);
            REQUIRE(several.insert_points(xyz.data() + 3 * first, count).ok);
        }
        require_delaunay(several);
        CHECK(cbr::test::canonical(finite_tets(several)) == reference);
    }
    SUBCASE("another input order") {
        std::vector<std::size_t> perm(n);
        std::iota(perm.begin(), perm.end(), 0);
        std::reverse(perm.begin(), perm.end());
        std::vector<double> shuffled;
        for (std::size_t i : perm) shuffled.insert(shuffled.end(), &xyz[3 * i], &xyz[3 * i + 3]);
        Delaunay other;
        build(other, shuffled);
        // Map ids back to the original numbering before comparing.
        std::vector<std::int64_t> tets = finite_tets(other);
        for (auto& v : tets) v = static_cast<std::int64_t>(perm[static_cast<std::size_t>(v)]);
        CHECK(cbr::test::canonical(tets) == reference);
    }
}

TEST_CASE("clustered points at 1e-9 and 1e+9 scales") {
    for (double scale : {1e-9, 1e+9}) {
        CAPTURE(scale);
        std::vector<double> xyz;
        // Ten tight clusters: each spread 1e-6 of the scale around a centre.
        auto centres = cbr::test::random_points(10, 3, -scale, scale);
        auto offsets = cbr::test::random_points(3000, 4, -1e-6 * scale, 1e-6 * scale);
        for (std::size_t i = 0; i < offsets.size(); i += 3) {
            const std::size_t c = (i / 3) % 10;
            for (int k = 0; k < 3; ++k) xyz.push_back(centres[3 * c + k] + offsets[i + k]);
        }
        Delaunay d;
        build(d, xyz);
        require_delaunay(d);
    }
}

TEST_CASE("nearly equal large coordinates with tiny offsets") {
    std::vector<double> xyz;
    auto r = cbr::test::random_points(500, 11);
    for (std::size_t i = 0; i < r.size(); ++i) xyz.push_back(1e15 + std::floor(r[i] * 64) * 0.125);
    // Integer-ish lattice far from the origin: many exact degeneracies.
    std::vector<double> unique;
    std::set<std::array<double, 3>> seen;
    for (std::size_t i = 0; i < xyz.size(); i += 3)
        if (seen.insert({xyz[i], xyz[i + 1], xyz[i + 2]}).second) unique.insert(unique.end(), &xyz[i], &xyz[i + 3]);
    Delaunay d;
    build(d, unique);
    require_delaunay(d);
}

TEST_CASE("duplicate points are reported and the mesh is left exactly as it was") {
    Delaunay d;
    build(d, cbr::test::random_points(300, 5));
    const auto before = finite_tets(d);
    const auto coords_before = d.mesh().coordinates();

    SUBCASE("a duplicate of an existing point") {
        std::vector<double> batch = cbr::test::random_points(50, 6);
        const double* p17 = d.mesh().point(d.internal_id(17));  // the caller's point 17
        for (int k = 0; k < 3; ++k) batch[3 * 20 + k] = p17[k];
        const auto outcome = d.insert_points(batch.data(), 50);
        CHECK_FALSE(outcome.ok);
        CHECK(outcome.duplicate_first == 17);
        CHECK(outcome.duplicate_second == 300 + 20);
    }
    SUBCASE("two identical points in one batch") {
        std::vector<double> batch = cbr::test::random_points(50, 8);
        for (int k = 0; k < 3; ++k) batch[3 * 40 + k] = batch[3 * 9 + k];
        const auto outcome = d.insert_points(batch.data(), 50);
        CHECK_FALSE(outcome.ok);
        CHECK(outcome.duplicate_first == 309);
        CHECK(outcome.duplicate_second == 340);
    }
    CHECK(d.mesh().coordinates() == coords_before);
    CHECK(finite_tets(d) == before);  // same tetrahedra in the same order
    require_delaunay(d);
}

TEST_CASE("internal and external ids are inverse permutations") {
    Delaunay d;
    const auto xyz = cbr::test::random_points(3000, 21);
    build(d, xyz);
    for (cbr::mesh::VertexId e = 0; e < 3000; ++e) {
        REQUIRE(d.external_id(d.internal_id(e)) == e);
        const double* p = d.mesh().point(d.internal_id(e));
        REQUIRE((p[0] == xyz[3 * e] && p[1] == xyz[3 * e + 1] && p[2] == xyz[3 * e + 2]));
    }
}

TEST_CASE("duplicates before the first tetrahedron exists") {
    Delaunay d;
    const auto outcome = d.insert_points(std::vector<double>{0, 0, 0, 1, 1, 1, 0, 0, 0}.data(), 3);
    CHECK_FALSE(outcome.ok);
    CHECK(outcome.duplicate_first == 0);
    CHECK(outcome.duplicate_second == 2);
    CHECK(d.mesh().vertex_count() == 0);
}

TEST_CASE("Hilbert index visits neighbouring cells consecutively") {
    // On a 2^b grid, consecutive Hilbert indices are adjacent cells.
    for (const int bits : {3, 6}) {
        const int side = 1 << bits;
        std::vector<std::array<int, 3>> by_index(static_cast<std::size_t>(side * side * side));
        for (int x = 0; x < side; ++x)
            for (int y = 0; y < side; ++y)
                for (int z = 0; z < side; ++z) {
                    const std::uint64_t i = cbr::delaunay::hilbert_index(x, y, z, bits);
                    REQUIRE(i < by_index.size());
                    by_index[i] = {x, y, z};
                }
        std::set<std::array<int, 3>> distinct(by_index.begin(), by_index.end());
        CHECK(distinct.size() == by_index.size());  // a bijection
        std::size_t not_adjacent = 0;
        for (std::size_t i = 1; i < by_index.size(); ++i) {
            int manhattan = 0;
            for (int k = 0; k < 3; ++k) manhattan += std::abs(by_index[i][k] - by_index[i - 1][k]);
            not_adjacent += manhattan != 1;
        }
        CHECK(not_adjacent == 0);
    }
    // At full depth the first level decides: the eight octants of the
    // 2^21 grid come in eight ranges of 2^60 indices, in curve order.
    const std::uint32_t half = 1u << 20;
    std::set<std::uint64_t> octant_ranges;
    for (std::uint32_t o = 0; o < 8; ++o) {
        const std::uint32_t x = (o & 1) * half, y = (o >> 1 & 1) * half, z = (o >> 2) * half;
        const std::uint64_t low = cbr::delaunay::hilbert_index(x + 1, y + 2, z + 3, 21);
        const std::uint64_t high = cbr::delaunay::hilbert_index(x + half - 1, y + half - 5, z + 7, 21);
        CHECK((low >> 60) == (high >> 60));
        CHECK(low < (std::uint64_t{1} << 63));
        octant_ranges.insert(low >> 60);
    }
    CHECK(octant_ranges.size() == 8);
}

TEST_CASE("check_mesh reports each kind of corruption") {
    // A valid mesh, then one defect at a time in a copy of it.
    const std::vector<double> xyz = cbr::test::random_points(60, 7);
    Delaunay d;
    build(d, xyz);
    const TetMesh& valid = d.mesh();
    REQUIRE(cbr::mesh::check_mesh(valid).ok());
    cbr::mesh::TetId t = 0, n = 0;
    int f = 0;
    for (t = 0; t < valid.slot_count(); ++t)
        if (!valid.is_free(t) && !valid.is_ghost(t)) break;
    for (f = 0; f < 4; ++f) {
        n = cbr::mesh::facet_tet(valid.neighbor(t, f));
        if (!valid.is_ghost(n)) break;
    }
    REQUIRE(f < 4);
    auto first_error = [](const TetMesh& m) {
        const cbr::mesh::CheckReport r = cbr::mesh::check_mesh(m);
        return r.errors.empty() ? std::string() : r.errors[0];
    };
    auto has = [](const std::string& s, const char* what) { return s.find(what) != std::string::npos; };
    {
        // Linked across faces with different vertices: t's vertex on that
        // face replaced by n's apex (t also turns inverted or flat, and its
        // other links no longer match; any of these is a report).
        TetMesh m = valid;
        const int g = cbr::mesh::facet_face(valid.neighbor(t, f));
        m.set_vertex(t, cbr::mesh::kFaceVertices[f][0], valid.vertex(n, g));
        const cbr::mesh::CheckReport r = cbr::mesh::check_mesh(m);
        CHECK(!r.ok());
        bool across = false;
        for (const std::string& e : r.errors) across = across || has(e, "linked across different faces");
        CHECK(across);
    }
    {
        TetMesh m = valid;  // a one-sided link
        m.set_neighbor(t, f, cbr::mesh::make_facet(t, f));
        CHECK(has(first_error(m), "link is not symmetric"));
    }
    {
        TetMesh m = valid;  // inverted: two vertices swapped, links kept
        const cbr::mesh::VertexId a = valid.vertex(t, 0), b = valid.vertex(t, 1);
        m.set_vertex(t, 0, b);
        m.set_vertex(t, 1, a);
        const cbr::mesh::CheckReport r = cbr::mesh::check_mesh(m);
        CHECK(!r.ok());
    }
}

namespace {

// Whether THP can be asked for here (Linux with THP not "never").
bool huge_pages_offered() {
    std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    return std::getline(f, line) && line.find("[never]") == std::string::npos;
}

// The VmFlags of the mapping holding p (/proc/self/smaps), "" if none.
std::string mapping_flags(const void* p) {
    std::ifstream f("/proc/self/smaps");
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    bool inside = false;
    for (std::string line; std::getline(f, line);) {
        unsigned long long lo = 0, hi = 0;
        if (std::sscanf(line.c_str(), "%llx-%llx ", &lo, &hi) == 2) inside = lo <= at && at < hi;
        else if (inside && line.rfind("VmFlags:", 0) == 0) return line;
    }
    return "";
}

}  // namespace

TEST_CASE("large arrays: huge-page aligned and advised from 2 MiB, contents kept as they grow; reserve_huge advises") {
    using cbr::mesh::LargeArray;
    constexpr std::size_t kHuge = std::size_t{2} << 20;
    // Below 2 MiB: operator new, aligned for the type (a tetrahedron
    // record is 32-byte aligned).
    struct alignas(32) Record {
        std::uint32_t v[8];
    };
    LargeArray<Record> small(100);
    CHECK(reinterpret_cast<std::uintptr_t>(small.data()) % 32 == 0);
    // Grown one entry at a time across 2 MiB: every value kept.
    LargeArray<std::uint32_t> grown;
    for (std::uint32_t i = 0; i < (3 << 20) / 4; ++i) grown.push_back(i * 7u);
    bool kept = true;
    for (std::uint32_t i = 0; i < grown.size(); ++i) kept = kept && grown[i] == i * 7u;
    CHECK(kept);
    CHECK(reinterpret_cast<std::uintptr_t>(grown.data()) % kHuge == 0);
    // A copy is a large array too.
    const LargeArray<std::uint32_t> copy = grown;
    CHECK(copy == grown);
    CHECK(reinterpret_cast<std::uintptr_t>(copy.data()) % kHuge == 0);
#if defined(__linux__)
    if (!huge_pages_offered()) {
        MESSAGE("transparent huge pages not offered here: the advice is not checked");
        return;
    }
    const std::string flags = mapping_flags(copy.data());
    INFO("VmFlags: " << flags);
    CHECK(flags.find(" hg") != std::string::npos);  // MADV_HUGEPAGE
    // A plain vector reserved with reserve_huge: the whole huge pages
    // inside its storage are advised.
    std::vector<double> plain;
    cbr::mesh::reserve_huge(plain, std::size_t{1} << 20);  // 8 MiB
    REQUIRE(plain.capacity() >= std::size_t{1} << 20);
    const auto inside = (reinterpret_cast<std::uintptr_t>(plain.data()) + kHuge) / kHuge * kHuge;
    const std::string plain_flags = mapping_flags(reinterpret_cast<const void*>(inside));
    INFO("VmFlags: " << plain_flags);
    CHECK(plain_flags.find(" hg") != std::string::npos);
#endif
}
