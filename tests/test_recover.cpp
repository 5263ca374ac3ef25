// Boundary recovery, the parts that do not need flips yet: constraint faces
// found after Delaunay, region classification, missing faces reported.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <random>
#include <set>

#include "delaunay/delaunay.hpp"
#include "geom/intersect.hpp"
#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/mesh_check.hpp"
#include "recover/constraint_faces.hpp"
#include "recover/recovery.hpp"
#include "recover/regions.hpp"
#include "recover/segment_crossings.hpp"
#include "recover/segment_search.hpp"
#include "recover/segment_walk.hpp"
#include "geom/point_in_triangle.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh_test_util.hpp"
#include "test_util.hpp"

using cbr::mesh::TetId;
using cbr::mesh::TetMesh;
using cbr::mesh::VertexId;
using cbr::recover::ConstraintFaces;
using cbr::recover::Triangle;

namespace {

// The faces between tetrahedra inside and outside `inside`, oriented with
// their normal pointing out of `inside`: a closed surface whose every
// triangle is a face of the mesh.
std::vector<Triangle> boundary_of(const TetMesh& m, const std::vector<char>& inside,
                                  std::vector<TetId>* inner_tets = nullptr) {
    std::vector<Triangle> tris;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t) || !inside[t]) continue;
        for (int f = 0; f < 4; ++f) {
            const TetId n = cbr::mesh::facet_tet(m.neighbor(t, f));
            if (inside[n]) continue;
            const VertexId* v = m.vertices(t);
            // kFaceVertices faces into t: reverse it to face out.
            tris.push_back({v[cbr::mesh::kFaceVertices[f][0]], v[cbr::mesh::kFaceVertices[f][2]],
                            v[cbr::mesh::kFaceVertices[f][1]]});
            if (inner_tets) inner_tets->push_back(t);
        }
    }
    return tris;
}

std::vector<char> tets_within(const TetMesh& m, const double centre[3], double radius) {
    std::vector<char> inside(m.slot_count(), 0);
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t) || m.is_ghost(t)) continue;
        double c[3] = {0, 0, 0};
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 3; ++k) c[k] += m.point(m.vertex(t, i))[k] / 4;
        const double d2 = (c[0] - centre[0]) * (c[0] - centre[0]) + (c[1] - centre[1]) * (c[1] - centre[1]) +
                          (c[2] - centre[2]) * (c[2] - centre[2]);
        inside[t] = d2 < radius * radius;
    }
    return inside;
}

double volume(const TetMesh& m, TetId t) {
    const double* a = m.point(m.vertex(t, 0));
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = m.point(m.vertex(t, 1))[k] - a[k];
        v[k] = m.point(m.vertex(t, 2))[k] - a[k];
        w[k] = m.point(m.vertex(t, 3))[k] - a[k];
    }
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6;
}

}  // namespace

TEST_CASE("a surface made of Delaunay faces is recovered as is, and its regions found") {
    cbr::delaunay::Delaunay d;
    const auto xyz = cbr::test::random_points(3000, 77);
    REQUIRE(d.insert_points(xyz.data(), 3000).ok);
    TetMesh& m = d.mesh_for_update();
    const double centre[3] = {0.5, 0.5, 0.5};
    const std::vector<char> inside = tets_within(m, centre, 0.3);
    const ConstraintFaces faces(boundary_of(m, inside), {});
    REQUIRE(faces.size() > 100);

    cbr::recover::RecoveryStats stats;
    const auto result = cbr::recover::recover_faces(m, faces, stats);
    CHECK(result.ok);
    CHECK(stats.missing_faces == 0);
    CHECK(result.unrecovered.empty());

    const auto regions = cbr::recover::classify_regions(m, faces);
    REQUIRE(regions.count >= 2);
    double inside_volume = 0, region_volume = 0;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        if (m.is_ghost(t)) {
            CHECK(regions.of_tet[t] == 0);
            continue;
        }
        if (inside[t]) inside_volume += volume(m, t);
        if (regions.of_tet[t] > 0) region_volume += volume(m, t);
        // Across an input triangle the regions differ; elsewhere they agree.
        for (int f = 0; f < 4; ++f) {
            const TetId n = cbr::mesh::facet_tet(m.neighbor(t, f));
            if (m.is_constrained(t, f)) CHECK(regions.of_tet[t] != regions.of_tet[n]);
            else CHECK(regions.of_tet[t] == regions.of_tet[n]);
        }
        // Constraint marks are exactly the input triangles.
        for (int f = 0; f < 4; ++f) {
            const VertexId* v = m.vertices(t);
            const bool is_input = faces.find(v[cbr::mesh::kFaceVertices[f][0]], v[cbr::mesh::kFaceVertices[f][1]],
                                             v[cbr::mesh::kFaceVertices[f][2]]) != ConstraintFaces::npos;
            CHECK(m.is_constrained(t, f) == is_input);
        }
    }
    CHECK(region_volume == doctest::Approx(inside_volume).epsilon(1e-12));
}

