#include "cli/quality.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include "mesh/huge_pages.hpp"

namespace cbr::cli {
namespace {

using Vec = std::array<double, 3>;

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Vec sub(const double* p, const double* q) { return {p[0] - q[0], p[1] - q[1], p[2] - q[2]}; }
Vec sub(const Vec& p, const Vec& q) { return {p[0] - q[0], p[1] - q[1], p[2] - q[2]}; }
Vec scaled(const Vec& p, double s) { return {p[0] * s, p[1] * s, p[2] * s}; }
double dot(const Vec& p, const Vec& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }
double norm(const Vec& p) { return std::sqrt(dot(p, p)); }
Vec cross(const Vec& p, const Vec& q) {
    return {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
}

// The corners of abcd relative to a, scaled so that the longest edge has
// length 1: {0, u, v, w}. False when every corner is the same point.
bool normalized_corners(const double* a, const double* b, const double* c, const double* d, std::array<Vec, 4>& p) {
    const Vec u = sub(b, a), v = sub(c, a), w = sub(d, a);
    const double longest = std::max({norm(u), norm(v), norm(w), norm(sub(v, u)), norm(sub(w, u)), norm(sub(w, v))});
    if (!(longest > 0) || !std::isfinite(longest)) return false;
    const double s = 1 / longest;
    p = {Vec{0, 0, 0}, scaled(u, s), scaled(v, s), scaled(w, s)};
    return true;
}

// A dihedral angle as atan2(sine, cosine) with sine >= 0, both scaled by
// the same positive factor (the lengths of the two face normals): angles
// compare without the arctangent (Angle::below), which runs only for the
// minimum and maximum a Table II reports (on every edge it was 40% of
// measuring igea's tetrahedra after recovery; twice per tetrahedron,
// still 3% of its `cbr recover`).
struct Angle {
    double sine = 0, cosine = 1;  // 0 degrees

    // Whether this < other: sin(other - this) = s2 c1 - c2 s1 (times the
    // lengths) is positive; where it is 0 the directions are parallel
    // (equal angles, or 0 against 180 degrees, told apart by c). A
    // vanishing normal, (0, 0), is atan2's 0 degrees; it comes only with
    // four coplanar corners, whose other angles are 0 or 180, and against
    // those c tells it right.
    bool below(const Angle& other) const {
        const double sin_difference = other.sine * cosine - other.cosine * sine;
        return sin_difference != 0 ? sin_difference > 0 : cosine > other.cosine;
    }
    double degrees() const { return std::atan2(sine, cosine) * (180 / kPi); }
};

// Running sums of Table II over some tetrahedra.
struct Accumulator {
    std::int64_t tets = 0, above = 0, below = 0, bad_steiner = 0;
    double sum = 0;
    double q_min = std::numeric_limits<double>::infinity();
    Angle dih_min, dih_max;  // meaningful once tets > 0

    void add(double q, const Angle& lo, const Angle& hi, bool touches_steiner) {
        if (tets == 0) dih_min = lo, dih_max = hi;
        ++tets;
        sum += q;
        q_min = std::min(q_min, q);
        if (q > 0.4) ++above;
        if (q < 0.1) {
            ++below;
            if (touches_steiner) ++bad_steiner;
        }
        if (lo.below(dih_min)) dih_min = lo;
        if (dih_max.below(hi)) dih_max = hi;
    }

    QualityStats stats() const {
        QualityStats s;
        s.tets = tets;
        s.bad_touching_steiner = bad_steiner;
        if (tets == 0) {
            s.quality_average = s.quality_min = s.dihedral_min_deg = s.dihedral_max_deg = kNaN;
            s.percent_above_0_4 = s.percent_below_0_1 = kNaN;
            return s;
        }
        const auto n = static_cast<double>(tets);
        s.quality_average = sum / n;
        s.quality_min = q_min;
        s.percent_above_0_4 = 100.0 * static_cast<double>(above) / n;
        s.percent_below_0_1 = 100.0 * static_cast<double>(below) / n;
        s.dihedral_min_deg = dih_min.degrees();
        s.dihedral_max_deg = dih_max.degrees();
        return s;
    }
};

// tet_quality of corners as normalized_corners gives them.
double quality_of(const std::array<Vec, 4>& p) {
    const Vec &u = p[1], &v = p[2], &w = p[3];
    const Vec vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
    const double det = dot(u, vw);
    if (det == 0) return 0;
    const double area_sum = 0.5 * (norm(uv) + norm(wu) + norm(vw) + norm(cross(sub(v, u), sub(w, u))));
    const double uu = dot(u, u), vv = dot(v, v), ww = dot(w, w);
    const Vec n = {uu * vw[0] + vv * wu[0] + ww * uv[0], uu * vw[1] + vv * wu[1] + ww * uv[1],
                   uu * vw[2] + vv * wu[2] + ww * uv[2]};
    const double q = 3 * det * det / (area_sum * norm(n));
    if (!std::isfinite(q)) return 0;
    return std::clamp(q, 0.0, 1.0);
}

// The smallest and largest dihedral angle of corners as normalized_corners
// gives them.
void dihedral_range_of(const std::array<Vec, 4>& p, Angle& smallest, Angle& largest) {
    // Edge (i, j) and the two other corners (k, l).
    static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                         {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    for (int i = 0; i < 6; ++i) {
        const int* e = kEdges[i];
        const Vec edge = sub(p[e[1]], p[e[0]]);
        const Vec n1 = cross(edge, sub(p[e[2]], p[e[0]]));
        const Vec n2 = cross(edge, sub(p[e[3]], p[e[0]]));
        const Angle a{norm(cross(n1, n2)), dot(n1, n2)};
        if (i == 0 || a.below(smallest)) smallest = a;
        if (i == 0 || largest.below(a)) largest = a;
    }
}

}  // namespace

double tet_quality(const double* a, const double* b, const double* c, const double* d) {
    std::array<Vec, 4> p;
    return normalized_corners(a, b, c, d, p) ? quality_of(p) : 0;
}

void tet_dihedral_range(const double* a, const double* b, const double* c, const double* d, double& min_deg,
                        double& max_deg) {
    std::array<Vec, 4> p;
    Angle smallest, largest;  // 0 degrees for coincident corners
    if (normalized_corners(a, b, c, d, p)) dihedral_range_of(p, smallest, largest);
    min_deg = smallest.degrees();
    max_deg = largest.degrees();
}

QualityReport measure_quality(io::VolumeMesh& mesh) {
    std::vector<double> qualities;
    QualityReport report = measure_quality(static_cast<const io::VolumeMesh&>(mesh), qualities);
    mesh.tet_quality.swap(qualities);
    return report;
}

QualityReport measure_quality(const io::VolumeMesh& mesh, std::vector<double>& qualities) {
    const std::size_t nt = mesh.num_tets();
    cbr::mesh::reserve_huge(qualities, nt);
    qualities.assign(nt, 0.0);
    Accumulator all;
    std::map<std::int32_t, Accumulator> by_region;
    Accumulator* last = nullptr;  // by_region's entry of the last tetrahedron's region
    std::int32_t last_region = 0;
    for (std::size_t t = 0; t < nt; ++t) {
        const std::int64_t* ids = &mesh.tets[4 * t];
        const double* corner[4];
        bool steiner = false;
        for (int k = 0; k < 4; ++k) {
            const auto id = static_cast<std::size_t>(ids[k]);
            corner[k] = &mesh.xyz[3 * id];
            steiner = steiner || (!mesh.is_steiner.empty() && mesh.is_steiner[id] != 0);
        }
        // The corners normalized once for both measures.
        std::array<Vec, 4> p;
        double q = 0;
        Angle lo, hi;  // 0 degrees for coincident corners
        if (normalized_corners(corner[0], corner[1], corner[2], corner[3], p)) {
            q = quality_of(p);
            dihedral_range_of(p, lo, hi);
        }
        qualities[t] = q;
        all.add(q, lo, hi, steiner);
        if (last == nullptr || mesh.tet_regions[t] != last_region) {  // neighbours mostly share one
            last_region = mesh.tet_regions[t];
            last = &by_region[last_region];
        }
        last->add(q, lo, hi, steiner);
    }
    QualityReport report;
    report.all = all.stats();
    if (by_region.size() > 1) {
        for (const auto& [region, acc] : by_region) report.regions.push_back({region, acc.stats()});
    }
    return report;
}

}  // namespace cbr::cli
