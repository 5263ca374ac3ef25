#include "refine/steiner_relocation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/cavity_boundary.hpp"
#include "mesh/slot_marks.hpp"
#include "mesh/surgery.hpp"
#include "refine/quality_stats.hpp"
#include "refine/tet_measures.hpp"

namespace cbr::refine {
namespace {

using mesh::facet_tet;
using mesh::kFaceVertices;
using mesh::TetId;
using mesh::VertexId;

// Rings of neighbours taken into the cavity around the ball (0: the ball
// alone, i.e. a move within it).
constexpr int kMaxReach = 3;
// Boundary faces on which v's tetrahedron is below this radius ratio (and
// every constraint face of the boundary) get apex candidates.
constexpr double kApexBelow = 0.3;
// Heights of the apex candidates above a boundary face, in mean edge
// lengths of that face (0.8: about a regular tetrahedron's apex).
constexpr double kApexHeights[] = {0.8, 0.5, 0.3, 0.15};
// Fractions of the way from the point to each candidate also tried (a
// candidate that the cavity does not see may have a visible stretch).
constexpr double kSteps[] = {1.0, 0.5, 0.25, 0.125, 0.0625};

using Face = mesh::CavityFace;

class Relocator {
public:
    Relocator(RefineContext& c, const std::vector<char>& steiner) : c_(c), m_(c.m), steiner_(steiner) {}
    bool relocate(VertexId v, TetId start, double threshold);

private:
    bool in_cavity(TetId t) const { return marks_.has(t, kInCavity); }
    void add_to_cavity(TetId t) {
        cavity_.push_back(t);
        marks_.set(t, kInCavity);
    }
    bool collect_boundary(VertexId v);
    bool star_measures(const double* p, double threshold, double& worst, std::size_t& bad) const;
    bool is_steiner(VertexId v) const { return v < steiner_.size() && steiner_[v]; }
    bool star_within_size(VertexId v, const Point& p);
    void add_candidates(VertexId v, const Point& here);

