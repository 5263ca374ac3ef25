// Exact segment/triangle and triangle/triangle classification by orient3d
// signs (see intersect.hpp).
#include "geom/intersect.hpp"

#include <cassert>

#include "geom/orient2d.hpp"
#include "geom/predicates.hpp"

namespace cbr::geom {
namespace {

// A plane given by a non-degenerate triangle, seen through a projection in
// which that triangle stays non-degenerate (some coordinate of its normal is
// non-zero, and each such coordinate is one projected orientation). The
// projection is then a bijection of the plane onto the coordinate plane, so
// 2D answers for points of the plane are the true answers; `sign` is the
// projected orientation of the defining triangle (its "counter-clockwise").
struct PlaneView {
    Projection pr;
    int sign;
};

PlaneView view_plane(const double* a, const double* b, const double* c) {
    constexpr Projection kProjections[3] = {{0, 1}, {2, 0}, {1, 2}};
    for (const Projection pr : kProjections) {
        const int s = orient2d(pr, a, b, c);
        if (s != 0) return {pr, s};
    }
    assert(false && "view_plane: collinear points");
    return {kProjections[0], 0};
}

// Order along a line: for points on one line, the lexicographic (x, y, z)
// order is monotone along it, so it orders collinear points exactly.
const double* lex_min(const double* p, const double* q) {
    return lexicographic_compare(p, q) <= 0 ? p : q;
}
const double* lex_max(const double* p, const double* q) {
    return lexicographic_compare(p, q) <= 0 ? q : p;
}

// Two segments on one line: compare the larger start with the smaller end.
SegSegKind collinear_segments(const double* p, const double* q, const double* r,
                              const double* s) {
    const int c = lexicographic_compare(lex_max(lex_min(p, q), lex_min(r, s)),
                                        lex_min(lex_max(p, q), lex_max(r, s)));
    if (c < 0) return SegSegKind::Overlap;
    return c == 0 ? SegSegKind::Point : SegSegKind::Disjoint;
}

// Two segments of the viewed plane.
SegSegKind segments_in_plane(PlaneView pl, const double* p, const double* q, const double* r,
                             const double* s) {
    const int o1 = orient2d(pl.pr, p, q, r);
    const int o2 = orient2d(pl.pr, p, q, s);
    if (o1 == 0 && o2 == 0) return collinear_segments(p, q, r, s);
    if (o1 * o2 > 0) return SegSegKind::Disjoint;
    // Not collinear, so rs's line is not pq's: p and q cannot both be on it.
    const int o3 = orient2d(pl.pr, r, s, p);
    const int o4 = orient2d(pl.pr, r, s, q);
    if (o3 * o4 > 0) return SegSegKind::Disjoint;
    return SegSegKind::Point;
}

// Does segment pq of the viewed plane meet the *open* triangle v?
//
// By the separating axis theorem, the segment misses the open triangle
// exactly when a line weakly separates the two, and such a line can be taken
// parallel to an edge of the triangle or to the segment (the edges of their
// Minkowski difference). So: it misses when both endpoints are on the outer
// closed side of one edge line, or all three vertices on one closed side of
// the line pq.
bool segment_meets_open_triangle(PlaneView pl, const double* p, const double* q,
                                 const double* const v[3]) {
    for (int i = 0; i < 3; ++i) {
        const double* a = v[i];
        const double* b = v[(i + 1) % 3];
        if (pl.sign * orient2d(pl.pr, a, b, p) <= 0 && pl.sign * orient2d(pl.pr, a, b, q) <= 0)
            return false;
    }
    int pos = 0;
    int neg = 0;
    for (int i = 0; i < 3; ++i) {
        const int o = orient2d(pl.pr, p, q, v[i]);
        pos += o > 0;
        neg += o < 0;
    }
    return pos > 0 && neg > 0;
}

// pq in the plane of the non-degenerate triangle v.
SegTriResult coplanar_segment_triangle(const double* p, const double* q,
                                       const double* const v[3]) {
    const PlaneView pl = view_plane(v[0], v[1], v[2]);
    if (segment_meets_open_triangle(pl, p, q, v)) return {SegTriKind::CoplanarOverlap, -1, -1};
    // Otherwise the common part lies on the triangle's boundary; a piece of
    // positive length there lies along one edge.
    bool touch = false;
    for (int i = 0; i < 3; ++i) {
        const SegSegKind k = segments_in_plane(pl, p, q, v[i], v[(i + 1) % 3]);
        if (k == SegSegKind::Overlap) return {SegTriKind::CoplanarOverlap, -1, -1};
        touch = touch || k == SegSegKind::Point;
    }
    return {touch ? SegTriKind::CoplanarTouch : SegTriKind::Disjoint, -1, -1};
}

// Where the line pq, not parallel to the plane of v, meets the triangle.
//
// Let X be the point where the line meets the plane and n the normal of the
// plane. Subtracting multiples of q - p from the other columns,
// orient3d(p, q, a, b) = det[q-p, a-X, b-X] = ((q-p).n) * orient(a, b, X)
// in the plane, so the three edge tests share the factor (q-p).n != 0: X is
// in the closed triangle iff the non-zero signs agree, and a zero puts X on
// that edge's line.
SegTriResult locate_line_crossing(const double* p, const double* q, const double* const v[3]) {
    int s[3];
    int zeros = 0;
    int pos = 0;
    int neg = 0;
    for (int i = 0; i < 3; ++i) {
        s[i] = orient3d(p, q, v[i], v[(i + 1) % 3]);
        zeros += s[i] == 0;
        pos += s[i] > 0;
        neg += s[i] < 0;
        if (pos > 0 && neg > 0) return {SegTriKind::Disjoint, -1, -1};
    }
    assert(zeros < 3 && "locate_line_crossing: line in the plane");
    if (zeros == 0) return {SegTriKind::CrossInterior, -1, -1};
    if (zeros == 1) {
        const int e = s[0] == 0 ? 0 : (s[1] == 0 ? 1 : 2);
        return {SegTriKind::CrossEdge, static_cast<std::int8_t>(e), -1};
    }
    // Two edge lines through X: X is their common vertex, the one not on the
    // remaining edge k (which joins k and k + 1).
    const int k = s[0] != 0 ? 0 : (s[1] != 0 ? 1 : 2);
    return {SegTriKind::CrossVertex, static_cast<std::int8_t>((k + 2) % 3), -1};
}

// Promotes a Cross* answer to the Endpoint* one when X is an endpoint.
SegTriResult at_endpoint(SegTriResult r, int endpoint) {
    switch (r.kind) {
        case SegTriKind::CrossInterior: r.kind = SegTriKind::EndpointInterior; break;
        case SegTriKind::CrossEdge: r.kind = SegTriKind::EndpointEdge; break;
        case SegTriKind::CrossVertex: r.kind = SegTriKind::EndpointVertex; break;
        default: return r;
    }
    r.endpoint = static_cast<std::int8_t>(endpoint);
    return r;
}

// classify_segment_triangle with sp = orient3d(v, p), sq = orient3d(v, q)
// already known (the triangle/triangle test reuses them).
SegTriResult classify_with_sides(const double* p, const double* q, const double* const v[3],
                                 int sp, int sq) {
    if (sp == 0 && sq == 0) return coplanar_segment_triangle(p, q, v);
    if (sp * sq > 0) return {SegTriKind::Disjoint, -1, -1};
    const SegTriResult r = locate_line_crossing(p, q, v);
    if (sp == 0) return at_endpoint(r, 0);
    if (sq == 0) return at_endpoint(r, 1);
    return r;
}

bool all_strictly_one_side(const int s[3]) {
    return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
}

// Closed triangles t and u have a common point. If they do, an extreme point
// of the (convex) intersection lies on the boundary of t or of u, so some
// edge of one meets the other triangle; the converse is immediate.
bool closed_triangles_meet(const double* const t[3], const double* const u[3]) {
    int su[3];  // side of each vertex of u with respect to t's plane
    int st[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i) su[i] = orient3d(t[0], t[1], t[2], u[i]);
    if (all_strictly_one_side(su)) return false;
    // Coplanar triangles need no second plane test (exact zeros are the
    // costly answers of orient3d; coplanar inputs are common).
    if (su[0] != 0 || su[1] != 0 || su[2] != 0) {
        for (int i = 0; i < 3; ++i) st[i] = orient3d(u[0], u[1], u[2], t[i]);
        if (all_strictly_one_side(st)) return false;
    }
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        if (classify_with_sides(u[i], u[j], t, su[i], su[j]).kind != SegTriKind::Disjoint)
            return true;
        if (classify_with_sides(t[i], t[j], u, st[i], st[j]).kind != SegTriKind::Disjoint)
            return true;
    }
    return false;
}

// Triangles (s, t1, t2) and (s, u1, u2) sharing exactly vertex s. Where the
// planes differ, both triangles meet their common line in a segment starting
// at s; where they coincide, the intersection is a convex polygon with a
// corner at s. Either way, a common point other than s implies one whose
// position is limited by an edge that does not contain s: t1t2 meets u or
// u1u2 meets t. Conversely such a meeting point is not s (s is not on the
// line of the opposite edge of a non-degenerate triangle).
bool one_shared_vertex_meet(const double* const t[3], const double* const u[3]) {
    // Sides of u1, u2 with respect to t's plane, which contains s. Strictly
    // on one side: u leaves the plane at s, so it meets t only there.
    const int s1 = orient3d(t[0], t[1], t[2], u[1]);
    const int s2 = orient3d(t[0], t[1], t[2], u[2]);
    if (s1 * s2 > 0) return false;
    if (s1 == 0 && s2 == 0) {  // one plane: t1 and t2 are on u's too
        return classify_with_sides(t[1], t[2], u, 0, 0).kind != SegTriKind::Disjoint ||
               classify_with_sides(u[1], u[2], t, 0, 0).kind != SegTriKind::Disjoint;
    }
    const int r1 = orient3d(u[0], u[1], u[2], t[1]);
    const int r2 = orient3d(u[0], u[1], u[2], t[2]);
    if (r1 * r2 > 0) return false;
    return classify_with_sides(t[1], t[2], u, r1, r2).kind != SegTriKind::Disjoint ||
           classify_with_sides(u[1], u[2], t, s1, s2).kind != SegTriKind::Disjoint;
}

// Triangles (s0, s1, t2) and (s0, s1, u2) sharing edge s0s1. In different
// planes they meet only along the common line, i.e. in the shared edge; in
// one plane they overlap iff t2 and u2 are on the same side of s0s1.
bool shared_edge_overlap(const double* const t[3], const double* const u[3]) {
    if (orient3d(t[0], t[1], t[2], u[2]) != 0) return false;
    const PlaneView pl = view_plane(t[0], t[1], t[2]);
    return orient2d(pl.pr, t[0], t[1], u[2]) == pl.sign;
}

}  // namespace