TEST_CASE("facets_of_mesh: which triangles are faces of the mesh, whatever their ids, and where") {
    // The boundary of a ball of tetrahedra (every triangle a face), in
    // either orientation, mixed with triangles that are not faces (a face's
    // vertices with one replaced, all combinations of a tetrahedron's
    // vertices with an outside one), a triangle twice, ids out of range, a
    // repeated id and the ghost vertex. Checked against the faces of the
    // live tetrahedra, listed one by one.
    cbr::delaunay::Delaunay d;
    const auto xyz = cbr::test::random_points(1500, 91);
    REQUIRE(d.insert_points(xyz.data(), 1500).ok);
    const TetMesh& m = d.mesh();
    const double centre[3] = {0.5, 0.5, 0.5};
    std::vector<Triangle> tris = boundary_of(m, tets_within(m, centre, 0.3));
    const std::size_t boundary = tris.size();
    REQUIRE(boundary > 50);
    for (std::size_t i = 0; i < boundary; i += 3) {
        tris.push_back({tris[i][0], tris[i][2], tris[i][1]});
        tris.push_back({tris[i][0], tris[i][1], static_cast<VertexId>((tris[i][2] + 7) % 1500)});
    }
    tris.push_back(tris[0]);
    tris.push_back({0, 1, 1500});
    tris.push_back({2, 2, 3});
    tris.push_back({tris[1][0], tris[1][1], cbr::mesh::kGhostVertex});
    std::set<std::array<VertexId, 3>> faces;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        for (int f = 0; f < 4; ++f) {
            const VertexId* v = m.vertices(t);
            std::array<VertexId, 3> k = {v[cbr::mesh::kFaceVertices[f][0]], v[cbr::mesh::kFaceVertices[f][1]],
                                         v[cbr::mesh::kFaceVertices[f][2]]};
            std::sort(k.begin(), k.end());
            if (k[2] != cbr::mesh::kGhostVertex) faces.insert(k);
        }
    }
    const std::vector<cbr::mesh::FacetRef> facet = cbr::recover::facets_of_mesh(m, tris);
    REQUIRE(facet.size() == tris.size());
    std::size_t found = 0, not_found = 0;
    for (std::size_t i = 0; i < tris.size(); ++i) {
        std::array<VertexId, 3> k = tris[i];
        std::sort(k.begin(), k.end());
        const bool expected = faces.count(k) > 0;
        CHECK_MESSAGE((facet[i] != cbr::recover::kNoFacet) == expected, "triangle " << i);
        (expected ? found : not_found) += 1;
        if (facet[i] == cbr::recover::kNoFacet) continue;
        // The facet holds the triangle.
        const TetId t = cbr::mesh::facet_tet(facet[i]);
        REQUIRE(!m.is_free(t));
        const VertexId* v = m.vertices(t);
        const int* f = cbr::mesh::kFaceVertices[cbr::mesh::facet_face(facet[i])];
        std::array<VertexId, 3> held = {v[f[0]], v[f[1]], v[f[2]]};
        std::sort(held.begin(), held.end());
        CHECK_MESSAGE(held == k, "triangle " << i);
    }
    CHECK(found >= boundary + boundary / 3 + 1);  // both orientations and the copy
    CHECK(not_found >= 4);
    CHECK(facet.back() == cbr::recover::kNoFacet);
}

