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

// The four vertices of finite tetrahedron t are points of one input
// triangle (which then has an added point: it has three corners).
bool flat_in_a_triangle(const mesh::TetMesh& m, const SurfacePoints& points, TetId t,
                        std::vector<std::size_t>& faces) {
    const VertexId* v = m.vertices(t);
    int added = 0;
    while (added < 4 && !points.is_added(v[added])) ++added;
    if (added == 4) return false;
    points.faces_of(v[added], faces);
    return std::any_of(faces.begin(), faces.end(), [&](std::size_t f) {
        return std::all_of(v, v + 4, [&](VertexId x) { return points.belongs_to(x, f); });
    });
}

// Suppresses the Steiner points in the balls of the added points `stuck`
// (see the header), all in one call: the sub-faces are marked and unmarked
// over the whole mesh once, not once per point (hundreds of stuck points
// on a turned feeder body: minutes of scans); returns how many went, and
// erases them from `steiner`.
std::size_t suppress_around(mesh::TetMesh& m, const SurfacePoints& points, std::vector<TetId>& incident,
                            const std::vector<VertexId>& stuck, std::vector<VertexId>& steiner) {
    std::vector<TetId> ball;
    std::set<VertexId> near;
    for (VertexId e : stuck) {
        if (!mesh::ball(m, e, incident[e], ball)) continue;
        for (TetId t : ball)
            for (int i = 0; i < 4; ++i) {
                const VertexId v = m.vertex(t, i);
                if (v != kGhostVertex && v >= points.first_new_vertex() && !points.is_added(v)) near.insert(v);
            }
    }
    if (near.empty()) return 0;
    std::vector<VertexId> candidates(near.begin(), near.end());
    // Sub-faces become constraint faces for the suppression, which never
    // removes one (they are unmarked after, wherever they are then).
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t))
            for (int f = 0; f < 4; ++f)
                if (partial_subface(m, points, t, f)) m.set_constrained(t, f, true);
    const mesh::EdgeProtect links = [&points](VertexId a, VertexId b) { return points.is_chain_link(a, b); };
    // A ball whose link holds four points of one triangle must not be
    // rebuilt with a tetrahedron of those four: nearly coplanar, both its
    // upper and its lower face would count as sub-faces, and the fans of
    // the next splits would border more than two wedges (feeder body, with
    // another flip budget before).
    SuppressOptions options;
    std::vector<std::size_t> faces;
    options.accept = [&](const mesh::TetMesh& mesh, const std::vector<TetId>& created) {
        return std::none_of(created.begin(), created.end(),
                            [&](TetId t) { return !mesh.is_ghost(t) && flat_in_a_triangle(mesh, points, t, faces); });
    };
    const std::size_t gone = suppress_vertices(m, candidates, links, nullptr, options);
    for (TetId t = 0; t < m.slot_count(); ++t)
        if (!m.is_free(t))
            for (int f = 0; f < 4; ++f)
                if (m.is_constrained(t, f) && partial_subface(m, points, t, f)) m.set_constrained(t, f, false);
    // Also when nothing went: a ball put back (refused, or flips undone)
    // can sit in other slots.
    incident = mesh::incident_tets(m);
    if (gone == 0) return 0;
    const std::set<VertexId> kept(candidates.begin(), candidates.end());
    steiner.erase(std::remove_if(steiner.begin(), steiner.end(),
                                 [&](VertexId v) { return near.count(v) != 0 && kept.count(v) == 0; }),
                  steiner.end());
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
            if (suppress_around(m, points, incident, waiting, steiner) == 0) {
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
