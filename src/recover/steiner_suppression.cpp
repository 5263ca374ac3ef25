// Steiner point suppression (§6). Every change goes through replace_tets
// (directly, or through the flips of mesh/flips), so each step is exact:
// fresh tetrahedra positively oriented, the region tiled, no constraint
// face removed.
//
// Why only edges at v are ever removed: a contraction and the final 4-1
// remove the edges v-x and keep the link (the ball's boundary) as it is; an
// edge removal of v-x removes v-x only; a 2-3 flip removes no edge. So the
// protection callback is asked once, up front, about every edge v-x, and
// no other edge of the mesh can disappear.
//
// Why the flipping terminates: every kept step is an edge removal at v
// (the degree of v drops by one) or a 2-3 flip kept only because it makes
// an edge removal at v possible; a step budget bounds the rare case where
// replace_tets still refuses that removal.
//
// Why rollback is exact: all steps happen inside the region of the
// original ball (an edge removal of v-x replaces the shell of v-x, which
// lies in Ball(v); a 2-3 flip of a face at v replaces two ball
// tetrahedra), so the live tetrahedra created there tile that region and
// replace_tets can put the original tetrahedra back.
#include "recover/steiner_suppression.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <set>
#include <utility>

#include "mesh/ball_shell.hpp"
#include "mesh/errors.hpp"
#include "mesh/surgery.hpp"

