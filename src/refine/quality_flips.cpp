#include "refine/quality_flips.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/chunks.hpp"
#include "mesh/flips.hpp"
#include "mesh/key_table.hpp"
#include "mesh/slot_pool.hpp"
#include "refine/tet_measures.hpp"
#include "refine/vertex_halves.hpp"

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
    // `radius_ratio_floor`: a flip may not make a tetrahedron whose radius
    // ratio is below both this and the worst of those it replaces (0: no
    // condition).
    // `refused`: the context's table for this sweep (emptied here).
    Flipper(RefineContext& c, const FlipMeasure& measure, mesh::KeyTable<bool>& refused, double radius_ratio_floor = 0)
        : c_(c), m_(c.m), measure_(measure), radius_ratio_floor_(radius_ratio_floor), refused_(refused) {
        objective_.measure = measure.oriented;
        refused_.clear();
    }
    // Flips only among the tetrahedra whose slot `owner` gives to `half`
    // (improve_by_flips' halves); a flip that would replace another one
    // is not done, and counted in blocked().
    void keep_to_half(const std::vector<std::uint8_t>& owner, std::uint8_t half) {
        owner_ = &owner;
        half_ = half;
    }
    std::size_t blocked() const { return blocked_; }
    bool try_edge(TetId t, VertexId u, VertexId v);
    bool remove_edge(TetId t, VertexId u, VertexId v);
    bool remove_edge_after_another(TetId t, VertexId u, VertexId v);
    bool try_face(TetId t, int f);
    // Whether try_edge may remove another edge first
    // (remove_edge_after_another), and how many such pairs it did.
    bool after_another = false;
    std::size_t after_another_done = 0;
    // Whether an edge removal may make chords over the size bound when the
    // edge it removes is over it too, none longer than that edge
    // (chord_limit2).
    bool chords_up_to_removed_edge = false;
    // For tests (improve_dihedrals_by_flips' log): the corners of the
    // tetrahedra each flip replaced, noted before it changes the mesh, and
    // of those it made.
    std::vector<TetChange>* log = nullptr;
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
    template <typename Tets>
    void note_replaced(const Tets& tets) {
        if (log)
            for (TetId t : tets) replacing_.push_back(corners_of(m_, t));
    }
    // The new tetrahedra join the region; the edges around them have new
    // shells, so an edge removal refused there may now be possible.
    void adopt(const std::vector<TetId>& created, std::int32_t region) {
        if (log) {
            TetChange record;
            record.replaced.swap(replacing_);
            for (TetId t : created) record.made.push_back(corners_of(m_, t));
            log->push_back(std::move(record));
        }
        for (TetId t : created) {
            c_.set_region(t, region);
            if (t < quality_.size()) quality_[t] = kUnknown;  // a new tetrahedron in a slot used before
            const VertexId* w = m_.vertices(t);
            for (int i = 0; i < 4; ++i)
                for (int j = i + 1; j < 4; ++j)
                    if (bool* refused = refused_.find(mesh::edge_key(w[i], w[j]))) *refused = false;
        }
    }
    // The shell of uv (t holds it) into s, when edge removal may try it:
    // at most kMaxShell tetrahedra, at least 3, no ghost.
    bool removable_shell(VertexId u, VertexId v, TetId t, mesh::Shell& s) const {
        return mesh::shell(m_, u, v, t, s, kMaxShell) && s.size() >= 3 && !s.has_ghost();
    }
    // Whether t may be replaced (keep_to_half); counts the refusals.
    bool ours(TetId t) {
        if (!owner_ || (*owner_)[t] == half_) return true;
        ++blocked_;
        return false;
    }
    // Whether every tetrahedron of shell s is in the domain's `region`;
    // `worst` then falls to the smallest measure among them.
    bool shell_in_region(const mesh::Shell& s, std::int32_t region, double& worst);
    bool survivors_may_beat(VertexId end, VertexId r, VertexId other, const mesh::Shell& inner, double worst) const;
    bool second_removal_beats(VertexId u, VertexId v, double worst, const std::vector<Corners>& replaced,
                              const std::vector<TetId>& first, std::vector<TetId>& made);
    // Whether the tetrahedra `made` keep radius_ratio_floor_ against the
    // tetrahedra `replaced` (slots or corner quadruples of m_).
    template <typename Replaced, typename Made>
    bool keeps_radius_ratio(const Replaced& replaced, const Made& made) const;

    RefineContext& c_;
    mesh::TetMesh& m_;
    const FlipMeasure measure_;
    const double radius_ratio_floor_;
    const std::vector<std::uint8_t>* owner_ = nullptr;  // keep_to_half
    std::uint8_t half_ = 0;
    std::size_t blocked_ = 0;
    // Per slot: the measure of the tetrahedron in it, or kUnknown (no
    // measure is negative).
    static constexpr double kUnknown = -1;
    std::vector<double> quality_;
    // Edges whose removal was refused in this sweep and whose shell has not
    // changed since (nothing moves during a sweep): the same shell would be
    // refused again, so it is not tried again from the other tetrahedra
    // around it. (An open-addressing table: std::unordered_set's division
    // and scattered nodes were half the sweep's own time on igea.) The
    // context's, emptied here.
    mesh::KeyTable<bool>& refused_;
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
    // their length), but for the exception of chord_limit2.
    mesh::RingObjective objective_{oriented_radius_ratio, 0,
                                   [this](VertexId a, VertexId b) { return c_.edge_within_size(a, b, chord_limit2_); }};
    // The squared length up to which a chord may exceed the size bound in
    // the next ring triangulation (-1: none may).
    double chord_limit2_ = -1;
    double chord_limit2(VertexId u, VertexId v) const;
};

