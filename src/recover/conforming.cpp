#include "recover/conforming.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <unordered_set>

#include "geom/intersect.hpp"
#include "geom/predicates.hpp"
#include "geom/segment_point.hpp"
#include "geom/vec3.hpp"
#include "mesh/ball_shell.hpp"
#include "mesh/flips.hpp"
#include "recover/protected_insertion.hpp"
#include "recover/segment_walk.hpp"

namespace cbr::recover {

using mesh::kFaceVertices;
using mesh::kGhostVertex;
using mesh::kNoTet;
using mesh::TetId;
using mesh::VertexId;

namespace {

// Points added on one edge, or in one face, before recovery gives up: each
// insertion removes one crossing, so this only stops a bug from running
// forever.
constexpr std::size_t kMaxInsertionsPerConstraint = 100000;
// Where the rounded point on a face-interior crossing is refused, it is
// tried again this far along the crossed edge (in edge lengths; either
// way): still a point of the face to within rounding.
constexpr double kCrossingShifts[] = {1e-12, -1e-12, 1e-9, -1e-9};
// A segment passes by an edge of a face it crosses when their nearest
// points are this close, in edge lengths (other_crossing_points).
constexpr double kPassBy = 1e-3;

using geom::cross;
using geom::dot;

double signed_volume(const double* a, const double* b, const double* c, const double* d) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

bool contains_closed(const mesh::TetMesh& m, TetId t, const double* p) {
    const VertexId* v = m.vertices(t);
    for (int f = 0; f < 4; ++f) {
        const int* k = kFaceVertices[f];
        if (geom::orient3d(m.point(v[k[0]]), m.point(v[k[1]]), m.point(v[k[2]]), p) < 0) return false;
    }
    return true;
}

// Where segment pq meets the plane of abc (rounded; the caller has checked
// exactly that it does, in the open segment), moved off p and q if it
// rounds onto one of them; false when it did.
bool segment_plane_point(const double* p, const double* q, const double* a, const double* b, const double* c,
                         double out[3]) {
    const double vp = signed_volume(a, b, c, p), vq = signed_volume(a, b, c, q);
    double s = vp / (vp - vq);
    if (!(s > 0.0)) s = 0.5;  // only rounding can do this: stay on the segment
    if (s >= 1.0) s = 0.5;
    return !geom::segment_point_off_ends(p, q, s, out);
}

// The middle of the part of segment pq inside finite tetrahedron t
// (rounded, then checked exactly to lie in t), or false.
bool middle_in_tet(const mesh::TetMesh& m, TetId t, const double* p, const double* q, double out[3]) {
    const VertexId* v = m.vertices(t);
    double lo = 0, hi = 1;
    for (int f = 0; f < 4; ++f) {
        const int* k = kFaceVertices[f];
        const double* a = m.point(v[k[0]]);
        const double* b = m.point(v[k[1]]);
        const double* c = m.point(v[k[2]]);
        // Positive on t's side of the face (t is positively oriented: the
        // sign of orient3d, which contains_closed tests).
        const double vp = signed_volume(a, b, c, p), vq = signed_volume(a, b, c, q);
        if (vp >= 0 && vq >= 0) continue;
        if (vp < 0 && vq < 0) return false;
        const double s = vp / (vp - vq);
        if (vp < 0) lo = std::max(lo, s);
        else hi = std::min(hi, s);
    }
    if (!(lo < hi)) return false;
    const double s = 0.5 * (lo + hi);
    double x[3];
    for (int k = 0; k < 3; ++k) x[k] = p[k] + s * (q[k] - p[k]);
    if (geom::same_point(x, p) || geom::same_point(x, q) || !contains_closed(m, t, x)) return false;
    std::copy_n(x, 3, out);
    return true;
}

// The parameters of the nearest points of lines pq and xy: p + s (q - p)
// and x + t (y - x); false when the lines are parallel.
bool nearest_parameters(const double* p, const double* q, const double* x, const double* y, double& s, double& t) {
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; ++k) {
        d1[k] = q[k] - p[k];
        d2[k] = y[k] - x[k];
        r[k] = p[k] - x[k];
    }
    const double a = dot(d1, d1), e = dot(d2, d2), b = dot(d1, d2), c = dot(d1, r), f = dot(d2, r);
    const double denom = a * e - b * b;
    if (!(denom > 0)) return false;
    s = (b * f - c * e) / denom;
    t = (a * f - b * c) / denom;
    return true;
}

// The point of segment pq nearest to line xy (the segments cross, so it is
// their common point up to rounding).
void segment_line_point(const double* p, const double* q, const double* x, const double* y, double out[3]) {
    double s = 0.5, t = 0;
    if (!nearest_parameters(p, q, x, y, s, t) || !(s > 0.0) || s >= 1.0) s = 0.5;
    geom::segment_point_off_ends(p, q, s, out);
}

// Segment pq passes by segment xy: their nearest points are interior to
// both and closer than kPassBy times xy's length.
bool passes_by(const double* p, const double* q, const double* x, const double* y) {
    double s = 0, t = 0;
    if (!nearest_parameters(p, q, x, y, s, t) || !(s > 0 && s < 1 && t > 0 && t < 1)) return false;
    double gap2 = 0, length2 = 0;
    for (int k = 0; k < 3; ++k) {
        const double d = (p[k] + s * (q[k] - p[k])) - (x[k] + t * (y[k] - x[k]));
        gap2 += d * d;
        length2 += (y[k] - x[k]) * (y[k] - x[k]);
    }
    return gap2 < kPassBy * kPassBy * length2;
}

// Where segment pq crosses segment xy (exactly coplanar, crossing in their
// interiors), as a rounded point of xy: x + t (y - x) with
// t = ((p - x) x (q - p)) . ((y - x) x (q - p)) / |(y - x) x (q - p)|^2
// (cross products: no squared condition number, unlike the normal
// equations of segment_line_point).
void segment_crossing_on_edge(const double* p, const double* q, const double* x, const double* y, double out[3]) {
    double d[3], e[3], r[3];
    for (int k = 0; k < 3; ++k) {
        d[k] = q[k] - p[k];
        e[k] = y[k] - x[k];
        r[k] = p[k] - x[k];
    }
    double rd[3], ed[3];
    cross(r, d, rd);
    cross(e, d, ed);
    const double num = dot(rd, ed);
    const double den = dot(ed, ed);
    double t = den > 0 ? num / den : 0.5;
    if (!(t > 0.0) || t >= 1.0) t = 0.5;
    geom::segment_point_off_ends(x, y, t, out);
}

}  // namespace

