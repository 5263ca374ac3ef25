#include "recover/flip_recovery.hpp"

#include <algorithm>
#include <iterator>
#include <numeric>
#include <utility>

#include "geom/intersect.hpp"
#include "geom/predicates.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/failed_rings.hpp"
#include "mesh/flips.hpp"
#include "recover/failed_searches.hpp"
#include "recover/segment_crossings.hpp"
#include "recover/segment_walk.hpp"

namespace cbr::recover {
namespace {

using mesh::FlipResult;
using mesh::kFaceVertices;
using mesh::kGhostVertex;
using mesh::kNoTet;
using mesh::TetId;
using mesh::VertexId;

// Flips tried on one edge or one face before giving up: each flip removes
// one crossing, but a flip can also create one, so a bound keeps a cycle
// from running forever.
constexpr int kMaxFlipsPerConstraint = 64;
// How hard flip recovery looks, in rounds over the faces still missing
// (recover_by_flips): the nesting of edge removals that first shrink the
// shell of an edge (n-to-m flips), the edge removals attempted for one
// face with nesting included (hard faces fail fast instead of exploring
// every nested removal), and whether a missing edge's crossings are
// searched all along it (remove_any_crossing) or only at its ends.
struct Search {
    int depth;
    int budget;
    bool wide;
    // Each later pass of the round gets the budget of the one before
    // divided by 2^shrink (0: the same budget every pass).
    int shrink = 0;
    // A face the round does not recover leaves the mesh as it found it.
    bool rollback = false;
    // Edge removals for the whole round, every face and pass together
    // (0: no limit); a face gets at most what is left.
    long allowance = 0;
};
// Plain: 2 levels recover the flat, cospherical configurations of CAD
// boxes (hull faces) at about (2n)^2 attempts. Then, for what is left,
// wide searches deepened step by step (3 levels and 400 removals a face,
// then 5 and 2000): Steiner points inside the domain on the golf ball
// 238 -> 69, on a flat cylinder's fanned caps 81 -> 2, and octocat
// recovers; each round is paid only by the faces the cheaper ones leave.
// (Measured alternatives: the deep round alone gives fewer Steiner points
// on the golf ball, 44, but octocat fails; a shallow round after the deep
// one is slower and octocat fails too.)
// A last, much deeper round (8 levels, 40,000 removals a face) for the few
// faces left, in which a face that is not recovered leaves the mesh as it
// found it (the partial flips of a failed deep search made configurations
// that point splitting then refused: 6 of the pierced-tetrahedron cases
// broke without the rollback, 2 more recover with it). Steiner points
// inside the domain on the nine shared surfaces that need any: 282 -> 175
// (golf ball 69 -> 16, octocat 47 -> 20, guide arm 16 -> 10, upsampled
// box 117 -> 104), for 2.1x their recovery time (user seconds, 12.2 ->
// 25.3). Its second and third passes, which only catch faces a
// neighbour's recovery unblocked, get an eighth and a sixty-fourth of the
// budget. (Measured: depth 7, 191 points; depth 6, octocat fails; one
// pass, 179 for nearly the same time: the first pass is the cost.)
// That deepest round runs in two stages. Most faces it recovers need few
// removals, while each face it cannot recover spends the whole budget
// (feeder body: 258 failures spent 4.67 million removals, 46 successes
// 71,000; of the successes on the five hard shared surfaces, 16 of 111
// needed more than 2,000). So every face first gets 1,500, and the faces
// left get 40,000 each only while the stage has spent less than two such
// budgets in all. On the 37 shared surfaces (cbr recover, sums of the
// recovery seconds): 8.1 -> 6.7 s (feeder body 4.0 -> 3.0, upsampled box
// 0.92 -> 0.49), Steiner points inside 147 -> 150; on 144 turned copies
// (rotate_surface.py seeds 1, 2, 10, 11, the feeder body left out) 191
// -> 207, all recovered, as fast. (Measured: 1,500 alone, 152 and 6.1 s,
// but the sprocket keeps a Steiner point that 40,000 removes; an
// allowance of eight budgets, 148 and 8.3 s.)
constexpr Search kSearches[] = {{2, 100, false},
                                {3, 400, true},
                                {5, 2000, true},
                                {8, 1500, true, 3, true},
                                {8, 40000, true, 3, true, 2 * 40000L}};
// The last rounds, the deepest stages: FlipRounds::kWithoutDeepest leaves
// them out, and recover_by_flips' deepest_budget replaces them.
constexpr std::size_t kDeepestRounds = 2;
static_assert(kSearches[std::size(kSearches) - 1].depth <= FailedSearches::kMaxDepth,
              "the deepest searches would not be remembered");
// Tetrahedra searched for crossings of one segment (remove_any_crossing).
constexpr std::size_t kMaxSearchedTets = 4096;
// Passes over the faces still missing (recover_by_flips).
constexpr int kMaxPasses = 3;

class FlipRecovery {
public:
    FlipRecovery(mesh::TetMesh& m, const ConstraintFaces& faces, FlipMemo memo, FlipDirection direction,
                 NestedOrder nested)
        : m_(m), faces_(faces), memo_(memo), direction_(direction), nested_(nested) {
        incident_ = mesh::incident_tets(m_);
        protect_ = [this](VertexId a, VertexId b) { return is_input_edge(a, b); };
        changed_at_.assign(m_.vertex_count(), 0);
        incident_saved_at_.assign(m_.vertex_count(), 0);
        tried_at_.assign(faces_.size(), 0);
    }

