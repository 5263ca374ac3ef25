#include "recover/unblocking_points.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geom/point_in_triangle.hpp"
#include "geom/predicates.hpp"
#include "geom/triangle_distance.hpp"
#include "geom/vec3.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/slot_marks.hpp"
#include "recover/protected_insertion.hpp"
#include "recover/segment_search.hpp"

namespace cbr::recover {
namespace {

using mesh::kFaceVertices;
using mesh::kGhostVertex;
using mesh::kNoTet;
using mesh::TetId;
using mesh::VertexId;

// Tetrahedra searched along one edge.
constexpr std::size_t kMaxSearchedTets = std::size_t{1} << 16;
// Points tried per missing edge: one per options.tets_per_point
// tetrahedra the edge meets, at most kMaxPointsPerEdge, spread evenly
// along it. Offsets from the edge: from a quarter of its length, halved
// down to options.clearance times the face's shortest edge, which is also
// the least distance kept from every missing triangle (a point nearer the
// surface makes the thin tetrahedra that later steps must then split
// around).
constexpr std::size_t kMaxPointsPerEdge = 8;
// Steps of the walk to a point.
constexpr int kMaxWalk = 10000;

using geom::cross;
using geom::dot;

void centroid(const mesh::TetMesh& m, TetId t, double out[3]) {
    out[0] = out[1] = out[2] = 0;
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) out[k] += 0.25 * m.point(m.vertex(t, i))[k];
}

bool strictly_inside(const mesh::TetMesh& m, TetId t, const double* p) {
    const VertexId* v = m.vertices(t);
    for (int f = 0; f < 4; ++f) {
        const int* k = kFaceVertices[f];
        if (geom::orient3d(m.point(v[k[0]]), m.point(v[k[1]]), m.point(v[k[2]]), p) <= 0) return false;
    }
    return true;
}

// Unit normal of triangle t (rounded) and its shortest edge's length.
void normal_and_scale(const mesh::TetMesh& m, const Triangle& t, double n[3], double& scale) {
    const double* a = m.point(t[0]);
    const double* b = m.point(t[1]);
    const double* c = m.point(t[2]);
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = c[k] - b[k];
    }
    cross(u, v, n);
    const double l = std::sqrt(dot(n, n));
    for (int k = 0; k < 3; ++k) n[k] /= l;
    scale = std::sqrt(std::min({dot(u, u), dot(v, v), dot(w, w)}));
}

class Unblocker {
public:
    Unblocker(mesh::TetMesh& m, const ConstraintFaces& faces, const std::vector<std::size_t>& missing,
              const UnblockingOptions& options)
        : m_(m), faces_(faces), missing_(missing), options_(options), incident_(mesh::incident_tets(m)) {
        boxes_.reserve(missing_.size());
        for (std::size_t f : missing_) {
            const Triangle& t = faces_.triangle(f);
            Box b;
            for (int k = 0; k < 3; ++k) {
                b.lo[k] = std::min({m_.point(t[0])[k], m_.point(t[1])[k], m_.point(t[2])[k]});
                b.hi[k] = std::max({m_.point(t[0])[k], m_.point(t[1])[k], m_.point(t[2])[k]});
            }
            boxes_.push_back(b);
        }
    }

    UnblockingResult run(std::vector<VertexId>& steiner) {
        const std::size_t before = steiner.size();
        for (std::size_t f : missing_) {
            const Triangle& t = faces_.triangle(f);
            for (int k = 0; k < 3; ++k) unblock_edge(t, t[k], t[(k + 1) % 3], steiner);
        }
        result_.kept = steiner.size() - before;
        return result_;
    }

private:
    struct Box {
        double lo[3], hi[3];
        bool apart(const double* p, double margin) const {
            for (int k = 0; k < 3; ++k)
                if (p[k] < lo[k] - margin || p[k] > hi[k] + margin) return true;
            return false;
        }
    };
    struct Met {
        double d2;  // squared distance of the centroid from the target point
        TetId tet;
    };

    bool edge_exists(VertexId a, VertexId b) const { return mesh::find_edge_tet(m_, a, incident_[a], b) != kNoTet; }

    // The finite tetrahedra the closed segment ab meets other than at a or b
    // (SegmentSearch from a's ball, never across a constraint face),
    // nearest `target` first (nullptr: in the order found, d2 0; for a count).
    std::vector<Met> met_tets(VertexId a, VertexId b, const double* target) {
        std::vector<Met> out;
        const SegmentSearch::Limits up_to_constraints{false, kMaxSearchedTets};
        search_.run(m_, a, incident_[a], b, up_to_constraints, [&](TetId t, SegmentSearch::FaceBits bits) {
            if (bits == 0) return;  // no face met
            if (target == nullptr) {
                out.push_back({0, t});
                return;
            }
            double c[3];
            centroid(m_, t, c);
            const double d[3] = {c[0] - target[0], c[1] - target[1], c[2] - target[2]};
            out.push_back({dot(d, d), t});
        });
        if (target == nullptr) return out;
        // Ties by id: the order is then a function of the mesh alone, not of
        // the walk from incident_[a], so that a list kept across points
        // tried and undone (unblock_edge) is the one a new search would give.
        std::sort(out.begin(), out.end(),
                  [](const Met& x, const Met& y) { return x.d2 < y.d2 || (x.d2 == y.d2 && x.tet < y.tet); });
        return out;
    }

