// Exact segment/triangle and triangle/triangle classification (geom/intersect).
//
// Three layers: hand-made configurations for every kind (each checked under
// all vertex relabellings and both segment directions), exactness cases one
// ulp away from degeneracy, and a randomized cross-check on small integer
// coordinates against an independent reference that computes the
// intersection explicitly in exact integer/rational arithmetic.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "geom/intersect.hpp"
#include "geom/segment_point.hpp"

namespace {

using cbr::geom::SegSegKind;
using cbr::geom::SegTriKind;
using cbr::geom::SegTriResult;
using P = std::array<double, 3>;
using Tri = std::array<P, 3>;

SegTriResult seg_tri(const P& p, const P& q, const Tri& t) {
    return cbr::geom::classify_segment_triangle(p.data(), q.data(), t[0].data(), t[1].data(),
                                                t[2].data());
}

bool tri_tri(const Tri& t, const Tri& u, int shared) {
    const double* tp[3] = {t[0].data(), t[1].data(), t[2].data()};
    const double* up[3] = {u[0].data(), u[1].data(), u[2].data()};
    return cbr::geom::triangles_meet_illegally(tp, up, shared);
}

SegSegKind seg_seg(const P& p, const P& q, const P& r, const P& s) {
    return cbr::geom::classify_coplanar_segments(p.data(), q.data(), r.data(), s.data());
}

// The triangle vertices a result points at, as labels of the original order.
std::vector<int> feature_labels(const SegTriResult& r, const std::array<int, 3>& perm) {
    std::vector<int> out;
    switch (r.kind) {
        case SegTriKind::CrossVertex:
        case SegTriKind::EndpointVertex: out = {perm[r.feature]}; break;
        case SegTriKind::CrossEdge:
        case SegTriKind::EndpointEdge: out = {perm[r.feature], perm[(r.feature + 1) % 3]}; break;
        default: break;
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Classifies pq against t under all 6 vertex orders and both directions of
// pq; every answer must describe the same kind, feature and endpoint.
void expect_seg_tri(const P& p, const P& q, const Tri& t, SegTriKind kind,
                    std::vector<int> features = {}, int endpoint = -1) {
    std::sort(features.begin(), features.end());
    std::array<int, 3> perm = {0, 1, 2};
    do {
        const Tri tp = {t[perm[0]], t[perm[1]], t[perm[2]]};
        for (int dir = 0; dir < 2; ++dir) {
            const SegTriResult r = dir == 0 ? seg_tri(p, q, tp) : seg_tri(q, p, tp);
            CAPTURE(perm[0]);
            CAPTURE(perm[1]);
            CAPTURE(dir);
            CHECK(static_cast<int>(r.kind) == static_cast<int>(kind));
            CHECK(feature_labels(r, perm) == features);
            const int expected_endpoint = endpoint < 0 ? -1 : (dir == 0 ? endpoint : 1 - endpoint);
            CHECK(r.endpoint == expected_endpoint);
        }
    } while (std::next_permutation(perm.begin(), perm.end()));
}

// triangles_meet_illegally under swapping t and u and under every
// relabelling that keeps the shared vertices first and in matching order.
void expect_tri_tri(const Tri& t, const Tri& u, int shared, bool expected) {
    std::array<int, 3> pt = {0, 1, 2};
    do {
        std::array<int, 3> pu = {0, 1, 2};
        do {
            bool keeps_shared = true;
            for (int i = 0; i < shared; ++i) keeps_shared = keeps_shared && pt[i] == pu[i];
            for (int i = 0; i < shared; ++i) keeps_shared = keeps_shared && pt[i] < shared;
            if (!keeps_shared) continue;
            const Tri tp = {t[pt[0]], t[pt[1]], t[pt[2]]};
            const Tri up = {u[pu[0]], u[pu[1]], u[pu[2]]};
            CAPTURE(pt[0]);
            CAPTURE(pu[0]);
            CHECK(tri_tri(tp, up, shared) == expected);
            CHECK(tri_tri(up, tp, shared) == expected);
        } while (std::next_permutation(pu.begin(), pu.end()));
    } while (std::next_permutation(pt.begin(), pt.end()));
}

// The reference triangle of the hand-made cases, in the plane z = 0:
// edge 0 = ab on y = 0, edge 1 = bc on x + y = 4, edge 2 = ca on x = 0.
const Tri kT = {P{0, 0, 0}, P{4, 0, 0}, P{0, 4, 0}};

}  // namespace

// ---------------------------------------------------------------------------
// Segment / triangle, hand-made.
// ---------------------------------------------------------------------------

TEST_CASE("segment/triangle: disjoint") {
    expect_seg_tri({1, 1, 1}, {1, 1, 2}, kT, SegTriKind::Disjoint);      // above
    expect_seg_tri({5, 5, -1}, {5, 5, 1}, kT, SegTriKind::Disjoint);     // plane hit outside
    expect_seg_tri({5, 5, 0}, {5, 5, 1}, kT, SegTriKind::Disjoint);      // endpoint in plane, out
    expect_seg_tri({-1, 2, -1}, {-1, 2, 1}, kT, SegTriKind::Disjoint);   // beside edge 2
    expect_seg_tri({2, -1e-30, -1}, {2, -1e-30, 1}, kT, SegTriKind::Disjoint);  // just outside
    expect_seg_tri({3, 3, 0.5}, {5, 5, -0.5}, kT, SegTriKind::Disjoint); // plane hit at (4,4,0)
}

TEST_CASE("segment/triangle: crossings with the segment's interior") {
    expect_seg_tri({1, 1, -1}, {1, 1, 1}, kT, SegTriKind::CrossInterior);
    expect_seg_tri({0, 0, -1}, {2, 2, 1}, kT, SegTriKind::CrossInterior);  // slanted, X = (1,1,0)
    expect_seg_tri({2, 0, -1}, {2, 0, 1}, kT, SegTriKind::CrossEdge, {0, 1});
    expect_seg_tri({2, 2, -1}, {2, 2, 1}, kT, SegTriKind::CrossEdge, {1, 2});
    expect_seg_tri({0, 2, -1}, {0, 2, 1}, kT, SegTriKind::CrossEdge, {0, 2});
    expect_seg_tri({0, 0, -1}, {0, 0, 1}, kT, SegTriKind::CrossVertex, {0});
    expect_seg_tri({3, -1, -1}, {5, 1, 1}, kT, SegTriKind::CrossVertex, {1});
    expect_seg_tri({0, 4, -1}, {0, 4, 1}, kT, SegTriKind::CrossVertex, {2});
    // A segment through a vertex in a plane containing an edge, not the face.
    expect_seg_tri({-1, 0, -1}, {1, 0, 1}, kT, SegTriKind::CrossVertex, {0});
    expect_seg_tri({1, 0, -1}, {3, 0, 1}, kT, SegTriKind::CrossEdge, {0, 1});
}

TEST_CASE("segment/triangle: an endpoint on the triangle") {
    expect_seg_tri({1, 1, 0}, {1, 1, 1}, kT, SegTriKind::EndpointInterior, {}, 0);
    expect_seg_tri({7, 3, 9}, {1, 2, 0}, kT, SegTriKind::EndpointInterior, {}, 1);
    expect_seg_tri({2, 0, 0}, {2, 0, 3}, kT, SegTriKind::EndpointEdge, {0, 1}, 0);
    expect_seg_tri({1, 3, 0}, {0, 0, -3}, kT, SegTriKind::EndpointEdge, {1, 2}, 0);
    expect_seg_tri({0, 3, 0}, {-5, 3, 1}, kT, SegTriKind::EndpointEdge, {0, 2}, 0);
    expect_seg_tri({4, 0, 0}, {5, 5, 5}, kT, SegTriKind::EndpointVertex, {1}, 0);
    expect_seg_tri({1, 1, 1}, {0, 4, 0}, kT, SegTriKind::EndpointVertex, {2}, 1);
}

TEST_CASE("segment/triangle: coplanar") {
    using K = SegTriKind;
    expect_seg_tri({5, 5, 0}, {6, 6, 0}, kT, K::Disjoint);
    expect_seg_tri({5, 0, 0}, {6, 0, 0}, kT, K::Disjoint);       // on edge 0's line, beyond b
    expect_seg_tri({3, 3, 0}, {-1, 7, 0}, kT, K::Disjoint);      // parallel to edge 1
    expect_seg_tri({4, 0, 0}, {6, 0, 0}, kT, K::CoplanarTouch);  // edge line, only b
    expect_seg_tri({4, 0, 0}, {5, 1, 0}, kT, K::CoplanarTouch);  // from b outward
    expect_seg_tri({-1, 1, 0}, {1, -1, 0}, kT, K::CoplanarTouch);  // through vertex a only
    expect_seg_tri({2, 0, 0}, {2, -1, 0}, kT, K::CoplanarTouch);   // from an edge outward
    expect_seg_tri({3, 3, 0}, {1, 1, 0}, kT, K::CoplanarOverlap);  // crosses edge 1 inward
    expect_seg_tri({1, 1, 0}, {2, 1, 0}, kT, K::CoplanarOverlap);  // inside
    expect_seg_tri({-1, 1, 0}, {5, 1, 0}, kT, K::CoplanarOverlap); // through
    expect_seg_tri({1, 0, 0}, {2, 0, 0}, kT, K::CoplanarOverlap);  // along edge 0
    expect_seg_tri({-1, 0, 0}, {5, 0, 0}, kT, K::CoplanarOverlap); // covers edge 0
    expect_seg_tri({-1, 2, 0}, {2, -1, 0}, kT, K::CoplanarOverlap); // cuts corner a
    expect_seg_tri({0, 0, 0}, {4, 0, 0}, kT, K::CoplanarOverlap);  // is edge 0
}

TEST_CASE("segment/triangle: the convenience predicates") {
    const P a = kT[0], b = kT[1], c = kT[2];
    const P p{1, 1, -1}, q{1, 1, 1}, r{2, 0, 1}, s{2, 0, -1}, far{9, 9, 9};
    CHECK(cbr::geom::segment_crosses_triangle_interior(p.data(), q.data(), a.data(), b.data(),
                                                       c.data()));
    CHECK_FALSE(cbr::geom::segment_crosses_triangle_interior(r.data(), s.data(), a.data(),
                                                             b.data(), c.data()));
    CHECK(cbr::geom::segment_meets_triangle(r.data(), s.data(), a.data(), b.data(), c.data()));
    CHECK_FALSE(
        cbr::geom::segment_meets_triangle(q.data(), far.data(), a.data(), b.data(), c.data()));
}

// ---------------------------------------------------------------------------
// Coplanar segments.
// ---------------------------------------------------------------------------

TEST_CASE("coplanar segments") {
    // In the plane x + y + z = 1 (no coordinate plane), and on one line.
    const P p{1, 0, 0}, q{0, 1, 0}, m{0.5, 0.5, 0}, c{0, 0, 1}, e{-1, 2, 0};
    CHECK(seg_seg(p, q, m, c) == SegSegKind::Point);      // T at the midpoint
    CHECK(seg_seg(p, c, q, c) == SegSegKind::Point);      // common endpoint
    CHECK(seg_seg(p, m, q, c) == SegSegKind::Disjoint);
    CHECK(seg_seg(p, q, m, e) == SegSegKind::Overlap);    // collinear, overlapping
    CHECK(seg_seg(p, m, q, e) == SegSegKind::Disjoint);   // collinear, apart
    CHECK(seg_seg(p, m, m, q) == SegSegKind::Point);      // collinear, end to end
    CHECK(seg_seg(p, q, q, p) == SegSegKind::Overlap);
    const P x0{0.5, 0, 0.5}, x1{0, 0.5, 0.5};              // parallel to pq
    CHECK(seg_seg(p, q, x0, x1) == SegSegKind::Disjoint);
    const P d0{1, 0, 0}, d1{0, 0, 1}, d2{0.25, 0.5, 0.25}, d3{0.75, -0.5, 0.75};
    CHECK(seg_seg(d0, d1, d2, d3) == SegSegKind::Point);  // proper crossing at (0.5,0,0.5)
}

// ---------------------------------------------------------------------------
// Triangle / triangle, hand-made.
// ---------------------------------------------------------------------------

TEST_CASE("triangles without shared vertex") {
    expect_tri_tri(kT, {P{0, 0, 1}, P{4, 0, 1}, P{0, 4, 1}}, 0, false);       // parallel
    expect_tri_tri(kT, {P{1, 1, -1}, P{1, 1, 1}, P{5, 5, 5}}, 0, true);       // edge pierces
    expect_tri_tri(kT, {P{1, 1, 0}, P{1, 1, 2}, P{2, 3, 4}}, 0, true);        // vertex inside
    expect_tri_tri(kT, {P{2, 0, 0}, P{2, -1, 1}, P{3, -2, 2}}, 0, true);      // vertex on edge
    expect_tri_tri(kT, {P{4, 0, 0}, P{5, 0, 1}, P{5, 1, 1}}, 0, true);        // same coordinates
    expect_tri_tri(kT, {P{2, -1, -1}, P{2, 1, 1}, P{9, 9, -9}}, 0, true);     // edge meets edge
    expect_tri_tri(kT, {P{2, -1, -1}, P{2, -1, 1}, P{2, -5, 0}}, 0, false);   // near miss
    expect_tri_tri(kT, {P{-1, -1, -1}, P{5, 5, -1}, P{2, 2, -3}}, 0, false);  // below
    // The planes cross inside both, but the triangles lie on either side.
    expect_tri_tri(kT, {P{3, 3, -1}, P{3, 3, 1}, P{8, 1, 0}}, 0, false);
}

TEST_CASE("coplanar triangles without shared vertex") {
    expect_tri_tri(kT, {P{5, 5, 0}, P{9, 5, 0}, P{5, 9, 0}}, 0, false);
    expect_tri_tri(kT, {P{3, 3, 0}, P{6, 3, 0}, P{3, 6, 0}}, 0, false);       // beyond edge 1
    expect_tri_tri(kT, {P{1, 1, 0}, P{5, 1, 0}, P{1, 5, 0}}, 0, true);        // overlap
    expect_tri_tri(kT, {P{1, 1, 0}, P{2, 1, 0}, P{1, 2, 0}}, 0, true);        // u inside t
    expect_tri_tri(kT, {P{-1, -1, 0}, P{9, -1, 0}, P{-1, 9, 0}}, 0, true);    // t inside u
    expect_tri_tri(kT, {P{4, 0, 0}, P{6, 0, 0}, P{5, -2, 0}}, 0, true);       // vertex coincides
    expect_tri_tri(kT, {P{4, 0, 0}, P{0, 4, 0}, P{4, 4, 0}}, 0, true);        // edge coincides
    expect_tri_tri(kT, {P{1, 0, 0}, P{3, 0, 0}, P{2, -2, 0}}, 0, true);       // along an edge
    expect_tri_tri(kT, {P{2, 0, 0}, P{5, -1, 0}, P{3, -2, 0}}, 0, true);      // T-junction
    expect_tri_tri(kT, {P{-1, 3, 0}, P{3, 3, 0}, P{1, -1, 0}}, 0, true);      // star of David
    expect_tri_tri(kT, {P{2.5, 2.5, 0}, P{6, 2, 0}, P{2, 6, 0}}, 0, false);   // just beyond
}

TEST_CASE("triangles sharing one vertex") {
    // s = (0,0,0) comes first in both.
    expect_tri_tri(kT, {P{0, 0, 0}, P{-4, 1, 1}, P{1, -4, 1}}, 1, false);     // fan
    expect_tri_tri(kT, {P{0, 0, 0}, P{0, 0, 4}, P{-4, 0, 0}}, 1, false);      // plane y = 0, apart
    expect_tri_tri(kT, {P{0, 0, 0}, P{0, 0, 4}, P{4, 0, -4}}, 1, true);       // contains edge ab
    expect_tri_tri(kT, {P{0, 0, 0}, P{2, 1, -5}, P{2, 1, 5}}, 1, true);       // far edge pierces
    expect_tri_tri(kT, {P{0, 0, 0}, P{1, 1, 0}, P{0, 0, 3}}, 1, true);        // edge from s in t
    expect_tri_tri(kT, {P{0, 0, 0}, P{9, 9, 0}, P{0, 0, 3}}, 1, true);        // ... and beyond
    expect_tri_tri(kT, {P{0, 0, 0}, P{-1, -1, 0}, P{0, 0, 3}}, 1, false);     // edge from s outside
    expect_tri_tri(kT, {P{0, 0, 0}, P{5, 5, 1}, P{5, 5, 2}}, 1, false);       // above t
    expect_tri_tri(kT, {P{0, 0, 0}, P{4, 0, 0.5}, P{0, 4, 0.5}}, 1, false);   // thin wedge above
}

TEST_CASE("coplanar triangles sharing one vertex") {
    expect_tri_tri(kT, {P{0, 0, 0}, P{-4, 0, 0}, P{0, -4, 0}}, 1, false);     // opposite wedge
    expect_tri_tri(kT, {P{0, 0, 0}, P{0, -4, 0}, P{4, -4, 0}}, 1, false);     // adjacent wedge
    expect_tri_tri(kT, {P{0, 0, 0}, P{3, 3, 0}, P{-2, 5, 0}}, 1, true);       // wedges overlap
    expect_tri_tri(kT, {P{0, 0, 0}, P{8, 0, 0}, P{5, -5, 0}}, 1, true);       // common ray, longer
    expect_tri_tri(kT, {P{0, 0, 0}, P{2, 0, 0}, P{1, -3, 0}}, 1, true);       // vertex on edge ab
    expect_tri_tri(kT, {P{0, 0, 0}, P{1, 1, 0}, P{1, 2, 0}}, 1, true);        // u inside t's corner
    expect_tri_tri(kT, {P{0, 0, 0}, P{9, 1, 0}, P{1, 9, 0}}, 1, true);        // wider, longer
}

TEST_CASE("triangles sharing an edge") {
    // Shared edge s0 s1 = (0,0,0) (4,0,0) first in both.
    expect_tri_tri(kT, {P{0, 0, 0}, P{4, 0, 0}, P{2, -3, 0}}, 2, false);      // coplanar, apart
    expect_tri_tri(kT, {P{0, 0, 0}, P{4, 0, 0}, P{2, 3, 0}}, 2, true);        // coplanar, fold
    expect_tri_tri(kT, {P{0, 0, 0}, P{4, 0, 0}, P{9, 1, 0}}, 2, true);        // coplanar sliver
    expect_tri_tri(kT, {P{0, 0, 0}, P{4, 0, 0}, P{0, 4, 0}}, 2, true);        // same coordinates
    expect_tri_tri(kT, {P{0, 0, 0}, P{4, 0, 0}, P{2, 2, 5}}, 2, false);       // dihedral
    expect_tri_tri(kT, {P{0, 0, 0}, P{4, 0, 0}, P{0, 4, 1e-30}}, 2, false);   // nearly folded
    expect_tri_tri(kT, {P{0, 0, 0}, P{4, 0, 0}, P{1, 1, -1e-30}}, 2, false);  // nearly folded
}

// ---------------------------------------------------------------------------
// Exactness: one ulp decides.
// ---------------------------------------------------------------------------

TEST_CASE("exactness on a plane with no coordinate normal") {
    const Tri t = {P{1, 0, 0}, P{0, 1, 0}, P{0, 0, 1}};  // x + y + z = 1
    const P on{0.25, 0.25, 0.5};
    const P up{0.25, 0.25, 2};
    expect_seg_tri(on, up, t, SegTriKind::EndpointInterior, {}, 0);
    const P above{0.25, 0.25, std::nextafter(0.5, 1.0)};
    const P below{0.25, 0.25, std::nextafter(0.5, 0.0)};
    expect_seg_tri(above, up, t, SegTriKind::Disjoint);
    expect_seg_tri(below, up, t, SegTriKind::CrossInterior);
    // In the plane, on edge (0,1,0)-(0,0,1) exactly, then one ulp off it.
    const P edge_pt{0, 0.75, 0.25};
    expect_seg_tri(edge_pt, up, t, SegTriKind::EndpointEdge, {1, 2}, 0);
    // Shared-edge folds in that plane: apart, folded, and one ulp out of it.
    const Tri apart = {P{1, 0, 0}, P{0, 1, 0}, P{0.5, 0.75, -0.25}};
    const Tri fold = {P{1, 0, 0}, P{0, 1, 0}, P{0.25, 0.25, 0.5}};
    const Tri lifted = {P{1, 0, 0}, P{0, 1, 0}, above};
    expect_tri_tri(t, apart, 2, false);
    expect_tri_tri(t, fold, 2, true);
    expect_tri_tri(t, lifted, 2, false);
}

TEST_CASE("exactness: a vertex one ulp from an edge") {
    const double tiny = 1e-40;  // the smallest magnitude orient3d supports
    // Vertex on edge ab (T-junction), then just off it on either side.
    expect_tri_tri(kT, {P{2, 0, 0}, P{3, -2, 1}, P{1, -2, 1}}, 0, true);
    expect_tri_tri(kT, {P{2, -tiny, 0}, P{3, -2, 1}, P{1, -2, 1}}, 0, false);
    expect_tri_tri(kT, {P{2, tiny, 0}, P{3, -2, 1}, P{1, -2, 1}}, 0, true);
    // Large offsets: the same configuration translated by 2^40 stays exact.
    const double o = std::ldexp(1.0, 40);
    const Tri t = {P{o, o, o}, P{o + 4, o, o}, P{o, o + 4, o}};
    expect_tri_tri(t, {P{o + 2, o, o}, P{o + 3, o - 2, o + 1}, P{o + 1, o - 2, o + 1}}, 0, true);
    expect_tri_tri(t, {P{o + 2, o - std::ldexp(1.0, -12), o}, P{o + 3, o - 2, o + 1},
                       P{o + 1, o - 2, o + 1}},
                   0, false);
}

// ---------------------------------------------------------------------------
// Randomized cross-check against an explicit exact construction.
//
// Coordinates are small integers (|x| <= 32), so the reference below can
// compute intersection points as rationals with 64-bit integers without
// overflow; it shares no code or case analysis with intersect.cpp.
// ---------------------------------------------------------------------------
namespace {

using I = long long;
using IP = std::array<I, 3>;

IP sub(const IP& a, const IP& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
IP add(const IP& a, const IP& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
IP mul(const IP& a, I k) { return {a[0] * k, a[1] * k, a[2] * k}; }
I dot(const IP& a, const IP& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
IP cross(const IP& a, const IP& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
bool is_zero(const IP& a) { return a[0] == 0 && a[1] == 0 && a[2] == 0; }
P to_p(const IP& a) {
    return {static_cast<double>(a[0]), static_cast<double>(a[1]), static_cast<double>(a[2])};
}

struct Rat {  // num / den, den > 0
    I num;
    I den;
};
bool less(Rat a, Rat b) { return a.num * b.den < b.num * a.den; }
bool equal(Rat a, Rat b) { return a.num * b.den == b.num * a.den; }

// The parameter interval {t in [0,1] : p + t (q - p) in closed triangle v}.
struct Piece {
    bool empty = true;
    bool coplanar = false;
    Rat lo{0, 1};
    Rat hi{1, 1};
};

// (Scaled) side of point x/den with respect to edge i, inside >= 0.
I edge_side(const std::array<IP, 3>& v, const IP& n, int i, const IP& x, I den) {
    const IP e = sub(v[(i + 1) % 3], v[i]);
    return dot(n, cross(e, sub(x, mul(v[i], den))));
}

Piece ref_piece(const IP& p, const IP& q, const std::array<IP, 3>& v) {
    const IP n = cross(sub(v[1], v[0]), sub(v[2], v[0]));
    const I dp = dot(n, sub(p, v[0]));
    const I dq = dot(n, sub(q, v[0]));
    Piece r;
    if (dp == 0 && dq == 0) {  // clip [0, 1] by the three edge half-planes
        r.coplanar = true;
        for (int i = 0; i < 3; ++i) {
            const I alpha = edge_side(v, n, i, p, 1);
            const I beta = edge_side(v, n, i, q, 1) - alpha;  // side(t) = alpha + t beta
            if (beta == 0 && alpha < 0) return r;
            if (beta > 0 && less(r.lo, Rat{-alpha, beta})) r.lo = Rat{-alpha, beta};
            if (beta < 0 && less(Rat{alpha, -beta}, r.hi)) r.hi = Rat{alpha, -beta};
        }
        r.empty = less(r.hi, r.lo);
        return r;
    }
    if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0)) return r;
    Rat t{dp, dp - dq};
    if (t.den < 0) t = Rat{-t.num, -t.den};
    const IP x = add(mul(p, t.den), mul(sub(q, p), t.num));
    for (int i = 0; i < 3; ++i)
        if (edge_side(v, n, i, x, t.den) < 0) return r;
    r.empty = false;
    r.lo = r.hi = t;
    return r;
}

SegTriResult ref_seg_tri(const IP& p, const IP& q, const std::array<IP, 3>& v) {
    const Piece pc = ref_piece(p, q, v);
    SegTriResult r;
    if (pc.empty) return r;
    if (pc.coplanar) {
        r.kind = equal(pc.lo, pc.hi) ? SegTriKind::CoplanarTouch : SegTriKind::CoplanarOverlap;
        return r;
    }
    const Rat t = pc.lo;
    const IP x = add(mul(p, t.den), mul(sub(q, p), t.num));
    const bool at_end = t.num == 0 || t.num == t.den;
    r.endpoint = static_cast<std::int8_t>(t.num == 0 ? 0 : (t.num == t.den ? 1 : -1));
    const IP n = cross(sub(v[1], v[0]), sub(v[2], v[0]));
    for (int i = 0; i < 3; ++i)
        if (is_zero(sub(x, mul(v[i], t.den)))) {
            r.kind = at_end ? SegTriKind::EndpointVertex : SegTriKind::CrossVertex;
            r.feature = static_cast<std::int8_t>(i);
            return r;
        }
    for (int i = 0; i < 3; ++i)
        if (edge_side(v, n, i, x, t.den) == 0) {
            r.kind = at_end ? SegTriKind::EndpointEdge : SegTriKind::CrossEdge;
            r.feature = static_cast<std::int8_t>(i);
            return r;
        }
    r.kind = at_end ? SegTriKind::EndpointInterior : SegTriKind::CrossInterior;
    return r;
}

// Is the rational point x/den outside the shared part (vertices 0..shared-1
// of t, which is empty, a vertex or an edge)?
bool outside_shared(const IP& x, I den, const std::array<IP, 3>& t, int shared) {
    if (shared == 0) return true;
    const IP d = sub(x, mul(t[0], den));
    if (shared == 1) return !is_zero(d);
    const IP e = sub(t[1], t[0]);
    if (!is_zero(cross(d, e))) return true;
    const I along = dot(d, e);  // in [0, den |e|^2] on the edge
    return along < 0 || along > den * dot(e, e);
}

// Reference: the intersection is convex, so it leaves the shared part iff
// one of its extreme points does; those lie on an edge of one triangle, in
// the other, so they are endpoints of the six edge/triangle pieces.
bool ref_tri_tri(const std::array<IP, 3>& t, const std::array<IP, 3>& u, int shared) {
    for (int side = 0; side < 2; ++side) {
        const auto& a = side == 0 ? t : u;
        const auto& b = side == 0 ? u : t;
        for (int i = 0; i < 3; ++i) {
            const IP& p = a[i];
            const IP& q = a[(i + 1) % 3];
            const Piece pc = ref_piece(p, q, b);
            if (pc.empty) continue;
            for (const Rat r : {pc.lo, pc.hi}) {
                const IP x = add(mul(p, r.den), mul(sub(q, p), r.num));
                if (outside_shared(x, r.den, t, shared)) return true;
            }
        }
    }
    return false;
}

SegSegKind ref_seg_seg(const IP& p, const IP& q, const IP& r, const IP& s) {
    const IP d = sub(q, p);
    const IP e = sub(s, r);
    if (is_zero(cross(d, sub(r, p))) && is_zero(cross(d, sub(s, p)))) {  // one line
        const I tr = dot(sub(r, p), d), ts = dot(sub(s, p), d);
        const I lo = std::max<I>(0, std::min(tr, ts)), hi = std::min(dot(d, d), std::max(tr, ts));
        if (lo < hi) return SegSegKind::Overlap;
        return lo == hi ? SegSegKind::Point : SegSegKind::Disjoint;
    }
    const IP m = cross(d, e);
    if (is_zero(m)) return SegSegKind::Disjoint;  // parallel lines
    // p + t d = r + w e, solved by Cramer in the plane with normal m.
    const I den = dot(m, m);
    const I tn = dot(cross(sub(r, p), e), m);
    const I wn = dot(cross(sub(r, p), d), m);
    const bool in = tn >= 0 && tn <= den && wn >= 0 && wn <= den;
    return in ? SegSegKind::Point : SegSegKind::Disjoint;
}

bool degenerate(const std::array<IP, 3>& v) {
    return is_zero(cross(sub(v[1], v[0]), sub(v[2], v[0])));
}

// Random points biased to the degenerate: lattice points of a triangle's
// plane (its vertices, edge midpoints, points on edge lines, outside it),
// copies of its vertices, points of the plane z = 0, and free ones.
class Gen {
public:
    explicit Gen(std::uint64_t seed) : rng_(seed) {}

    I coord(I lo, I hi) {
        return lo + static_cast<I>(rng_() % static_cast<std::uint64_t>(hi - lo + 1));
    }
    bool chance(int percent) { return static_cast<int>(rng_() % 100) < percent; }

    // Vertices with even coordinates (half the time multiples of 4), so that
    // half (quarter) edge vectors are integral.
    std::array<IP, 3> triangle(bool flat) {
        const I unit = chance(50) ? 2 : 4;
        const I n = 8 / unit;
        for (;;) {
            std::array<IP, 3> v;
            for (IP& x : v)
                x = {unit * coord(0, n), unit * coord(0, n), flat ? 0 : unit * coord(0, n)};
            if (!degenerate(v)) return v;
        }
    }

    IP point_near(const std::array<IP, 3>& v, bool flat) {
        switch (coord(0, 3)) {
            case 0: return v[static_cast<std::size_t>(coord(0, 2))];
            case 1: return point_in_plane(v);
            case 2: return {coord(0, 8), coord(0, 8), flat ? 0 : coord(-1, 1)};
            default: return {coord(0, 8), coord(0, 8), flat ? 0 : coord(0, 8)};
        }
    }

    // a + i (b - a)/k + j (c - a)/k for small i, j, with k = 4 when that is
    // integral, else 2: vertices, edge midpoints, points of the edge lines,
    // inside and outside.
    IP point_in_plane(const std::array<IP, 3>& v) {
        const IP e1 = sub(v[1], v[0]), e2 = sub(v[2], v[0]);
        I k = 4;
        for (int c = 0; c < 3; ++c)
            if (e1[c] % 4 != 0 || e2[c] % 4 != 0) k = 2;
        const I i = coord(-k, 2 * k), j = coord(-k, 2 * k);
        return add(v[0], add(mul(IP{e1[0] / k, e1[1] / k, e1[2] / k}, i),
                             mul(IP{e2[0] / k, e2[1] / k, e2[2] / k}, j)));
    }

private:
    std::mt19937_64 rng_;
};

// An exact symmetry of the integer lattice (axis permutation, sign flips,
// translation) plus a power-of-two scale: it changes every coordinate and
// projection but no answer.
struct Transform {
    std::array<int, 3> axis;
    std::array<double, 3> sign;
    std::array<double, 3> shift;
    int exponent;
    P operator()(const P& a) const {
        P r;
        for (int k = 0; k < 3; ++k) r[k] = std::ldexp(sign[k] * a[axis[k]] + shift[k], exponent);
        return r;
    }
};

Transform random_transform(Gen& g) {
    Transform t{{0, 1, 2}, {1, 1, 1}, {0, 0, 0}, 0};
    std::array<int, 3> ax = {0, 1, 2};
    for (int k = 2; k > 0; --k) std::swap(ax[k], ax[static_cast<std::size_t>(g.coord(0, k))]);
    t.axis = ax;
    for (int k = 0; k < 3; ++k) {
        t.sign[k] = g.chance(50) ? 1.0 : -1.0;
        t.shift[k] = static_cast<double>(g.coord(-1000, 1000));
    }
    t.exponent = static_cast<int>(g.coord(-60, 60));
    return t;
}

}  // namespace

TEST_CASE("segment/triangle agrees with an explicit exact construction") {
    Gen g(20240601);
    std::array<int, 9> seen{};
    for (int iter = 0; iter < 40000; ++iter) {
        const bool flat = g.chance(30);
        const auto v = g.triangle(flat);
        IP p = g.point_near(v, flat);
        IP q = g.point_near(v, flat);
        if (g.chance(30)) {  // a segment through a lattice point of the plane
            const IP m = g.point_in_plane(v);
            const IP d = {g.coord(-3, 3), g.coord(-3, 3), flat ? 0 : g.coord(-3, 3)};
            p = add(m, d);
            q = sub(m, d);
        }
        if (p == q) continue;
        const SegTriResult ref = ref_seg_tri(p, q, v);
        const Transform tr = random_transform(g);
        const Tri t = {tr(to_p(v[0])), tr(to_p(v[1])), tr(to_p(v[2]))};
        const SegTriResult got = seg_tri(tr(to_p(p)), tr(to_p(q)), t);
        CAPTURE(iter);
        REQUIRE(static_cast<int>(got.kind) == static_cast<int>(ref.kind));
        REQUIRE(got.feature == ref.feature);
        REQUIRE(got.endpoint == ref.endpoint);
        ++seen[static_cast<std::size_t>(got.kind)];
    }
    for (std::size_t k = 0; k < seen.size(); ++k) {
        CAPTURE(k);
        CHECK(seen[k] > 20);  // the generator reaches every kind
    }
}

TEST_CASE("coplanar segments agree with an explicit exact construction") {
    Gen g(77);
    std::array<int, 3> seen{};
    for (int iter = 0; iter < 20000; ++iter) {
        const auto v = g.triangle(g.chance(30));
        std::array<IP, 4> s;  // four lattice points of v's plane
        for (IP& x : s) x = g.point_in_plane(v);
        if (s[0] == s[1] || s[2] == s[3]) continue;
        const SegSegKind ref = ref_seg_seg(s[0], s[1], s[2], s[3]);
        const Transform tr = random_transform(g);
        const SegSegKind got =
            seg_seg(tr(to_p(s[0])), tr(to_p(s[1])), tr(to_p(s[2])), tr(to_p(s[3])));
        CAPTURE(iter);
        REQUIRE(static_cast<int>(got) == static_cast<int>(ref));
        ++seen[static_cast<std::size_t>(got)];
    }
    for (int n : seen) CHECK(n > 20);
}

TEST_CASE("triangle/triangle agrees with an explicit exact construction") {
    Gen g(31337);
    std::array<std::array<int, 2>, 3> seen{};  // [shared][illegal]
    for (int iter = 0; iter < 30000; ++iter) {
        const bool flat = g.chance(35);
        const auto t = g.triangle(flat);
        const int shared = static_cast<int>(g.coord(0, 2));
        std::array<IP, 3> u = t;
        for (int i = shared; i < 3; ++i) u[static_cast<std::size_t>(i)] = g.point_near(t, flat);
        if (degenerate(u)) continue;  // u may repeat t's coordinates: distinct vertices
        const bool ref = ref_tri_tri(t, u, shared);
        const Transform tr = random_transform(g);
        const Tri tt = {tr(to_p(t[0])), tr(to_p(t[1])), tr(to_p(t[2]))};
        const Tri uu = {tr(to_p(u[0])), tr(to_p(u[1])), tr(to_p(u[2]))};
        CAPTURE(iter);
        CAPTURE(shared);
        REQUIRE(tri_tri(tt, uu, shared) == ref);
        REQUIRE(tri_tri(uu, tt, shared) == ref);
        ++seen[static_cast<std::size_t>(shared)][ref ? 1 : 0];
    }
    for (const auto& s : seen) {
        CHECK(s[0] > 100);
        CHECK(s[1] > 100);
    }
}

// Conforming recovery's rounded crossing points (geom/segment_point.hpp):
// a parameter so small that p + s (q - p) rounds to p must still give a
// point other than either end, on the segment (between the ends on every
// axis), and one that does not round to an end must be left as it is.
TEST_CASE("segment point: a crossing within rounding of an end is moved off it") {
    const double p[3] = {12.5, -3.25, 7.0};
    const double q[3] = {13.5, -2.25, 9.0};
    for (double s : {1e-300, 1e-18, 1e-17}) {
        double out[3];
        cbr::geom::segment_point_off_ends(p, q, s, out);
        CHECK_FALSE(cbr::geom::same_point(out, p));
        CHECK_FALSE(cbr::geom::same_point(out, q));
        for (int k = 0; k < 3; ++k) {
            CHECK(out[k] >= std::min(p[k], q[k]));
            CHECK(out[k] <= std::max(p[k], q[k]));
        }
        CHECK(std::abs(out[0] - p[0]) < 1e-12);  // only a few ulps along
    }
    for (double s : {1 - 1e-18, 1 - 1e-17}) {  // the same next to q
        double out[3];
        cbr::geom::segment_point_off_ends(p, q, s, out);
        CHECK_FALSE(cbr::geom::same_point(out, q));
        CHECK(std::abs(out[2] - q[2]) < 1e-12);
    }
    double mid[3];
    cbr::geom::segment_point_off_ends(p, q, 0.25, mid);
    CHECK(mid[0] == 12.75);
    CHECK(mid[1] == -3.0);
    CHECK(mid[2] == 7.5);
}