// Edge removal of uv (Definition 5.8, the shell transformation) with the
// ring triangulation of mesh/flips.hpp.
bool Flipper::try_edge(TetId t, VertexId u, VertexId v) {
    if (c_.is_surface_edge(u, v)) return false;
    if (const bool* refused = refused_.find(mesh::edge_key(u, v)); refused && *refused) return false;
    const std::size_t blocked = blocked_;
    if (!remove_edge(t, u, v) && !(after_another && remove_edge_after_another(t, u, v))) {
        // Refused for its shell, unless a tetrahedron of the shell was
        // not this half's (the border's sweep tries it again).
        if (blocked_ == blocked) refused_[mesh::edge_key(u, v)] = true;
        return false;
    }
    return true;
}

// A removal judged by the smallest dihedral angle may find that every ring
// triangulation that would raise the angle has a chord over the size bound.
// That happens around a flat tetrahedron whose own inner edge is over the
// bound and stays so (refinement left it; RefineStats::unresolved_size
// counts such tetrahedra): thingiverse-chain-link's smallest angle stayed
// at 0.0028 deg (TetGen -pYq1.414: 0.0029) in a tetrahedron of four input
// points under two nearly coplanar input triangles, whose other diagonal,
// 1.76 long, is its inner edge. So an edge over the bound may be replaced
// by chords no longer than itself (a pair of removals: than the longer of
// its two edges where over the bound; the chain link's tetrahedron went
// with a pair). The mesh's longest edges do not grow, and the tetrahedra
// left over the bound are still counted.
// `cbr mesh` on the 37 shared surfaces changed on 8: smallest angle on the
// chain link 0.0028 -> 0.076 deg, golf ball 0.61 -> 3.4, octocat 0.0020
// -> 0.0022 (TetGen's own smallest, the same tetrahedron), openscad-
// example016 4.1 -> 4.6, the same on the other 4; tetrahedra over the
// bound fewer on 5 of the 8 (chain link 392 -> 367), more on 2
// (cheburashka 24 -> 28).
double Flipper::chord_limit2(VertexId u, VertexId v) const {
    return chords_up_to_removed_edge && !c_.edge_within_size(u, v) ? squared_distance(m_.point(u), m_.point(v)) : -1;
}

