#include "recover/steiner_merging.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <set>
#include <unordered_set>

#include "mesh/ball_shell.hpp"
#include "mesh/flips.hpp"
#include "mesh/surgery.hpp"

namespace cbr::recover {

using mesh::kGhostVertex;
using mesh::kNoTet;
using mesh::TetId;
using mesh::TetMesh;
using mesh::VertexId;

namespace {

using Point = std::array<double, 3>;

class Merger {
public:
    Merger(TetMesh& m, const std::vector<VertexId>& steiner)
        : m_(m), incident_(mesh::incident_tets(m)), steiner_(steiner.begin(), steiner.end()) {}

    // Merges t into s when the union of their balls is star-shaped from a
    // candidate point; s moves there, t leaves the mesh.
    bool merge(VertexId s, VertexId t);
    // The Steiner points joined to s by an edge, in increasing order.
    std::vector<VertexId> steiner_neighbours(VertexId s);
    bool in_mesh(VertexId v) const { return v < incident_.size() && incident_[v] != kNoTet; }
    void forget(VertexId v) { steiner_.erase(v); }

private:
    TetMesh& m_;
    std::vector<TetId> incident_;
    std::set<VertexId> steiner_;
    std::vector<TetId> ball_s_, ball_t_;
};

std::vector<VertexId> Merger::steiner_neighbours(VertexId s) {
    std::set<VertexId> out;
    if (!in_mesh(s) || !mesh::ball(m_, s, incident_[s], ball_s_)) return {};
    for (TetId x : ball_s_)
        for (int i = 0; i < 4; ++i) {
            const VertexId v = m_.vertex(x, i);
            if (v != s && v != kGhostVertex && steiner_.count(v)) out.insert(v);
        }
    return {out.begin(), out.end()};
}

bool Merger::merge(VertexId s, VertexId t) {
    if (!in_mesh(s) || !in_mesh(t)) return false;
    if (!mesh::ball(m_, s, incident_[s], ball_s_) || !mesh::ball(m_, t, incident_[t], ball_t_)) return false;
    std::set<TetId> region(ball_s_.begin(), ball_s_.end());
    region.insert(ball_t_.begin(), ball_t_.end());
    // The union's faces: boundary ones are coned to the kept point; the
    // interior ones vanish, so none may be a constraint face.
    std::vector<std::pair<TetId, int>> boundary;
    std::unordered_set<VertexId> on_boundary;
    for (TetId x : region) {
        if (m_.is_ghost(x)) return false;
        for (int f = 0; f < 4; ++f) {
            if (region.count(mesh::facet_tet(m_.neighbor(x, f)))) {
                if (m_.is_constrained(x, f)) return false;
                continue;
            }
            boundary.emplace_back(x, f);
            for (int i = 0; i < 4; ++i)
                if (i != f) on_boundary.insert(m_.vertex(x, i));
        }
    }
    for (TetId x : region)
        for (int i = 0; i < 4; ++i) {
            const VertexId v = m_.vertex(x, i);
            if (v != s && v != t && !on_boundary.count(v)) return false;  // it would leave the mesh
        }
    // Candidates on the segment st (where both points' balls meet), then
    // the centroid of the union's boundary vertices.
    const double* ps = m_.point(s);
    const double* pt = m_.point(t);
    std::vector<Point> candidates;
    for (const double w : {0.5, 0.0, 1.0, 0.25, 0.75})
        candidates.push_back({ps[0] + w * (pt[0] - ps[0]), ps[1] + w * (pt[1] - ps[1]), ps[2] + w * (pt[2] - ps[2])});
    Point centroid{0, 0, 0};
    for (VertexId v : on_boundary)
        for (int k = 0; k < 3; ++k) centroid[k] += m_.point(v)[k] / static_cast<double>(on_boundary.size());
    candidates.push_back(centroid);
    const auto cone_quality = [&](const Point& p) {
        double q = std::numeric_limits<double>::infinity();
        for (const auto& [x, f] : boundary) {
            std::array<const double*, 4> v{};
            for (int i = 0; i < 4; ++i) v[i] = i == f ? p.data() : m_.point(m_.vertex(x, i));
            q = std::min(q, mesh::tet_quality(v[0], v[1], v[2], v[3]));  // -inf unless positive (exact)
            if (!(q > 0)) return q;
        }
        return q;
    };
    const Point* best = nullptr;
    double best_q = 0;
    for (const Point& p : candidates) {
        const double q = cone_quality(p);
        if (q > best_q) {
            best_q = q;
            best = &p;
        }
    }
    if (best == nullptr) return false;
    std::vector<std::array<VertexId, 4>> fresh;
    for (const auto& [x, f] : boundary) {
        std::array<VertexId, 4> v = {m_.vertex(x, 0), m_.vertex(x, 1), m_.vertex(x, 2), m_.vertex(x, 3)};
        v[static_cast<std::size_t>(f)] = s;
        fresh.push_back(v);
    }
    const Point before = {ps[0], ps[1], ps[2]};
    const Point chosen = *best;
    m_.set_point(s, chosen.data());
    std::vector<TetId> created;
    const std::vector<TetId> old(region.begin(), region.end());
    if (mesh::replace_tets(m_, old, fresh, &created) != mesh::ReplaceResult::kDone) {
        m_.set_point(s, before.data());
        return false;
    }
    for (TetId x : created)
        for (int i = 0; i < 4; ++i) incident_[m_.vertex(x, i)] = x;
    incident_[t] = kNoTet;
    return true;
}

}  // namespace

std::size_t merge_steiner_pairs(TetMesh& m, std::vector<VertexId>& steiner) {
    Merger merger(m, steiner);
    std::unordered_set<VertexId> gone;
    for (bool progress = true; progress;) {
        progress = false;
        for (VertexId s : steiner) {
            if (gone.count(s)) continue;
            for (VertexId t : merger.steiner_neighbours(s)) {
                if (!merger.merge(s, t)) continue;
                gone.insert(t);
                merger.forget(t);
                progress = true;
                break;
            }
        }
    }
    steiner.erase(std::remove_if(steiner.begin(), steiner.end(), [&](VertexId v) { return gone.count(v) != 0; }),
                  steiner.end());
    return gone.size();
}

}  // namespace cbr::recover
