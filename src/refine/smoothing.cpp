#include "refine/smoothing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/chunks.hpp"
#include "mesh/slot_marks.hpp"
#include "refine/compass_search.hpp"
#include "refine/tet_measures.hpp"
#include "refine/vertex_halves.hpp"

namespace cbr::refine {
namespace {

using mesh::TetId;
using mesh::VertexId;

// Below this radius ratio, the worst tetrahedron of a ball also gets
// candidates that lift the vertex off its opposite face.
constexpr double kLiftBelow = 0.3;
// A ball whose worst tetrahedron is at least kMeanFrom is smoothed for its
// mean quality (what Table II's average counts), its worst kept at least
// min(old worst, kMeanFloor); below kMeanFrom, for its worst. A move must
// raise the ball's sum of qualities by the factor kMeanGain (no drift on
// ties).
constexpr double kMeanFrom = 0.15;
constexpr double kMeanFloor = 0.3;
constexpr double kMeanGain = 1.0 + 1e-3;
// smooth_for_dihedrals: a move must raise the ball's smallest dihedral
// angle by this factor, keep this share of its mean radius ratio, and
// its pattern search halves its step this many times.
constexpr double kAngleGain = 1.0 + 1e-3;
constexpr double kAngleMeanKept = 0.9;
constexpr int kAngleHalvings = 8;

class Smoother {
public:
    explicit Smoother(RefineContext& c) : c_(c), m_(c.m) {}
    bool smooth(VertexId v, const mesh::VertexBalls& balls);
    bool raise_smallest_angle(VertexId v, TetId start, double below_degrees, double keep_radius_ratio,
                              std::uint32_t since);

private:
    // The ball at v's current position, as raise_smallest_angle judges it.
    struct BallAngles {
        double smallest = -1;  // smallest dihedral angle; -1: some tetrahedron not positively oriented
        double worst_q = 1;    // smallest radius ratio
        double sum_q = 0;
        std::size_t under = 0;  // tetrahedra with radius ratio under the bound kept
    };
    BallAngles rate_angles(double keep_radius_ratio, double to_beat = -1);
    bool collect_link(VertexId v);
    template <typename Visit>
    bool each_quality(Visit visit) const;
    double min_quality(double floor) const;
    double sum_quality(double floor, double to_beat) const;
    bool odt_point(Point& out) const;
    std::size_t oriented_prefix() const;
    bool link_keeps_size(VertexId v) const;
    bool ball_valid(VertexId v) const;