bool Flipper::remove_edge(TetId t, VertexId u, VertexId v) {
    mesh::Shell& s = shell_;
    const std::int32_t region = c_.region(t);
    double old_min = std::numeric_limits<double>::infinity();
    if (!removable_shell(u, v, t, s) || !shell_in_region(s, region, old_min)) return false;
    std::vector<mesh::RingTriangle>& tris = triangles_;
    objective_.floor = old_min * kGain;
    chord_limit2_ = chord_limit2(u, v);
    if (!mesh::best_ring_triangulation(m_, u, v, s, tris, nullptr, objective_)) return false;
    if (radius_ratio_floor_ > 0) {
        std::vector<Corners>& made = made_;
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
        if (!ours(x) || !c_.in_domain(x) || c_.region(x) != region) return false;
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
// (second_removal_beats), else the mesh's journal takes both back
// (refinement never runs inside another journal).
bool Flipper::remove_edge_after_another(TetId t, VertexId u, VertexId v) {
    mesh::Shell outer;
    const std::int32_t region = c_.region(t);
    double outer_worst = std::numeric_limits<double>::infinity();
    if (!removable_shell(u, v, t, outer) || !shell_in_region(outer, region, outer_worst)) return false;
    mesh::RingObjective any_valid = objective_;
    any_valid.floor = 0;  // the measures are non-negative on valid tetrahedra
    const double outer_limit2 = chord_limit2(u, v);
    for (std::size_t i = 0; i < outer.size(); ++i) {
        const VertexId r = outer.ring[i];
        for (VertexId end : {u, v}) {
            if (c_.is_surface_edge(end, r)) continue;
            mesh::Shell& inner = shell_;
            double worst = outer_worst;
            // The pair removes both edges: its chords may be as long as
            // the longer of the two where it is over the bound.
            chord_limit2_ = std::max(outer_limit2, chord_limit2(end, r));
            if (!removable_shell(end, r, outer.tets[i], inner) || !shell_in_region(inner, region, worst) ||
                !mesh::best_ring_triangulation(m_, end, r, inner, triangles_, nullptr, any_valid) ||
                !survivors_may_beat(end, r, end == u ? v : u, inner, worst))
                continue;
            // Both shells, by their corners: the first removal frees their slots.
            std::vector<Corners> replaced;
            for (const mesh::Shell* shell : {&outer, &inner})
                for (TetId x : shell->tets) replaced.push_back(corners_of(m_, x));
            m_.open_journal();
            std::vector<TetId> first, made;
            const bool kept =
                mesh::transform_shell(m_, end, r, inner, triangles_, &first) == mesh::FlipResult::kDone &&
                second_removal_beats(u, v, worst, replaced, first, made);
            if (!kept) m_.undo_journal();
            m_.close_journal();
            if (!kept) continue;
            if (log) replacing_ = std::move(replaced);
            adopt(made, region);
            ++after_another_done;
            return true;
        }
    }
    return false;
}

// Whether the tetrahedra that the first removal of a pair (of edge
// end-r, its ring triangulation in triangles_) would make and the second
// (of edge end-other, i.e. uv) would keep may beat `worst` by kGain, as
// second_removal_beats requires of them: those coned to r, and those
// coned to end whose triangle lacks `other`. Asked before the two
// transformations and their undo, which most pairs need (feeder body:
// 1,688 pairs kept of 103,725 tried). A tetrahedron refused here is
// refused there: the margin covers the rounding of the same measure with
// the corners in another order.
bool Flipper::survivors_may_beat(VertexId end, VertexId r, VertexId other, const mesh::Shell& inner,
                                 double worst) const {
    const double bar = worst * kGain;
    const double margin = 1e-9 * (1 + std::fabs(bar));
    for (const mesh::RingTriangle& t : triangles_) {
        const VertexId a = inner.ring[static_cast<std::size_t>(t[0])], b = inner.ring[static_cast<std::size_t>(t[1])],
                       d = inner.ring[static_cast<std::size_t>(t[2])];
        if (q(a, b, d, r) + margin <= bar) return false;
        if (a != other && b != other && d != other && q(a, d, b, end) + margin <= bar) return false;
    }
    return true;
}

// The second removal of remove_edge_after_another, uv's, after the first
// made `first`: done, and true, when every tetrahedron the two leave
// (`made`, the second's and the first's it left) beats `worst` by kGain
// and keeps radius_ratio_floor_ against all they replaced. The caller
// undoes both otherwise.
bool Flipper::second_removal_beats(VertexId u, VertexId v, double worst, const std::vector<Corners>& replaced,
                                   const std::vector<TetId>& first, std::vector<TetId>& made) {
    const auto at_uv = std::find_if(first.begin(), first.end(), [&](TetId x) { return mesh::holds_edge(m_, x, u, v); });
    mesh::Shell& second = shell_;
    objective_.floor = worst * kGain;  // chord_limit2_ stays the pair's
    if (at_uv == first.end() || !removable_shell(u, v, *at_uv, second) ||
        !mesh::best_ring_triangulation(m_, u, v, second, triangles_, nullptr, objective_) ||
        mesh::transform_shell(m_, u, v, second, triangles_, &made) != mesh::FlipResult::kDone)
        return false;
    for (TetId x : first)
        if (std::find(second.tets.begin(), second.tets.end(), x) == second.tets.end()) made.push_back(x);
    const bool beats = std::all_of(made.begin(), made.end(), [&](TetId x) {
        const VertexId* w = m_.vertices(x);
        return q(w[0], w[1], w[2], w[3]) > worst * kGain;
    });
    return beats && (radius_ratio_floor_ <= 0 || keeps_radius_ratio(replaced, made));
}

// 2-3 flip across face f of t: the two tetrahedra become three around the
// edge joining their apexes.
bool Flipper::try_face(TetId t, int f) {
    if (m_.is_constrained(t, f)) return false;
    const mesh::FacetRef r = m_.neighbor(t, f);
    const TetId n = facet_tet(r);
    const std::int32_t region = c_.region(t);
    if (!ours(n) || !c_.in_domain(n) || c_.region(n) != region) return false;
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
    for (const auto& t : replaced) worst = std::min(worst, radius_ratio(m_, t));
    for (const auto& w : made)
        if (radius_ratio(m_, w) < worst) return false;
    return true;
}

// The edge removals of t's six edges, then the 2-3 flips across its
// faces, until one is done; whether one was.
bool flip_once(RefineContext& c, Flipper& flipper, TetId t) {
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
            if (flipper.try_edge(t, c.m.vertex(t, i), c.m.vertex(t, j))) return true;
    for (int f = 0; f < 4; ++f)
        if (flipper.try_face(t, f)) return true;
    return false;
}

// One sweep of `flipper` over the tetrahedra of the bounded regions that
// `wanted` picks, in slot order (flip_once each).
template <typename Wanted>
std::size_t sweep(RefineContext& c, Flipper& flipper, Wanted wanted) {
    std::size_t flips = 0;
    const std::size_t slots = c.m.slot_count();
    for (TetId t = 0; t < slots; ++t)
        if (c.in_domain(t) && wanted(t)) flips += flip_once(c, flipper, t);
    return flips;
}

// improve_by_flips in two halves, so that two threads (CBR_PARAM_THREADS)
// can flip at once and the mesh is the same whatever the number of
// threads. The vertices are split at the median (vertex_halves.hpp); a
// tetrahedron is a half's when its four corners are in it, the border's
// otherwise (ghosts too). Each half sweeps its own tetrahedra in slot
// order and flips only among them (Flipper::keep_to_half), taking new
// slots from a pool of its own (mesh/slot_pool.hpp); then one sweep, in
// slot order, over the border's tetrahedra and those a half left (a flip
// there needed a tetrahedron not its own, or its pool ran low).
// Why the halves never touch the same data: a flip writes the tetrahedra
// it replaces (the half's), the slots it fills (its pool's) and the links
// of the tetrahedra across their outer faces, which share three corners
// with them, so have at least three in the half. It reads tetrahedra
// around an edge of the half (at least two corners in it) or across a
// face of its own (three). A tetrahedron the other half writes has at
// least three corners there, so at most one here: neither half reads
// what the other writes.
constexpr std::uint8_t kBorder = kNoHalf;
// The most slots one flip takes beyond those it frees: an edge removal
// turns a shell of n <= kMaxShell tetrahedra into 2 (n - 2).
constexpr std::size_t kMostNewSlots = 2 * (kMaxShell - 2) - kMaxShell;
// A half's pool: this many slots, plus one per kPoolShare tetrahedra it owns.
constexpr std::size_t kPoolBase = 64;
constexpr std::size_t kPoolShare = 8;

// Per slot of m: 0 or 1 for a live tetrahedron with its four corners in
// that half, kBorder for the others; `owned` counts each half's.
std::vector<std::uint8_t> tet_halves(const mesh::TetMesh& m, std::array<std::size_t, 2>& owned) {
    std::vector<VertexId> vertices(m.vertex_count());
    for (VertexId v = 0; v < vertices.size(); ++v) vertices[v] = v;
    const std::vector<std::uint8_t> half = median_halves(m, vertices);
    std::vector<std::uint8_t> owner(m.slot_count(), kBorder);
    owned = {0, 0};
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t) || m.is_ghost(t)) continue;
        const std::uint8_t h = common_half(half, m, t);
        if (h == kNoHalf) continue;
        owner[t] = h;
        ++owned[h];
    }
    return owner;
}