TEST_CASE("mark_present_faces: from the facets found, as by the scan") {
    // Half the boundary of a ball of tetrahedra (present) and triangles
    // that are not faces (missing): the marks and the missing list from
    // facets_of_mesh equal the scan's; a stale facet (of a triangle that is
    // not the one given) falls back to the scan.
    cbr::delaunay::Delaunay d;
    const auto xyz = cbr::test::random_points(800, 17);
    REQUIRE(d.insert_points(xyz.data(), 800).ok);
    const double centre[3] = {0.5, 0.5, 0.5};
    std::vector<Triangle> tris = boundary_of(d.mesh(), tets_within(d.mesh(), centre, 0.25));
    REQUIRE(tris.size() > 40);
    tris.resize(tris.size() / 2);
    for (VertexId a = 0; a + 2 < 60; a += 3) tris.push_back({a, static_cast<VertexId>(a + 200), static_cast<VertexId>(a + 400)});
    // Distinct triangles only (ConstraintFaces' contract).
    std::set<std::array<VertexId, 3>> seen;
    std::vector<Triangle> distinct;
    for (const Triangle& t : tris) {
        std::array<VertexId, 3> k = t;
        std::sort(k.begin(), k.end());
        if (seen.insert(k).second) distinct.push_back(t);
    }
    const cbr::recover::ConstraintFaces faces(distinct, {});
    const auto constrained = [](const TetMesh& m) {
        std::vector<char> marks;
        for (TetId t = 0; t < m.slot_count(); ++t)
            for (int f = 0; f < 4; ++f) marks.push_back(!m.is_free(t) && m.is_constrained(t, f));
        return marks;
    };
    TetMesh by_scan = d.mesh(), by_facets = d.mesh(), stale = d.mesh();
    const std::vector<std::size_t> missing = cbr::recover::mark_present_faces(by_scan, faces);
    const std::vector<cbr::mesh::FacetRef> found = cbr::recover::facets_of_mesh(d.mesh(), distinct);
    CHECK(cbr::recover::mark_present_faces(by_facets, faces, &found) == missing);
    CHECK(constrained(by_facets) == constrained(by_scan));
    CHECK(missing.size() >= 10);
    CHECK(missing.size() < distinct.size());
    // A facet that holds another triangle: not trusted.
    std::vector<cbr::mesh::FacetRef> wrong = found;
    const std::size_t present = std::find_if(wrong.begin(), wrong.end(),
                                             [](cbr::mesh::FacetRef r) { return r != cbr::recover::kNoFacet; }) -
                                wrong.begin();
    REQUIRE(present < wrong.size());
    wrong[present] = wrong[present] ^ 1u;  // the next face of the same tetrahedron
    CHECK(cbr::recover::mark_present_faces(stale, faces, &wrong) == missing);
    CHECK(constrained(stale) == constrained(by_scan));
}

TEST_CASE("input triangles are found by their vertices, and their edges by their ends") {
    // A fan of 40 triangles around hub 0 (its 40 edges: the lookup's long
    // list), listed out of order, each rim edge shared by two triangles,
    // and a strip whose ids are not in ascending order; vertex 41 is used
    // by no triangle.
    std::vector<Triangle> tris;
    constexpr VertexId kRim = 40;
    for (VertexId j = 0; j < kRim; ++j) {
        const VertexId i = (7 * j) % kRim + 1;
        tris.push_back({0, i, i % kRim + 1});
    }
    for (VertexId i = 1; i <= kRim; ++i) tris.push_back({i % kRim + 1, i, 45});
    tris.push_back({47, 43, 44});
    tris.push_back({44, 46, 42});
    const ConstraintFaces faces(tris, {});
    std::set<std::pair<VertexId, VertexId>> edges;
    for (const auto& t : tris)
        for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    // Every pair of ids, both orders, against the set of edges.
    for (VertexId a = 0; a < 50; ++a)
        for (VertexId b = 0; b < 50; ++b) {
            const bool expected = edges.count(std::minmax(a, b)) > 0;
            if (faces.has_edge(a, b) != expected) FAIL_CHECK("edge " << a << "-" << b << ": expected " << expected);
        }
    CHECK(faces.has_edge(0, 40));
    CHECK(faces.has_edge(46, 44));
    CHECK_FALSE(faces.has_edge(0, 45));
    CHECK_FALSE(faces.has_edge(41, 42));
    CHECK_FALSE(faces.has_edge(0, cbr::mesh::kGhostVertex));
    CHECK_FALSE(faces.has_edge(cbr::mesh::kGhostVertex, 44));
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const auto& t = tris[i];
        CHECK(faces.find(t[2], t[0], t[1]) == i);
        CHECK(faces.find(t[1], t[0], t[2]) == i);
    }
    CHECK(faces.find(0, 1, 3) == ConstraintFaces::npos);
}

