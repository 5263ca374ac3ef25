// Mutated surfaces: a robustness sweep through the C API. Small valid
// closed surfaces (built in the tests, or fixtures of tests/data/recover)
// are each changed in one way that a broken file or a careless caller
// produces: a point moved anywhere, onto another triangle's edge or face,
// onto another point or next to it, a triangle turned over, dropped,
// repeated or made nearly flat, an id out of range or repeated, a NaN, a
// scale out of the supported range, a far offset. Whatever the change,
// the answer is one of three, each checked:
//
//   - recovered: proved with the project's exact checks
//     (recovery_checks.hpp: every input triangle a face, no inverted
//     tetrahedron, no Steiner point on an input triangle, regions apart
//     across each triangle, the enclosed volume filled);
//   - CBR_ERR_INVALID_INPUT with a message (from cbr_mesh_insert_points or
//     cbr_mesh_recover_faces);
//   - CBR_ERR_RECOVERY_FAILED naming triangles, the mesh left as Delaunay
//     left it.
//
// The first draw of each pair that recovers a closed surface goes on to
// mesh generation (cbr_mesh_refine), which must succeed and keep the same
// checks, none of its points on an input triangle.
//
// Never a crash, an internal error, another code or an unproved mesh; in
// CI's sanitizer build a read out of bounds on any of these inputs fails
// too. Where a change makes the input invalid for certain (identical
// points, a NaN, an id out of range, ...), the invalid-input answer is
// required; where it keeps the surface (a triangle turned over), recovery
// is. The changes are drawn from a fixed seed (SplitMix64, the same on
// every platform), so every run tries the same inputs.
#include <doctest/doctest.h>

#include <cbr/cbr.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "capi_test_util.hpp"
#include "hard_cases.hpp"
#include "recovery_checks.hpp"
#include "test_util.hpp"

namespace {

using cbr::test::Polyhedron;

// SplitMix64 (Steele, Lea & Flood 2014): a fixed sequence on every
// platform, unlike the standard distributions.
class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }

private:
    std::uint64_t state_;
};

enum class Expect {
    kAny,             // recovered, invalid input or recovery failed: each checked
    kInvalidPoints,   // cbr_mesh_insert_points must refuse the points
    kInvalidSurface,  // cbr_mesh_recover_faces must refuse the triangles
    kRecovered,       // the same surface: it must recover, filling the same volume
};

struct Mutation {
    const char* name;
    Expect expect;
    bool closes = true;  // the surface stays closed (regions apart across each triangle)
    std::function<void(Polyhedron&, Random&)> apply;
};

std::size_t point_count(const Polyhedron& p) { return p.xyz.size() / 3; }
std::size_t triangle_count(const Polyhedron& p) { return p.tris.size() / 3; }
double* point(Polyhedron& p, std::int64_t v) { return &p.xyz[3 * static_cast<std::size_t>(v)]; }
std::int64_t* triangle(Polyhedron& p, std::size_t t) { return &p.tris[3 * t]; }

// A point that is not a corner of triangle t.
std::int64_t point_off_triangle(Polyhedron& p, std::size_t t, Random& r) {
    const std::int64_t* f = triangle(p, t);
    for (;;) {
        const auto v = static_cast<std::int64_t>(r.below(point_count(p)));
        if (v != f[0] && v != f[1] && v != f[2]) return v;
    }
}

// Point v moved to a + s (b - a), rounded.
void put_on_line(Polyhedron& p, std::int64_t v, std::int64_t a, std::int64_t b, double s) {
    const double* pa = point(p, a);
    const double* pb = point(p, b);
    double* pv = point(p, v);
    for (int k = 0; k < 3; ++k) pv[k] = pa[k] + s * (pb[k] - pa[k]);
}

