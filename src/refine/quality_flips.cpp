#include "refine/quality_flips.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/flips.hpp"
#include "mesh/key_table.hpp"
#include "refine/tet_measures.hpp"

namespace cbr::refine {
namespace {

using mesh::facet_face;
using mesh::facet_tet;
using mesh::kFaceVertices;
using mesh::TetId;
using mesh::VertexId;

// A flip must raise the minimum quality by this much (relative) to count:
// no cycling on ties.
constexpr double kGain = 1.0 + 1e-3;

// Edge removal is tried on shells of up to this many tetrahedra (the ring
// triangulation is O(n^3)).
constexpr std::size_t kMaxShell = 7;

// What a sweep maximizes: the smallest `value` over the tetrahedra a flip
// replaces against the smallest over those it makes; `oriented` is the
// same with -infinity for a tetrahedron that is not positively oriented
// (how a ring triangulation is judged, mesh::RingObjective).
struct FlipMeasure {
    using Function = double (*)(const double*, const double*, const double*, const double*);
    Function value;
    Function oriented;
};
constexpr FlipMeasure kRadiusRatio{static_cast<FlipMeasure::Function>(radius_ratio), oriented_radius_ratio};
constexpr FlipMeasure kMinDihedral{min_dihedral, oriented_min_dihedral};

class Flipper {
public:
    using Corners = std::array<VertexId, 4>;
    // `radius_ratio_floor`: a flip may not make a tetrahedron whose radius
    // ratio is below both this and the worst of those it replaces (0: no
    // condition).
    Flipper(RefineContext& c, const FlipMeasure& measure, double radius_ratio_floor = 0)
        : c_(c), m_(c.m), measure_(measure), radius_ratio_floor_(radius_ratio_floor) {
        objective_.measure = measure.oriented;
    }
    bool try_edge(TetId t, VertexId u, VertexId v);
    bool remove_edge(TetId t, VertexId u, VertexId v);
    bool remove_edge_after_another(TetId t, VertexId u, VertexId v);
    bool try_face(TetId t, int f);
    // Whether try_edge may remove another edge first
    // (remove_edge_after_another), and how many such pairs it did.
    bool after_another = false;
    std::size_t after_another_done = 0;
    // For tests (improve_dihedrals_by_flips' log): the corners of the
    // tetrahedra each flip replaced, noted before it changes the mesh, and
    // of those it made.
    std::vector<FlipRecord>* log = nullptr;
    double q(VertexId a, VertexId b, VertexId d, VertexId e) const {
        return measure_.value(m_.point(a), m_.point(b), m_.point(d), m_.point(e));
    }
    // A tetrahedron's measure, computed once per sweep: every tetrahedron
    // below the threshold rates the shells of its six edges, each of which
    // rates its own tetrahedra again (octocat: radius ratios were a sixth
    // of the sweep's time).
    double q(TetId t) {
        if (t >= quality_.size()) quality_.resize(m_.slot_count(), kUnknown);
        double& known = quality_[t];
        if (known == kUnknown) {
            const VertexId* w = m_.vertices(t);
            known = q(w[0], w[1], w[2], w[3]);
        }
        return known;
    }

private:
    static std::uint64_t key(VertexId a, VertexId b) {
        if (a > b) std::swap(a, b);
        return (std::uint64_t{a} << 32) | b;
    }
    template <typename Tets>
    void note_replaced(const Tets& tets) {
        if (log)
            for (TetId t : tets) replacing_.push_back(corners(t));
    }
    Corners corners(TetId t) const { return {m_.vertex(t, 0), m_.vertex(t, 1), m_.vertex(t, 2), m_.vertex(t, 3)}; }
    // The new tetrahedra join the region; the edges around them have new
    // shells, so an edge removal refused there may now be possible.
    void adopt(const std::vector<TetId>& created, std::int32_t region) {
        if (log) {
            FlipRecord record;
            record.replaced.swap(replacing_);
            for (TetId t : created) record.made.push_back(corners(t));
            log->push_back(std::move(record));
        }
        for (TetId t : created) {
            c_.set_region(t, region);
            if (t < quality_.size()) quality_[t] = kUnknown;  // a new tetrahedron in a slot used before
            const VertexId* w = m_.vertices(t);
            for (int i = 0; i < 4; ++i)
                for (int j = i + 1; j < 4; ++j)
                    if (bool* refused = refused_.find(key(w[i], w[j]))) *refused = false;
        }
    }
    // Whether every tetrahedron of shell s is in the domain's `region`;
    // `worst` then falls to the smallest measure among them.
    bool shell_in_region(const mesh::Shell& s, std::int32_t region, double& worst);
    bool undo_unless_better(VertexId u, VertexId v, double worst, double worst_radius_ratio,
                            const std::vector<TetId>& first, std::int32_t region);
    // Whether the tetrahedra `made` keep radius_ratio_floor_ against the
    // tetrahedra `replaced` (corner quadruples of m_).
    template <typename Replaced, typename Made>
    bool keeps_radius_ratio(const Replaced& replaced, const Made& made) const;

