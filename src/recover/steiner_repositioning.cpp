// Steiner point repositioning (§6). Candidate points are constructed in
// floating point and then judged only through tet_quality, whose sign is
// the exact orient3d: a point is acceptable when every ball tetrahedron
// stays strictly positive and it lies on no input triangle of the link.
#include "recover/steiner_repositioning.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "geom/point_in_triangle.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/flips.hpp"

namespace cbr::recover {

using mesh::kFaceVertices;
using mesh::kGhostVertex;
using mesh::TetId;
using mesh::TetMesh;
using mesh::VertexId;

namespace {

using Point = std::array<double, 3>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Ball(v) as the link faces (a, b, c), each listed so that (a, b, c, v)
// is its ball tetrahedron up to an even permutation: orient3d(a, b, c, v)
// > 0 (kFaceVertices order: the face's normal points toward v).
struct Ball {
    std::vector<std::array<VertexId, 3>> faces;
    std::vector<std::array<VertexId, 3>> input_faces;  // link faces that are constraints or input triangles
};

enum class BallStatus { kOk, kNotInMesh, kHull, kOnConstraint };

// Every input triangle whose bounding box meets the ball's. A point kept
// strictly inside the ball's region stays inside the bounding box of the
// ball's vertices (the region is a union of tetrahedra on them), and a
// point of a closed triangle lies in the triangle's bounding box: both
// comparisons are exact on doubles, so no triangle that the point could
// reach is left out, even one that is not (yet) a face of the mesh.
void add_reachable_inputs(const TetMesh& m, VertexId v, Ball& b, const ConstraintFaces& input) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = m.point(v)[k];
    for (const auto& f : b.faces)
        for (VertexId w : f)
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], m.point(w)[k]);
                hi[k] = std::max(hi[k], m.point(w)[k]);
            }
    for (std::size_t i = 0; i < input.size(); ++i) {
        const Triangle& t = input.triangle(i);
        bool meets = true;
        for (int k = 0; k < 3 && meets; ++k) {
            const double a = m.point(t[0])[k], c = m.point(t[1])[k], d = m.point(t[2])[k];
            meets = std::max({a, c, d}) >= lo[k] && std::min({a, c, d}) <= hi[k];
        }
        if (meets) b.input_faces.push_back(t);
    }
}

// `inputs`: also collect the input triangles that the point could reach.
BallStatus gather(const TetMesh& m, VertexId v, TetId start, const ConstraintFaces& input, Ball& b, bool inputs) {
    std::vector<TetId> tets;
    if (!mesh::ball(m, v, start, tets)) return BallStatus::kNotInMesh;
    for (TetId t : tets) {
        if (m.is_ghost(t)) return BallStatus::kHull;
        const int iv = mesh::vertex_index(m, t, v);
        for (int f = 0; f < 4; ++f)
            if (f != iv && m.is_constrained(t, f)) return BallStatus::kOnConstraint;
        const std::array<VertexId, 3> face = {m.vertex(t, kFaceVertices[iv][0]), m.vertex(t, kFaceVertices[iv][1]),
                                              m.vertex(t, kFaceVertices[iv][2])};
        b.faces.push_back(face);
        if (m.is_constrained(t, iv)) b.input_faces.push_back(face);
    }
    if (inputs) add_reachable_inputs(m, v, b, input);
    return BallStatus::kOk;
}

// The quality of the ball tetrahedron on link face f with v at p.
double quality_at(const TetMesh& m, const std::array<VertexId, 3>& f, const double* p) {
    return mesh::tet_quality(m.point(f[0]), m.point(f[1]), m.point(f[2]), p);
}

// Worst quality of the ball with v at p, and the index of the worst face;
// -inf when some tetrahedron is not strictly positive (exact).
double min_quality(const TetMesh& m, const Ball& b, const double* p, std::size_t* worst = nullptr) {
    double q = kInf;
    for (std::size_t i = 0; i < b.faces.size(); ++i) {
        const double qi = quality_at(m, b.faces[i], p);
        if (qi < q) {
            q = qi;
            if (worst) *worst = i;
        }
        if (q == -kInf) return q;
    }
    return q;
}

// Whether every tetrahedron of the ball with v at p rates above `bar`;
// then `q` is the ball's minimum quality (min_quality's value). The line
// search asks this of every step, and most steps are refused, by the same
// tetrahedron as the step before more often than not: that one, the
// `suspect`, is rated first, and the first tetrahedron at or under the bar
// ends the rating and becomes the suspect.
bool min_quality_above(const TetMesh& m, const Ball& b, const double* p, double bar, std::size_t& suspect,
                       double& q) {
    q = quality_at(m, b.faces[suspect], p);
    if (q <= bar) return false;
    for (std::size_t i = 0; i < b.faces.size(); ++i) {
        if (i == suspect) continue;
        const double qi = quality_at(m, b.faces[i], p);
        if (qi <= bar) {
            suspect = i;
            q = qi;
            return false;
        }
        q = std::min(q, qi);
    }
    return true;
}

bool on_input_face(const TetMesh& m, const Ball& b, const double* p) {
    for (const auto& f : b.input_faces)
        if (geom::point_in_triangle(p, m.point(f[0]), m.point(f[1]), m.point(f[2]))) return true;
    return false;
}