    void set_search(const Search& s) { search_ = s; }

    // Edge removals the last attempt left unspent of its budget.
    int budget_left() const { return budget_; }

    bool is_input_edge(VertexId a, VertexId b) const { return faces_.has_edge(a, b); }

    // One attempt at face i (with a rollback when `rollback` and it fails);
    // the vertices of the tetrahedra it leaves in the mesh are stamped with
    // the attempt's number.
    bool attempt(std::size_t i, bool rollback) {
        tried_at_[i] = ++attempts_;
        touched_.clear();
        const bool recovered = rollback ? recover_or_roll_back(i) : recover(i);
        for (VertexId v : touched_) changed_at_[v] = attempts_;
        return recovered;
    }

    // Whether a later pass of a round should try face i again: only when
    // the mesh changed at one of its vertices since its last attempt began
    // (its own attempt's flips included). Elsewhere a neighbour's recovery
    // rarely unblocks it, and its search would spend its whole budget
    // again: on the feeder body, 645 of the deepest round's 852 repeats.
    bool worth_retrying(std::size_t i) const {
        const Triangle& t = faces_.triangle(i);
        return std::any_of(t.begin(), t.end(), [&](VertexId v) { return changed_at_[v] >= tried_at_[i]; });
    }

private:
    // Recovers face i, or leaves the mesh exactly as it was: the mesh's
    // journal takes back what the attempt changed, and incident_'s changes
    // are undone from their own log (each vertex's entry as the attempt
    // found it). A copy of the mesh taken before each attempt that followed
    // a change was a fifth of the golf ball's run.
    bool recover_or_roll_back(std::size_t i) {
        const FailedSearches::State before = state_;
        const mesh::JournalScope journal(m_);  // flip recovery never runs inside another journal
        struct IncidentLog {  // closed however the attempt ends
            FlipRecovery& r;
            explicit IncidentLog(FlipRecovery& f) : r(f) {
                r.incident_undo_.clear();
                r.journal_incident_ = true;
            }
            ~IncidentLog() { r.journal_incident_ = false; }
        } log(*this);
        if (recover(i)) return true;
        touched_.clear();  // rolled back: the mesh is as the attempt found it
        if (state_ != before) {
            m_.undo_journal();
            for (const auto& [v, t] : incident_undo_) incident_[v] = t;
            set_state(before);
        }
        return false;
    }