// One half's sweep over slots [0, slots) (the slots when the pass began,
// as sweep's); the slots it leaves to the border's sweep go to `again`.
template <typename Wanted>
std::size_t sweep_half(RefineContext& c, Flipper& flipper, std::size_t slots, const std::vector<std::uint8_t>& owner,
                       std::uint8_t half, const mesh::SlotPool& pool, Wanted wanted, std::vector<TetId>& again) {
    std::size_t flips = 0;
    for (TetId t = 0; t < slots; ++t) {
        if (owner[t] != half || !c.in_domain(t) || !wanted(t)) continue;
        if (pool.size() < kMostNewSlots) {
            again.push_back(t);
            continue;
        }
        const std::size_t blocked = flipper.blocked();
        if (flip_once(c, flipper, t)) ++flips;
        else if (flipper.blocked() != blocked) again.push_back(t);
    }
    return flips;
}

}  // namespace

HalvesFlips improve_by_flips(RefineContext& c, double threshold, std::vector<TetChange>* log) {
    const std::size_t slots = c.m.slot_count();
    std::array<std::size_t, 2> owned;
    std::vector<std::uint8_t> owner = tet_halves(c.m, owned);
    std::array<std::unique_ptr<mesh::SlotPool>, 2> pools;
    for (std::uint8_t h = 0; h < 2; ++h)
        pools[h] = std::make_unique<mesh::SlotPool>(c.m, kPoolBase + owned[h] / kPoolShare);
    owner.resize(c.m.slot_count(), kBorder);
    for (std::uint8_t h = 0; h < 2; ++h)
        for (TetId s : pools[h]->slots()) owner[s] = h;
    c.reserve_slots();
    HalvesFlips flips;
    std::array<std::vector<TetId>, 2> again;
    std::array<std::vector<TetChange>, 2> logs;
    mesh::run_chunks(2, c.options.threads > 1 ? 2 : 1, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const auto h = static_cast<std::uint8_t>(k);
            const mesh::SlotPool::Use use(*pools[h]);
            Flipper flipper(c, kRadiusRatio, c.half_refused_edges[h]);
            flipper.keep_to_half(owner, h);
            if (log) flipper.log = &logs[h];
            flips.in_half[h] = sweep_half(c, flipper, slots, owner, h, *pools[h],
                                  [&](TetId t) { return c.changed_near(t) && flipper.q(t) < threshold; }, again[h]);
        }
    });
    for (std::unique_ptr<mesh::SlotPool>& pool : pools) pool.reset();  // the slots left back to the free list
    std::vector<char> retry(slots, 0);
    for (const std::vector<TetId>& list : again)
        for (TetId t : list) retry[t] = 1;
    if (log)
        for (std::vector<TetChange>& half_log : logs) log->insert(log->end(), half_log.begin(), half_log.end());
    Flipper border(c, kRadiusRatio, c.refused_edges);
    border.log = log;
    flips.on_border = sweep(c, border, [&](TetId t) {
        return t < slots && (owner[t] == kBorder || retry[t]) && c.changed_near(t) && border.q(t) < threshold;
    });
    return flips;
}