ConformingRecovery::ConformingRecovery(mesh::TetMesh& m, SurfacePoints& points)
    : m_(m), points_(points), incident_(mesh::incident_tets(m)) {}

bool ConformingRecovery::edge_exists(VertexId a, VertexId b) const {
    return mesh::find_edge_tet(m_, a, incident_[a], b) != kNoTet;
}

void ConformingRecovery::note_created(const std::vector<TetId>& created) {
    for (TetId t : created)
        for (int i = 0; i < 4; ++i) {
            const VertexId v = m_.vertex(t, i);
            if (v == kGhostVertex) continue;
            if (v >= incident_.size()) incident_.resize(std::size_t{v} + 1, kNoTet);
            incident_[v] = t;
        }
}

VertexId ConformingRecovery::insert(const double* xyz, std::vector<TetId> cavity, bool keep_cavity) {
    TetId start = kNoTet;
    for (TetId t : cavity)
        if (!m_.is_ghost(t) && contains_closed(m_, t, xyz)) {
            start = t;
            break;
        }
    // Rounding can put the point just outside the crossing it was computed
    // for: then the cavity takes in the neighbour that holds it.
    for (std::size_t i = 0, n = cavity.size(); i < n && start == kNoTet; ++i)
        for (int f = 0; f < 4; ++f) {
            const TetId t = mesh::facet_tet(m_.neighbor(cavity[i], f));
            if (m_.is_ghost(t) || m_.is_constrained(cavity[i], f) ||
                std::find(cavity.begin(), cavity.end(), t) != cavity.end() || !contains_closed(m_, t, xyz))
                continue;
            cavity.push_back(t);
            start = t;
            break;
        }
    // On the hull (coplanar hull faces whose diagonal is missing) the point
    // can fall outside every tetrahedron: nudge it towards the inside of
    // the first finite one, by the least amount that puts it in. The point
    // is temporary (splitting removes it), so this costs nothing but its
    // distance from the surface, a few ulps.
    double nudged[3] = {xyz[0], xyz[1], xyz[2]};
    for (TetId t : cavity) {
        if (start != kNoTet || m_.is_ghost(t)) continue;
        double c[3] = {0, 0, 0};
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 3; ++k) c[k] += 0.25 * m_.point(m_.vertex(t, i))[k];
        for (double f = 1.0 / 1024 / 1024 / 1024 / 1024; f < 0.5 && start == kNoTet; f *= 8) {
            for (int k = 0; k < 3; ++k) nudged[k] = xyz[k] + f * (c[k] - xyz[k]);
            if (contains_closed(m_, t, nudged)) start = t;
        }
    }
    if (start != kNoTet) xyz = nudged;
    if (start == kNoTet) {
        why_ = "a rounded intersection point fell outside the tetrahedra it was meant to split";
        return kGhostVertex;
    }
    const VertexId p = m_.add_points(xyz, 1);
    const BlockedFace subface = [this](TetId t, int f) {
        const VertexId* v = m_.vertices(t);
        return points_.is_subface(v[kFaceVertices[f][0]], v[kFaceVertices[f][1]], v[kFaceVertices[f][2]]);
    };
    const ProtectedInsertResult& r = inserter_.insert_in_cavity(m_, p, start, cavity, subface, keep_cavity);
    if (!r.ok) {
        m_.truncate_vertices(p);
        why_ = "protected insertion refused an intersection point: " + r.why;
        return kGhostVertex;
    }
    note_created(r.created);
    return p;
}