    bool recover(std::size_t i) {
        budget_ = search_.budget;
        Triangle t = faces_.triangle(i);
        if (direction_ == FlipDirection::kReversed) std::swap(t[1], t[2]);
        for (int k = 0; k < 3; ++k)
            if (!recover_edge(t[k], t[(k + 1) % 3])) return false;
        return recover_face(t);
    }

    TetId edge_tet(VertexId a, VertexId b) const { return mesh::find_edge_tet(m_, a, incident_[a], b); }

    void note_created() {
        for (TetId t : created_)
            for (int i = 0; i < 4; ++i)
                if (m_.vertex(t, i) != kGhostVertex) {
                    if (journal_incident_) save_incident(m_.vertex(t, i));
                    incident_[m_.vertex(t, i)] = t;
                    touched_.push_back(m_.vertex(t, i));
                }
    }

    // incident_[v] as the attempt found it, once per attempt.
    void save_incident(VertexId v) {
        if (incident_saved_at_[v] == attempts_) return;
        incident_saved_at_[v] = attempts_;
        incident_undo_.emplace_back(v, incident_[v]);
    }

    void set_state(FailedSearches::State s) {
        state_ = s;
        failed_removals_.set_state(s);
        failed_wide_searches_.set_state(s);
    }

    bool done(FlipResult r) {
        if (r != FlipResult::kDone) return false;
        set_state(++last_state_);
        note_created();
        return true;
    }

    Crossing first_crossing(VertexId u, VertexId w) { return recover::first_crossing(m_, u, incident_[u], w); }

    bool remove_crossing(const Crossing& c) {
        created_.clear();
        switch (c.kind) {
            case Crossing::kFace: {
                if (done(mesh::flip23(m_, c.tet, c.face, protect_, &created_))) return true;
                // The face cannot be flipped: remove one of its edges.
                const VertexId* v = m_.vertices(c.tet);
                VertexId edge[3][2];
                for (int k = 0; k < 3; ++k) {
                    edge[k][0] = v[kFaceVertices[c.face][k]];
                    edge[k][1] = v[kFaceVertices[c.face][(k + 1) % 3]];
                }
                const TetId t = c.tet;
                for (const auto& e : edge)
                    if (remove_edge_deep(t, e[0], e[1], search_.depth)) return true;
                return false;
            }
            case Crossing::kEdge: return remove_edge_deep(c.tet, c.x, c.y, search_.depth);
            default: return false;  // through a vertex: no flip helps
        }
    }

    bool recover_edge(VertexId u, VertexId w) {
        for (int step = 0; step < kMaxFlipsPerConstraint; ++step) {
            if (edge_tet(u, w) != kNoTet) return true;
            // The first crossing from either end; when neither can be
            // flipped away, any crossing along the segment.
            const bool removed = remove_crossing(first_crossing(u, w)) || remove_crossing(first_crossing(w, u)) ||
                                 (search_.wide && unless_known_to_fail(failed_wide_searches_, u, w, search_.depth,
                                                                       [&] { return remove_any_crossing(u, w); }));
            // A nested removal can change the mesh and still fail (the
            // inner flip worked, the outer did not): it may have made uw.
            if (!removed) return edge_tet(u, w) != kNoTet;
        }
        return edge_tet(u, w) != kNoTet;
    }

    // When neither first crossing can be flipped away, another crossing of
    // the segment may be: as in Sloan's edge insertion in a plane, where
    // some crossing edge always has a convex quadrilateral, while the ones
    // at the ends need not (flat CAD facets, e.g. a disk cap fanned from
    // one rim vertex over a Delaunay mesh whose in-plane edges are another
    // triangulation). In 3D nothing guarantees one works; this only widens
    // the search. Every crossing of the segment (SegmentCrossings: from
    // u's ball outwards) is tried in turn.
    bool remove_any_crossing(VertexId u, VertexId w) {
        if (!crossings_.find(m_, u, incident_[u], w, kMaxSearchedTets)) return false;
        for (const Crossing& c : crossings_.crossings())  // remove_crossing never searches: the list stays put
            if (remove_crossing(c)) return true;
        return false;
    }