DihedralFlips improve_dihedrals_by_flips(RefineContext& c, double below_degrees, double keep_radius_ratio,
                                         int max_sweeps, std::vector<TetChange>* log, std::uint32_t since) {
    // The radius ratio first: cheaper, and most tetrahedra are above the
    // bound it puts on the angle.
    const double q_bound = radius_ratio_bound_for_dihedral(below_degrees);
    DihedralFlips flips;
    for (int k = 0; k < max_sweeps; ++k) {
        // The first sweep looks at every tetrahedron (none was tried for
        // its angles before) or, after an earlier call, at what changed
        // since its last sweep (the points moved for the angle in between;
        // the rest was tried and failed), the next ones where the last one
        // flipped.
        const std::uint32_t from = k > 0 ? flips.last_sweep : since;  // since 0: all
        c.start_pass();
        flips.last_sweep = c.pass();
        Flipper flipper(c, kMinDihedral, c.refused_edges, keep_radius_ratio);
        flipper.after_another = c.options.edge_removal_after_another;
        flipper.chords_up_to_removed_edge = c.options.dihedral_chords_up_to_removed_edge;
        flipper.log = log;
        const std::size_t done = sweep(c, flipper, [&](TetId t) {
            return c.changed_near_since(t, from) && radius_ratio(c.m, t) < q_bound && flipper.q(t) < below_degrees;
        });
        flips.flips += done + flipper.after_another_done;  // a pair is two removals
        flips.after_another += flipper.after_another_done;
        if (done == 0) break;
    }
    return flips;
}

}  // namespace cbr::refine