namespace cbr::recover {

using mesh::kGhostVertex;
using mesh::TetId;
using mesh::TetMesh;
using mesh::VertexId;

namespace {

using Tet = std::array<VertexId, 4>;
constexpr double kInf = std::numeric_limits<double>::infinity();

bool live(const TetMesh& m, TetId t) { return t < m.slot_count() && !m.is_free(t); }

Tet tet_of(const TetMesh& m, TetId t) { return {m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)}; }

double quality(const TetMesh& m, const Tet& t) {
    return mesh::tet_quality(m.point(t[0]), m.point(t[1]), m.point(t[2]), m.point(t[3]));
}

// The link vertices of v (sorted, so that every choice is deterministic).
std::vector<VertexId> link_vertices(const TetMesh& m, VertexId v, const std::vector<TetId>& ball) {
    std::vector<VertexId> out;
    for (TetId t : ball)
        for (int i = 0; i < 4; ++i)
            if (m.vertex(t, i) != v) out.push_back(m.vertex(t, i));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// Mechanism 1 (and the 4-1 flip, which is a contraction of a ball of four).
struct Contraction {
    VertexId x = kGhostVertex;  // the link vertex v goes onto
    double min_quality = -kInf;
    std::vector<Tet> fresh;
};

// The contraction of v onto x: ball tetrahedra without x with v replaced
// by x (same position, so a valid one keeps its orientation sign). True
// when it makes tetrahedra and every one rates above `floor` (-inf: every
// one is valid); the rating stops at the first that does not.
bool contraction_onto(const TetMesh& m, VertexId v, VertexId x, const std::vector<TetId>& ball, double floor,
                      Contraction& c) {
    c.x = x;
    c.min_quality = kInf;
    c.fresh.clear();
    for (TetId t : ball) {
        Tet k = tet_of(m, t);
        if (std::find(k.begin(), k.end(), x) != k.end()) continue;
        for (VertexId& w : k)
            if (w == v) w = x;
        c.min_quality = std::min(c.min_quality, quality(m, k));
        if (c.min_quality <= floor) return false;
        c.fresh.push_back(k);
    }
    return !c.fresh.empty();
}

// The best valid contraction of v (the largest worst tet_quality; the
// first link vertex among equals), the targets in `refused` left out,
// searched above the best so far as best_edge_removal searches its rings:
// a later target must beat the floor strictly, so the winner is the first
// of a ranking of every contraction by quality. (Rating every contraction
// in full was 2.8% of the feeder body's recovery.)
bool best_contraction(const TetMesh& m, VertexId v, const std::vector<TetId>& ball,
                      const std::vector<VertexId>& refused, Contraction& best) {
    Contraction c;
    double floor = -kInf;
    bool found = false;
    for (VertexId x : link_vertices(m, v, ball)) {
        if (std::find(refused.begin(), refused.end(), x) != refused.end()) continue;
        if (!contraction_onto(m, v, x, ball, floor, c)) continue;
        floor = c.min_quality;
        std::swap(best, c);
        found = true;
    }
    return found;
}

// The best choice (a Contraction or a Removal, each for a link vertex x)
// that `apply` carries out: `find_best(refused, best)` gives the best one
// whose x is not in `refused`; a refused one leaves the mesh as it was, so
// the next best is then the next of the ranking. Refusals are
// configurations (a link that is not star-shaped from x, a constraint
// face), not bugs.
template <class Choice, class FindBest, class Apply>
bool apply_best(FindBest find_best, Apply apply) {
    std::vector<VertexId> refused;
    Choice best;
    while (find_best(refused, best)) {
        if (apply(best)) return true;
        refused.push_back(best.x);
    }
    return false;
}

// The best valid contraction that replace_tets accepts. True when one was
// done; `region` then holds the new tets.
bool contract(TetMesh& m, VertexId v, const std::vector<TetId>& ball, std::set<TetId>& region, double& min_quality) {
    return apply_best<Contraction>(
        [&](const std::vector<VertexId>& refused, Contraction& best) {
            return best_contraction(m, v, ball, refused, best);
        },
        [&](const Contraction& c) {
            std::vector<TetId> created;
            if (mesh::replace_tets(m, ball, c.fresh, &created) != mesh::ReplaceResult::kDone) return false;
            for (TetId t : ball) region.erase(t);
            region.insert(created.begin(), created.end());
            min_quality = c.min_quality;
            return true;
        });
}

// An edge removal of v-x that best_ring_triangulation finds valid.
struct Removal {
    VertexId x = kGhostVertex;
    double min_quality = -kInf;
    mesh::Shell shell;
    std::vector<mesh::RingTriangle> triangles;
};

// The link vertices of v, ascending, each with the first tetrahedron of
// `ball` that holds it. `ball` in mesh::ball's order is the breadth-first
// order in which mesh::find_edge_tet(m, v, ball.front(), x) looks, so this
// is the tetrahedron it would return, found for every x in one pass
// instead of one walk per link vertex (those walks were 3.6% of the
// feeder body's recovery).
std::vector<std::pair<VertexId, TetId>> link_vertices_with_tets(const TetMesh& m, VertexId v,
                                                                const std::vector<TetId>& ball) {
    // Each (vertex, position in the ball) as one key: sorted, a vertex's
    // first key holds its first tetrahedron in ball order.
    std::vector<std::uint64_t> keys;
    keys.reserve(3 * ball.size());
    for (std::size_t k = 0; k < ball.size(); ++k)
        for (int i = 0; i < 4; ++i)
            if (m.vertex(ball[k], i) != v) keys.push_back((std::uint64_t{m.vertex(ball[k], i)} << 32) | k);
    std::sort(keys.begin(), keys.end());
    std::vector<std::pair<VertexId, TetId>> out;
    for (const std::uint64_t key : keys) {
        const auto x = static_cast<VertexId>(key >> 32);
        if (out.empty() || out.back().first != x)
            out.emplace_back(x, ball[static_cast<std::size_t>(key & 0xffffffffu)]);
    }
    return out;
}

// Whether some link vertex x of v has a valid edge removal of vx. `ball`
// is v's ball as mesh::ball returns it.
bool has_edge_removal(const TetMesh& m, VertexId v, const std::vector<TetId>& ball) {
    mesh::Shell shell;
    std::vector<mesh::RingTriangle> triangles;
    for (const auto& [x, t] : link_vertices_with_tets(m, v, ball))
        if (mesh::shell(m, v, x, t, shell) && shell.size() >= 3 &&
            mesh::best_ring_triangulation(m, v, x, shell, triangles))
            return true;
    return false;
}

// The best valid edge removal at v (the largest worst tet_quality; the
// first link vertex among equals), the link vertices in `refused` left
// out. Once a ring has a valid triangulation, the next ones are searched
// only above its quality (RingObjective::floor), where most of them stop
// at once: the winner, its triangulation and quality are those of the
// full search, since a later ring must beat the floor strictly. (Ranking
// every ring in full was 6.6% of the feeder body's recovery.)
bool best_edge_removal(const TetMesh& m, VertexId v, const std::vector<TetId>& ball,
                       const std::vector<VertexId>& refused, Removal& best) {
    mesh::RingObjective above_best;  // tet_quality, as best_ring_triangulation's default
    Removal r;
    bool found = false;
    for (const auto& [x, t] : link_vertices_with_tets(m, v, ball)) {
        if (std::find(refused.begin(), refused.end(), x) != refused.end()) continue;
        if (!mesh::shell(m, v, x, t, r.shell) || r.shell.size() < 3) continue;
        if (!mesh::best_ring_triangulation(m, v, x, r.shell, r.triangles, &r.min_quality, above_best)) continue;
        r.x = x;
        above_best.floor = r.min_quality;
        std::swap(best, r);
        found = true;
    }
    return found;
}

// One edge removal at v: the best valid one that transform_shell accepts.
bool remove_one_edge(TetMesh& m, VertexId v, const std::vector<TetId>& ball, std::set<TetId>& region) {
    return apply_best<Removal>(
        [&](const std::vector<VertexId>& refused, Removal& best) {
            return best_edge_removal(m, v, ball, refused, best);
        },
        [&](const Removal& r) {
            std::vector<TetId> created;
            if (mesh::transform_shell(m, v, r.x, r.shell, r.triangles, &created) != mesh::FlipResult::kDone)
                return false;
            for (TetId t : r.shell.tets) region.erase(t);
            region.insert(created.begin(), created.end());
            return true;
        });
}

// A tetrahedron of the region that contains v (its ball is then found
// from it), or kNoTet.
TetId tet_at(const TetMesh& m, VertexId v, const std::set<TetId>& region) {
    for (TetId t : region)
        if (live(m, t) && mesh::vertex_index(m, t, v) >= 0) return t;
    return mesh::kNoTet;
}

// The edges ab of the link of v: the faces (v, a, b) inside the ball.
std::vector<std::array<VertexId, 2>> link_edges(const TetMesh& m, VertexId v, const std::vector<TetId>& ball) {
    std::vector<std::array<VertexId, 2>> out;
    for (TetId t : ball)
        for (int f = 0; f < 4; ++f) {
            if (m.vertex(t, f) == v) continue;
            std::array<VertexId, 2> e;
            int k = 0;
            for (int i = 0; i < 4; ++i)
                if (i != f && m.vertex(t, i) != v) e[static_cast<std::size_t>(k++)] = m.vertex(t, i);
            if (e[0] > e[1]) std::swap(e[0], e[1]);
            out.push_back(e);
        }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// Face f of a ball tetrahedron that is (v, a, b): f is the position of
// the vertex other than v, a, b. False when no ball tetrahedron has it.
bool find_face(const TetMesh& m, VertexId v, VertexId a, VertexId b, const std::vector<TetId>& ball, TetId& t,
               int& f) {
    for (TetId k : ball) {
        if (mesh::vertex_index(m, k, a) < 0 || mesh::vertex_index(m, k, b) < 0) continue;
        for (int i = 0; i < 4; ++i) {
            const VertexId w = m.vertex(k, i);
            if (w != v && w != a && w != b) {
                t = k;
                f = i;
                return true;
            }
        }
    }
    return false;
}

// A 2-3 flip of a face (v, a, b) inside the ball: the two ball
// tetrahedra (v, a, b, c) and (v, a, b, d) become three around the new edge
// cd, one of which, (a, b, c, d), leaves the ball. In the link this flips
// edge ab to cd; the degree of v is unchanged. Kept only when it makes an
// edge removal at v possible (one step of look-ahead); otherwise undone by
// the inverse 3-2 flip of cd, and the next link edge is tried.
bool flip_link_edge(TetMesh& m, VertexId v, const std::vector<TetId>& ball0, std::set<TetId>& region,
                    SuppressReport& rep) {
    std::vector<TetId> ball;
    for (const auto& [a, b] : link_edges(m, v, ball0)) {
        const TetId at = tet_at(m, v, region);
        TetId t = mesh::kNoTet;
        int f = -1;
        if (at == mesh::kNoTet || !mesh::ball(m, v, at, ball) || !find_face(m, v, a, b, ball, t, f)) continue;
        const TetId n = mesh::facet_tet(m.neighbor(t, f));
        const VertexId c = m.vertex(t, f);
        const VertexId d = m.vertex(n, mesh::facet_face(m.neighbor(t, f)));
        std::vector<TetId> created;
        if (mesh::flip23(m, t, f, {}, &created) != mesh::FlipResult::kDone) continue;
        ++rep.flips;
        region.erase(t);
        region.erase(n);
        region.insert(created.begin(), created.end());
        TetId at_v = mesh::kNoTet;
        for (TetId k : created)
            if (mesh::vertex_index(m, k, v) >= 0) at_v = k;
        if (at_v != mesh::kNoTet && mesh::ball(m, v, at_v, ball) && has_edge_removal(m, v, ball)) {
            ++rep.link_flips;
            return true;
        }
        // Undo: the 3-2 flip of the edge cd just made (no protection: cd
        // is new).
        std::vector<TetId> back;
        if (mesh::flip32(m, created.front(), c, d, {}, &back) != mesh::FlipResult::kDone)
            throw InternalError("steiner suppression: the 3-2 flip undoing a 2-3 flip was refused");
        ++rep.flips;
        ++rep.flips_undone;
        for (TetId k : created) region.erase(k);
        region.insert(back.begin(), back.end());
    }
    return false;
}

// Puts the original tetrahedra back into the region (exact inverse).
void rollback(TetMesh& m, const std::set<TetId>& region, const std::vector<Tet>& original,
              std::vector<TetId>* created) {
    const std::vector<TetId> now(region.begin(), region.end());
    if (mesh::replace_tets(m, now, original, created) != mesh::ReplaceResult::kDone)
        throw InternalError("steiner suppression: rollback of the ball refused");
}

// Mechanism 2; on failure the caller rolls the region back.
bool flip_down(TetMesh& m, VertexId v, std::set<TetId>& region, const SuppressOptions& options,
               SuppressReport& rep) {
    const bool contraction = options.contraction;
    const std::size_t budget = options.max_flip_steps ? options.max_flip_steps : 2 * region.size() + 8;
    std::vector<TetId> ball;
    for (std::size_t step = 0; step < budget; ++step) {
        const TetId at = tet_at(m, v, region);
        if (at == mesh::kNoTet || !mesh::ball(m, v, at, ball)) return false;
        // The 4-1 flip; or any contraction when mechanism 1 is allowed
        // (at step 0 it was just tried on this very ball).
        if ((ball.size() == 4 || (contraction && step > 0)) && contract(m, v, ball, region, rep.min_quality))
            return true;
        if (remove_one_edge(m, v, ball, region)) {
            ++rep.flips;
            ++rep.edge_removals;
            continue;
        }
        if (!flip_link_edge(m, v, ball, region, rep)) return false;
    }
    return false;
}

}  // namespace

const char* to_string(SuppressResult r) {
    switch (r) {
        case SuppressResult::kSuppressed: return "suppressed";
        case SuppressResult::kBadInput: return "bad input";
        case SuppressResult::kHullVertex: return "hull vertex";
        case SuppressResult::kOnConstraint: return "on a constraint face";
        case SuppressResult::kProtectedEdge: return "protected edge";
        case SuppressResult::kNoRetriangulation: return "no retriangulation of the ball without it";
        case SuppressResult::kRefused: return "the retriangulation was refused";
    }
    return "?";
}

bool suppress_vertex(TetMesh& m, VertexId v, TetId start, const mesh::EdgeProtect& protect, SuppressReport* report,
                     const SuppressOptions& options) {
    SuppressReport local;
    SuppressReport& rep = report ? *report : local;
    rep = SuppressReport{};
    std::vector<TetId> ball;
    if (v == kGhostVertex || !mesh::ball(m, v, start, ball)) {
        rep.result = SuppressResult::kBadInput;
        return false;
    }
    if (std::any_of(ball.begin(), ball.end(), [&](TetId t) { return m.is_ghost(t); })) {
        rep.result = SuppressResult::kHullVertex;
        return false;
    }
    for (TetId t : ball) {
        for (int f = 0; f < 4; ++f)
            if (m.vertex(t, f) != v && m.is_constrained(t, f)) {
                rep.result = SuppressResult::kOnConstraint;
                return false;
            }
    }
    if (protect)
        for (VertexId x : link_vertices(m, v, ball))
            if (protect(v, x)) {
                rep.result = SuppressResult::kProtectedEdge;
                return false;
            }

    std::set<TetId> region(ball.begin(), ball.end());
    std::vector<Tet> original;
    for (TetId t : ball) original.push_back(tet_of(m, t));
    // A failed attempt leaves the mesh bit for bit as it found it (slots,
    // flags and free list: the mesh's journal), so that trying it again on
    // an unchanged ball fails again (suppress_vertices skips such tries).
    // Inside a caller's open journal, the ball is put back by replace_tets
    // instead (same tetrahedra, other slots).
    const mesh::JournalScope journal(m);
    auto roll_back = [&](const std::set<TetId>& now) {
        if (journal.owns()) m.undo_journal();
        else rollback(m, now, original, &rep.created);
    };

    bool done = false;
    if (options.contraction && contract(m, v, ball, region, rep.min_quality)) {
        rep.method = SuppressMethod::kContraction;
        done = true;
    } else if (options.flips) {
        done = flip_down(m, v, region, options, rep);
        if (done) rep.method = SuppressMethod::kFlips;
        else if (rep.flips > 0) roll_back(region);
    }
    if (!done) {
        rep.result = SuppressResult::kNoRetriangulation;
        return false;
    }
    rep.result = SuppressResult::kSuppressed;
    for (TetId t : region)
        if (live(m, t)) rep.created.push_back(t);
    if (options.accept && !options.accept(m, rep.created)) {
        const std::set<TetId> now(rep.created.begin(), rep.created.end());
        rep.created.clear();
        roll_back(now);
        rep.result = SuppressResult::kRefused;
        rep.method = SuppressMethod::kNone;
        return false;
    }
    return true;
}

namespace {

// What a suppression attempt at v reads of the mesh: the tetrahedra of
// Ball(v), each as its slot, its vertices (stored order) and its
// constraint marks, in slot order (the order of the attempt's region).
// Every step of an attempt stays inside the ball (see the top of this
// file), and a failed attempt leaves the mesh as it was; so an attempt
// that failed fails again while this is unchanged.
using BallState = std::vector<std::array<VertexId, 6>>;

BallState ball_state(const TetMesh& m, VertexId v, TetId t, std::vector<TetId>& scratch) {
    BallState state;
    if (!mesh::ball(m, v, t, scratch)) return state;
    state.reserve(scratch.size());
    for (TetId x : scratch) {
        VertexId marks = 0;
        for (int f = 0; f < 4; ++f)
            if (m.is_constrained(x, f)) marks |= 1u << f;
        state.push_back({x, m.vertex(x, 0), m.vertex(x, 1), m.vertex(x, 2), m.vertex(x, 3), marks});
    }
    std::sort(state.begin(), state.end());
    return state;
}

}  // namespace

std::size_t suppress_vertices(TetMesh& m, std::vector<VertexId>& steiner, const mesh::EdgeProtect& protect,
                              SuppressStats* stats, const SuppressOptions& options) {
    SuppressStats local;
    SuppressStats& st = stats ? *stats : local;
    std::size_t total = 0;
    std::vector<TetId> start = mesh::incident_tets(m);
    // The points the last pass kept, in order, each with its ball as the
    // failed attempt left it and the reason. A later pass does not try
    // again a point whose ball is unchanged: the attempt would fail the
    // same way (suppress_vertex reads nothing else, and a failure leaves
    // the mesh bit for bit as it was; with a journal of the caller's
    // open, the ball comes back in other slots, so every point is tried).
    // On the feeder body the second and later passes were nearly all such
    // repeats, each as costly as the first failure.
    struct Failure {
        VertexId v;
        BallState ball;
        SuppressResult why;
    };
    const bool skip = options.skip_unchanged_balls && !m.journal_open();
    std::vector<Failure> failed, failed_now;
    std::vector<TetId> scratch;
    auto count_kept = [&st](SuppressResult why) {
        switch (why) {
            case SuppressResult::kHullVertex: ++st.kept_hull; break;
            case SuppressResult::kOnConstraint: ++st.kept_on_constraint; break;
            case SuppressResult::kProtectedEdge: ++st.kept_protected; break;
            default: ++st.kept_no_retriangulation; break;
        }
    };
    bool progress = true;
    while (progress && !steiner.empty()) {
        progress = false;
        ++st.passes;
        st.kept_hull = st.kept_on_constraint = st.kept_protected = st.kept_no_retriangulation = 0;
        std::vector<VertexId> kept;
        failed_now.clear();
        std::size_t next_failed = 0;  // `failed` lists its points in the order of `steiner`
        for (VertexId v : steiner) {
            if (v >= start.size()) continue;  // not a vertex of the mesh
            TetId t = start[v];
            if (t == mesh::kNoTet) continue;  // in no tetrahedron: not in the mesh
            if (!live(m, t) || mesh::vertex_index(m, t, v) < 0) {
                // An earlier suppression reused this slot: refresh every entry.
                start = mesh::incident_tets(m);
                t = start[v];
                if (t == mesh::kNoTet) continue;
            }
            while (next_failed < failed.size() && failed[next_failed].v != v) ++next_failed;
            if (next_failed < failed.size() && failed[next_failed].ball == ball_state(m, v, t, scratch)) {
                kept.push_back(v);
                count_kept(failed[next_failed].why);
                ++st.skipped;
                failed_now.push_back(std::move(failed[next_failed]));
                continue;
            }
            SuppressReport rep;
            if (suppress_vertex(m, v, t, protect, &rep, options)) {
                ++total;
                progress = true;
                (rep.method == SuppressMethod::kContraction ? st.by_contraction : st.by_flips) += 1;
                start[v] = mesh::kNoTet;
                // The ball's link vertices now start in the new tetrahedra.
                for (TetId k : rep.created)
                    for (int i = 0; i < 4; ++i)
                        if (m.vertex(k, i) != kGhostVertex) start[m.vertex(k, i)] = k;
                continue;
            }
            kept.push_back(v);
            count_kept(rep.result);
            // Under a caller's journal a refused attempt puts the ball back
            // in other slots, listed in rep.created.
            for (TetId k : rep.created)
                for (int i = 0; i < 4; ++i)
                    if (m.vertex(k, i) != kGhostVertex) start[m.vertex(k, i)] = k;
            if (skip) failed_now.push_back({v, ball_state(m, v, start[v], scratch), rep.result});
        }
        failed.swap(failed_now);
        steiner.swap(kept);
    }
    st.suppressed += total;
    return total;
}

}  // namespace cbr::recover