    // Face abc, its edges present: present already, or remove a mesh edge
    // crossing its interior, found in the shell of one of its edges.
    bool recover_face(const Triangle& tri) {
        for (int step = 0; step < kMaxFlipsPerConstraint; ++step) {
            if (mark_if_present(tri)) return true;
            if (!remove_edge_crossing(tri)) return mark_if_present(tri);
        }
        return mark_if_present(tri);
    }

    bool mark_if_present(const Triangle& tri) {
        const TetId t = edge_tet(tri[0], tri[1]);
        if (t == kNoTet || !mesh::shell(m_, tri[0], tri[1], t, shell_)) return false;
        for (std::size_t i = 0; i < shell_.size(); ++i) {
            if (shell_.ring[i] != tri[2]) continue;
            // The face (a, b, c) lies between shell tetrahedra i-1 and i.
            const TetId s = shell_.tets[i];
            const int f = mesh::vertex_index(m_, s, shell_.ring[(i + 1) % shell_.size()]);
            const mesh::FacetRef across = m_.neighbor(s, f);
            if (!m_.is_constrained(s, f)) {
                m_.set_constrained(s, f, true);
                m_.set_constrained(mesh::facet_tet(across), mesh::facet_face(across), true);
                // A mark is a change too: a rollback copy taken before it
                // must not come back over it (a face recovered without a
                // flip, then another face rolled back).
                set_state(++last_state_);
            }
            return true;
        }
        return false;
    }

    bool remove_edge_crossing(const Triangle& tri) {
        const double* a = m_.point(tri[0]);
        const double* b = m_.point(tri[1]);
        const double* c = m_.point(tri[2]);
        for (int k = 0; k < 3; ++k) {
            const VertexId p = tri[k], q = tri[(k + 1) % 3];
            const TetId t = edge_tet(p, q);
            if (t == kNoTet || !mesh::shell(m_, p, q, t, shell_)) continue;
            const mesh::Shell around = shell_;
            for (std::size_t i = 0; i < around.size(); ++i) {
                const VertexId r = around.ring[i], s = around.ring[(i + 1) % around.size()];
                if (r == kGhostVertex || s == kGhostVertex) continue;
                if (!geom::segment_crosses_triangle_interior(m_.point(r), m_.point(s), a, b, c)) continue;
                if (remove_edge_deep(around.tets[i], r, s, search_.depth)) return true;
            }
        }
        return false;
    }

    // Edge removal of uv (t contains it); when no triangulation of its ring
    // is valid, first remove an edge from u or v to a ring vertex (that
    // vertex then leaves the ring), up to `depth` levels, and try again.
    // A search known to fail in the mesh as it is is not run again
    // (FailedSearches: same outcome, same budget spent).
    bool remove_edge_deep(TetId t, VertexId u, VertexId v, int depth) {
        if (is_input_edge(u, v) || u == kGhostVertex || v == kGhostVertex || budget_ <= 0) return false;
        // t is stale when a removal tried before this one changed the mesh
        // and still failed: that ends this search at once, whatever the
        // mesh now allows (a search's outcome must depend on the mesh alone).
        if (!mesh::holds_edge(m_, t, u, v)) {
            --budget_;
            return false;
        }
        return unless_known_to_fail(failed_removals_, u, v, depth, [&] { return search_edge_removal(t, u, v, depth); });
    }