TEST_CASE("region numbers follow the input, not the storage") {
    // Two disjoint balls of tetrahedra: the one bounded by triangle 0 on its
    // normal's side is region 1.
    cbr::delaunay::Delaunay d;
    const auto xyz = cbr::test::random_points(4000, 5);
    REQUIRE(d.insert_points(xyz.data(), 4000).ok);
    TetMesh& m = d.mesh_for_update();
    const double c1[3] = {0.25, 0.5, 0.5}, c2[3] = {0.75, 0.5, 0.5};
    std::vector<char> in1 = tets_within(m, c1, 0.15), in2 = tets_within(m, c2, 0.15);
    std::vector<TetId> behind2, behind1;
    std::vector<Triangle> tris = boundary_of(m, in2, &behind2);
    const std::vector<Triangle> first = boundary_of(m, in1, &behind1);
    tris.insert(tris.end(), first.begin(), first.end());
    const ConstraintFaces faces(tris, {});
    cbr::recover::RecoveryStats stats;
    REQUIRE(cbr::recover::recover_faces(m, faces, stats).ok);
    const auto regions = cbr::recover::classify_regions(m, faces);
    // Ball 2 is listed first: the tetrahedron behind triangle 0 (on side 1,
    // the normals point out) is region 1; ball 1 comes later.
    CHECK(regions.of_tet[behind2.front()] == 1);
    CHECK(regions.of_tet[behind1.front()] > 1);
    // Classifying again gives the same numbers (no dependence on state).
    CHECK(cbr::recover::classify_regions(m, faces).of_tet == regions.of_tet);
}

TEST_CASE("the Schonhardt prism: flips are not enough; splitting leaves a Steiner point inside") {
    const cbr::test::Polyhedron prism = cbr::test::schonhardt_prism();
    cbr::delaunay::Delaunay d;
    REQUIRE(d.insert_points(prism.xyz.data(), 6).ok);
    std::vector<Triangle> tris;
    for (std::size_t i = 0; i < prism.tris.size(); i += 3) {
        Triangle t;
        for (int k = 0; k < 3; ++k) t[k] = d.internal_id(static_cast<VertexId>(prism.tris[i + k]));
        tris.push_back(t);
    }
    const ConstraintFaces faces(tris, {});
    cbr::recover::RecoveryStats stats;
    const auto result = cbr::recover::recover_faces(d.mesh_for_update(), faces, stats);
    REQUIRE(result.ok);
    CHECK(result.unrecovered.empty());
    CHECK(result.invalid.empty());
    // Flips recover some faces, never all: the prism needs a Steiner point
    // (an interior point that unblocks the flips, or conforming recovery's
    // added points split off the surface).
    CHECK(stats.missing_faces > stats.recovered_by_flips);
    CHECK(stats.steiner_generated > 0);
    CHECK(stats.steiner_generated >= stats.steiner_remaining);
    REQUIRE(stats.steiner_remaining >= 1);
    // Steiner points follow the input points, and every vertex is used.
    const TetMesh& m = d.mesh();
    REQUIRE(result.steiner.size() == stats.steiner_remaining);
    CHECK(m.vertex_count() == 6 + result.steiner.size());
    for (std::size_t k = 0; k < result.steiner.size(); ++k) CHECK(result.steiner[k] == 6 + k);
    std::set<VertexId> used;
    std::set<std::size_t> present;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        const VertexId* v = m.vertices(t);
        for (int i = 0; i < 4; ++i) used.insert(v[i]);
        for (int f = 0; f < 4; ++f) {
            const std::size_t i = faces.find(v[cbr::mesh::kFaceVertices[f][0]], v[cbr::mesh::kFaceVertices[f][1]],
                                             v[cbr::mesh::kFaceVertices[f][2]]);
            if (i != ConstraintFaces::npos) present.insert(i);
        }
    }
    CHECK(used.size() == m.vertex_count() + 1);  // the ghost vertex too
    CHECK(present.size() == faces.size());
    // Strictly off every input triangle, and inside the prism (a Steiner
    // point outside would not help the prism).
    for (VertexId s : result.steiner)
        for (const Triangle& t : tris)
            CHECK_FALSE(cbr::geom::point_in_triangle(m.point(s), m.point(t[0]), m.point(t[1]), m.point(t[2])));
    CHECK(cbr::mesh::check_mesh(m).ok());
}