    RefineContext& c_;
    mesh::TetMesh& m_;
    const FlipMeasure measure_;
    const double radius_ratio_floor_;
    // Per slot: the measure of the tetrahedron in it, or kUnknown (no
    // measure is negative).
    static constexpr double kUnknown = -1;
    std::vector<double> quality_;
    // Edges whose removal was refused in this sweep and whose shell has not
    // changed since (nothing moves during a sweep): the same shell would be
    // refused again, so it is not tried again from the other tetrahedra
    // around it. (An open-addressing table: std::unordered_set's division
    // and scattered nodes were half the sweep's own time on igea.)
    mesh::KeyTable<bool> refused_;
    // remove_edge's scratch, kept across calls.
    mesh::Shell shell_;
    std::vector<mesh::RingTriangle> triangles_;
    std::vector<Corners> made_;
    std::vector<Corners> replacing_;  // note_replaced
    // What remove_edge asks of a ring triangulation: the best worst value
    // of the measure a flip is judged by, searched only above the bar
    // it must beat (floor, set per shell): most shells cannot beat it
    // (igea: 146 thousand of a million triangulable shells flip in the
    // first pass, 14 thousand of 670 thousand in the third), and the
    // floor ends their search early. The chords are new edges: the size
    // bound applies to them (the ring's sides are edges already, whatever
    // their length).
    mesh::RingObjective objective_{oriented_radius_ratio, 0,
                                   [this](VertexId a, VertexId b) { return c_.edge_within_size(a, b); }};
};

// Edge removal of uv (Definition 5.8, the shell transformation) with the
// ring triangulation of mesh/flips.hpp.
bool Flipper::try_edge(TetId t, VertexId u, VertexId v) {
    if (c_.is_surface_edge(u, v)) return false;
    if (const bool* refused = refused_.find(key(u, v)); refused && *refused) return false;
    if (!remove_edge(t, u, v) && !(after_another && remove_edge_after_another(t, u, v))) {
        refused_[key(u, v)] = true;
        return false;
    }
    return true;
}

bool Flipper::remove_edge(TetId t, VertexId u, VertexId v) {
    mesh::Shell& s = shell_;
    if (!mesh::shell(m_, u, v, t, s, kMaxShell) || s.size() < 3 || s.has_ghost()) return false;
    const std::int32_t region = c_.region(t);
    double old_min = std::numeric_limits<double>::infinity();
    for (TetId x : s.tets) {
        if (!c_.in_domain(x) || c_.region(x) != region) return false;
        old_min = std::min(old_min, q(x));
    }
    std::vector<mesh::RingTriangle>& tris = triangles_;
    objective_.floor = old_min * kGain;
    if (!mesh::best_ring_triangulation(m_, u, v, s, tris, nullptr, objective_)) return false;
    if (radius_ratio_floor_ > 0) {
        std::vector<std::array<VertexId, 4>>& made = made_;
        made.clear();
        for (const mesh::RingTriangle& r : tris) {
            const VertexId a = s.ring[static_cast<std::size_t>(r[0])], b = s.ring[static_cast<std::size_t>(r[1])],
                           d = s.ring[static_cast<std::size_t>(r[2])];
            made.push_back({a, b, d, v});
            made.push_back({a, d, b, u});
        }
        if (!keeps_radius_ratio(s.tets, made)) return false;
    }
    std::vector<TetId> created;
    note_replaced(s.tets);
    if (mesh::transform_shell(m_, u, v, s, tris, &created) != mesh::FlipResult::kDone) {
        replacing_.clear();
        return false;
    }
    adopt(created, region);
    return true;
}

bool Flipper::shell_in_region(const mesh::Shell& s, std::int32_t region, double& worst) {
    for (TetId x : s.tets) {
        if (!c_.in_domain(x) || c_.region(x) != region) return false;
        worst = std::min(worst, q(x));
    }
    return true;
}

// When no triangulation of uv's ring beats its shell, the ring may still
// be the wrong one: a ring vertex r whose edge to u (or v) is removed
// first leaves it, and uv's new ring may have a good triangulation. This
// is the nesting of flip recovery's edge removal (§5.1, one level) for
// quality. Flat tetrahedra of four input points under two nearly coplanar
// input triangles, in a layer where every point around is nearly in their
// plane too, have such shells (thingiverse-chain-link: four tetrahedra
// around the inner edge of one at 2.5e-6 deg, and neither triangulation
// of their ring is valid; with the pairs it goes, and the surface's
// smallest angle is 1.5e-4 deg; wildmeshing-supershape 1.0 -> 5.2 deg).
// The first removal takes its ring's best triangulation whatever its
// worst (the second replaces most of it); the pair is kept only when
// every tetrahedron it leaves beats the worst of all it replaced
// (undo_unless_better), else the mesh's journal takes both back
// (refinement never runs inside another journal).
bool Flipper::remove_edge_after_another(TetId t, VertexId u, VertexId v) {
    mesh::Shell outer;
    if (!mesh::shell(m_, u, v, t, outer, kMaxShell) || outer.size() < 3 || outer.has_ghost()) return false;
    const std::int32_t region = c_.region(t);
    double outer_worst = std::numeric_limits<double>::infinity();
    if (!shell_in_region(outer, region, outer_worst)) return false;
    double outer_radius_ratio = 1;
    for (TetId x : outer.tets) outer_radius_ratio = std::min(outer_radius_ratio, radius_ratio(m_, x));
    mesh::RingObjective any_valid = objective_;
    any_valid.floor = 0;  // the measures are non-negative on valid tetrahedra
    for (std::size_t i = 0; i < outer.size(); ++i) {
        const VertexId r = outer.ring[i];
        for (VertexId end : {u, v}) {
            if (c_.is_surface_edge(end, r)) continue;
            mesh::Shell& inner = shell_;
            double worst = outer_worst;
            if (!mesh::shell(m_, end, r, outer.tets[i], inner, kMaxShell) || inner.size() < 3 || inner.has_ghost() ||
                !shell_in_region(inner, region, worst))
                continue;
            if (!mesh::best_ring_triangulation(m_, end, r, inner, triangles_, nullptr, any_valid)) continue;
            double worst_radius_ratio = outer_radius_ratio;
            for (TetId x : inner.tets) worst_radius_ratio = std::min(worst_radius_ratio, radius_ratio(m_, x));
            note_replaced(outer.tets);
            note_replaced(inner.tets);
            m_.open_journal();
            std::vector<TetId> first;
            const bool done = mesh::transform_shell(m_, end, r, inner, triangles_, &first) == mesh::FlipResult::kDone;
            if (done && undo_unless_better(u, v, worst, worst_radius_ratio, first, region)) {
                ++after_another_done;
                return true;
            }
            if (!done) {  // nothing changed; the journal is closed as it is opened, in this scope
                m_.undo_journal();
                m_.close_journal();
            }
            replacing_.clear();
        }
    }
    return false;
}

// The second removal of remove_edge_after_another, uv's, after the first
// made `first` (the journal open since before it): kept, and the journal
// closed, when every tetrahedron the two leave beats `worst` by kGain
// (and keeps radius_ratio_floor_ against `worst_radius_ratio`, both over
// all they replaced); else both are undone and the journal closed.
bool Flipper::undo_unless_better(VertexId u, VertexId v, double worst, double worst_radius_ratio,
                                 const std::vector<TetId>& first, std::int32_t region) {
    const auto has = [&](TetId x, VertexId w) {
        const VertexId* c = m_.vertices(x);
        return std::find(c, c + 4, w) != c + 4;
    };
    const auto at_uv = std::find_if(first.begin(), first.end(), [&](TetId x) { return has(x, u) && has(x, v); });
    mesh::Shell& second = shell_;
    objective_.floor = worst * kGain;
    std::vector<TetId> made;
    bool better = at_uv != first.end() && mesh::shell(m_, u, v, *at_uv, second, kMaxShell) && second.size() >= 3 &&
                  !second.has_ghost() &&
                  mesh::best_ring_triangulation(m_, u, v, second, triangles_, nullptr, objective_) &&
                  mesh::transform_shell(m_, u, v, second, triangles_, &made) == mesh::FlipResult::kDone;
    if (better) {
        // The first removal's tetrahedra that the second left stay too.
        for (TetId x : first)
            if (std::find(second.tets.begin(), second.tets.end(), x) == second.tets.end()) made.push_back(x);
        const double floor = std::min(radius_ratio_floor_, worst_radius_ratio);
        for (TetId x : made) {
            const VertexId* w = m_.vertices(x);
            better = better && q(w[0], w[1], w[2], w[3]) > worst * kGain &&
                     (radius_ratio_floor_ <= 0 || radius_ratio(m_, x) >= floor);
        }
    }
    if (!better) m_.undo_journal();
    m_.close_journal();
    if (better) adopt(made, region);
    return better;
}

// 2-3 flip across face f of t: the two tetrahedra become three around the
// edge joining their apexes.
bool Flipper::try_face(TetId t, int f) {
    if (m_.is_constrained(t, f)) return false;
    const mesh::FacetRef r = m_.neighbor(t, f);
    const TetId n = facet_tet(r);
    const std::int32_t region = c_.region(t);
    if (!c_.in_domain(n) || c_.region(n) != region) return false;
    const VertexId d = m_.vertex(t, f), e = m_.vertex(n, facet_face(r));
    const int* k = kFaceVertices[f];
    const VertexId x[3] = {m_.vertex(t, k[0]), m_.vertex(t, k[1]), m_.vertex(t, k[2])};
    // The flip exists only when de crosses the face's interior: the three
    // new tetrahedra turn the same way (exact). Tested before any quality:
    // on igea 148 of 3.4 million tries flip, and most fail here.
    int turn[3];
    for (int i = 0; i < 3; ++i)
        turn[i] = geom::orient3d(m_.point(x[i]), m_.point(x[(i + 1) % 3]), m_.point(d), m_.point(e));
    if (turn[0] == 0 || turn[1] != turn[0] || turn[2] != turn[0]) return false;
    if (!c_.edge_within_size(d, e)) return false;
    const double old_min = std::min(q(t), q(n));
    double new_min = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) new_min = std::min(new_min, q(x[i], x[(i + 1) % 3], d, e));
    if (new_min <= old_min * kGain) return false;
    if (radius_ratio_floor_ > 0) {
        const TetId replaced[2] = {t, n};
        const std::array<VertexId, 4> made[3] = {
            {x[0], x[1], d, e}, {x[1], x[2], d, e}, {x[2], x[0], d, e}};
        if (!keeps_radius_ratio(replaced, made)) return false;
    }
    std::vector<TetId> created;
    note_replaced(std::array<TetId, 2>{t, n});
    if (mesh::flip23(m_, t, f, {}, &created) != mesh::FlipResult::kDone) {
        replacing_.clear();
        return false;
    }
    adopt(created, region);
    return true;
}

template <typename Replaced, typename Made>
bool Flipper::keeps_radius_ratio(const Replaced& replaced, const Made& made) const {
    double worst = radius_ratio_floor_;
    for (TetId t : replaced) worst = std::min(worst, radius_ratio(m_, t));
    for (const std::array<VertexId, 4>& w : made)
        if (radius_ratio(m_.point(w[0]), m_.point(w[1]), m_.point(w[2]), m_.point(w[3])) < worst) return false;
    return true;
}

// One sweep of `flipper` over the tetrahedra of the bounded regions that
// `wanted` picks: the edge removals of each one's six edges, then the 2-3
// flips across its faces, until one is done.
template <typename Wanted>
std::size_t sweep(RefineContext& c, Flipper& flipper, Wanted wanted) {
    std::size_t flips = 0;
    const std::size_t slots = c.m.slot_count();
    for (TetId t = 0; t < slots; ++t) {
        if (!c.in_domain(t) || !wanted(t)) continue;
        bool done = false;
        for (int i = 0; i < 4 && !done; ++i)
            for (int j = i + 1; j < 4 && !done; ++j)
                done = flipper.try_edge(t, c.m.vertex(t, i), c.m.vertex(t, j));
        for (int f = 0; f < 4 && !done; ++f) done = flipper.try_face(t, f);
        flips += done;
    }
    return flips;
}

}  // namespace

