// Exact intersection classification of segments and triangles in 3D.
//
// Every answer is decided by signs of orient3d (predicates.hpp) on input
// coordinates, never by a constructed intersection point, so it is exact
// for every input that orient3d accepts. Coplanar configurations are
// decided in 2D on a projection onto a coordinate plane; the projected
// points are copies of input coordinates (no arithmetic), and the 2D
// orientation is itself an orient3d call (see intersect.cpp).
//
// Conventions: points are `const double*` to three coordinates. Triangle
// edge i joins vertex i and vertex (i + 1) % 3; segment endpoint 0 is p,
// endpoint 1 is q. Segments and triangles are closed sets.
#pragma once

#include <cstdint>

namespace cbr::geom {

// How the closed segment pq meets the closed triangle abc.
enum class SegTriKind : std::uint8_t {
    Disjoint,  // no common point

    // pq is not in the plane of abc and meets the triangle in one point X.
    // X is interior to pq:
    CrossInterior,  // ...and interior to abc: a proper crossing
    CrossEdge,      // ...and in the relative interior of edge `feature`
    CrossVertex,    // ...and equal to vertex `feature`
    // X is endpoint `endpoint` of pq:
    EndpointInterior,  // ...interior to abc
    EndpointEdge,      // ...in the relative interior of edge `feature`
    EndpointVertex,    // ...equal to vertex `feature`

    // pq lies in the plane of abc and meets the triangle:
    CoplanarTouch,    // in exactly one point (necessarily on abc's boundary)
    CoplanarOverlap,  // in a sub-segment of positive length (through the
                      // interior or along an edge)
};

struct SegTriResult {
    SegTriKind kind = SegTriKind::Disjoint;
    std::int8_t feature = -1;   // vertex or edge index of abc, or -1
    std::int8_t endpoint = -1;  // 0 (p) or 1 (q) for Endpoint*, else -1
};

// Classifies closed segment pq against closed triangle abc.
// Preconditions: a, b, c not collinear; p and q distinct.
SegTriResult classify_segment_triangle(const double* p, const double* q, const double* a,
                                       const double* b, const double* c);

// True when the closed segment pq and the closed triangle abc have a common
// point (same preconditions).
bool segment_meets_triangle(const double* p, const double* q, const double* a, const double* b,
                            const double* c);

// True when the open segment pq crosses the open triangle abc in a single
// point (the kind CrossInterior).
bool segment_crosses_triangle_interior(const double* p, const double* q, const double* a,
                                       const double* b, const double* c);

// How two closed segments pq and rs lying in one plane meet.
enum class SegSegKind : std::uint8_t {
    Disjoint,
    Point,    // exactly one common point
    Overlap,  // collinear, sharing a sub-segment of positive length
};

// Classifies two coplanar segments (precondition: p, q, r, s coplanar,
// p != q, r != s; the result is meaningless otherwise).
SegSegKind classify_coplanar_segments(const double* p, const double* q, const double* r,
                                      const double* s);

// True when the closed triangles t = (t[0], t[1], t[2]) and
// u = (u[0], u[1], u[2]) meet other than in their shared vertices and edge:
// the illegal contacts of an input surface (crossings, coplanar overlaps,
// a vertex on the other triangle's edge or interior, T-junctions).
//
// `shared` (0, 1 or 2) says how many vertices the triangles share, and the
// shared ones come first in the same order: t[i] and u[i] are the same
// vertex for i < shared. The other vertices are distinct vertices, even if
// their coordinates coincide (then the triangles meet illegally there).
// Preconditions: neither triangle is degenerate (collinear vertices).
bool triangles_meet_illegally(const double* const t[3], const double* const u[3], int shared);

}  // namespace cbr::geom