const std::vector<Mutation>& mutations() {
    static const std::vector<Mutation> list = {
        {"point moved anywhere in the box", Expect::kAny, true,
         [](Polyhedron& p, Random& r) {
             double lo[3], hi[3];
             for (int k = 0; k < 3; ++k) {
                 lo[k] = std::numeric_limits<double>::infinity();
                 hi[k] = -lo[k];
             }
             for (std::size_t i = 0; i < p.xyz.size(); ++i) {
                 lo[i % 3] = std::min(lo[i % 3], p.xyz[i]);
                 hi[i % 3] = std::max(hi[i % 3], p.xyz[i]);
             }
             double* v = point(p, static_cast<std::int64_t>(r.below(point_count(p))));
             for (int k = 0; k < 3; ++k) v[k] = lo[k] + r.uniform() * (hi[k] - lo[k]);
         }},
        {"point onto another triangle's edge", Expect::kAny, true,
         [](Polyhedron& p, Random& r) {
             const std::size_t t = r.below(triangle_count(p));
             const std::int64_t v = point_off_triangle(p, t, r);
             put_on_line(p, v, triangle(p, t)[0], triangle(p, t)[1], 0.5);
         }},
        {"point onto another triangle's centroid", Expect::kAny, true,
         [](Polyhedron& p, Random& r) {
             const std::size_t t = r.below(triangle_count(p));
             const std::int64_t v = point_off_triangle(p, t, r);
             const std::int64_t* f = triangle(p, t);
             double c[3];
             for (int k = 0; k < 3; ++k) c[k] = (point(p, f[0])[k] + point(p, f[1])[k] + point(p, f[2])[k]) / 3;
             std::copy_n(c, 3, point(p, v));
         }},
        {"point onto another point", Expect::kInvalidPoints, true,
         [](Polyhedron& p, Random& r) {
             const auto a = static_cast<std::int64_t>(r.below(point_count(p)));
             auto b = static_cast<std::int64_t>(r.below(point_count(p) - 1));
             if (b >= a) ++b;
             std::copy_n(point(p, b), 3, point(p, a));
         }},
        {"point next to another point", Expect::kAny, true,
         [](Polyhedron& p, Random& r) {
             const auto a = static_cast<std::int64_t>(r.below(point_count(p)));
             auto b = static_cast<std::int64_t>(r.below(point_count(p) - 1));
             if (b >= a) ++b;
             const double eps = std::pow(10.0, -15 + 7 * r.uniform());
             for (int k = 0; k < 3; ++k)
                 point(p, a)[k] = point(p, b)[k] * (1 + eps * (r.uniform() - 0.5)) + eps * (r.uniform() - 0.5);
         }},
        {"point moved by a few ulps", Expect::kAny, true,
         [](Polyhedron& p, Random& r) {
             double* v = point(p, static_cast<std::int64_t>(r.below(point_count(p))));
             for (int k = 0; k < 3; ++k) {
                 const int steps = static_cast<int>(r.below(9)) - 4;
                 for (int s = 0; s < std::abs(steps); ++s)
                     v[k] = std::nextafter(v[k], steps > 0 ? std::numeric_limits<double>::infinity()
                                                           : -std::numeric_limits<double>::infinity());
             }
         }},
        {"triangle made nearly flat", Expect::kAny, true,
         [](Polyhedron& p, Random& r) {
             const std::int64_t* f = triangle(p, r.below(triangle_count(p)));
             put_on_line(p, f[2], f[0], f[1], 0.1 + 0.8 * r.uniform());
         }},
        {"triangle turned over", Expect::kRecovered, true,
         [](Polyhedron& p, Random& r) {
             std::int64_t* f = triangle(p, r.below(triangle_count(p)));
             std::swap(f[0], f[1]);
         }},
        {"triangle dropped (open surface)", Expect::kAny, false,
         [](Polyhedron& p, Random& r) {
             const std::size_t t = r.below(triangle_count(p));
             p.tris.erase(p.tris.begin() + static_cast<std::ptrdiff_t>(3 * t),
                          p.tris.begin() + static_cast<std::ptrdiff_t>(3 * t + 3));
         }},
        {"triangle repeated", Expect::kInvalidSurface, true,
         [](Polyhedron& p, Random& r) {
             const std::int64_t* f = triangle(p, r.below(triangle_count(p)));
             const std::int64_t copy[3] = {f[1], f[2], f[0]};  // the same triangle, another first corner
             p.tris.insert(p.tris.end(), copy, copy + 3);
         }},
        {"id out of range", Expect::kInvalidSurface, true,
         [](Polyhedron& p, Random& r) {
             const std::int64_t bad[] = {static_cast<std::int64_t>(point_count(p)), -1,
                                         std::numeric_limits<std::int64_t>::max()};
             triangle(p, r.below(triangle_count(p)))[r.below(3)] = bad[r.below(3)];
         }},
        {"id repeated in a triangle", Expect::kInvalidSurface, true,
         [](Polyhedron& p, Random& r) {
             std::int64_t* f = triangle(p, r.below(triangle_count(p)));
             f[2] = f[r.below(2)];
         }},
        {"coordinate not finite", Expect::kInvalidPoints, true,
         [](Polyhedron& p, Random& r) {
             const double bad[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                   -std::numeric_limits<double>::infinity()};
             p.xyz[r.below(p.xyz.size())] = bad[r.below(3)];
         }},
        {"scaled beyond the supported range", Expect::kInvalidPoints, true,
         [](Polyhedron& p, Random& r) {
             const double scale = r.below(2) == 0 ? 1e60 : 1e-60;
             for (double& x : p.xyz) x *= scale;
         }},
        {"moved far from the origin", Expect::kAny, true,
         [](Polyhedron& p, Random& r) {
             const double offset = std::ldexp(1.0, 20 + static_cast<int>(r.below(25)));
             for (std::size_t i = 0; i < p.xyz.size(); ++i) p.xyz[i] += (i % 3 == 1 ? -offset : offset);
         }},
    };
    return list;
}

struct Base {
    const char* name;
    std::function<Polyhedron()> make;
};

std::function<Polyhedron()> fixture(const std::string& file) {
    return [file] {
        cbr::test::OffSurface s;
        REQUIRE(cbr::test::read_off(CBR_TEST_DATA_DIR "/recover/" + file, s));
        return Polyhedron{s.xyz, s.tris};
    };
}

