#include "refine/steiner_removal.hpp"

#include <algorithm>
#include <array>

#include "mesh/ball_shell.hpp"
#include "mesh/errors.hpp"
#include "mesh/surgery.hpp"
#include "recover/steiner_suppression.hpp"
#include "refine/field_points.hpp"
#include "refine/quality_stats.hpp"
#include "refine/tet_measures.hpp"

namespace cbr::refine {
namespace {

using mesh::TetId;
using mesh::VertexId;

// Above every radius ratio: "not a vertex of a bounded region".
constexpr double kNotInside = 2;
// Rings of vertices around the suppressions (and the Steiner points left)
// whose tetrahedra are refined again.
constexpr int kRefillRings = 1;

class Remover {
public:
    Remover(RefineContext& c, double threshold)
        : c_(c), m_(c.m), threshold_(threshold), incident_(mesh::incident_tets(c.m)) {}

    // The worst radius ratio of v's ball (gathered for suppress), or
    // kNotInside when v is not a vertex of a bounded region (in no
    // tetrahedron, on the surface, or its ball leaves the region).
    double ball_worst(VertexId v);
    // Suppresses v (its ball as gathered by ball_worst) if it can; with
    // `no_worse`, only if the new tetrahedra have no more below the
    // threshold than the ball and a worst no lower than the ball's.
    bool suppress(VertexId v, bool no_worse);
    // The link vertices of v that are field points of this refinement
    // (movable, neither on the surface nor Steiner points).
    std::vector<VertexId> field_neighbours(VertexId v, const std::vector<char>& is_steiner);

