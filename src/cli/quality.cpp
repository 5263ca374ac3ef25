#include "cli/quality.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

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

// Running sums of Table II over some tetrahedra.
struct Accumulator {
    std::int64_t tets = 0, above = 0, below = 0, bad_steiner = 0;
    double sum = 0;
    double q_min = std::numeric_limits<double>::infinity();
    double dih_min = std::numeric_limits<double>::infinity();
    double dih_max = -std::numeric_limits<double>::infinity();

    void add(double q, double lo, double hi, bool touches_steiner) {
        ++tets;
        sum += q;
        q_min = std::min(q_min, q);
        if (q > 0.4) ++above;
        if (q < 0.1) {
            ++below;
            if (touches_steiner) ++bad_steiner;
        }
        dih_min = std::min(dih_min, lo);
        dih_max = std::max(dih_max, hi);
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
        s.dihedral_min_deg = dih_min;
        s.dihedral_max_deg = dih_max;
        return s;
    }
};

// Whether atan2(s1, c1) < atan2(s2, c2), for s1, s2 >= 0: sin(second -
// first) = s2 c1 - c2 s1 (times the lengths) is positive; where it is 0 the
// directions are parallel (equal angles, or 0 against 180 degrees, told
// apart by c). A vanishing normal, (0, 0), is atan2's 0 degrees; it comes
// only with four coplanar corners, whose other angles are 0 or 180, and
// against those c tells it right.
bool angle_below(double s1, double c1, double s2, double c2) {
    const double sine = s2 * c1 - c2 * s1;
    return sine != 0 ? sine > 0 : c1 > c2;
}

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

// tet_dihedral_range of corners as normalized_corners gives them.
void dihedral_range_of(const std::array<Vec, 4>& p, double& min_deg, double& max_deg) {
    // Edge (i, j) and the two other corners (k, l).
    static constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                         {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    // The angle at an edge is atan2(sine, cosine), sine = |n1 x n2| >= 0,
    // cosine = n1 . n2 (both scaled by |n1| |n2|). Angles in [0, 180]
    // compare without it (angle_below), so atan2 runs twice, not six
    // times (on every edge it was 40% of measuring igea's 800,000
    // tetrahedra after recovery).
    double sine[6], cosine[6];
    int smallest = 0, largest = 0;
    for (int i = 0; i < 6; ++i) {
        const int* e = kEdges[i];
        const Vec edge = sub(p[e[1]], p[e[0]]);
        const Vec n1 = cross(edge, sub(p[e[2]], p[e[0]]));
        const Vec n2 = cross(edge, sub(p[e[3]], p[e[0]]));
        sine[i] = norm(cross(n1, n2));
        cosine[i] = dot(n1, n2);
        if (angle_below(sine[i], cosine[i], sine[smallest], cosine[smallest])) smallest = i;
        if (angle_below(sine[largest], cosine[largest], sine[i], cosine[i])) largest = i;
    }
    min_deg = std::atan2(sine[smallest], cosine[smallest]) * (180 / kPi);
    max_deg = std::atan2(sine[largest], cosine[largest]) * (180 / kPi);
}

}  // namespace

double tet_quality(const double* a, const double* b, const double* c, const double* d) {
    std::array<Vec, 4> p;
    return normalized_corners(a, b, c, d, p) ? quality_of(p) : 0;
}

void tet_dihedral_range(const double* a, const double* b, const double* c, const double* d, double& min_deg,
                        double& max_deg) {
    std::array<Vec, 4> p;
    if (normalized_corners(a, b, c, d, p)) {
        dihedral_range_of(p, min_deg, max_deg);
    } else {
        min_deg = max_deg = 0;
    }
}

QualityReport measure_quality(io::VolumeMesh& mesh) {
    const std::size_t nt = mesh.num_tets();
    mesh.tet_quality.assign(nt, 0.0);
    Accumulator all;
    std::map<std::int32_t, Accumulator> by_region;
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
        double q = 0, lo = 0, hi = 0;
        if (normalized_corners(corner[0], corner[1], corner[2], corner[3], p)) {
            q = quality_of(p);
            dihedral_range_of(p, lo, hi);
        }
        mesh.tet_quality[t] = q;
        all.add(q, lo, hi, steiner);
        by_region[mesh.tet_regions[t]].add(q, lo, hi, steiner);
    }
    QualityReport report;
    report.all = all.stats();
    if (by_region.size() > 1) {
        for (const auto& [region, acc] : by_region) report.regions.push_back({region, acc.stats()});
    }
    return report;
}

}  // namespace cbr::cli
