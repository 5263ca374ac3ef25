// Interior Steiner points that unblock flips (recover/unblocking_points):
// on Schonhardt-type prisms, which no flip can tetrahedralize, the points
// must be strictly off every input triangle, keep the mesh valid and every
// recovered face, and let the flips recover faces they could not before.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "delaunay/delaunay.hpp"
#include "geom/point_in_triangle.hpp"
#include "mesh/mesh_check.hpp"
#include "recover/constraint_faces.hpp"
#include "recover/flip_recovery.hpp"
#include "recover/recovery.hpp"
#include "recover/unblocking_points.hpp"
#include "hard_cases.hpp"
#include "test_util.hpp"

using cbr::mesh::TetMesh;
using cbr::mesh::VertexId;
using cbr::recover::ConstraintFaces;
using cbr::recover::Triangle;

namespace {

constexpr double kPi = 3.14159265358979323846;

// `levels` prisms (Schonhardt's when levels = 1 and twist = 30 degrees),
// only the bottom and top triangles between them faces.
cbr::test::Polyhedron twisted_prism(int levels, double twist, double radius = 1.0) {
    return cbr::test::twisted_prisms(levels + 1, twist, false, radius);
}

struct Built {
    std::unique_ptr<cbr::delaunay::Delaunay> d = std::make_unique<cbr::delaunay::Delaunay>();
    std::unique_ptr<ConstraintFaces> faces;
    std::size_t input_count = 0;
    TetMesh& m() { return d->mesh_for_update(); }
};

void build(Built& c, const cbr::test::Polyhedron& p) {
    c.input_count = p.xyz.size() / 3;
    REQUIRE(c.d->insert_points(p.xyz.data(), c.input_count).ok);
    std::vector<Triangle> t;
    for (std::size_t i = 0; i + 2 < p.tris.size(); i += 3)
        t.push_back({c.d->internal_id(static_cast<VertexId>(p.tris[i])),
                     c.d->internal_id(static_cast<VertexId>(p.tris[i + 1])),
                     c.d->internal_id(static_cast<VertexId>(p.tris[i + 2]))});
    c.faces = std::make_unique<ConstraintFaces>(std::move(t), std::vector<std::int32_t>{});
}

bool on_some_input_triangle(const TetMesh& m, const ConstraintFaces& faces, VertexId v) {
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const Triangle& t = faces.triangle(i);
        if (cbr::geom::point_in_triangle(m.point(v), m.point(t[0]), m.point(t[1]), m.point(t[2]))) return true;
    }
    return false;
}

}  // namespace

TEST_CASE("unblocking points: Schonhardt-type prisms, then flips") {
    struct Variant {
        const char* name;
        cbr::test::Polyhedron p;
    };
    const std::vector<Variant> variants = {
        {"Schonhardt prism", cbr::test::schonhardt_prism()},
        {"twist 25 degrees", twisted_prism(1, 25 * kPi / 180)},
        {"twist 20 degrees, radius 2", twisted_prism(1, 20 * kPi / 180, 2.0)},
        {"stack of three", twisted_prism(3, kPi / 6)},
    };
    for (const Variant& v : variants) {
        INFO(std::string(v.name));
        Built c;
        build(c, v.p);
        TetMesh& m = c.m();
        const std::vector<std::size_t> missing = cbr::recover::mark_present_faces(m, *c.faces);
        const std::vector<std::size_t> after_flips = cbr::recover::recover_by_flips(m, *c.faces, missing);
        REQUIRE_FALSE(after_flips.empty());  // flips alone cannot: that is the point
        const auto input = m.coordinates();

        std::vector<VertexId> steiner;
        const std::size_t made = cbr::recover::insert_unblocking_points(m, *c.faces, after_flips, steiner).kept;
        CHECK(made > 0);
        REQUIRE(steiner.size() == made);
        // Ids after the input ones, in order; input points untouched.
        for (std::size_t i = 0; i < steiner.size(); ++i) CHECK(steiner[i] == c.input_count + i);
        CHECK(m.vertex_count() == c.input_count + made);
        CHECK(std::equal(input.begin(), input.end(), m.coordinates().begin()));
        for (VertexId s : steiner) CHECK_FALSE(on_some_input_triangle(m, *c.faces, s));
        const cbr::mesh::CheckReport report = cbr::mesh::check_mesh(m);
        REQUIRE_MESSAGE(report.ok(), (report.errors.empty() ? std::string() : report.errors[0]));
        // Every face recovered before is still a face.
        const std::vector<std::size_t> now = cbr::recover::mark_present_faces(m, *c.faces);
        CHECK(std::includes(after_flips.begin(), after_flips.end(), now.begin(), now.end()));

        // The flips now recover every face, with no point on the surface.
        const std::vector<std::size_t> left = cbr::recover::recover_by_flips(m, *c.faces, now);
        CHECK_MESSAGE(left.empty(), left.size() << " of " << after_flips.size() << " still missing, " << made
                                                << " points");
        CHECK(cbr::mesh::check_mesh(m).ok());
    }
}

TEST_CASE("recover_faces: the Schonhardt prism recovers through unblocking points alone") {
    Built c;
    build(c, cbr::test::schonhardt_prism());
    cbr::recover::RecoveryStats stats;
    const cbr::recover::RecoveryResult r = cbr::recover::recover_faces(c.m(), *c.faces, stats);
    REQUIRE_MESSAGE(r.ok, r.why);
    CHECK(stats.conforming_points == 0);  // no point ever put on the surface
    CHECK(stats.steiner_generated >= stats.steiner_remaining);
    CHECK(stats.steiner_remaining == r.steiner.size());
    CHECK(stats.steiner_remaining >= 1);  // Schonhardt: one must stay
    for (VertexId s : r.steiner) CHECK_FALSE(on_some_input_triangle(c.m(), *c.faces, s));
}
