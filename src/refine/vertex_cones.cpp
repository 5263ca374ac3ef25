#include "refine/vertex_cones.hpp"

#include <algorithm>
#include <array>

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
using mesh::kGhostVertex;
using mesh::TetId;
using mesh::VertexId;

// Tetrahedra a cavity may grow to: a bound on the work per apex (each
// tetrahedron taken in costs up to four exact orientation tests).
constexpr std::size_t kMaxCavity = 64;
// A cone kept for its angle beats the cavity's smallest dihedral angle by
// this factor (as the points for small angles, sliver_removal.cpp).
constexpr double kAngleGain = 1.0 + 1e-3;

using Face = mesh::CavityFace;

// What Table II counts in a set of tetrahedra.
struct Rating {
    std::size_t bad = 0;             // under the threshold
    std::size_t bad_at_steiner = 0;  // of them, with a Steiner corner
    double worst_ratio = 1;          // smallest radius ratio
    double smallest_angle = 180;     // smallest dihedral angle, degrees
    // The squared length of the longest edge over the size bound (0: none).
    double longest_over_bound2 = 0;
};

class ConeMaker {
public:
    ConeMaker(RefineContext& c, const std::vector<char>& steiner, double threshold)
        : c_(c), m_(c.m), steiner_(steiner), threshold_(threshold) {}

    // The best cone for t, if one is kept (then true, and `log` gets it);
    // `suppressed` is then the Steiner point it took out of the mesh, or
    // kGhostVertex.
    bool improve(TetId t, VertexId& suppressed, std::vector<TetChange>* log);

private:
    bool is_steiner(VertexId v) const { return v < steiner_.size() && steiner_[v]; }
    bool in_cavity(TetId t) const { return marks_.has(t, kInCavity); }
    void add_to_cavity(TetId t) {
        cavity_.push_back(t);
        marks_.set(t, kInCavity);
    }
    // Where a cavity starts: {t}, or the ball of a Steiner corner of t
    // that the cone then takes out of the mesh (`inside`).
    struct Start {
        std::vector<TetId> tets;
        VertexId inside = kGhostVertex;
    };
    void collect_starts(TetId t, std::int32_t region);
    void collect_apexes(TetId t);
    bool grow(const Start& start, VertexId apex, std::int32_t region);
    bool collect_boundary(VertexId apex, VertexId inside);
    Rating rate_cavity() const;
    bool rate_cone(VertexId apex, const Rating& cavity, Rating& cone) const;
    void count(double q, bool at_steiner, Rating& r) const {
        r.worst_ratio = std::min(r.worst_ratio, q);
        if (q >= threshold_) return;
        ++r.bad;
        r.bad_at_steiner += at_steiner;
    }

    RefineContext& c_;
    mesh::TetMesh& m_;
    const std::vector<char>& steiner_;
    const double threshold_;
    static constexpr std::uint8_t kInCavity = 1u << 0;
    mesh::SlotMarks marks_;
    std::vector<TetId> ball_, cavity_;
    std::vector<Start> starts_;
    std::vector<VertexId> apexes_;
    static constexpr std::uint8_t kOnBoundary = 1u << 0;
    mesh::SlotMarks vertex_marks_;  // per vertex: kOnBoundary (collect_boundary)
    std::vector<Face> boundary_;
};

// The vertices of the tetrahedra around t's corners (t's own too: over {t}
// a corner's cone is t itself, which no rule keeps; over the ball of
// another corner, it is that corner's contraction onto it).
void ConeMaker::collect_apexes(TetId t) {
    apexes_.clear();
    const VertexId* corners = m_.vertices(t);
    for (int i = 0; i < 4; ++i) {
        if (!mesh::ball(m_, corners[i], t, ball_)) continue;
        for (TetId s : ball_)
            for (int k = 0; k < 4; ++k) apexes_.push_back(m_.vertex(s, k));
    }
    std::sort(apexes_.begin(), apexes_.end());
    apexes_.erase(std::unique(apexes_.begin(), apexes_.end()), apexes_.end());
    if (!apexes_.empty() && apexes_.back() == kGhostVertex) apexes_.pop_back();  // the largest id
}