std::size_t improve_by_flips(RefineContext& c, double threshold) {
    Flipper flipper(c, kRadiusRatio);
    return sweep(c, flipper, [&](TetId t) { return c.changed_near(t) && flipper.q(t) < threshold; });
}

DihedralFlips improve_dihedrals_by_flips(RefineContext& c, double below_degrees, double keep_radius_ratio,
                                         int max_sweeps, std::vector<FlipRecord>* log) {
    // The radius ratio first: cheaper, and most tetrahedra are above the
    // bound it puts on the angle.
    const double q_bound = radius_ratio_bound_for_dihedral(below_degrees);
    DihedralFlips flips;
    for (int k = 0; k < max_sweeps; ++k) {
        // The first sweep looks at every tetrahedron (none was tried for
        // its angles before), the next ones where the last one flipped.
        c.start_pass();
        Flipper flipper(c, kMinDihedral, keep_radius_ratio);
        flipper.after_another = c.options.edge_removal_after_another;
        flipper.log = log;
        const std::size_t done = sweep(c, flipper, [&](TetId t) {
            return (k == 0 || c.changed_near(t)) && radius_ratio(c.m, t) < q_bound && flipper.q(t) < below_degrees;
        });
        flips.flips += done + flipper.after_another_done;  // a pair is two removals
        flips.after_another += flipper.after_another_done;
        if (done == 0) break;
    }
    return flips;
}

}  // namespace cbr::refine