bool ConformingRecovery::recover_face(std::size_t face) {
    const Triangle& t = points_.faces().triangle(face);
    for (int k = 0; k < 3; ++k)
        if (!recover_edge(t[k], t[(k + 1) % 3])) return false;
    // The edge removals that take flat tetrahedra away can make an edge
    // that crosses the face again (between points on either side of it,
    // in the ring of the removed edge: a pierced tetrahedron, mask 57 with
    // far points): the interior is searched again until no flat
    // tetrahedron is left.
    for (std::size_t round = 0; round < kMaxInsertionsPerConstraint; ++round) {
        std::size_t removed = 0;
        if (!recover_interior(face) || !remove_flat_tets(face, removed)) return false;
        if (removed == 0) return disk_is_complete(face);
    }
    return fail("flat tetrahedra keep coming back in one face");
}

// §5.2 for a missing edge ab: walk from a towards b; where the segment
// leaves the ball of the current chain end q, put a point on what it
// crosses (a face, or an edge when it runs through one) and continue from
// there. Each point becomes the next link of the chain a = q0, q1, ..., b.
bool ConformingRecovery::recover_edge(VertexId a, VertexId b) {
    if (!points_.chain(a, b).empty()) return true;
    std::vector<VertexId> chain{a};
    VertexId q = a;
    for (std::size_t step = 0; step < kMaxInsertionsPerConstraint; ++step) {
        if (edge_exists(q, b)) {
            chain.push_back(b);
            points_.set_chain(a, b, std::move(chain));
            return true;
        }
        const Crossing c = first_crossing(m_, q, incident_[q], b);
        std::vector<TetId> cavity;
        Position xyz{};
        if (!crossing_point(c, q, b, xyz, cavity)) return false;
        VertexId p = insert_joined(xyz, cavity, q);
        if (p == kGhostVertex) {
            const std::string first_why = why_;
            for (const Candidate& other : other_crossing_points(c, q, b, cavity))
                if ((p = insert_joined(other.xyz, other.cavity, q)) != kGhostVertex) break;
            if (p == kGhostVertex) return fail(first_why);
        }
        points_.add_edge_point(p, a, b);
        chain.push_back(p);
        q = p;
    }
    return fail("too many points on one edge");
}