    // Runs `search` (of edge uv at `depth`) unless it is known to fail in
    // the mesh as it is, in which case only its budget is spent again.
    template <class SearchFn>
    bool unless_known_to_fail(FailedSearches& memo, VertexId u, VertexId v, int depth, SearchFn search) {
        const int known = memo_ == FlipMemo::kOn ? memo.spent(u, v, depth) : -1;
        if (known >= 0) {
            budget_ = std::max(budget_ - known, 0);
            return false;
        }
        const int budget_before = budget_;
        const FailedSearches::State state_before = state_;
        if (search()) return true;
        // Cut short by the budget, or it changed the mesh: not a repeatable failure.
        if (budget_ > 0 && state_ == state_before) memo.failed(u, v, depth, budget_before - budget_);
        return false;
    }

    bool search_edge_removal(TetId t, VertexId u, VertexId v, int depth) {
        --budget_;
        created_.clear();
        if (shells_.size() <= static_cast<std::size_t>(depth)) {
            shells_.resize(static_cast<std::size_t>(depth) + 1);
            orders_.resize(static_cast<std::size_t>(depth) + 1);
        }
        mesh::Shell& around = shells_[static_cast<std::size_t>(depth)];  // one per nesting level, reused
        // One walk around uv: a failed removal leaves the mesh unchanged,
        // so the shell it was given is still the shell of uv below.
        if (!mesh::shell(m_, u, v, t, around)) return false;
        // Nested removals try the ring vertices where the ring is not
        // convex as seen from u and v first: no valid triangulation of the
        // ring has their ear (NestedOrder). Those ears also tell, for the
        // price of n sign tests, that most rings have no valid
        // triangulation at all, before the dynamic program asks (guide
        // arm: 5% fewer instructions for the whole recovery, the same mesh).
        std::vector<std::size_t>& order = orders_[static_cast<std::size_t>(depth)];
        bool may_triangulate = true;
        if (depth > 0 && nested_ == NestedOrder::kBlockingFirst) {
            const std::size_t blocking = mesh::ring_positions_blocking_first(m_, u, v, around, order);
            may_triangulate = mesh::ring_may_be_triangulated(order, blocking);
        }
        // Small rings are quicker to search than to look up.
        const bool memo = memo_ == FlipMemo::kOn && around.size() >= mesh::FailedRings::kMinRing;
        const std::uint64_t ring = memo ? mesh::FailedRings::key(u, v, around) : 0;
        if (!memo || !failed_rings_.contains(ring)) {
            const FlipResult r = may_triangulate ? mesh::remove_edge(m_, u, v, around, protect_, &created_)
                                                 : FlipResult::kNoValidTriangulation;
            if (done(r)) return true;
            if (memo && r == FlipResult::kNoValidTriangulation) failed_rings_.insert(ring);
        }
        if (depth == 0) return false;
        if (nested_ != NestedOrder::kBlockingFirst) {
            order.resize(around.size());
            std::iota(order.begin(), order.end(), std::size_t{0});
        }
        for (std::size_t i : order) {
            const VertexId r = around.ring[i];
            if (r == kGhostVertex) continue;
            for (VertexId end : {u, v}) {
                if (!remove_edge_deep(around.tets[i], end, r, depth - 1)) continue;
                const TetId again = edge_tet(u, v);
                if (again == kNoTet) return true;  // uv went with it
                return remove_edge_deep(again, u, v, depth - 1);
            }
        }
        return false;
    }