// Closed, consistently oriented surfaces that bound one region each (so
// that the volume the triangles enclose is the domain's) and recover as
// they are (test_hard_cases.cpp).
const std::vector<Base>& bases() {
    static const std::vector<Base> list = {
        {"schonhardt-prism", cbr::test::schonhardt_prism},
        {"slit-cube", [] { return cbr::test::slit_cube(); }},
        {"chazelle-2", [] { return cbr::test::chazelle_polyhedron(2); }},
        {"csg-x-r19", fixture("csg-x-r19.off")},
        {"cylinder-turned-r3", fixture("cylinder-turned-r3.off")},
        {"prism-48-fan-caps-q4", fixture("prism-48-fan-caps-q4.off")},
    };
    return list;
}

// How each answer came out, per mutation (printed: what the sweep reached).
struct Tally {
    int recovered = 0, invalid = 0, failed = 0, refined = 0;
};

// Mesh generation (cbr_mesh_refine) on a recovered closed surface: it must
// succeed, keep every check of the recovered mesh, and put none of its
// points (field points, Steiner points kept) on an input triangle (exact).
void check_refined(cbr_mesh* m, const Polyhedron& p, double volume) {
    REQUIRE_MESSAGE(cbr_mesh_refine(m) == CBR_OK, cbr_mesh_last_error(m));
    cbr::test::check_recovered(m, p.xyz, p.tris, volume);
    const std::int64_t np = cbr_mesh_point_count(m);
    std::vector<double> xyz(3 * static_cast<std::size_t>(np));
    REQUIRE(cbr_mesh_get_points(m, xyz.data()) == CBR_OK);
    std::vector<std::int64_t> added;  // every point after the input's
    for (auto v = static_cast<std::int64_t>(point_count(p)); v < np; ++v) added.push_back(v);
    CHECK(cbr::test::points_on_triangles(xyz, added, p.tris) == 0);
}

constexpr int kDrawsPerPair = 3;

}  // namespace

TEST_CASE("mutated surfaces: recovered and proved, or refused with a clear error") {
    std::map<std::string, Tally> tally;
    std::uint64_t seed = 42;
    for (const Base& base : bases()) {
        const Polyhedron original = base.make();
        const long double original_volume = cbr::test::enclosed_volume(original.xyz, original.tris);
        REQUIRE(original_volume > 0);
        for (const Mutation& mutation : mutations()) {
            for (int draw = 0; draw < kDrawsPerPair; ++draw) {
                Random r(++seed);
                Polyhedron p = original;
                mutation.apply(p, r);
                const std::string what = std::string(base.name) + ", " + mutation.name + ", draw " +
                                         std::to_string(draw);
                CAPTURE(what);
                Tally& t = tally[mutation.name];
                const cbr::test::Handle h;
                cbr_mesh* m = h.m;
                const auto np = static_cast<std::int64_t>(point_count(p));
                const int inserted = cbr_mesh_insert_points(m, np, p.xyz.data());
                if (mutation.expect == Expect::kInvalidPoints) CHECK(inserted == CBR_ERR_INVALID_INPUT);
                if (inserted != CBR_OK) {
                    CHECK(inserted == CBR_ERR_INVALID_INPUT);
                    CHECK(!h.error().empty());
                    ++t.invalid;
                    continue;
                }
                const std::int64_t delaunay_tets = cbr_mesh_tet_count(m);
                const auto nt = static_cast<std::int64_t>(triangle_count(p));
                const int status = cbr_mesh_recover_faces(m, nt, p.tris.data(), nullptr);
                const std::string message = h.error();
                CAPTURE(message);
                switch (mutation.expect) {
                    case Expect::kInvalidPoints: break;  // checked above
                    case Expect::kInvalidSurface: CHECK(status == CBR_ERR_INVALID_INPUT); break;
                    case Expect::kRecovered: CHECK(status == CBR_OK); break;
                    case Expect::kAny: break;
                }
                if (status == CBR_OK) {
                    ++t.recovered;
                    // A triangle turned over leaves the domain as it was.
                    const double volume =
                        mutation.expect == Expect::kRecovered ? static_cast<double>(original_volume) : 0.0;
                    cbr::test::check_recovered(m, p.xyz, p.tris, volume, mutation.closes);
                    // The first draw of each pair goes on to a full mesh.
                    if (draw == 0 && mutation.closes) {
                        check_refined(m, p, volume);
                        ++t.refined;
                    }
                } else if (status == CBR_ERR_INVALID_INPUT) {
                    ++t.invalid;
                    CHECK(!message.empty());
                } else {
                    ++t.failed;
                    CHECK(status == CBR_ERR_RECOVERY_FAILED);
                    CHECK(cbr::test::contains(message, "could not recover triangle"));
                    CHECK(cbr_mesh_tet_count(m) == delaunay_tets);
                }
            }
        }
    }
    std::printf("%-40s %9s %7s %7s %6s\n", "mutation", "recovered", "refined", "invalid", "failed");
    for (const Mutation& mutation : mutations()) {
        const Tally& t = tally[mutation.name];
        std::printf("%-40s %9d %7d %7d %6d\n", mutation.name, t.recovered, t.refined, t.invalid, t.failed);
    }
}