// The point that removes crossing c of segment qb (the crossing itself,
// rounded) and the crossing's tetrahedra, the initial cavity.
bool ConformingRecovery::crossing_point(const Crossing& c, VertexId q, VertexId b, Position& xyz,
                                        std::vector<TetId>& cavity) {
    const double* pq = m_.point(q);
    const double* pb = m_.point(b);
    switch (c.kind) {
        case Crossing::kFace: {
            const VertexId* v = m_.vertices(c.tet);
            const int* k = kFaceVertices[c.face];
            const TetId beyond = mesh::facet_tet(m_.neighbor(c.tet, c.face));
            cavity = {c.tet, beyond};
            // A crossing that rounds onto q (a chain end that rounding put
            // next to a face of its own ball: feeder body, with another
            // flip budget before) would be q again; a point an ulp from q
            // would be no better, its ball too thin to split later. The
            // middle of the segment's part in the tetrahedron beyond is a
            // point of the segment that clears both.
            if (!segment_plane_point(pq, pb, m_.point(v[k[0]]), m_.point(v[k[1]]), m_.point(v[k[2]]), xyz.data()) &&
                !m_.is_ghost(beyond))
                middle_in_tet(m_, beyond, pq, pb, xyz.data());
            return true;
        }
        case Crossing::kEdge: {
            mesh::Shell s;
            if (!mesh::shell(m_, c.x, c.y, c.tet, s)) return fail("edge walk: no shell");
            cavity = s.tets;
            segment_line_point(pq, pb, m_.point(c.x), m_.point(c.y), xyz.data());
            return true;
        }
        case Crossing::kVertex: return fail("an input edge runs exactly through another vertex");
        default: return fail("edge walk found no tetrahedron towards the other end");
    }
}

// Where else a point may remove crossing c, when crossing_point's cannot be
// inserted joined to q. Where the tetrahedra are thin (nearly coplanar
// points far from the origin: a CAD cylinder's fanned cap, turned in
// space), rounding can put the crossing where the insertion refuses it or
// cuts q off. Other points of the segment (the middle of its part in a
// tetrahedron of the crossing, checked exactly to lie in it) or of the
// crossed edge may fare better: on the turned cylinder, the middle of the
// segment in the tetrahedron beyond the crossed face does. Last, for a
// crossed face: where the segment passes by one of the face's edges, the
// point of the segment nearest to that edge, with the edge's shell as the
// cavity. In a flat layer (a fanned cap over the Delaunay triangulation
// of its rim, turned) the segment meets the faces of flat tetrahedra at
// grazing angles: the crossing point of such a face is ill-conditioned,
// while the in-plane edge the segment passes is what really blocks it.
std::vector<ConformingRecovery::Candidate> ConformingRecovery::other_crossing_points(
    const Crossing& c, VertexId q, VertexId b, const std::vector<TetId>& cavity) {
    const double* pq = m_.point(q);
    const double* pb = m_.point(b);
    std::vector<Candidate> out;
    Position xyz{};
    if (c.kind == Crossing::kEdge) {
        segment_crossing_on_edge(pq, pb, m_.point(c.x), m_.point(c.y), xyz.data());
        out.push_back({xyz, cavity});
    }
    std::vector<TetId> tets = cavity;
    if (c.kind == Crossing::kFace) std::reverse(tets.begin(), tets.end());  // the tetrahedron beyond the face first
    for (TetId t : tets)
        if (!m_.is_ghost(t) && middle_in_tet(m_, t, pq, pb, xyz.data())) out.push_back({xyz, cavity});
    if (c.kind == Crossing::kFace) {
        const VertexId* v = m_.vertices(c.tet);
        for (int k = 0; k < 3; ++k) {
            const VertexId x = v[kFaceVertices[c.face][k]], y = v[kFaceVertices[c.face][(k + 1) % 3]];
            if (!passes_by(pq, pb, m_.point(x), m_.point(y))) continue;
            mesh::Shell shell;
            if (!mesh::shell(m_, x, y, c.tet, shell)) continue;
            segment_line_point(pq, pb, m_.point(x), m_.point(y), xyz.data());
            out.push_back({xyz, shell.tets});
        }
    }
    return out;
}

// Inserts a point at xyz into `cavity` and keeps it when it ends up joined
// to the chain end q (an edge qp); otherwise takes it out again (its cavity
// put back as it was) and returns kGhostVertex, why() saying why.
VertexId ConformingRecovery::insert_joined(const Position& xyz, const std::vector<TetId>& cavity, VertexId q) {
    const VertexId p = insert(xyz.data(), cavity, false);
    if (p == kGhostVertex || edge_exists(q, p)) return p;
    undo_last_insertion(p);
    why_ = "an added point is not joined to the chain it extends";
    return kGhostVertex;
}

