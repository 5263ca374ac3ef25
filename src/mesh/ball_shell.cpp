#include "mesh/ball_shell.hpp"

#include <algorithm>
#include <cstdint>

#include "mesh/slot_marks.hpp"

namespace cbr::mesh {
namespace {

bool live(const TetMesh& m, TetId t) { return t < m.slot_count() && !m.is_free(t); }

// 1 when the permutation (p[0], p[1], p[2], p[3]) of 0..3 is odd.
constexpr int parity(const int p[4]) {
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) inversions += p[i] > p[j];
    return inversions & 1;
}

// The position x of one of the two vertices of t other than u and v
// (at positions iu != iv): the one for which (u, v, vertex x, the other)
// is an even permutation of t. shell() crosses the face opposite it.
constexpr int ring_position(int iu, int iv) {
    int rest[2] = {0, 0}, k = 0;
    for (int i = 0; i < 4; ++i)
        if (i != iu && i != iv) rest[k++] = i;
    const int p[4] = {iu, iv, rest[0], rest[1]};
    return rest[parity(p)];
}

// ring_position for every (iu, iv), looked up: shell() takes one step per
// tetrahedron around an edge, millions of times in flip recovery.
struct RingTable {
    int x[4][4] = {};
    constexpr RingTable() {
        for (int iu = 0; iu < 4; ++iu)
            for (int iv = 0; iv < 4; ++iv)
                if (iu != iv) x[iu][iv] = ring_position(iu, iv);
    }
};
constexpr RingTable kRing;

}  // namespace

bool Shell::has_ghost() const {
    return std::find(ring.begin(), ring.end(), kGhostVertex) != ring.end();
}

int vertex_index(const TetMesh& m, TetId t, VertexId v) {
    for (int i = 0; i < 4; ++i)
        if (m.vertex(t, i) == v) return i;
    return -1;
}

namespace {

// Reused by every ball walk of the thread: ball() and find_edge_tet() run
// millions of times in a recovery, and a visited list searched linearly
// (with a vector allocated per call) was a large part of their cost. A
// per-slot mark answers "seen?" in O(1) and starts each walk clear in O(1).
// One thread_local object: each one costs a TLS look-up per call.
struct BallScratch {
    SlotMarks seen;
    std::vector<TetId> queue;  // find_edge_tet's breadth-first list
};

BallScratch& ball_scratch() {
    thread_local BallScratch scratch;
    return scratch;
}

constexpr std::uint8_t kSeen = 1;

// Starts a walk: every slot of m unseen. (Fetched once per walk: the
// library is also built shared, where each thread_local use is a call.)
BallScratch& fresh_scratch(const TetMesh& m) {
    BallScratch& scratch = ball_scratch();
    scratch.seen.new_round(m.slot_count());
    return scratch;
}

// Appends the tetrahedra across the faces of t that contain v (all but
// the one opposite v) not seen yet, in face order, and marks them seen.
void push_unseen_neighbors(const TetMesh& m, TetId t, VertexId v, SlotMarks& seen, std::vector<TetId>& list) {
    for (int f = 0; f < 4; ++f) {
        if (m.vertex(t, f) == v) continue;
        const TetId n = facet_tet(m.neighbor(t, f));
        if (seen.has(n, kSeen)) continue;
        seen.set(n, kSeen);
        list.push_back(n);
    }
}

// The breadth-first walk of ball(), returning the first tetrahedron of
// its order that `accept` takes. Each one is tested as it joins the list
// rather than when its turn comes: the same one is found (the list is in
// the same order either way), without expanding the tetrahedra before it.
template <typename Accept>
TetId first_accepted(const TetMesh& m, VertexId v, TetId start, const Accept& accept) {
    if (!live(m, start) || vertex_index(m, start, v) < 0) return kNoTet;
    if (accept(start)) return start;
    BallScratch& scratch = fresh_scratch(m);
    SlotMarks& seen = scratch.seen;
    std::vector<TetId>& tets = scratch.queue;
    tets.clear();
    seen.set(start, kSeen);
    tets.push_back(start);
    for (std::size_t next = 0; next < tets.size(); ++next) {
        const std::size_t tested = tets.size();
        push_unseen_neighbors(m, tets[next], v, seen, tets);
        for (std::size_t i = tested; i < tets.size(); ++i)
            if (accept(tets[i])) return tets[i];
    }
    return kNoTet;
}

}  // namespace