    mesh::TetMesh& m_;
    const ConstraintFaces& faces_;
    const FlipMemo memo_;
    const FlipDirection direction_;
    const NestedOrder nested_;
    Search search_ = kSearches[0];
    int budget_ = 0;
    std::vector<TetId> incident_;
    // recover_or_roll_back: incident_'s old entries while it runs, and
    // per vertex the attempt that saved its entry.
    bool journal_incident_ = false;
    std::vector<std::pair<VertexId, TetId>> incident_undo_;
    std::vector<std::uint64_t> incident_saved_at_;
    mesh::EdgeProtect protect_;
    // Kept through rollbacks: a ring without a valid triangulation stays so.
    mesh::FailedRings failed_rings_;
    // remove_edge_deep and remove_any_crossing that failed in this state.
    FailedSearches failed_removals_, failed_wide_searches_;
    // The mesh's state: a new id after each flip, the old one back after
    // a rollback.
    FailedSearches::State state_ = 1, last_state_ = 1;
    std::vector<TetId> created_;
    mesh::Shell shell_;
    std::vector<mesh::Shell> shells_;
    std::vector<std::vector<std::size_t>> orders_;  // per nesting level, as shells_: the ring positions to try
    SegmentCrossings crossings_;  // remove_any_crossing's
    // worth_retrying: per vertex, the last attempt that left new tetrahedra
    // at it; per face, its last attempt (0: none).
    std::vector<VertexId> touched_;
    std::vector<std::uint64_t> changed_at_, tried_at_;
    std::uint64_t attempts_ = 0;
};

// The rounds recover_by_flips runs: kSearches, without the deepest stages
// (kWithoutDeepest), or with one deepest round of `deepest_budget` removals
// a face and no allowance in their place (the deepest round before session
// 37; the retries after a failure and the tests take it).
std::vector<Search> rounds_of(FlipRounds rounds, int deepest_budget) {
    const Search* deepest = std::end(kSearches) - kDeepestRounds;
    std::vector<Search> list(std::begin(kSearches), deepest);
    if (rounds == FlipRounds::kWithoutDeepest) return list;
    if (deepest_budget == 0) {
        list.insert(list.end(), deepest, std::end(kSearches));
        return list;
    }
    Search one = kSearches[std::size(kSearches) - 1];
    one.budget = deepest_budget;
    one.allowance = 0;
    list.push_back(one);
    return list;
}

}  // namespace

std::vector<std::size_t> recover_by_flips(mesh::TetMesh& m, const ConstraintFaces& faces,
                                          const std::vector<std::size_t>& missing, FlipMemo memo,
                                          FlipRounds rounds, int deepest_budget, FlipDirection direction,
                                          NestedOrder nested, std::vector<FlipRoundReport>* per_round) {
    FlipRecovery flips(m, faces, memo, direction, nested);
    std::vector<std::size_t> left = missing;
    // A face recovered later can unblock one tried earlier: each round
    // repeats while a pass makes progress, a few times, for the faces whose
    // mesh changed since their last attempt (FlipRecovery::worth_retrying;
    // the faces flips cannot recover would spend their whole budget again
    // on every pass; point splitting recovers them anyway). Each harder
    // round only sees the faces the previous ones left, whose meshes it
    // would otherwise disturb before their own turn.
    if (per_round) per_round->clear();
    for (const Search& search : rounds_of(rounds, deepest_budget)) {
        FlipRoundReport report;
        report.faces = left.size();
        long& spent = report.removals;
        bool progress = true;
        for (int pass = 0; pass < kMaxPasses && progress && !left.empty(); ++pass) {
            Search this_face = search;
            const int pass_budget = search.budget >> (search.shrink * pass);
            progress = false;
            std::vector<std::size_t> still;
            for (std::size_t i : left) {
                const bool round_spent = search.allowance != 0 && spent >= search.allowance;
                if (round_spent || (pass > 0 && !flips.worth_retrying(i))) {
                    still.push_back(i);
                    continue;
                }
                // The pass's budget, or what the round's allowance has left.
                this_face.budget = search.allowance == 0
                                       ? pass_budget
                                       : static_cast<int>(std::min<long>(pass_budget, search.allowance - spent));
                flips.set_search(this_face);
                ++report.attempts;
                const bool recovered = flips.attempt(i, search.rollback);
                spent += this_face.budget - flips.budget_left();
                if (recovered) progress = true;
                else still.push_back(i);
            }
            left.swap(still);
        }
        if (per_round) per_round->push_back(report);
    }
    return left;
}

}  // namespace cbr::recover
