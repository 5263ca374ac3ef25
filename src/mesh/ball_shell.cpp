#include "mesh/ball_shell.hpp"

#include <algorithm>
#include <unordered_set>

namespace cbr::mesh {
namespace {

bool live(const TetMesh& m, TetId t) { return t < m.slot_count() && !m.is_free(t); }

// 1 when the permutation (p[0], p[1], p[2], p[3]) of 0..3 is odd.
int parity(const int p[4]) {
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) inversions += p[i] > p[j];
    return inversions & 1;
}

// Positions x, y of the two vertices of t other than u and v, ordered so
// that (u, v, vertex x, vertex y) is an even permutation of t.
void ring_positions(int iu, int iv, int& x, int& y) {
    int rest[2], k = 0;
    for (int i = 0; i < 4; ++i)
        if (i != iu && i != iv) rest[k++] = i;
    const int p[4] = {iu, iv, rest[0], rest[1]};
    x = rest[parity(p)];
    y = rest[1 - parity(p)];
}

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

// Membership in a growing list of tetrahedra: a linear scan while the list
// is short (a ball has a few dozen tetrahedra; no allocation per call), a
// hash set once it is long (the ball of the infinite vertex is the hull).
class Visited {
public:
    explicit Visited(const std::vector<TetId>& list) : list_(list) {}
    bool contains(TetId t) {
        if (list_.size() <= kLinear) return std::find(list_.begin(), list_.end(), t) != list_.end();
        for (; indexed_ < list_.size(); ++indexed_) set_.insert(list_[indexed_]);
        return set_.count(t) != 0;
    }

private:
    static constexpr std::size_t kLinear = 64;
    const std::vector<TetId>& list_;
    std::unordered_set<TetId> set_;
    std::size_t indexed_ = 0;
};

}  // namespace

bool ball(const TetMesh& m, VertexId v, TetId start, std::vector<TetId>& out) {
    out.clear();
    if (!live(m, start) || vertex_index(m, start, v) < 0) return false;
    out.push_back(start);
    Visited seen(out);
    // Breadth-first over the faces that contain v (all but the one opposite v).
    for (std::size_t next = 0; next < out.size(); ++next) {
        const TetId t = out[next];
        for (int f = 0; f < 4; ++f) {
            if (m.vertex(t, f) == v) continue;
            const TetId n = facet_tet(m.neighbor(t, f));
            if (!seen.contains(n)) out.push_back(n);
        }
    }
    return true;
}

bool shell(const TetMesh& m, VertexId u, VertexId v, TetId start, Shell& out) {
    out.tets.clear();
    out.ring.clear();
    if (u == v || !live(m, start)) return false;
    TetId t = start;
    int iu = vertex_index(m, t, u), iv = vertex_index(m, t, v);
    if (iu < 0 || iv < 0) return false;
    // Around the edge: cross the face opposite ring[i] (it holds u, v and
    // ring[i+1]); a valid mesh comes back to `start`, a broken one is cut
    // off after slot_count() steps.
    for (std::size_t steps = 0; steps <= m.slot_count(); ++steps) {
        int x, y;
        ring_positions(iu, iv, x, y);
        out.tets.push_back(t);
        out.ring.push_back(m.vertex(t, x));
        t = facet_tet(m.neighbor(t, x));
        if (t == start) return true;
        iu = vertex_index(m, t, u);
        iv = vertex_index(m, t, v);
        if (iu < 0 || iv < 0) break;
    }
    out.tets.clear();
    out.ring.clear();
    return false;
}

TetId find_edge_tet(const TetMesh& m, VertexId u, TetId start, VertexId v) {
    // The breadth-first walk of ball(), stopping at the first tetrahedron
    // that has v.
    if (!live(m, start) || vertex_index(m, start, u) < 0) return kNoTet;
    std::vector<TetId> tets{start};
    Visited seen(tets);
    for (std::size_t next = 0; next < tets.size(); ++next) {
        const TetId t = tets[next];
        if (vertex_index(m, t, v) >= 0) return t;
        for (int f = 0; f < 4; ++f) {
            if (m.vertex(t, f) == u) continue;
            const TetId n = facet_tet(m.neighbor(t, f));
            if (!seen.contains(n)) tets.push_back(n);
        }
    }
    return kNoTet;
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

}  // namespace cbr::mesh