// classify_segment_face (recover/segment_walk) answers a face at one end of
// the segment with one orientation: it must give classify_segment_triangle's
// kind on every face and segment, including faces at an end whose plane
// holds the other end (on a grid, many), where it must not take the
// shortcut.
TEST_CASE("classify_segment_face gives classify_segment_triangle's kind, shortcut or not") {
    for (const bool grid : {true, false}) {
        CAPTURE(grid);
        const std::vector<double> xyz = grid ? cbr::test::grid_points(4) : cbr::test::random_points(60, 46);
        const TetMesh m = cbr::test::delaunay_mesh(xyz);
        const VertexId n = static_cast<VertexId>(m.vertex_count());
        std::mt19937_64 rng(7);
        std::size_t at_one_end = 0, in_plane = 0, compared = 0;
        for (int pair = 0; pair < 200; ++pair) {
            const VertexId u = static_cast<VertexId>(rng() % n);
            VertexId w = static_cast<VertexId>(rng() % n);
            if (w == u) w = (w + 1) % n;
            for (TetId t = 0; t < m.slot_count(); ++t) {
                if (m.is_free(t) || m.is_ghost(t)) continue;
                for (int f = 0; f < 4; ++f) {
                    const int* k = cbr::mesh::kFaceVertices[f];
                    const VertexId a = m.vertex(t, k[0]), b = m.vertex(t, k[1]), c = m.vertex(t, k[2]);
                    const bool at_u = a == u || b == u || c == u, at_w = a == w || b == w || c == w;
                    if (at_u != at_w) {
                        ++at_one_end;
                        if (cbr::geom::orient3d(m.point(a), m.point(b), m.point(c), m.point(at_u ? w : u)) == 0)
                            ++in_plane;
                    }
                    const auto expected =
                        cbr::geom::classify_segment_triangle(m.point(u), m.point(w), m.point(a), m.point(b),
                                                             m.point(c))
                            .kind;
                    const auto got = cbr::recover::classify_segment_face(m, u, w, a, b, c);
                    if (got != expected) {
                        CAPTURE(u);
                        CAPTURE(w);
                        CAPTURE(t);
                        CAPTURE(f);
                        CHECK(static_cast<int>(got) == static_cast<int>(expected));
                    }
                    ++compared;
                }
            }
        }
        MESSAGE("compared " << compared << ", at one end " << at_one_end << ", in its plane " << in_plane);
        CHECK(at_one_end > 0);
        if (grid) CHECK(in_plane > 0);  // the fallback is exercised
    }
}