    RefineContext& c_;
    mesh::TetMesh& m_;
    std::vector<TetId> ball_;
    std::vector<VertexId> neighbours_;
    std::vector<double> link_lengths_;  // squared length of v's edge to each of neighbours_ before the move
    std::vector<double> qualities_;  // radius ratios of ball_ at the vertex's position, in ball_'s order
    std::vector<Point> candidates_;  // smooth(): the positions tried (kept: one allocation, not four per ball)
    // rate_angles: the ball tetrahedra (indices in ball_) that held the
    // smallest angle at the last positions rated, the latest first; past
    // the ball's size where unknown (kNoSuspect: a new ball).
    static constexpr std::size_t kNoSuspect = std::numeric_limits<std::size_t>::max();
    std::array<std::size_t, 4> suspects_ = {kNoSuspect, kNoSuspect, kNoSuspect, kNoSuspect};
    void suspect(std::size_t k);
    mesh::SlotMarks seen_;  // per vertex: kSeen when already in neighbours_
    static constexpr std::uint8_t kSeen = 1;
};

// Calls visit(q) with the radius ratios of ball_'s tetrahedra in ball_'s
// order until it returns false (then false): each_radius_ratio.
template <typename Visit>
bool Smoother::each_quality(Visit visit) const {
    return each_radius_ratio(
        ball_.size(), [&](std::size_t k, const double* c[4]) { corner_points(m_, ball_[k], c); }, visit);
}

// The ball's minimum quality when it is above `floor`; otherwise some value
// at most `floor` (the search stops at the first tetrahedron not above it:
// a candidate that does not beat the best so far is not looked at further).
double Smoother::min_quality(double floor) const {
    double q = 1;
    each_quality([&](double r) {
        q = std::min(q, r);
        return q > floor;
    });
    return q;
}

// The sum of the ball's qualities; -1 as soon as one is below `floor`, or
// as soon as the sum cannot exceed `to_beat` even if every tetrahedron
// left scored 1 (radius ratios are at most 1; the margin covers the
// rounding of the sums, so a candidate cut short here would not have
// beaten `to_beat` either).
double Smoother::sum_quality(double floor, double to_beat) const {
    const double reachable = to_beat * (1 - 1e-9);
    double sum = 0;
    double left = static_cast<double>(ball_.size());
    const bool whole = each_quality([&](double q) {
        if (q < floor) return false;
        sum += q;
        left -= 1;
        return !(sum + left < reachable);
    });
    return whole ? sum : -1;
}

// The volume-weighted mean of the circumcentres of the ball's tetrahedra
// (the vertex position of an optimal Delaunay triangulation, Chen & Xu
// 2004); false when the ball has no volume.
bool Smoother::odt_point(Point& out) const {
    Point sum = {0, 0, 0};
    double weight = 0;
    for (TetId t : ball_) {
        const VertexId* w = m_.vertices(t);
        const double* a = m_.point(w[0]);
        Point centre;
        if (!circumcentre(a, m_.point(w[1]), m_.point(w[2]), m_.point(w[3]), centre)) continue;
        const double volume = six_volume(a, m_.point(w[1]), m_.point(w[2]), m_.point(w[3]));
        for (int k = 0; k < 3; ++k) sum[k] += volume * centre[k];
        weight += volume;
    }
    if (!(weight > 0)) return false;
    for (int k = 0; k < 3; ++k) out[k] = sum[k] / weight;
    return std::isfinite(out[0]) && std::isfinite(out[1]) && std::isfinite(out[2]);
}

// neighbours_: the vertices of ball_'s link, once each (a mark per
// vertex), then ascending (the centroid's sum runs in that order); false
// when a tetrahedron of the ball is not in the domain.
bool Smoother::collect_link(VertexId v) {
    neighbours_.clear();
    seen_.new_round(m_.vertex_count());
    for (TetId t : ball_) {
        if (!c_.in_domain(t)) return false;
        for (int i = 0; i < 4; ++i) {
            const VertexId u = m_.vertex(t, i);
            if (u == v || seen_.has(u, kSeen)) continue;
            seen_.set(u, kSeen);
            neighbours_.push_back(u);
        }
    }
    std::sort(neighbours_.begin(), neighbours_.end());
    link_lengths_.clear();
    for (VertexId u : neighbours_) link_lengths_.push_back(squared_distance(m_.point(u), m_.point(v)));
    return true;
}

// How many of ball_'s tetrahedra, from the first, are positively oriented
// (exact): all of them when the ball is valid.
std::size_t Smoother::oriented_prefix() const {
    std::size_t n = 0;
    for (; n < ball_.size(); ++n) {
        const VertexId* w = m_.vertices(ball_[n]);
        if (geom::orient3d(m_.point(w[0]), m_.point(w[1]), m_.point(w[2]), m_.point(w[3])) <= 0) break;
    }
    return n;
}

// Every edge from v to its link within the size bound, or at most as long as
// it was where v stood when its link was collected (collect_link): an edge
// over the bound already (the refinement leaves some next to short input
// edges) must not freeze v, only not grow. thingiverse-feeder-body: a field
// point at a 3.8e-4 input edge, its ball's smallest dihedral angle 2.9e-4
// deg, had an edge over the bound, and no move of it was ever kept.
bool Smoother::link_keeps_size(VertexId v) const {
    for (std::size_t i = 0; i < neighbours_.size(); ++i)
        if (!c_.edge_within_size(neighbours_[i], v, link_lengths_[i])) return false;
    return true;
}

bool Smoother::ball_valid(VertexId v) const { return oriented_prefix() == ball_.size() && link_keeps_size(v); }

// Candidate positions: the centroid of the ball's other vertices (Laplacian
// smoothing, §6 "local constrained Laplacian smoothing"), half and a quarter
// of the way there; the ODT point and half the way there; then, when the
// worst tetrahedron of the ball is still bad, steps away from its face
// opposite v, along that face's normal (a vertex too close to a face, often
// a face of the surface, is lifted off it). A ball with a bad tetrahedron
// (worst below kMeanFrom) takes the candidate that raises its worst
// quality most; any other ball the one that raises its mean most, its
// worst kept above min(old worst, kMeanFloor). Every candidate keeps the
// ball valid and within the size bound. Skipped when nothing in the ball
// changed since the previous pass.
bool Smoother::smooth(VertexId v, const mesh::VertexBalls& balls) {
    balls.get(v, ball_);
    bool changed = false;
    for (TetId t : ball_) changed = changed || c_.changed(t);
    // Nothing changed around v since its last try: it would fail again.
    if (!changed || !collect_link(v)) return false;
    Point centroid = {0, 0, 0};
    double mean_edge = 0;
    const Point here = {m_.point(v)[0], m_.point(v)[1], m_.point(v)[2]};
    for (VertexId u : neighbours_) {
        for (int k = 0; k < 3; ++k) centroid[k] += m_.point(u)[k];
        mean_edge += std::sqrt(squared_distance(m_.point(u), here.data()));
    }
    for (double& x : centroid) x /= static_cast<double>(neighbours_.size());
    mean_edge /= static_cast<double>(neighbours_.size());
    std::vector<Point>& candidates = candidates_;
    candidates.clear();
    for (double step : {1.0, 0.5, 0.25}) {
        Point p;
        for (int k = 0; k < 3; ++k) p[k] = here[k] + step * (centroid[k] - here[k]);
        candidates.push_back(p);
    }
    // Optimal-Delaunay (ODT) smoothing: the volume-weighted mean of the
    // ball's circumcentres, and half the way there.
    Point odt;
    if (odt_point(odt)) {
        for (double step : {1.0, 0.5}) {
            Point p;
            for (int k = 0; k < 3; ++k) p[k] = here[k] + step * (odt[k] - here[k]);
            candidates.push_back(p);
        }
    }
    // The worst tetrahedron and the unit normal of its face opposite v,
    // pointing toward v (the face's vertices in kFaceVertices order).
    std::size_t worst_at = 0;
    double worst_q = 2;
    qualities_.resize(ball_.size());
    radius_ratios(m_, ball_.data(), ball_.size(), qualities_.data());
    for (std::size_t j = 0; j < ball_.size(); ++j)
        if (qualities_[j] < worst_q) worst_q = qualities_[j], worst_at = j;
    // The worst tetrahedron first: the likeliest to stay below the best
    // quality so far, which ends min_quality early.
    std::swap(ball_[0], ball_[worst_at]);
    std::swap(qualities_[0], qualities_[worst_at]);
    const TetId worst = ball_[0];
    if (worst_q < kLiftBelow) {
        const int i = mesh::vertex_index(m_, worst, v);
        const int* k = mesh::kFaceVertices[i];
        const double* a = m_.point(m_.vertex(worst, k[0]));
        const double* b = m_.point(m_.vertex(worst, k[1]));
        const double* c = m_.point(m_.vertex(worst, k[2]));
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (len > 0) {
            for (double& x : n) x /= len;
            for (double step : {0.05, 0.1, 0.2, 0.4}) {
                Point p;
                for (int d = 0; d < 3; ++d) p[d] = here[d] + step * mean_edge * n[d];
                candidates.push_back(p);
            }
        }
    }
    const double old_min = worst_q;
    double best_q = old_min;
    const Point* best = nullptr;
    if (old_min >= kMeanFrom) {
        // A ball without a bad tetrahedron: the candidate with the best
        // mean quality, as long as its worst stays above kMeanFloor (or
        // above the old worst, when that was lower).
        const double floor = std::min(old_min, kMeanFloor);
        // The ball as it is (no quality below its worst, so none below
        // floor): the sum of the qualities already rated, in ball order.
        double best_sum = 0;
        for (double q : qualities_) best_sum += q;
        best_sum *= kMeanGain;
        // The quality first: most candidates do not beat the best so far,
        // and for those the validity and size tests are not needed. A
        // winner still needs them: the radius ratio is unsigned, so an
        // inverted ball scores too (the same holds in the loop below).
        for (const Point& p : candidates) {
            m_.set_point(v, p.data());
            const double sum = sum_quality(floor, best_sum);
            if (sum > best_sum && ball_valid(v)) best_sum = sum, best = &p;
        }
    } else {
        for (const Point& p : candidates) {
            m_.set_point(v, p.data());
            const double q = min_quality(best_q);
            if (q > best_q && ball_valid(v)) best_q = q, best = &p;
        }
    }
    m_.set_point(v, best ? best->data() : here.data());
    if (best)
        for (TetId t : ball_) c_.touch(t);
    return best != nullptr;
}

// The ball's smallest dihedral angle, and its radius ratios. The
// suspects first (suspects_: the tetrahedra of the smallest angle at the
// last positions rated): after a small move one of them mostly still
// has it, and most positions a search tries are refused by one of them
// alone, before any radius ratio (on thingiverse-feeder-body, checking
// only the last one left half of the full ratings refused by another
// tetrahedron's angle). Then the radius ratios, and the angles of the
// other tetrahedra whose radius ratio is under the bound of the smallest
// angle so far (radius_ratio_bound_for_dihedral: a tetrahedron above it
// has no smaller angle): a few per ball instead of all (the angles'
// arctangents were half of thingiverse-chain-link's mesh generation).
// Stops at an angle at or below `to_beat`: the caller refuses the
// position then, whichever tetrahedron refused it.
Smoother::BallAngles Smoother::rate_angles(double keep_radius_ratio, double to_beat) {
    BallAngles r;
    const auto angle_of = [&](std::size_t k) {
        const VertexId* w = m_.vertices(ball_[k]);
        return min_dihedral(m_.point(w[0]), m_.point(w[1]), m_.point(w[2]), m_.point(w[3]));
    };
    if (suspects_[0] >= ball_.size()) suspects_[0] = 0;  // a new ball: its first tetrahedron
    double smallest = std::numeric_limits<double>::infinity();
    std::size_t smallest_at = 0;
    std::size_t checked = 0;  // suspects_[0 .. checked) measured (those in the ball)
    for (; checked < suspects_.size() && suspects_[checked] < ball_.size(); ++checked) {
        const double angle = angle_of(suspects_[checked]);
        if (angle < smallest) smallest = angle, smallest_at = suspects_[checked];
        if (angle <= to_beat) {
            suspect(suspects_[checked]);
            r.smallest = angle;
            return r;
        }
    }
    const auto was_checked = [&](std::size_t k) {
        return std::find(suspects_.begin(), suspects_.begin() + static_cast<std::ptrdiff_t>(checked), k) !=
               suspects_.begin() + static_cast<std::ptrdiff_t>(checked);
    };
    // Every tetrahedron positively oriented (exact), then the radius
    // ratios two at a time (radius_ratios); an inverted one leaves r as
    // the ratios before it made it.
    const std::size_t valid = oriented_prefix();
    qualities_.resize(valid);
    radius_ratios(m_, ball_.data(), valid, qualities_.data());
    for (const double q : qualities_) {
        r.worst_q = std::min(r.worst_q, q);
        r.sum_q += q;
        r.under += q < keep_radius_ratio;
    }
    if (valid < ball_.size()) return r;
    double q_bound = radius_ratio_bound_for_dihedral(smallest);
    for (std::size_t k = 0; k < ball_.size() && smallest > to_beat; ++k) {
        // The margin keeps a tetrahedron whose bound ties within rounding.
        if (qualities_[k] * (1 - 1e-9) >= q_bound || was_checked(k)) continue;
        const double angle = angle_of(k);
        if (angle >= smallest) continue;
        smallest = angle;
        smallest_at = k;
        q_bound = radius_ratio_bound_for_dihedral(smallest);
    }
    suspect(smallest_at);
    r.smallest = smallest;
    return r;
}

// k goes to the front of suspects_ (from its place there, or pushing the
// last one out).
void Smoother::suspect(std::size_t k) {
    auto at = std::find(suspects_.begin(), suspects_.end(), k);
    if (at == suspects_.end()) at = suspects_.end() - 1;
    std::rotate(suspects_.begin(), at, at + 1);
    suspects_[0] = k;
}

// Table II's minimum dihedral angle does not follow the radius ratio that
// smooth() raises: a field point between the two fanned caps of a thin
// disc (thingicsg-sprocket-small) sits where its ball's worst radius ratio
// is best, and there the edges to the fans' centres lean, which narrows
// the dihedral angles at them to 3.45 deg (TetGen -pYq1.414: 3.75). Here
// a pattern search (26 directions, compass_search's kCube, of a quarter
// of the link's mean edge length at first, halved when none raises the
// angle) moves v to raise the ball's smallest dihedral angle instead,
// within bounds that keep the radius ratio: no more tetrahedra under
// keep_radius_ratio, the mean at least kAngleMeanKept of the old one.
// The worst radius ratio may fall: those of the tetrahedra already under
// keep_radius_ratio, which the count holds; bounding it too (by the
// smaller of keep_radius_ratio and the old worst) refused the moves that
// took thingiverse-mouth's smallest angle from 1.75 deg to 3.4 and its
// tetrahedra under q = 0.1 from 29 to 2, or common3d-rocker-arm's from
// 2.8 deg to 5.3. The ball stays valid (exact) and within the size bound;
// the move is kept when the angle rises by kAngleGain.
bool Smoother::raise_smallest_angle(VertexId v, TetId start, double below_degrees, double keep_radius_ratio,
                                    std::uint32_t since) {
    if (!mesh::ball(m_, v, start, ball_)) return false;
    if (std::none_of(ball_.begin(), ball_.end(), [&](TetId t) { return c_.changed_since(t, since); })) return false;
    const double q_bound = radius_ratio_bound_for_dihedral(below_degrees);
    const bool wanted = std::any_of(ball_.begin(), ball_.end(),
                                    [&](TetId t) { return has_dihedral_below(m_, t, below_degrees, q_bound); });
    if (!wanted || !collect_link(v)) return false;
    suspects_.fill(kNoSuspect);
    const Point here = {m_.point(v)[0], m_.point(v)[1], m_.point(v)[2]};
    const BallAngles old = rate_angles(keep_radius_ratio);
    const double sum_floor = kAngleMeanKept * old.sum_q;
    const auto acceptable = [&](const BallAngles& r, double to_beat) {
        // A rating above to_beat was a full one: the ball is oriented.
        return r.smallest > to_beat && r.under <= old.under && r.sum_q >= sum_floor && link_keeps_size(v);
    };
    double step = 0;
    for (VertexId u : neighbours_) step += std::sqrt(squared_distance(m_.point(u), here.data()));
    step /= 4 * static_cast<double>(neighbours_.size());
    Point p = here;
    double angle = old.smallest;
    const auto rate = [&](const Point& trial, double to_beat) {
        m_.set_point(v, trial.data());
        const BallAngles r = rate_angles(keep_radius_ratio, to_beat);
        return acceptable(r, to_beat) ? r.smallest : -1.0;
    };
    compass_search(p, angle, step, kAngleHalvings, rate, Stencil::kCube);
    const bool moved = angle > old.smallest * kAngleGain;
    m_.set_point(v, moved ? p.data() : here.data());
    if (moved)
        for (TetId t : ball_) c_.touch(t);
    return moved;
}

// Calls move(smoother, v, list) for each vertex of `moving` (increasing
// ids; a move reads v's ball and link and writes v and its ball's stamps):
// the inner vertices of the two halves at once, list 0 and 1, each half on
// its own thread with its own Smoother (scratch storage) when the context
// allows two; then the border vertices, list 2 (vertex_halves.hpp). The
// order does not depend on the number of threads. Returns how many moves
// returned true.
template <typename Move>
std::size_t move_in_halves(RefineContext& c, const std::vector<VertexId>& moving, Move move) {
    const VertexHalves halves = split_in_halves(c.m, moving);
    c.reserve_slots();
    std::array<std::size_t, 2> moved = {0, 0};
    mesh::run_chunks(2, c.options.threads > 1 ? 2 : 1, [&](std::size_t, std::size_t begin, std::size_t end) {
        Smoother s(c);
        for (std::size_t h = begin; h < end; ++h)
            for (VertexId v : halves.inner[h]) moved[h] += move(s, v, h);
    });
    Smoother s(c);
    std::size_t border_moved = 0;
    for (VertexId v : halves.border) border_moved += move(s, v, std::size_t{2});
    return moved[0] + moved[1] + border_moved;
}

}  // namespace

std::size_t smooth_for_dihedrals(RefineContext& c, double below_degrees, double keep_radius_ratio,
                                 std::vector<VertexMove>* log, std::uint32_t since) {
    // The vertices of the tetrahedra under the angle first (the radius
    // ratio's bound before the angle, as the flips do): most balls have
    // none, and rating every ball was 2% of homer's mesh generation.
    const double q_bound = radius_ratio_bound_for_dihedral(below_degrees);
    std::vector<char> near_small_angle(c.m.vertex_count(), 0);
    for (TetId t = 0; t < c.m.slot_count(); ++t)
        if (c.in_domain(t) && has_dihedral_below(c.m, t, below_degrees, q_bound))
            for (int i = 0; i < 4; ++i) near_small_angle[c.m.vertex(t, i)] = 1;
    const std::vector<TetId> incident = mesh::incident_tets(c.m);
    std::vector<VertexId> moving;
    for (VertexId v = 0; v < c.m.vertex_count(); ++v)
        if (near_small_angle[v] && c.is_movable(v) && !c.is_surface_vertex(v) && incident[v] != mesh::kNoTet)
            moving.push_back(v);
    // The two halves at once, then the border (move_in_halves); the log
    // lists the moves in that order, in which they can be replayed.
    std::array<std::vector<VertexMove>, 3> logs;
    const std::size_t moved = move_in_halves(c, moving, [&](Smoother& s, VertexId v, std::size_t list) {
        const Point from = {c.m.point(v)[0], c.m.point(v)[1], c.m.point(v)[2]};
        if (!s.raise_smallest_angle(v, incident[v], below_degrees, keep_radius_ratio, since)) return false;
        if (log) logs[list].push_back({v, from, {c.m.point(v)[0], c.m.point(v)[1], c.m.point(v)[2]}});
        return true;
    });
    if (log)
        for (const std::vector<VertexMove>& list : logs) log->insert(log->end(), list.begin(), list.end());
    return moved;
}

std::size_t smooth_vertices(RefineContext& c) {
    const mesh::VertexBalls balls(c.m);  // moves change no tetrahedron
    std::vector<VertexId> moving;
    for (VertexId v = 0; v < c.m.vertex_count(); ++v)
        if (c.is_movable(v) && !c.is_surface_vertex(v) && !balls.empty(v)) moving.push_back(v);
    return move_in_halves(c, moving, [&](Smoother& s, VertexId v, std::size_t) { return s.smooth(v, balls); });
}

}  // namespace cbr::refine