SegTriResult classify_segment_triangle(const double* p, const double* q, const double* a,
                                       const double* b, const double* c) {
    assert(!collinear(a, b, c) && lexicographic_compare(p, q) != 0);
    const double* const v[3] = {a, b, c};
    return classify_with_sides(p, q, v, orient3d(a, b, c, p), orient3d(a, b, c, q));
}

bool segment_meets_triangle(const double* p, const double* q, const double* a, const double* b,
                            const double* c) {
    return classify_segment_triangle(p, q, a, b, c).kind != SegTriKind::Disjoint;
}

bool segment_crosses_triangle_interior(const double* p, const double* q, const double* a,
                                       const double* b, const double* c) {
    return classify_segment_triangle(p, q, a, b, c).kind == SegTriKind::CrossInterior;
}

SegSegKind classify_coplanar_segments(const double* p, const double* q, const double* r,
                                      const double* s) {
    assert(lexicographic_compare(p, q) != 0 && lexicographic_compare(r, s) != 0);
    // View the plane through a non-degenerate triple; none means one line.
    if (!collinear(p, q, r)) return segments_in_plane(view_plane(p, q, r), p, q, r, s);
    if (!collinear(p, q, s)) return segments_in_plane(view_plane(p, q, s), p, q, r, s);
    return collinear_segments(p, q, r, s);
}

bool triangles_meet_illegally(const double* const t[3], const double* const u[3], int shared) {
    assert(!collinear(t[0], t[1], t[2]) && !collinear(u[0], u[1], u[2]));
    switch (shared) {
        case 0: return closed_triangles_meet(t, u);
        case 1: return one_shared_vertex_meet(t, u);
        case 2: return shared_edge_overlap(t, u);
        default:
            assert(false && "triangles_meet_illegally: shared must be 0, 1 or 2");
            return false;
    }
}

}  // namespace cbr::geom