    // The tetrahedra made by the suppressions (some slots may have been
    // reused since).
    std::vector<TetId> created;

private:
    RefineContext& c_;
    mesh::TetMesh& m_;
    const double threshold_;
    std::vector<TetId> incident_;
    std::vector<TetId> ball_;
    std::int32_t region_ = 0;
};

double Remover::ball_worst(VertexId v) {
    ball_.clear();
    if (v >= incident_.size() || incident_[v] == mesh::kNoTet || c_.is_surface_vertex(v)) return kNotInside;
    if (!mesh::ball(m_, v, incident_[v], ball_) || ball_.empty()) {
        ball_.clear();
        return kNotInside;
    }
    region_ = c_.region(ball_.front());
    double worst = 1;
    for (TetId t : ball_) {
        if (!c_.in_domain(t) || c_.region(t) != region_) {
            ball_.clear();
            return kNotInside;
        }
        worst = std::min(worst, radius_ratio(m_, t));
    }
    return worst;
}

bool Remover::suppress(VertexId v, bool no_worse) {
    if (ball_.empty()) return false;
    std::vector<std::array<VertexId, 4>> original;
    std::size_t bad_before = 0;
    double worst_before = 1;
    for (TetId t : ball_) {
        original.push_back({m_.vertex(t, 0), m_.vertex(t, 1), m_.vertex(t, 2), m_.vertex(t, 3)});
        const double q = radius_ratio(m_, t);
        bad_before += q < threshold_;
        worst_before = std::min(worst_before, q);
    }
    recover::SuppressReport report;
    bool done = recover::suppress_vertex(m_, v, incident_[v], {}, &report);
    if (done && no_worse) {
        std::size_t bad_after = 0;
        double worst_after = 1;
        for (TetId t : report.created) {
            const double q = radius_ratio(m_, t);
            bad_after += q < threshold_;
            worst_after = std::min(worst_after, q);
        }
        if (bad_after > bad_before || worst_after < worst_before) {
            // v goes back: its ball is the same polyhedron, which the
            // original tetrahedra tile again exactly.
            std::vector<TetId> back;
            if (mesh::replace_tets(m_, report.created, original, &back) != mesh::ReplaceResult::kDone)
                throw InternalError("steiner removal: putting a suppressed point back was refused");
            report.created = back;
            done = false;
        }
    }
    // On success the new tetrahedra fill the ball; after putting v back,
    // the original ones, possibly in other slots. Both are listed in
    // report.created and lie in the ball's region. (A failed suppression
    // leaves the mesh as it was and lists nothing.)
    for (TetId t : report.created) {
        c_.set_region(t, region_);
        for (int i = 0; i < 4; ++i) incident_[m_.vertex(t, i)] = t;
    }
    if (done) {
        incident_[v] = mesh::kNoTet;
        created.insert(created.end(), report.created.begin(), report.created.end());
    }
    ball_.clear();
    return done;
}

std::vector<VertexId> Remover::field_neighbours(VertexId v, const std::vector<char>& is_steiner) {
    std::vector<VertexId> out;
    if (ball_worst(v) == kNotInside) return out;
    for (TetId t : ball_)
        for (int i = 0; i < 4; ++i) {
            const VertexId u = m_.vertex(t, i);
            if (u != v && c_.is_movable(u) && !c_.is_surface_vertex(u) && !(u < is_steiner.size() && is_steiner[u]))
                out.push_back(u);
        }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// The live tetrahedra of the bounded regions with a corner within
// kRefillRings rings of vertices of `seeds` (tetrahedra) or of `points`.
std::vector<TetId> neighbourhood(const RefineContext& c, const std::vector<TetId>& seeds,
                                 const std::vector<VertexId>& points) {
    const mesh::TetMesh& m = c.m;
    std::vector<char> near(m.vertex_count(), 0);
    for (TetId t : seeds)
        if (t < m.slot_count() && !m.is_free(t))
            for (int i = 0; i < 4; ++i)
                if (m.vertex(t, i) != mesh::kGhostVertex) near[m.vertex(t, i)] = 1;
    for (VertexId v : points) near[v] = 1;
    for (int ring = 0; ring < kRefillRings; ++ring) near = grown_by_one_ring(c, near, [](VertexId) { return true; });
    std::vector<TetId> out;
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (c.in_domain(t) && has_flagged_corner(m, t, near)) out.push_back(t);
    return out;
}

}  // namespace

std::size_t remove_bad_steiner_points(RefineContext& c, std::vector<VertexId>& steiner, double threshold,
                                      RefineStats& stats, bool& dropped) {
    if (steiner.empty()) return 0;
    Remover r(c, threshold);
    const std::vector<char> is_steiner = steiner_flags(c.m, steiner);
    std::vector<VertexId> kept;
    std::size_t suppressed = 0, cleared = 0;
    for (VertexId v : steiner) {
        if (r.ball_worst(v) < threshold) {
            bool done = r.suppress(v, true);
            if (!done) {
                // No tetrahedralization of the ball without v as it is: the
                // field points of its link go first (whatever tetrahedra
                // that leaves: they are refined again below), then v once
                // more.
                for (VertexId u : r.field_neighbours(v, is_steiner))
                    if (r.ball_worst(u) != kNotInside && r.suppress(u, false)) ++cleared;
                if (r.ball_worst(v) < threshold) done = r.suppress(v, true);
            }
            if (done) {
                ++suppressed;
                continue;
            }
        }
        kept.push_back(v);
    }
    steiner.swap(kept);
    if (suppressed == 0 && cleared == 0) return 0;
    dropped = true;
    stats.field_points -= cleared;
    stats.steiner_suppressed += suppressed;
    // Refined again where the suppressions changed the mesh (§6 step (d)).
    const std::vector<TetId> seeds = neighbourhood(c, r.created, steiner);
    insert_field_points(c, stats, &seeds);
    return suppressed;
}

std::size_t bad_tets_at_steiner(const RefineContext& c, const std::vector<VertexId>& steiner, double threshold) {
    const std::vector<char> is_steiner = steiner_flags(c.m, steiner);
    std::size_t bad = 0;
    for (TetId t = 0; t < c.m.slot_count(); ++t) {
        if (!c.in_domain(t)) continue;
        if (has_flagged_corner(c.m, t, is_steiner) && radius_ratio(c.m, t) < threshold) ++bad;
    }
    return bad;
}

}  // namespace cbr::refine
