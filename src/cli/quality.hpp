// Element quality of a tetrahedral mesh: the rows of the paper's Table II
// (Du & Wang 2004), computed by the command from the points and tetrahedra
// libcbr returns.
//
// Quality q = 3 r_in / r_circ (the radius ratio): 1 for the regular
// tetrahedron, 0 for a flat one. With a the first corner, u = b - a,
// v = c - a, w = d - a (after scaling by 1 / the longest edge, which leaves
// q unchanged and keeps every product near 1, far from overflow and
// underflow):
//
//   D      = u . (v x w)                         (6 x the signed volume)
//   S      = sum of the four face areas, each |(q - p) x (r - p)| / 2
//   N      = |u|^2 (v x w) + |v|^2 (w x u) + |w|^2 (u x v)
//   r_in   = 3 V / S = |D| / (2 S)
//   r_circ = |N| / (2 |D|)           (N / (2D) is the circumcentre - a)
//   q      = 3 r_in / r_circ = 3 D^2 / (S |N|)
//
// A tetrahedron with D = 0 (flat, or a repeated corner) has q = 0; q is
// clamped to [0, 1] against rounding.
//
// Dihedral angle at edge pq, with r and s the two other corners: the angle
// between n1 = e x (r - p) and n2 = e x (s - p), e = q - p, computed as
// atan2(|n1 x n2|, n1 . n2) (accurate near 0 and 180 degrees, where acos
// is not).
#pragma once

#include <cstdint>
#include <vector>

#include "io/mesh_types.hpp"

namespace cbr::cli {

// q = 3 r_in / r_circ of the tetrahedron abcd (each a pointer to x, y, z).
double tet_quality(const double* a, const double* b, const double* c, const double* d);

// The smallest and largest of the six dihedral angles of abcd, in degrees.
void tet_dihedral_range(const double* a, const double* b, const double* c, const double* d, double& min_deg,
                        double& max_deg);

// Table II over a set of tetrahedra. With no tetrahedron, the averages,
// percentages, minima and maxima are NaN (printed "-", null in JSON).
struct QualityStats {
    std::int64_t tets = 0;
    double quality_average = 0;
    double quality_min = 0;
    double percent_above_0_4 = 0;        // % of tetrahedra with q > 0.4
    double percent_below_0_1 = 0;        // % with q < 0.1
    std::int64_t bad_touching_steiner = 0;  // tetrahedra with q < 0.1 and a Steiner corner
    double dihedral_min_deg = 0;
    double dihedral_max_deg = 0;
};

struct RegionQuality {
    std::int32_t region = 0;
    QualityStats stats;
};

struct QualityReport {
    QualityStats all;
    std::vector<RegionQuality> regions;  // by increasing region; filled when there are several
};

// Table II of `mesh` (points, tets, tet_regions, is_steiner; not
// tet_quality), and q of each tetrahedron in `qualities` (one per
// tetrahedron, what the .vtu writer stores): `mesh` is only read, so it
// may be written to a file meanwhile.
QualityReport measure_quality(const io::VolumeMesh& mesh, std::vector<double>& qualities);
// The same with mesh.tet_quality filled.
QualityReport measure_quality(io::VolumeMesh& mesh);

}  // namespace cbr::cli