void ConformingRecovery::undo_last_insertion(VertexId p) {
    std::vector<TetId> restored;
    inserter_.undo_last(m_, p, restored);
    note_created(restored);
}

// §5.2 for the interior of a face whose edges are chains: put a point where
// a mesh edge between two vertices that do not belong to the face crosses
// it, until none does. If one does, one does in the ball of a point of the
// face (follow the cut of the face by the mesh from that crossing to the
// face's boundary: the last crossing before a point of the face shares a
// mesh face with it), so only those balls are searched.
bool ConformingRecovery::recover_interior(std::size_t face) {
    const Triangle& tri = points_.faces().triangle(face);
    // Copies: insertions grow the coordinate array.
    double A[3], B[3], C[3];
    std::copy_n(m_.point(tri[0]), 3, A);
    std::copy_n(m_.point(tri[1]), 3, B);
    std::copy_n(m_.point(tri[2]), 3, C);
    // Points whose balls are still to be searched, each queued once.
    std::vector<VertexId> work;
    std::unordered_set<VertexId> queued;
    const auto queue = [&](VertexId v) {
        if (queued.insert(v).second) work.push_back(v);
    };
    for (int k = 0; k < 3; ++k)
        for (VertexId v : points_.chain(tri[k], tri[(k + 1) % 3])) queue(v);
    std::vector<TetId> ball;
    std::size_t inserted = 0;
    while (!work.empty()) {
        const VertexId v = work.back();
        work.pop_back();
        queued.erase(v);
        if (!mesh::ball(m_, v, incident_[v], ball)) return fail("a point of the face lost its ball");
        bool found = false;
        VertexId u = 0, w = 0;
        TetId where = kNoTet;
        for (TetId t : ball) {
            if (m_.is_ghost(t)) continue;
            const VertexId* tv = m_.vertices(t);
            for (int i = 0; i < 4 && !found; ++i)
                for (int j = i + 1; j < 4 && !found; ++j) {
                    if (tv[i] == v || tv[j] == v) continue;
                    if (points_.belongs_to(tv[i], face) || points_.belongs_to(tv[j], face)) continue;
                    if (!geom::segment_crosses_triangle_interior(m_.point(tv[i]), m_.point(tv[j]), A, B, C)) continue;
                    found = true;
                    u = tv[i];
                    w = tv[j];
                    where = t;
                }
            if (found) break;
        }
        if (!found) continue;
        if (++inserted > kMaxInsertionsPerConstraint) return fail("too many points in one face");
        double xyz[3];
        segment_plane_point(m_.point(u), m_.point(w), A, B, C, xyz);
        mesh::Shell s;
        if (!mesh::shell(m_, u, w, where, s)) return fail("face cut: no shell");
        // The shell stays whole: the edge must go (a rounded point can
        // land behind a face of a thin shell tetrahedron).
        const VertexId p = insert_on_crossing(xyz, u, w, A, B, C, s.tets);
        if (p == kGhostVertex) return false;
        points_.add_face_point(p, face);
        if (edge_exists(u, w)) return fail("an intersection point did not cut the edge it was put on");
        // Balls the insertion changed: p's, and those of the points of the
        // face around it (v among them).
        queue(v);
        queue(p);
        std::vector<TetId> star;
        if (mesh::ball(m_, p, incident_[p], star))
            for (TetId t : star)
                for (int i = 0; i < 4; ++i) {
                    const VertexId x = m_.vertex(t, i);
                    if (x != kGhostVertex && x != p && points_.belongs_to(x, face)) queue(x);
                }
    }
    return true;
}