Point sub(const double* a, const double* b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm(const Point& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

// The apex of the regular tetrahedron on face abc, on the side of `side`
// (an approximate construction: only a candidate).
Point ideal_apex(const double* a, const double* b, const double* c, const double* side) {
    const Point u = sub(b, a), w = sub(c, a);
    Point n = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const Point s = sub(side, a);
    if (n[0] * s[0] + n[1] * s[1] + n[2] * s[2] < 0) n = {-n[0], -n[1], -n[2]};
    const double len = norm(n);
    const double edge = (norm(u) + norm(w) + norm(sub(c, b))) / 3;
    const double h = std::sqrt(2.0 / 3.0) * edge;
    Point out;
    for (int k = 0; k < 3; ++k) out[k] = (a[k] + b[k] + c[k]) / 3 + (len > 0 ? n[k] / len * h : 0);
    return out;
}

// Candidate targets for the 1-D search from p.
std::vector<Point> candidates(const TetMesh& m, const Ball& b, const double* p, std::size_t worst) {
    Point centroid = {0, 0, 0}, apexes = {0, 0, 0}, weighted = {0, 0, 0};
    double wsum = 0, count = 0;
    for (const auto& f : b.faces) {
        const Point ap = ideal_apex(m.point(f[0]), m.point(f[1]), m.point(f[2]), p);
        const double q = quality_at(m, f, p);
        const double w = 1.0 / std::max(q * q, 1e-12);  // the bad tetrahedra pull hardest
        for (int k = 0; k < 3; ++k) {
            centroid[k] += (m.point(f[0])[k] + m.point(f[1])[k] + m.point(f[2])[k]) / 3;
            apexes[k] += ap[k];
            weighted[k] += w * ap[k];
        }
        wsum += w;
        count += 1;
    }
    for (int k = 0; k < 3; ++k) {
        centroid[k] /= count;
        apexes[k] /= count;
        weighted[k] /= wsum;
    }
    const auto& f = b.faces[worst];
    return {centroid, apexes, weighted, ideal_apex(m.point(f[0]), m.point(f[1]), m.point(f[2]), p)};
}

// The ball's minimum quality, or +inf when v is not movable / not there.
double ball_min_quality(const TetMesh& m, VertexId v, TetId start, const ConstraintFaces& faces) {
    Ball b;
    if (start == mesh::kNoTet || gather(m, v, start, faces, b, false) != BallStatus::kOk) return kInf;
    return min_quality(m, b, m.point(v));
}

}  // namespace

bool reposition_vertex(TetMesh& m, VertexId v, TetId start, const ConstraintFaces& faces,
                       const RepositionOptions& options, double* before, double* after) {
    Ball b;
    if (v == kGhostVertex || gather(m, v, start, faces, b, !options.all_faces_present) != BallStatus::kOk || b.faces.empty()) return false;
    Point cur = {m.point(v)[0], m.point(v)[1], m.point(v)[2]};
    std::size_t worst = 0;
    double q = min_quality(m, b, cur.data(), &worst);
    if (before) *before = q;
    bool moved = false;
    std::size_t suspect = worst;
    for (int round = 0; round < options.rounds; ++round) {
        Point best = cur;
        double best_q = q;
        for (const Point& target : candidates(m, b, cur.data(), worst)) {
            double step = 1;
            for (int h = 0; h <= options.halvings; ++h, step /= 2) {
                Point p;
                for (int k = 0; k < 3; ++k) p[k] = cur[k] + step * (target[k] - cur[k]);
                double qp = 0;
                if (min_quality_above(m, b, p.data(), best_q, suspect, qp) && !on_input_face(m, b, p.data())) {
                    best_q = qp;
                    best = p;
                }
            }
        }
        if (!(best_q > q)) break;
        cur = best;
        q = min_quality(m, b, cur.data(), &worst);
        moved = true;
    }
    if (moved) m.set_point(v, cur.data());
    if (after) *after = q;
    return moved;
}

RepositionStats reposition_steiner_points(TetMesh& m, const std::vector<VertexId>& steiner,
                                          const ConstraintFaces& faces, const RepositionOptions& options) {
    RepositionStats st;
    // Moving points changes no tetrahedron, so these stay valid.
    const std::vector<TetId> start = mesh::incident_tets(m);
    auto start_of = [&](VertexId v) { return v < start.size() ? start[v] : mesh::kNoTet; };
    st.min_quality_before = kInf;
    for (VertexId v : steiner) st.min_quality_before = std::min(st.min_quality_before, ball_min_quality(m, v, start_of(v), faces));
    std::vector<char> movable(steiner.size(), 1), moved(steiner.size(), 0);
    for (std::size_t i = 0; i < steiner.size(); ++i) {
        Ball b;
        const TetId t = start_of(steiner[i]);
        if (t == mesh::kNoTet || gather(m, steiner[i], t, faces, b, false) != BallStatus::kOk) {
            movable[i] = 0;
            ++st.skipped;
        }
    }
    st.points = steiner.size();
    for (int pass = 0; pass < options.passes; ++pass) {
        bool any = false;
        for (std::size_t i = 0; i < steiner.size(); ++i)
            if (movable[i] && reposition_vertex(m, steiner[i], start_of(steiner[i]), faces, options)) {
                moved[i] = 1;
                any = true;
            }
        if (!any) break;
    }
    st.moved = static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
    st.min_quality_after = kInf;
    for (VertexId v : steiner) st.min_quality_after = std::min(st.min_quality_after, ball_min_quality(m, v, start_of(v), faces));
    return st;
}

}  // namespace cbr::recover