    std::size_t met_count(VertexId a, VertexId b) {
        if (edge_exists(a, b)) return 0;
        return met_tets(a, b, nullptr).size();
    }

    // Points off face `tri` near its missing edge ab; see the header.
    void unblock_edge(const Triangle& tri, VertexId a, VertexId b, std::vector<VertexId>& steiner) {
        if (edge_exists(a, b)) return;
        double pa[3], pb[3], n[3], scale = 0;
        std::copy_n(m_.point(a), 3, pa);
        std::copy_n(m_.point(b), 3, pb);
        normal_and_scale(m_, tri, n, scale);
        const double mid[3] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2])};
        const std::vector<Met> met = met_tets(a, b, mid);
        std::size_t count = met.size();
        if (count == 0) return;
        // The side of the face most of the crossed tetrahedra lie on first.
        double side = 0;
        for (const Met& x : met) {
            double c[3];
            centroid(m_, x.tet, c);
            const double d[3] = {c[0] - pa[0], c[1] - pa[1], c[2] - pa[2]};
            side += dot(d, n);
        }
        const double first = side >= 0 ? 1.0 : -1.0;
        const double ab[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
        const double length = std::sqrt(dot(ab, ab));
        const std::size_t targets =
            std::clamp<std::size_t>(count / std::max<std::size_t>(options_.tets_per_point, 1), 1, kMaxPointsPerEdge);
        const double clearance = options_.clearance * scale;
        for (std::size_t i = 0; i < targets && count > 0; ++i) {
            const double s = (static_cast<double>(i) + 0.5) / static_cast<double>(targets);
            const double on_edge[3] = {pa[0] + s * ab[0], pa[1] + s * ab[1], pa[2] + s * ab[2]};
            // Found once for the target's tries, and again only when a point
            // not kept moved tetrahedra to other slots (undo_last_insertion);
            // a kept point ends them.
            std::vector<Met> met_here;
            bool met_known = false;
            bool kept = false;
            for (double d = length / 4; d >= clearance && !kept; d /= 2)
                for (const double dir : {first, -first}) {
                    const double p[3] = {on_edge[0] + dir * d * n[0], on_edge[1] + dir * d * n[1],
                                         on_edge[2] + dir * d * n[2]};
                    if (!met_known) {
                        met_here = met_tets(a, b, on_edge);
                        met_known = true;
                    }
                    if (try_point(a, b, met_here, p, clearance, count, steiner, met_known)) {
                        kept = true;
                        break;
                    }
                }
        }
    }

    // Inserts p if it passes the tests and ab then meets fewer than `count`
    // tetrahedra (count updated) with a star of at most options_.max_star
    // tetrahedra; otherwise leaves the mesh as it was (and counts a point
    // that only its star kept out). `met`: the tetrahedra ab meets now,
    // nearest p's target on ab first (met_tets); `met_known` turns false
    // when p, not kept, was undone into other slots (the list then no
    // longer names them).
    bool try_point(VertexId a, VertexId b, const std::vector<Met>& met, const double* p, double clearance,
                   std::size_t& count, std::vector<VertexId>& steiner, bool& met_known) {
        if (met.empty()) return false;
        const TetId at = walk(met.front().tet, p);
        if (at == kNoTet || near_missing_face(p, clearance) || !conflicts_reach(at, p, met)) return false;
        std::size_t star = 0;
        if (!insert(at, p, steiner, star)) return false;
        const std::size_t after = met_count(a, b);
        if ((after < count || options_.keep_first) && star <= options_.max_star) {
            count = std::min(after, count);
            return true;
        }
        if (after < count) ++result_.refused_for_star;
        if (!undo_last_insertion(steiner)) met_known = false;
        return false;
    }

    // The star of the last point inserted goes back to the cavity it
    // replaced, and the point goes. Returns whether every tetrahedron of
    // the cavity is back in its own slot (ProtectedInserter::undo_last).
    bool undo_last_insertion(std::vector<VertexId>& steiner) {
        std::vector<TetId> restored;
        const bool same_slots = inserter_.undo_last(m_, steiner.back(), restored);
        for (TetId t : restored)
            for (int i = 0; i < 4; ++i)
                if (m_.vertex(t, i) != kGhostVertex) incident_[m_.vertex(t, i)] = t;
        steiner.pop_back();
        return same_slots;
    }

    // The finite tetrahedra whose circumspheres hold p, connected to `at`
    // across faces that are not constraint faces (the Delaunay cavity
    // before its correction), include one that ab meets: else p cannot
    // remove a crossing, and is not worth an insertion and a rollback.
    bool conflicts_reach(TetId at, const double* p, const std::vector<Met>& met) {
        marks_.new_round(m_.slot_count());
        for (const Met& x : met) marks_.set(x.tet, kWanted);
        std::vector<TetId> stack{at};
        marks_.set(at, kSeen);
        std::size_t seen = 1;
        while (!stack.empty() && seen < kMaxSearchedTets) {
            const TetId t = stack.back();
            stack.pop_back();
            if (marks_.has(t, kWanted)) return true;
            for (int f = 0; f < 4; ++f) {
                const TetId n = mesh::facet_tet(m_.neighbor(t, f));
                if (m_.is_constrained(t, f) || m_.is_ghost(n) || marks_.has(n, kSeen)) continue;
                marks_.set(n, kSeen);
                ++seen;
                const VertexId* v = m_.vertices(n);
                if (geom::insphere_sos(m_.point(v[0]), m_.point(v[1]), m_.point(v[2]), m_.point(v[3]), p) > 0)
                    stack.push_back(n);
            }
        }
        return false;
    }

    // Visibility walk from t towards p that never leaves the hull nor, unless
    // options_.walk_through_recovered, crosses a constraint face: the
    // tetrahedron that holds p strictly inside, or kNoTet (p on a face of
    // the mesh, behind the surface, or lost).
    TetId walk(TetId t, const double* p) const {
        for (int step = 0; step < kMaxWalk; ++step) {
            const VertexId* v = m_.vertices(t);
            int exit = -1;
            for (int f = 0; f < 4 && exit < 0; ++f) {
                const int* k = kFaceVertices[f];
                if (geom::orient3d(m_.point(v[k[0]]), m_.point(v[k[1]]), m_.point(v[k[2]]), p) < 0) exit = f;
            }
            if (exit < 0) return strictly_inside(m_, t, p) ? t : kNoTet;
            if (m_.is_constrained(t, exit) && !options_.walk_through_recovered) return kNoTet;
            t = mesh::facet_tet(m_.neighbor(t, exit));
            if (m_.is_ghost(t)) return kNoTet;
        }
        return kNoTet;
    }

    // p on a missing triangle (exact), or nearer one than `clearance`. The
    // recovered triangles are mesh faces: p strictly inside a tetrahedron is
    // on none of them.
    bool near_missing_face(const double* p, double clearance) const {
        for (std::size_t i = 0; i < missing_.size(); ++i) {
            // Farther than twice the clearance from the triangle's box: not
            // on it, and not near it even with the distance rounded.
            if (boxes_[i].apart(p, 2 * clearance)) continue;
            const Triangle& t = faces_.triangle(missing_[i]);
            const double* a = m_.point(t[0]);
            const double* b = m_.point(t[1]);
            const double* c = m_.point(t[2]);
            if (geom::point_in_triangle(p, a, b, c) || geom::distance2_to_triangle(p, a, b, c) < clearance * clearance)
                return true;
        }
        return false;
    }

    bool insert(TetId t, const double* xyz, std::vector<VertexId>& steiner, std::size_t& star) {
        const VertexId p = m_.add_points(xyz, 1);
        const ProtectedInsertResult& r = inserter_.insert(m_, p, t);
        if (!r.ok) {
            m_.truncate_vertices(p);
            return false;
        }
        star = r.created.size();
        if (incident_.size() <= p) incident_.resize(std::size_t{p} + 1, kNoTet);
        for (TetId s : r.created)
            for (int i = 0; i < 4; ++i)
                if (m_.vertex(s, i) != kGhostVertex) incident_[m_.vertex(s, i)] = s;
        steiner.push_back(p);
        return true;
    }

    mesh::TetMesh& m_;
    const ConstraintFaces& faces_;
    const std::vector<std::size_t>& missing_;
    const UnblockingOptions options_;
    UnblockingResult result_;
    std::vector<Box> boxes_;  // of the missing triangles, in missing_'s order
    std::vector<TetId> incident_;
    ProtectedInserter inserter_;
    SegmentSearch search_;  // met_tets'
    // Scratch of conflicts_reach: tetrahedra reached (kSeen) and those the
    // segment meets (kWanted).
    static constexpr std::uint8_t kSeen = 1u << 0;
    static constexpr std::uint8_t kWanted = 1u << 1;
    mesh::SlotMarks marks_;
};

}  // namespace

UnblockingResult insert_unblocking_points(mesh::TetMesh& m, const ConstraintFaces& faces,
                                          const std::vector<std::size_t>& missing, std::vector<VertexId>& steiner,
                                          const UnblockingOptions& options) {
    return Unblocker(m, faces, missing, options).run(steiner);
}

}  // namespace cbr::recover