// {t}, then the ball of each Steiner corner of t whose tetrahedra are all
// in t's region (§6, Steiner points minimization: a cone from a vertex of
// a cavity around the ball tetrahedralizes it without the point).
void ConeMaker::collect_starts(TetId t, std::int32_t region) {
    starts_.assign(1, Start{{t}, kGhostVertex});
    for (int i = 0; i < 4; ++i) {
        const VertexId v = m_.vertex(t, i);
        if (!is_steiner(v) || c_.is_surface_vertex(v) || !mesh::ball(m_, v, t, ball_)) continue;
        if (std::all_of(ball_.begin(), ball_.end(), [&](TetId b) { return c_.in_domain(b) && c_.region(b) == region; }))
            starts_.push_back(Start{ball_, v});
    }
}

// The cavity from `start` seen whole from `apex` (the header's growth);
// false when it would cross a constraint face, leave the region or exceed
// kMaxCavity.
bool ConeMaker::grow(const Start& start, VertexId apex, std::int32_t region) {
    marks_.new_round(m_.slot_count());
    cavity_.clear();
    for (TetId t : start.tets) add_to_cavity(t);
    const double* p = m_.point(apex);
    // Each tetrahedron taken in is scanned once; a face found blocking is
    // then interior (the tetrahedron behind it joins), so none is missed.
    for (std::size_t i = 0; i < cavity_.size(); ++i) {
        const TetId t = cavity_[i];
        const VertexId* w = m_.vertices(t);
        for (int f = 0; f < 4; ++f) {
            const TetId behind = facet_tet(m_.neighbor(t, f));
            const bool constrained = m_.is_constrained(t, f);
            if (!constrained && in_cavity(behind)) continue;
            const int* k = kFaceVertices[f];
            if (w[k[0]] == apex || w[k[1]] == apex || w[k[2]] == apex) continue;
            if (geom::orient3d(m_.point(w[k[0]]), m_.point(w[k[1]]), m_.point(w[k[2]]), p) > 0) continue;
            if (constrained || !c_.in_domain(behind) || c_.region(behind) != region || cavity_.size() >= kMaxCavity)
                return false;
            add_to_cavity(behind);
        }
    }
    return true;
}

// The boundary faces of the cavity and their vertices; false when a vertex
// other than `apex` and `inside` is inside the cavity (on no boundary
// face), or `inside` (when not kGhostVertex) is on the boundary.
bool ConeMaker::collect_boundary(VertexId apex, VertexId inside) {
    mesh::cavity_boundary(m_, cavity_, [&](TetId t) { return in_cavity(t); }, boundary_, vertex_marks_, kOnBoundary);
    for (TetId t : cavity_)
        for (int i = 0; i < 4; ++i) {
            const VertexId w = m_.vertex(t, i);
            const bool on_boundary = vertex_marks_.has(w, kOnBoundary);
            if (w == inside ? on_boundary : (w != apex && !on_boundary)) return false;
        }
    return true;
}

Rating ConeMaker::rate_cavity() const {
    Rating r;
    for (TetId t : cavity_) {
        const VertexId* w = m_.vertices(t);
        const double* p[4];
        corner_points(m_, t, p);
        count(radius_ratio(p[0], p[1], p[2], p[3]), has_flagged_corner(m_, t, steiner_), r);
        r.smallest_angle = std::min(r.smallest_angle, min_dihedral(p[0], p[1], p[2], p[3]));
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j)
                if (!c_.edge_within_size(w[i], w[j]))
                    r.longest_over_bound2 = std::max(r.longest_over_bound2, squared_distance(p[i], p[j]));
    }
    return r;
}

// The cone from `apex` over the boundary faces not at it, rated; false as
// soon as it breaks a rule: a tetrahedron under both the threshold and the
// cavity's worst, more bad tetrahedra (at Steiner points or in all) than
// the cavity, a new edge over the size bound and longer than every edge
// of the cavity over it (refine_options.hpp, kEdgeFactor: as a flip for
// the smallest angle, a cone may replace an over-long edge by no longer
// ones).
bool ConeMaker::rate_cone(VertexId apex, const Rating& cavity, Rating& cone) const {
    cone = Rating{};
    const double* p = m_.point(apex);
    const bool apex_steiner = is_steiner(apex);
    for (const Face& f : boundary_) {
        if (f.v[0] == apex || f.v[1] == apex || f.v[2] == apex) continue;
        const double* a = m_.point(f.v[0]);
        const double* b = m_.point(f.v[1]);
        const double* d = m_.point(f.v[2]);
        const double q = radius_ratio(a, b, d, p);
        if (q < threshold_ && q < cavity.worst_ratio) return false;
        count(q, apex_steiner || is_steiner(f.v[0]) || is_steiner(f.v[1]) || is_steiner(f.v[2]), cone);
        if (cone.bad > cavity.bad || cone.bad_at_steiner > cavity.bad_at_steiner) return false;
        cone.smallest_angle = std::min(cone.smallest_angle, min_dihedral(a, b, d, p));
    }
    for (const Face& f : boundary_) {
        if (f.v[0] == apex || f.v[1] == apex || f.v[2] == apex) continue;
        for (VertexId w : f.v)
            if (!c_.edge_within_size(apex, w, cavity.longest_over_bound2)) return false;
    }
    return true;
}

