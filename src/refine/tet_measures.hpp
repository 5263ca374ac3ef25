// Shape and size measures of one tetrahedron, in double: what refinement
// and optimisation decide with, and what Table II reports (Du & Wang 2004,
// §6, Table II). None of them decides validity: orientation is always
// tested exactly (geom::orient3d) by the callers.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "geom/vec3.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::refine {

using Point = std::array<double, 3>;

// |det[b - a, c - a, d - a]|: six times the volume of abcd, in doubles (a
// measure for weights and counts, not an orientation test).
double six_volume(const double* a, const double* b, const double* c, const double* d);

// Radius ratio q = 3 r_in / r_circ: 1 for the regular tetrahedron, 0 for a
// flat one (the paper's Table II measure). Orientation-blind (uses |volume|);
// from the raw edges, or after scaling to unit longest edge when their
// products would leave the range where double is exact to full precision;
// clamped to [0, 1].
double radius_ratio(const double* a, const double* b, const double* c, const double* d);
// The same for tetrahedron t of m.
inline double radius_ratio(const mesh::TetMesh& m, mesh::TetId t) {
    const mesh::VertexId* v = m.vertices(t);
    return radius_ratio(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3]));
}
// A tetrahedron by its corners (one that may no longer be in m), and its
// radius ratio.
using Corners = std::array<mesh::VertexId, 4>;
inline Corners corners_of(const mesh::TetMesh& m, mesh::TetId t) {
    const mesh::VertexId* v = m.vertices(t);
    return {v[0], v[1], v[2], v[3]};
}
inline double radius_ratio(const mesh::TetMesh& m, const Corners& w) {
    return radius_ratio(m.point(w[0]), m.point(w[1]), m.point(w[2]), m.point(w[3]));
}
// The coordinates of t's corners, in its vertex order.
inline void corner_points(const mesh::TetMesh& m, mesh::TetId t, const double* c[4]) {
    const mesh::VertexId* v = m.vertices(t);
    for (int i = 0; i < 4; ++i) c[i] = m.point(v[i]);
}

// Two radius ratios at once: out[0] of the tetrahedron with corners
// first, out[1] of second, each bit for bit what radius_ratio gives (the
// same operations in the same order, one tetrahedron per lane of SSE2
// registers, where the processor has them).
void radius_ratio_pair(const double* const first[4], const double* const second[4], double out[2]);

// Calls visit(q) with the radius ratios of `count` tetrahedra in order,
// the k-th given by corners(k, c) (filling const double* c[4]), until
// visit returns false (then false). Rated two at a time
// (radius_ratio_pair), so a stop leaves at most one rated in vain.
// Smoothing rates whole balls this way many times per vertex (a quarter
// of `cbr mesh`'s instructions on common3d-homer were radius ratios), and
// relocation and sliver removal the stars of their candidate points.
template <typename Corners, typename Visit>
bool each_radius_ratio(std::size_t count, Corners corners, Visit visit) {
    std::size_t k = 0;
    for (; k + 1 < count; k += 2) {
        const double* first[4];
        const double* second[4];
        corners(k, first);
        corners(k + 1, second);
        double pair[2];
        radius_ratio_pair(first, second, pair);
        if (!visit(pair[0]) || !visit(pair[1])) return false;
    }
    if (k == count) return true;
    const double* last[4];
    corners(k, last);
    return visit(radius_ratio(last[0], last[1], last[2], last[3]));
}

// The radius ratios of tetrahedra tets[0..count) of m into out[0..count)
// (each_radius_ratio).
void radius_ratios(const mesh::TetMesh& m, const mesh::TetId* tets, std::size_t count, double* out);

// The radius ratio of abcd when it is positively oriented (exact), else
// -infinity: the measure quality flips maximize over ring triangulations
// (mesh::RingObjective).
double oriented_radius_ratio(const double* a, const double* b, const double* c, const double* d);

// The six edges of a tetrahedron as corner slots, each followed by the two
// other corners: {i, j, k, l} is edge ij, between faces ijk and ijl.
inline constexpr std::array<std::array<int, 4>, 6> kTetEdges = {
    {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}}};

// Dihedral angle at each edge of abcd (kTetEdges order), in degrees;
// false (all 0) when the tetrahedron has no extent in double.
bool dihedral_angles(const double* a, const double* b, const double* c, const double* d,
                     std::array<double, 6>& deg);

// Smallest and largest dihedral angle, in degrees.
void dihedral_range(const double* a, const double* b, const double* c, const double* d, double& min_deg,
                    double& max_deg);

// The smallest dihedral angle of abcd, in degrees (0 when it has no extent
// in double); oriented_min_dihedral: the same when abcd is positively
// oriented (exact), else -infinity (a mesh::RingObjective measure).
double min_dihedral(const double* a, const double* b, const double* c, const double* d);
double oriented_min_dihedral(const double* a, const double* b, const double* c, const double* d);

// An upper bound on the radius ratio of a tetrahedron with a dihedral
// angle below `degrees` (0 < degrees <= 180): 6 sin(degrees / 2). The
// insphere lies in the wedge of that angle, so r_in <= L sin(angle / 2),
// L the longest edge, and r_circ >= L / 2.
double radius_ratio_bound_for_dihedral(double degrees);
// Whether tetrahedron t has a dihedral angle below `degrees`, its radius
// ratio tested first against `q_bound` = radius_ratio_bound_for_dihedral
// (degrees), which most tetrahedra are above.
bool has_dihedral_below(const mesh::TetMesh& m, mesh::TetId t, double degrees, double q_bound);

// An upper bound on the radius ratio of every tetrahedron with face abc,
// whatever its fourth corner: 3 r / R of the triangle (r, R its in- and
// circumradius), 1.5 for the equilateral triangle, near 0 for a needle.
// Every cross-section of the tetrahedron parallel to abc is a scaled-down
// copy of abc, so the insphere's largest disk fits in one and r_in <= r;
// the circumsphere holds a, b and c, so r_circ >= R. Computed with the
// perimeter taken as twice the longest edge (a larger bound, up to 1.5
// times for fat triangles, the same in the limit for needles and flat
// caps). Tight: tetrahedra on needle faces come within 1e-6 of it
// (test_refine).
double radius_ratio_bound_for_face(const double* a, const double* b, const double* c);

// Circumcentre of abcd; false when the tetrahedron is flat in double.
bool circumcentre(const double* a, const double* b, const double* c, const double* d, Point& centre);

// Circumcentre and squared circumradius of triangle abc; false when flat.
bool triangle_circumsphere(const double* a, const double* b, const double* c, Point& centre, double& radius2);

using geom::squared_distance;  // geom/vec3.hpp

// Apex candidates over triangle (a, b, d): points above its centroid, on
// the side (b - a) x (d - a) points to, at each of `heights` times its mean
// edge length, appended to `out` (nothing for a triangle flat in double).
// Where sliver removal and Steiner relocation look for a well-shaped
// tetrahedron on a face.
void add_apexes(const double* a, const double* b, const double* d, const double* heights, std::size_t count,
                std::vector<Point>& out);

// Circumradius over shortest edge (the radius-edge ratio of Delaunay
// refinement, TetGen's -q bound); +inf for a flat tetrahedron.
double radius_edge_ratio(const double* a, const double* b, const double* c, const double* d);

}  // namespace cbr::refine