bool ball(const TetMesh& m, VertexId v, TetId start, std::vector<TetId>& out) {
    out.clear();
    if (!live(m, start) || vertex_index(m, start, v) < 0) return false;
    SlotMarks& seen = fresh_scratch(m).seen;
    seen.set(start, kSeen);
    out.push_back(start);
    // Breadth-first: `out` is its own queue.
    for (std::size_t next = 0; next < out.size(); ++next) push_unseen_neighbors(m, out[next], v, seen, out);
    return true;
}

bool holds_edge(const TetMesh& m, TetId t, VertexId u, VertexId v) {
    return u != v && live(m, t) && vertex_index(m, t, u) >= 0 && vertex_index(m, t, v) >= 0;
}

bool shell(const TetMesh& m, VertexId u, VertexId v, TetId start, Shell& out, std::size_t max_size) {
    out.tets.clear();
    out.ring.clear();
    if (!holds_edge(m, start, u, v)) return false;
    TetId t = start;
    int iu = vertex_index(m, t, u), iv = vertex_index(m, t, v);
    // Around the edge: cross the face opposite ring[i] (it holds u, v and
    // ring[i+1]); a valid mesh comes back to `start`, a broken one is cut
    // off after slot_count() steps.
    for (std::size_t steps = 0; steps <= m.slot_count(); ++steps) {
        const int x = kRing.x[iu][iv];
        if (out.tets.size() == max_size) break;
        out.tets.push_back(t);
        out.ring.push_back(m.vertex(t, x));
        t = facet_tet(m.neighbor(t, x));
        if (t == start) return true;
        iu = iv = -1;
        const VertexId* w = m.vertices(t);
        for (int i = 0; i < 4; ++i) {
            if (w[i] == u) iu = i;
            else if (w[i] == v) iv = i;
        }
        if (iu < 0 || iv < 0) break;
    }
    out.tets.clear();
    out.ring.clear();
    return false;
}

TetId find_edge_tet(const TetMesh& m, VertexId u, TetId start, VertexId v) {
    return first_accepted(m, u, start, [&](TetId t) { return vertex_index(m, t, v) >= 0; });
}

TetId first_in_ball(const TetMesh& m, VertexId v, TetId start, const std::function<bool(TetId)>& accept) {
    return first_accepted(m, v, start, accept);
}

std::vector<TetId> incident_tets(const TetMesh& m) {
    std::vector<TetId> inc(m.vertex_count(), kNoTet);
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        const bool ghost = m.is_ghost(t);
        for (int i = 0; i < (ghost ? 3 : 4); ++i) {
            TetId& slot = inc[m.vertex(t, i)];
            if (slot == kNoTet || (!ghost && m.is_ghost(slot))) slot = t;
        }
    }
    return inc;
}

VertexBalls::VertexBalls(const TetMesh& m) : offsets_(m.vertex_count() + 1, 0) {
    const auto finite_corners = [&](TetId t) { return m.is_ghost(t) ? 3 : 4; };
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t))
            for (int i = 0; i < finite_corners(t); ++i) ++offsets_[m.vertex(t, i) + 1];
    for (std::size_t v = 0; v + 1 < offsets_.size(); ++v) offsets_[v + 1] += offsets_[v];
    tets_.resize(offsets_.back());
    std::vector<std::size_t> fill(offsets_.begin(), offsets_.end() - 1);
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t))
            for (int i = 0; i < finite_corners(t); ++i) tets_[fill[m.vertex(t, i)]++] = t;
}

void VertexBalls::get(VertexId v, std::vector<TetId>& out) const {
    out.assign(tets_.begin() + static_cast<std::ptrdiff_t>(offsets_[v]),
               tets_.begin() + static_cast<std::ptrdiff_t>(offsets_[v + 1]));
}

}  // namespace cbr::mesh