    RefineContext& c_;
    mesh::TetMesh& m_;
    const std::vector<char>& steiner_;  // per vertex: one of recovery's Steiner points
    std::vector<TetId> ball_, cavity_;
    static constexpr std::uint8_t kInCavity = 1u << 0;
    mesh::SlotMarks marks_;
    std::vector<Face> boundary_;
    std::vector<VertexId> boundary_vertices_;
    std::vector<Point> candidates_;

public:
    std::vector<TetId> created;  // after a relocation: the star
};

// The boundary faces of the cavity; false when a vertex other than v would
// be inside the cavity (the star would drop it from the mesh).
bool Relocator::collect_boundary(VertexId v) {
    mesh::cavity_boundary(m_, cavity_, [&](TetId t) { return in_cavity(t); }, boundary_, boundary_vertices_);
    for (TetId t : cavity_)
        for (int i = 0; i < 4; ++i) {
            const VertexId w = m_.vertex(t, i);
            if (w != v && !std::binary_search(boundary_vertices_.begin(), boundary_vertices_.end(), w)) return false;
        }
    // v itself must be inside (it is: the whole ball is in the cavity, and
    // the ball's faces at v are interior), so it is on no boundary face.
    return !std::binary_search(boundary_vertices_.begin(), boundary_vertices_.end(), v);
}

// The star of p over the boundary: false when a boundary face does not
// see p strictly (exact); else its worst radius ratio and its tetrahedra
// below `threshold`.
bool Relocator::star_measures(const double* p, double threshold, double& worst, std::size_t& bad) const {
    for (const Face& f : boundary_)
        if (geom::orient3d(m_.point(f.v[0]), m_.point(f.v[1]), m_.point(f.v[2]), p) <= 0) return false;
    // Then the radius ratios (each_radius_ratio: two at a time).
    worst = 1;
    bad = 0;
    each_radius_ratio(
        boundary_.size(),
        [&](std::size_t k, const double* c[4]) {
            const Face& f = boundary_[k];
            for (int i = 0; i < 3; ++i) c[i] = m_.point(f.v[i]);
            c[3] = p;
        },
        [&](double q) {
            worst = std::min(worst, q);
            bad += q < threshold;
            return true;
        });
    return true;
}

// Every edge of the star (v at p to a boundary vertex) within the size
// bound (refine_options.hpp, kEdgeFactor). Leaves v at p.
bool Relocator::star_within_size(VertexId v, const Point& p) {
    m_.set_point(v, p.data());
    for (VertexId u : boundary_vertices_)
        if (!c_.edge_within_size(u, v)) return false;
    return true;
}

// Candidates: where v is (the neighbourhood retetrahedralized around it);
// the centroid of the cavity's boundary vertices and of the ball's link;
// above each boundary face that a tetrahedron of the ball rests on badly
// and above each constraint face of the boundary, the apex of a
// well-shaped tetrahedron on it (lifting v off the surface, §6 "reposition
// them to better locations"); and for each, a few points on the way there.
void Relocator::add_candidates(VertexId v, const Point& here) {
    std::vector<Point> targets;
    Point all = {0, 0, 0}, link = {0, 0, 0};
    for (VertexId u : boundary_vertices_)
        for (int k = 0; k < 3; ++k) all[k] += m_.point(u)[k] / static_cast<double>(boundary_vertices_.size());
    targets.push_back(all);
    double link_count = 0;
    for (TetId t : ball_)
        for (int i = 0; i < 4; ++i)
            if (m_.vertex(t, i) != v) {
                for (int k = 0; k < 3; ++k) link[k] += m_.point(m_.vertex(t, i))[k];
                link_count += 1;
            }
    for (double& x : link) x /= link_count;
    targets.push_back(link);
    for (const Face& f : boundary_) {
        const double* a = m_.point(f.v[0]);
        const double* b = m_.point(f.v[1]);
        const double* d = m_.point(f.v[2]);
        if (!f.constrained && radius_ratio(a, b, d, here.data()) >= kApexBelow) continue;
        // (a, b, d) in kFaceVertices order: (b - a) x (d - a) points into the cavity.
        add_apexes(a, b, d, kApexHeights, std::size(kApexHeights), targets);
    }
    candidates_.clear();
    candidates_.push_back(here);
    for (const Point& t : targets)
        for (double step : kSteps) {
            Point p;
            for (int k = 0; k < 3; ++k) p[k] = here[k] + step * (t[k] - here[k]);
            candidates_.push_back(p);
        }
}

bool Relocator::relocate(VertexId v, TetId start, double threshold) {
    if (!mesh::ball(m_, v, start, ball_) || ball_.empty()) return false;
    const std::int32_t region = c_.region(ball_.front());
    double ball_min = 1;
    for (TetId t : ball_) {
        if (!c_.in_domain(t) || c_.region(t) != region) return false;
        ball_min = std::min(ball_min, radius_ratio(m_, t));
    }
    if (ball_min >= threshold) return false;
    const Point here = {m_.point(v)[0], m_.point(v)[1], m_.point(v)[2]};
    marks_.new_round(m_.slot_count());
    cavity_.clear();
    for (TetId t : ball_) add_to_cavity(t);
    // The best relocation so far: how many bad tetrahedra at Steiner points
    // it removes (gain), then the worst radius ratio of its star.
    Point best_point = here;
    long best_gain = 0;
    double best_min = -1;
    std::vector<TetId> best_cavity;
    for (int reach = 0; reach <= kMaxReach; ++reach) {
        if (reach > 0) {
            const std::size_t outer = cavity_.size();
            for (std::size_t i = 0; i < outer; ++i) {
                const TetId t = cavity_[i];
                for (int f = 0; f < 4; ++f) {
                    if (m_.is_constrained(t, f)) continue;
                    const TetId n = facet_tet(m_.neighbor(t, f));
                    if (c_.in_domain(n) && c_.region(n) == region && !in_cavity(n)) add_to_cavity(n);
                }
            }
        }
        if (!collect_boundary(v)) break;  // a larger cavity would swallow the vertex too
        // The cavity now: its worst radius ratio, its bad tetrahedra, and
        // those of them at a Steiner point (what Table II's last row
        // counts; every tetrahedron of the star has v as a corner).
        double old_min = 1;
        long old_bad = 0, old_bad_steiner = 0;
        for (TetId t : cavity_) {
            const double q = radius_ratio(m_, t);
            old_min = std::min(old_min, q);
            if (q >= threshold) continue;
            ++old_bad;
            const VertexId* w = m_.vertices(t);
            old_bad_steiner += is_steiner(w[0]) || is_steiner(w[1]) || is_steiner(w[2]) || is_steiner(w[3]);
        }
        add_candidates(v, here);
        for (const Point& p : candidates_) {
            double q = 0;
            std::size_t bad = 0;
            // A star no worse than the cavity at its worst, with no more
            // bad tetrahedra in all, and fewer at Steiner points (or as
            // many, with a better worst).
            if (!star_measures(p.data(), threshold, q, bad) || q < old_min || static_cast<long>(bad) > old_bad) continue;
            const long gain = old_bad_steiner - static_cast<long>(bad);
            if (gain < 0 || (gain == 0 && !(q > old_min))) continue;
            if (gain < best_gain || (gain == best_gain && !(q > best_min))) continue;
            if (!star_within_size(v, p)) continue;
            best_gain = gain, best_min = q, best_point = p, best_cavity = cavity_;
        }
        m_.set_point(v, here.data());
        // The smallest cavity that leaves v without a bad tetrahedron is
        // the least change.
        if (best_min >= threshold) break;
    }
    if (best_min < 0) return false;
    // Replace the chosen cavity by the star of v at its new place.
    marks_.new_round(m_.slot_count());
    cavity_.clear();
    for (TetId t : best_cavity) add_to_cavity(t);
    if (!collect_boundary(v)) return false;
    std::vector<std::array<VertexId, 4>> fresh;
    fresh.reserve(boundary_.size());
    for (const Face& f : boundary_) fresh.push_back({f.v[0], f.v[1], f.v[2], v});
    m_.set_point(v, best_point.data());
    if (mesh::replace_tets(m_, cavity_, fresh, &created) != mesh::ReplaceResult::kDone) {
        m_.set_point(v, here.data());
        return false;
    }
    for (TetId t : created) c_.set_region(t, region);
    return true;
}

}  // namespace

std::size_t relocate_steiner_points(RefineContext& c, const std::vector<VertexId>& steiner, double threshold) {
    if (steiner.empty()) return 0;
    const std::vector<char> is_steiner = steiner_flags(c.m, steiner);
    Relocator r(c, is_steiner);
    std::size_t moved = 0;
    std::vector<TetId> incident = mesh::incident_tets(c.m);
    for (VertexId v : steiner) {
        if (v >= incident.size() || incident[v] == mesh::kNoTet || c.is_surface_vertex(v)) continue;
        if (!r.relocate(v, incident[v], threshold)) continue;
        ++moved;
        // The star's vertices start in it (the cavity's old slots are
        // reused or freed).
        for (TetId t : r.created)
            for (int i = 0; i < 4; ++i) incident[c.m.vertex(t, i)] = t;
    }
    return moved;
}

}  // namespace cbr::refine
