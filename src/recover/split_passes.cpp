#include "recover/split_passes.hpp"

#include <algorithm>
#include <set>
#include <utility>

#include "mesh/ball_shell.hpp"
#include "recover/point_splitting.hpp"
#include "recover/steiner_suppression.hpp"

namespace cbr::recover {
namespace {

using mesh::kFaceVertices;
using mesh::kGhostVertex;
using mesh::TetId;
using mesh::VertexId;

// Face f of t is a sub-face of a triangle that still has an added point:
// part of the surface being recovered, not yet a recovered face.
bool partial_subface(const mesh::TetMesh& m, const SurfacePoints& points, TetId t, int f) {
    const int* k = kFaceVertices[f];
    const VertexId a = m.vertex(t, k[0]), b = m.vertex(t, k[1]), c = m.vertex(t, k[2]);
    if (a == kGhostVertex || b == kGhostVertex || c == kGhostVertex) return false;
    return (points.is_added(a) || points.is_added(b) || points.is_added(c)) && points.is_subface(a, b, c);
}

// Suppresses the Steiner points in the ball of added point e (see the
// header); returns how many went, and erases them from `steiner`.
std::size_t suppress_around(mesh::TetMesh& m, const SurfacePoints& points, std::vector<TetId>& incident, VertexId e,
                            std::vector<VertexId>& steiner) {
    std::vector<TetId> ball;
    if (!mesh::ball(m, e, incident[e], ball)) return 0;
    std::set<VertexId> near;
    for (TetId t : ball)
        for (int i = 0; i < 4; ++i) {
            const VertexId v = m.vertex(t, i);
            if (v != kGhostVertex && v >= points.first_new_vertex() && !points.is_added(v)) near.insert(v);
        }
    std::vector<VertexId> candidates(near.begin(), near.end());
    // Sub-faces become constraint faces for the suppression, which never
    // removes one (they are unmarked after, wherever they are then).
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t))
            for (int f = 0; f < 4; ++f)
                if (partial_subface(m, points, t, f)) m.set_constrained(t, f, true);
    const mesh::EdgeProtect links = [&points](VertexId a, VertexId b) { return points.is_chain_link(a, b); };
    const std::size_t gone = suppress_vertices(m, candidates, links);
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t))
            for (int f = 0; f < 4; ++f)
                if (m.is_constrained(t, f) && partial_subface(m, points, t, f)) m.set_constrained(t, f, false);
    if (gone == 0) return 0;
    const std::set<VertexId> kept(candidates.begin(), candidates.end());
    steiner.erase(std::remove_if(steiner.begin(), steiner.end(),
                                 [&](VertexId v) { return near.count(v) != 0 && kept.count(v) == 0; }),
                  steiner.end());
    incident = mesh::incident_tets(m);
    return gone;
}

}  // namespace

bool split_added_points(mesh::TetMesh& m, SurfacePoints& points, std::vector<TetId>& incident,
                        const std::vector<VertexId>& added, std::vector<VertexId>& steiner, std::size_t& made,
                        std::string& why) {
    PointSplitting splitting(m, points, incident);
    std::vector<VertexId> pending;
    for (const bool edges : {true, false})
        for (VertexId e : added)
            if (points.is_added(e) && points.on_edge(e, nullptr, nullptr, nullptr) == edges) pending.push_back(e);
    bool ok = true;
    while (!pending.empty()) {
        std::vector<VertexId> waiting;
        std::string first_why;
        for (VertexId e : pending) {
            if (!points.is_added(e) || splitting.split(e, steiner)) continue;
            if (waiting.empty()) first_why = splitting.why();
            waiting.push_back(e);
        }
        if (waiting.size() == pending.size()) {
            std::size_t gone = 0;
            for (VertexId e : waiting) gone += suppress_around(m, points, incident, e, steiner);
            if (gone == 0) {
                why = first_why;
                ok = false;
                break;
            }
        }
        pending.swap(waiting);
    }
    made = splitting.made();
    return ok;
}

}  // namespace cbr::recover