// Inserts the point where edge uw crosses the interior of face ABC,
// computed as xyz, into the edge's shell, which it must remove whole.
// Rounding can put xyz behind a face of a thin shell tetrahedron that
// cannot give way; the same crossing rounded from w's end, or a hair
// further along the edge either way (kCrossingShifts), may land on the
// right side (the turned 200-gon prism of tests/data/recover recovers with
// the point 1e-12 of the edge further towards w).
VertexId ConformingRecovery::insert_on_crossing(const double* xyz, VertexId u, VertexId w, const double* A,
                                                const double* B, const double* C, const std::vector<TetId>& shell) {
    VertexId p = insert(xyz, shell, true);
    if (p != kGhostVertex) return p;
    const std::string first_why = why_;
    const double* pu = m_.point(u);
    const double* pw = m_.point(w);
    const Position first = {xyz[0], xyz[1], xyz[2]};
    std::vector<Position> others(1);
    segment_plane_point(pw, pu, A, B, C, others[0].data());
    for (double shift : kCrossingShifts)
        others.push_back({xyz[0] + shift * (pw[0] - pu[0]), xyz[1] + shift * (pw[1] - pu[1]),
                          xyz[2] + shift * (pw[2] - pu[2])});
    for (const Position& other : others)  // the same position fails the same way: skipped
        if (other != first && (p = insert(other.data(), shell, true)) != kGhostVertex) return p;
    fail(first_why);
    return kGhostVertex;
}

// §5.2 wants each face a disk of sub-faces. A tetrahedron whose four
// vertices are points of the face (rounded points on its edges, a thin
// face) is flat, and its upper and lower faces would both be sub-faces.
// Each is removed with an edge between two of its vertices that the face
// does not need (Definition 5.8, edge removal).
bool ConformingRecovery::remove_flat_tets(std::size_t face, std::size_t& removed) {
    for (removed = 0; removed < kMaxInsertionsPerConstraint; ++removed) {
        const TetId t = find_flat_tet(face);
        if (t == kNoTet) return true;
        if (!remove_flat_tet(face, t)) return fail("a flat tetrahedron in a face could not be removed");
    }
    return fail("too many flat tetrahedra in one face");
}

// A live tetrahedron whose four vertices are points of the face, found in
// the balls of the face's points (reached from its chains), or kNoTet.
TetId ConformingRecovery::find_flat_tet(std::size_t face) {
    const Triangle& tri = points_.faces().triangle(face);
    std::vector<VertexId> work;
    for (int k = 0; k < 3; ++k)
        for (VertexId v : points_.chain(tri[k], tri[(k + 1) % 3])) work.push_back(v);
    std::unordered_set<VertexId> seen;
    std::vector<TetId> ball;
    while (!work.empty()) {
        const VertexId v = work.back();
        work.pop_back();
        if (!seen.insert(v).second || !mesh::ball(m_, v, incident_[v], ball)) continue;
        for (TetId t : ball) {
            if (m_.is_ghost(t)) continue;
            if (is_flat(t, face)) return t;
            for (int i = 0; i < 4; ++i)
                if (points_.belongs_to(m_.vertex(t, i), face)) work.push_back(m_.vertex(t, i));
        }
    }
    return kNoTet;
}

// The four vertices of finite tetrahedron t are points of the face.
bool ConformingRecovery::is_flat(TetId t, std::size_t face) const {
    for (int i = 0; i < 4; ++i)
        if (!points_.belongs_to(m_.vertex(t, i), face)) return false;
    return true;
}