namespace {

using cbr::recover::Crossing;

// SegmentSearch written the plain way: each face classified from every
// side. The tetrahedra searched in order, each with its face bits.
std::vector<std::pair<TetId, unsigned>> search_the_plain_way(const TetMesh& m, VertexId u, TetId start, VertexId w,
                                                             bool through_constraints, std::size_t max_tets) {
    using cbr::recover::SegmentSearch;
    std::vector<std::pair<TetId, unsigned>> out;
    std::vector<TetId> near;
    if (!cbr::mesh::ball(m, u, start, near)) return out;
    std::set<TetId> seen(near.begin(), near.end());
    for (std::size_t i = 0; i < near.size() && near.size() < max_tets; ++i) {
        const TetId t = near[i];
        if (m.is_ghost(t)) continue;
        const VertexId* v = m.vertices(t);
        unsigned bits = 0;
        for (int f = 0; f < 4; ++f) {
            const int* k = cbr::mesh::kFaceVertices[f];
            const auto kind = cbr::recover::classify_segment_face(m, u, w, v[k[0]], v[k[1]], v[k[2]]);
            if (kind == cbr::geom::SegTriKind::Disjoint || kind == cbr::geom::SegTriKind::EndpointVertex) continue;
            bits |= unsigned{SegmentSearch::kMeets} << (2 * f);
            if (kind == cbr::geom::SegTriKind::CrossInterior) bits |= unsigned{SegmentSearch::kCrossesInterior} << (2 * f);
            if (!through_constraints && m.is_constrained(t, f)) continue;
            const TetId n = cbr::mesh::facet_tet(m.neighbor(t, f));
            if (seen.insert(n).second) near.push_back(n);
        }
        out.push_back({t, bits});
    }
    return out;
}

// SegmentCrossings written the plain way, on the plain search (through
// constraint faces): per tetrahedron its faces crossed in their interior,
// then every edge tested the first time it is met.
std::vector<Crossing> crossings_the_plain_way(const TetMesh& m, VertexId u, TetId start, VertexId w,
                                              std::size_t max_tets) {
    using cbr::recover::SegmentSearch;
    std::vector<Crossing> out;
    std::set<std::pair<VertexId, VertexId>> tried;
    const double* pu = m.point(u);
    const double* pw = m.point(w);
    for (const auto& [t, bits] : search_the_plain_way(m, u, start, w, true, max_tets)) {
        for (int f = 0; f < 4; ++f)
            if ((bits >> (2 * f)) & SegmentSearch::kCrossesInterior) {
                Crossing c{};
                c.kind = Crossing::kFace;
                c.tet = t;
                c.face = f;
                out.push_back(c);
            }
        const VertexId* v = m.vertices(t);
        for (int i0 = 0; i0 < 4; ++i0)
            for (int i1 = i0 + 1; i1 < 4; ++i1) {
                const VertexId x = v[i0], y = v[i1];
                if (x == u || x == w || y == u || y == w) continue;
                if (!tried.insert({std::min(x, y), std::max(x, y)}).second) continue;
                const double* px = m.point(x);
                const double* py = m.point(y);
                if (cbr::geom::orient3d(pu, pw, px, py) != 0 || cbr::geom::collinear(pu, pw, px) ||
                    cbr::geom::collinear(pu, pw, py) ||
                    cbr::geom::classify_coplanar_segments(pu, pw, px, py) != cbr::geom::SegSegKind::Point)
                    continue;
                Crossing c{};
                c.kind = Crossing::kEdge;
                c.tet = t;
                c.x = x;
                c.y = y;
                out.push_back(c);
            }
    }
    return out;
}

bool same_crossing(const Crossing& a, const Crossing& b) {
    return a.kind == b.kind && a.tet == b.tet && a.face == b.face && a.x == b.x && a.y == b.y;
}

}  // namespace