bool ConeMaker::improve(TetId t, VertexId& suppressed, std::vector<TetChange>* log) {
    suppressed = kGhostVertex;
    const std::int32_t region = c_.region(t);
    collect_apexes(t);
    collect_starts(t, region);
    VertexId best = kGhostVertex, best_inside = kGhostVertex;
    Rating best_cone;
    std::size_t best_gain = 0;
    std::vector<TetId> best_cavity;
    std::vector<Face> best_boundary;
    for (const Start& start : starts_)
        for (VertexId apex : apexes_) {
            if (apex == start.inside || !grow(start, apex, region) || !collect_boundary(apex, start.inside)) continue;
            const Rating cavity = rate_cavity();
            Rating cone;
            if (!rate_cone(apex, cavity, cone)) continue;
            const bool fewer_at_steiner = cone.bad_at_steiner < cavity.bad_at_steiner;
            if (!fewer_at_steiner && !(cone.smallest_angle > cavity.smallest_angle * kAngleGain)) continue;
            // The gain at Steiner points first, then the angle.
            const std::size_t gain = cavity.bad_at_steiner - cone.bad_at_steiner;
            if (best != kGhostVertex &&
                (gain < best_gain || (gain == best_gain && !(cone.smallest_angle > best_cone.smallest_angle))))
                continue;
            best = apex;
            best_inside = start.inside;
            best_cone = cone;
            best_gain = gain;
            best_cavity = cavity_;
            best_boundary = boundary_;
        }
    if (best == kGhostVertex) return false;
    std::vector<std::array<VertexId, 4>> fresh;
    for (const Face& f : best_boundary)
        if (f.v[0] != best && f.v[1] != best && f.v[2] != best) fresh.push_back({f.v[0], f.v[1], f.v[2], best});
    TetChange change;
    if (log)
        for (TetId s : best_cavity) change.replaced.push_back(corners_of(m_, s));
    std::vector<TetId> made;
    if (mesh::replace_tets(m_, best_cavity, fresh, &made) != mesh::ReplaceResult::kDone) return false;
    for (TetId s : made) c_.set_region(s, region);
    suppressed = best_inside;
    if (log) {
        change.made = fresh;
        log->push_back(std::move(change));
    }
    return true;
}

}  // namespace

std::size_t improve_by_vertex_cones(RefineContext& c, std::vector<VertexId>& steiner, double below_degrees,
                                    double threshold, RefineStats& stats, bool& dropped,
                                    std::vector<TetChange>* log) {
    const std::vector<char> is_steiner = steiner_flags(c.m, steiner);
    ConeMaker maker(c, is_steiner, threshold);
    const double q_bound = radius_ratio_bound_for_dihedral(below_degrees);
    std::size_t made = 0;
    std::vector<VertexId> suppressed;
    const mesh::TetId slots = c.m.slot_count();
    for (TetId t = 0; t < slots; ++t) {
        if (!c.in_domain(t)) continue;
        const bool picked = has_dihedral_below(c.m, t, below_degrees, q_bound) ||
                            (has_flagged_corner(c.m, t, is_steiner) && radius_ratio(c.m, t) < threshold);
        VertexId gone = kGhostVertex;
        if (!picked || !maker.improve(t, gone, log)) continue;
        ++made;
        if (gone != kGhostVertex) suppressed.push_back(gone);
    }
    stats.vertex_cones += made;
    if (suppressed.empty()) return made;
    // The suppressed points are in no tetrahedron: the caller closes up
    // the vertex ids (mesh/vertex_compaction.hpp).
    std::sort(suppressed.begin(), suppressed.end());
    steiner.erase(std::remove_if(steiner.begin(), steiner.end(),
                                 [&](VertexId v) { return std::binary_search(suppressed.begin(), suppressed.end(), v); }),
                  steiner.end());
    stats.steiner_suppressed += suppressed.size();
    dropped = true;
    return made;
}

}  // namespace cbr::refine