// Removes flat tetrahedron t of the face by the removal of an edge ab of
// it that is no chain link, such that its two faces without ab, (s, r, a)
// and (s, r, b), lie on either side of sr within the face (they stay as
// sub-faces, side by side), and whose shell holds no sub-face of another
// input triangle (nothing else of the surface changes) unless ab is a
// shortcut of a chain. (A turned CAD part: three rounded points of the
// chain between two nearly coplanar triangles, nearly collinear, and an
// edge between the outer two that both triangles' flat tetrahedra use.)
bool ConformingRecovery::remove_flat_tet(std::size_t face, TetId t) {
    const Triangle& tri = points_.faces().triangle(face);
    // A point off the plane of the face: the side of line sr within the
    // face is the side of plane (s, r, apex), exactly.
    const double* A = m_.point(tri[0]);
    const double* B = m_.point(tri[1]);
    const double* C = m_.point(tri[2]);
    const double u1[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, u2[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
    double n[3];
    cross(u1, u2, n);
    double apex[3];
    for (int k = 0; k < 3; ++k) apex[k] = (A[k] + B[k] + C[k]) / 3 + n[k];
    const std::array<VertexId, 4> v{m_.vertex(t, 0), m_.vertex(t, 1), m_.vertex(t, 2), m_.vertex(t, 3)};
    const mesh::EdgeProtect is_link = [this](VertexId a, VertexId b) { return points_.is_chain_link(a, b); };
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            const VertexId a = v[i], b = v[j];
            if (is_link(a, b)) continue;
            VertexId s = kGhostVertex, r = kGhostVertex;
            for (int k = 0; k < 4; ++k)
                if (k != i && k != j) (s == kGhostVertex ? s : r) = v[k];
            const int side_a = geom::orient3d(m_.point(s), m_.point(r), apex, m_.point(a));
            const int side_b = geom::orient3d(m_.point(s), m_.point(r), apex, m_.point(b));
            if (side_a == 0 || side_a != -side_b) continue;
            mesh::Shell shell;
            if (!mesh::shell(m_, a, b, t, shell)) continue;
            // ab along one input edge, not a link of its chain, is a
            // shortcut past a point of the chain: no sub-face of any
            // triangle at that edge may use it (it would overlap the
            // links), so the faces at it are no loss.
            const bool shortcut = points_.on_one_edge(a, b, b);
            bool other_subface = false;
            if (!shortcut)
                for (VertexId x : shell.ring)
                    other_subface = other_subface ||
                                    (x != kGhostVertex && !points_.belongs_to(x, face) && points_.is_subface(a, b, x));
            if (other_subface) continue;
            std::vector<TetId> created;
            if (mesh::remove_edge(m_, a, b, shell, is_link, &created) != mesh::FlipResult::kDone) continue;
            note_created(created);
            return true;
        }
    return false;
}

// The face is a union of sub-faces: the mesh faces whose vertices all
// belong to it form a disk bounded by its three chains (every chain link
// on one of them, every other edge on two).
bool ConformingRecovery::disk_is_complete(std::size_t face) {
    const Triangle& tri = points_.faces().triangle(face);
    std::set<VertexId> boundary_points;
    std::set<std::pair<VertexId, VertexId>> boundary_links;
    for (int k = 0; k < 3; ++k) {
        const std::vector<VertexId> c = points_.chain(tri[k], tri[(k + 1) % 3]);
        for (std::size_t i = 0; i + 1 < c.size(); ++i)
            boundary_links.insert(std::minmax(c[i], c[i + 1]));
        boundary_points.insert(c.begin(), c.end());
    }
    std::set<std::array<VertexId, 3>> subfaces;
    std::set<VertexId> seen;
    std::vector<VertexId> work(boundary_points.begin(), boundary_points.end());
    std::vector<TetId> ball;
    while (!work.empty()) {
        const VertexId v = work.back();
        work.pop_back();
        if (!seen.insert(v).second) continue;
        if (!mesh::ball(m_, v, incident_[v], ball)) return fail("a point of the face lost its ball");
        for (TetId t : ball)
            for (int f = 0; f < 4; ++f) {
                std::array<VertexId, 3> fv{};
                bool all = true;
                for (int k = 0; k < 3; ++k) {
                    fv[k] = m_.vertex(t, kFaceVertices[f][k]);
                    all = all && fv[k] != kGhostVertex && points_.belongs_to(fv[k], face);
                }
                if (!all || (fv[0] != v && fv[1] != v && fv[2] != v)) continue;
                std::sort(fv.begin(), fv.end());
                if (!subfaces.insert(fv).second) continue;
                for (VertexId x : fv) work.push_back(x);
            }
    }
    std::map<std::pair<VertexId, VertexId>, int> uses;
    for (const auto& f : subfaces)
        for (int k = 0; k < 3; ++k) ++uses[std::minmax(f[k], f[(k + 1) % 3])];
    for (const auto& [edge, n] : uses) {
        const int expected = boundary_links.count(edge) ? 1 : 2;
        if (n != expected) return fail("the sub-faces of a face do not form a disk");
    }
    for (const auto& link : boundary_links)
        if (!uses.count(link)) return fail("a chain link bounds no sub-face");
    return true;
}

}  // namespace cbr::recover