// SegmentSearch reads a face's bits from the side searched first: the
// tetrahedra it visits, their order and their bits must be the plain
// search's, across constraint faces or stopping at them (a random tenth
// of the faces marked), capped or not. One searcher for every segment.
TEST_CASE("SegmentSearch visits what the plain search visits, with the same face bits") {
    cbr::recover::SegmentSearch search;
    for (const bool grid : {true, false}) {
        CAPTURE(grid);
        TetMesh m = cbr::test::delaunay_mesh(grid ? cbr::test::grid_points(5) : cbr::test::random_points(150, 53));
        std::mt19937_64 rng(grid ? 13 : 14);
        for (TetId t = 0; t < m.slot_count(); ++t)
            for (int f = 0; f < 4; ++f)
                if (!m.is_free(t) && rng() % 10 == 0) {
                    const cbr::mesh::FacetRef r = m.neighbor(t, f);
                    m.set_constrained(t, f, true);
                    m.set_constrained(cbr::mesh::facet_tet(r), cbr::mesh::facet_face(r), true);
                }
        const std::vector<TetId> incident = cbr::mesh::incident_tets(m);
        const VertexId n = static_cast<VertexId>(m.vertex_count());
        std::size_t visited = 0, stopped_short = 0;
        for (int pair = 0; pair < 400; ++pair) {
            const VertexId u = static_cast<VertexId>(rng() % n);
            VertexId w = static_cast<VertexId>(rng() % n);
            if (w == u) w = (w + 1) % n;
            const bool through = pair % 2 == 0;
            const std::size_t cap = pair % 3 == 0 ? 12 : 4096;
            CAPTURE(u);
            CAPTURE(w);
            CAPTURE(through);
            CAPTURE(cap);
            const auto expected = search_the_plain_way(m, u, incident[u], w, through, cap);
            std::vector<std::pair<TetId, unsigned>> got;
            REQUIRE(search.run(m, u, incident[u], w, {through, cap},
                               [&](TetId t, cbr::recover::SegmentSearch::FaceBits bits) { got.push_back({t, bits}); }));
            CHECK(got == expected);
            visited += got.size();
            if (!through && got.size() < search_the_plain_way(m, u, incident[u], w, true, cap).size()) ++stopped_short;
        }
        MESSAGE("tetrahedra visited " << visited << ", searches cut by a constraint face " << stopped_short);
        CHECK(visited > 1000);
        CHECK(stopped_short > 10);  // the marks do stop searches
    }
}

// SegmentCrossings classifies a face shared by two tetrahedra once and
// tests an edge only where both faces of the tetrahedron that hold it meet
// the segment: the list (and so flip recovery's order of tries) must be
// the plain search's, crossing for crossing, on scattered points and on a
// grid (segments through edges and along faces), with and without a cap on
// the tetrahedra searched. One searcher for every segment: its marks and
// face records are reused.
TEST_CASE("SegmentCrossings lists the crossings of the plain search, in its order") {
    cbr::recover::SegmentCrossings search;
    for (const bool grid : {true, false}) {
        CAPTURE(grid);
        const TetMesh m = cbr::test::delaunay_mesh(grid ? cbr::test::grid_points(5) : cbr::test::random_points(150, 52));
        const std::vector<TetId> incident = cbr::mesh::incident_tets(m);
        const VertexId n = static_cast<VertexId>(m.vertex_count());
        std::mt19937_64 rng(grid ? 11 : 12);
        std::size_t faces = 0, edges = 0;
        for (int pair = 0; pair < 400; ++pair) {
            const VertexId u = static_cast<VertexId>(rng() % n);
            VertexId w = static_cast<VertexId>(rng() % n);
            if (w == u) w = (w + 1) % n;
            const std::size_t cap = pair % 4 == 0 ? 12 : 4096;
            CAPTURE(u);
            CAPTURE(w);
            CAPTURE(cap);
            const std::vector<Crossing> expected = crossings_the_plain_way(m, u, incident[u], w, cap);
            REQUIRE(search.find(m, u, incident[u], w, cap));
            const std::vector<Crossing>& got = search.crossings();
            REQUIRE(got.size() == expected.size());
            for (std::size_t i = 0; i < got.size(); ++i) {
                CAPTURE(i);
                CHECK(same_crossing(got[i], expected[i]));
                (got[i].kind == Crossing::kFace ? faces : edges) += 1;
            }
        }
        MESSAGE("faces crossed " << faces << ", edges crossed " << edges);
        CHECK(faces > 100);
        if (grid) CHECK(edges > 100);  // scattered points put no edge in a segment's plane
    }
}
