// Protected insertion with the cavity correction of §5.1. The cavity is
// kept in this file's own sets (no scratch marks on the mesh), so every
// failure before replace_tets leaves the mesh untouched.
//
// Why the correction terminates: a tetrahedron that leaves the cavity is
// "rejected" and never enters it again, and one enters at most once (only
// across a face coplanar with p, and only if not rejected). Every round
// that does not stop changes the state of at least one tetrahedron, so
// there are at most 2 * (slots) rounds.
//
// Why the result is valid when it stops: every boundary face is strictly
// visible from p, so every cone (face, p) is positively oriented; the
// signed cones from any point sum to the cavity's indicator, so with all
// signs positive they tile the cavity exactly (and p is interior to it).
// What is left to check is combinatorial — the cavity is one component
// and no vertex is interior to it (it would vanish) — done here, and the
// face matching, done again by replace_tets.
#include "recover/protected_insertion.hpp"

#include <array>
#include <set>
#include <unordered_set>

#include "geom/flat_cone.hpp"
#include "geom/predicates.hpp"
#include "mesh/surgery.hpp"

namespace cbr::recover {

using mesh::facet_face;
using mesh::facet_tet;
using mesh::kFaceVertices;
using mesh::kGhostVertex;
using mesh::TetId;
using mesh::TetMesh;
using mesh::VertexId;

namespace {

enum class Pass { kStable, kChanged, kStartLost };


class Cavity {
public:
    Cavity(const TetMesh& m, VertexId p, TetId start, const BlockedFace& blocked)
        : m_(m), p_(m.point(p)), pid_(p), start_(start), blocked_(blocked) {}

    // The seed's finite tetrahedra are never dropped by the correction (it
    // grows past a face p does not see instead, or gives up).
    void keep_seed() {
        for (TetId t : in_)
            if (!m_.is_ghost(t)) keep_.insert(t);
    }

    bool check_start(std::string& why) const;
    void grow();
    bool seed(const std::vector<TetId>& tets, std::string& why);
    bool correct(std::string& why);
    std::vector<TetId> tets() const { return {in_.begin(), in_.end()}; }
    std::vector<std::array<VertexId, 4>> star() const;
    std::size_t size() const { return in_.size(); }
    std::size_t removed() const { return removed_; }
    std::size_t added() const { return added_; }

private:
    struct Face {
        TetId t;
        int f;
    };
    const double* pt(VertexId v) const { return m_.point(v); }
    TetId across(TetId t, int f) const { return facet_tet(m_.neighbor(t, f)); }
    bool in(TetId t) const { return in_.count(t) != 0; }
    bool is_protected(TetId t, int f) const;
    bool can_join(TetId n) const;
    bool can_take_in(TetId t, int f, TetId n) const;
    bool nearly_flat(TetId t, int f) const;
    bool in_conflict(TetId t) const;
    int face_sign(TetId t, int f) const;
    std::vector<Face> boundary() const;
    void remove(TetId t);
    Pass correction_pass();
    bool keep_start_component();
    bool drop_interior_vertices();

    const TetMesh& m_;
    const double* p_;
    VertexId pid_;
    TetId start_;
    const BlockedFace& blocked_;
    std::set<TetId> in_;                  // ordered: deterministic star
    std::unordered_set<TetId> rejected_;  // left the cavity: never again
    std::unordered_set<TetId> keep_;      // must stay (keep_seed)
    bool kept_lost_ = false;              // a tetrahedron of keep_ was removed
    std::size_t removed_ = 0, added_ = 0;
};

bool Cavity::check_start(std::string& why) const {
    if (start_ >= m_.slot_count() || m_.is_free(start_) || m_.is_ghost(start_)) {
        why = "start is not a live finite tetrahedron";
        return false;
    }
    const VertexId* v = m_.vertices(start_);
    for (int f = 0; f < 4; ++f) {
        const int* k = kFaceVertices[f];
        if (geom::orient3d(pt(v[k[0]]), pt(v[k[1]]), pt(v[k[2]]), p_) < 0) {
            why = "start does not contain p";
            return false;
        }
        const double* q = pt(v[f]);
        if (q[0] == p_[0] && q[1] == p_[1] && q[2] == p_[2]) {
            why = "p coincides with a vertex of the mesh";
            return false;
        }
    }
    return true;
}

// A constraint face, or one the caller forbids (asked from both sides).
bool Cavity::is_protected(TetId t, int f) const {
    if (m_.is_constrained(t, f)) return true;
    if (!blocked_) return false;
    const mesh::FacetRef r = m_.neighbor(t, f);
    return blocked_(t, f) || blocked_(facet_tet(r), facet_face(r));
}

// n may enter only if no protected face would become interior.
bool Cavity::can_join(TetId n) const {
    for (int g = 0; g < 4; ++g)
        if (in(across(n, g)) && is_protected(n, g)) return false;
    return true;
}

// The Delaunay kernel's conflict test: insphere_sos for finite tetrahedra;
// for a ghost, p strictly beyond its hull face, or on its plane and inside
// the (perturbed) circumcircle.
bool Cavity::in_conflict(TetId t) const {
    const VertexId* v = m_.vertices(t);
    if (v[3] != kGhostVertex) return geom::insphere_sos(pt(v[0]), pt(v[1]), pt(v[2]), pt(v[3]), p_) > 0;
    const int side = geom::orient3d(pt(v[0]), pt(v[1]), pt(v[2]), p_);
    if (side != 0) return side > 0;
    return geom::incircle_coplanar_sos(pt(v[0]), pt(v[1]), pt(v[2]), p_) > 0;
}

// Sign of the cone (face f of t, p): > 0 when p sees the face from t's
// side (§5.1 "Det(K_j) > 0"). A ghost belongs in the cavity only when p is
// on its hull plane (p is inside the hull); then its faces through the
// infinite vertex are tested with that vertex replaced by the apex d of
// the finite tetrahedron under the hull face: plane (x, y, d) cuts the
// hull plane along xy, and d lies on the side opposite to the infinite
// vertex, hence the minus sign.
int Cavity::face_sign(TetId t, int f) const {
    const VertexId* v = m_.vertices(t);
    const int* k = kFaceVertices[f];
    if (v[3] != kGhostVertex) return geom::orient3d(pt(v[k[0]]), pt(v[k[1]]), pt(v[k[2]]), p_);
    if (geom::orient3d(pt(v[0]), pt(v[1]), pt(v[2]), p_) != 0) return -1;
    if (f == 3) return 0;
    const mesh::FacetRef under = m_.neighbor(t, 3);
    const VertexId d = m_.vertex(facet_tet(under), facet_face(under));
    VertexId w[3] = {v[k[0]], v[k[1]], v[k[2]]};
    for (VertexId& x : w)
        if (x == kGhostVertex) x = d;
    return -geom::orient3d(pt(w[0]), pt(w[1]), pt(w[2]), p_);
}

// Bowyer-Watson growth from start, never across a protected face.
void Cavity::grow() {
    std::unordered_set<TetId> seen{start_};
    std::vector<TetId> stack{start_};
    in_.insert(start_);
    while (!stack.empty()) {
        const TetId t = stack.back();
        stack.pop_back();
        for (int f = 0; f < 4; ++f) {
            const TetId n = across(t, f);
            // can_join only gets stricter as the cavity grows: one test each.
            if (is_protected(t, f) || !seen.insert(n).second) continue;
            if (in_conflict(n) && can_join(n)) {
                in_.insert(n);
                stack.push_back(n);
            }
        }
    }
}

bool Cavity::seed(const std::vector<TetId>& tets, std::string& why) {
    for (TetId t : tets) {
        if (t >= m_.slot_count() || m_.is_free(t) || !in_.insert(t).second) {
            why = "initial cavity: a tetrahedron is not live or is listed twice";
            return false;
        }
    }
    if (!in(start_)) {
        why = "initial cavity does not contain start";
        return false;
    }
    for (TetId t : in_)
        for (int f = 0; f < 4; ++f)
            if (in(across(t, f)) && is_protected(t, f)) {
                why = "initial cavity contains a protected face";
                return false;
            }
    return true;
}

std::vector<Cavity::Face> Cavity::boundary() const {
    std::vector<Face> out;
    for (TetId t : in_)
        for (int f = 0; f < 4; ++f)
            if (!in(across(t, f))) out.push_back({t, f});
    return out;
}

void Cavity::remove(TetId t) {
    if (keep_.count(t)) kept_lost_ = true;
    in_.erase(t);
    rejected_.insert(t);
    ++removed_;
}

// One sweep of §5.1 step 2 over the boundary faces: Det > 0 keep; Det < 0
// drop the cavity tetrahedron; Det = 0 — or a cone flat to within rounding
// (nearly_flat), whatever its sign — take in the one beyond (unless the
// face is protected, or that tetrahedron was rejected or would enclose a
// protected face: then keep the face if Det > 0, else drop the cavity
// tetrahedron).
Pass Cavity::correction_pass() {
    bool changed = false;
    for (const Face& b : boundary()) {
        const TetId n = across(b.t, b.f);
        if (!in(b.t) || in(n)) continue;  // changed earlier in this sweep
        const int s = face_sign(b.t, b.f);
        // Coplanar, or flat to within rounding (either sign): take in the
        // tetrahedron beyond if it may join; else a visible face stays.
        const bool flat = s == 0 || nearly_flat(b.t, b.f);
        if (s > 0 && !flat) continue;
        if (flat && can_take_in(b.t, b.f, n)) {
            in_.insert(n);
            ++added_;
            changed = true;
            continue;
        }
        if (s > 0) continue;
        changed = true;
        if (b.t == start_) return Pass::kStartLost;
        if (keep_.count(b.t) && can_take_in(b.t, b.f, n)) {
            // p is behind a face of a tetrahedron that must stay (only
            // rounding puts it there: the seed is the crossing p splits):
            // take in the one beyond instead. (If it cannot join, remove()
            // records the loss and correct() gives up.)
            in_.insert(n);
            ++added_;
            continue;
        }
        remove(b.t);
    }
    return changed ? Pass::kChanged : Pass::kStable;
}

bool Cavity::can_take_in(TetId t, int f, TetId n) const {
    return !is_protected(t, f) && rejected_.count(n) == 0 && can_join(n);
}

// A computed point (an intersection point, rounded) that should lie on the
// plane of a face can land a rounding error off it: the cone would be a
// sliver flat to within rounding, positive only by chance, which later
// steps cannot work with (no point sees past it). Such a face is treated
// like a coplanar one (geom/flat_cone.hpp).
bool Cavity::nearly_flat(TetId t, int f) const {
    const VertexId* v = m_.vertices(t);
    if (v[3] == kGhostVertex) return false;
    const int* k = kFaceVertices[f];
    return geom::flat_cone(pt(v[k[0]]), pt(v[k[1]]), pt(v[k[2]]), p_);
}

// Keeps the face-connected component of start (through unprotected faces,
// the only ones a cavity contains); true when something was dropped.
bool Cavity::keep_start_component() {
    std::unordered_set<TetId> reached{start_};
    std::vector<TetId> stack{start_};
    while (!stack.empty()) {
        const TetId t = stack.back();
        stack.pop_back();
        for (int f = 0; f < 4; ++f) {
            const TetId n = across(t, f);
            if (in(n) && reached.insert(n).second) stack.push_back(n);
        }
    }
    if (reached.size() == in_.size()) return false;
    for (TetId t : tets())
        if (reached.count(t) == 0) remove(t);
    return true;
}

// A vertex of the cavity on no boundary face would vanish from the mesh:
// drop its cavity tetrahedra other than start (start's faces through it
// then become boundary faces). True when something was dropped.
bool Cavity::drop_interior_vertices() {
    std::unordered_set<VertexId> on_boundary;
    for (const Face& b : boundary())
        for (int i = 0; i < 3; ++i) on_boundary.insert(m_.vertex(b.t, kFaceVertices[b.f][i]));
    std::unordered_set<VertexId> lost;
    for (TetId t : in_)
        for (int i = 0; i < 4; ++i)
            if (on_boundary.count(m_.vertex(t, i)) == 0) lost.insert(m_.vertex(t, i));
    if (lost.empty()) return false;
    for (TetId t : tets()) {
        if (t == start_) continue;
        for (int i = 0; i < 4; ++i)
            if (lost.count(m_.vertex(t, i)) != 0) {
                remove(t);
                break;
            }
    }
    return true;
}

// §5.1 step 3: repeat until a sweep changes nothing; then the structural
// checks, which may start another round.
bool Cavity::correct(std::string& why) {
    for (;;) {
        const Pass r = correction_pass();
        if (r == Pass::kStartLost) {
            why = "cavity correction would remove the start tetrahedron (p on a protected face, or not "
                  "visible enough within the protected region)";
            return false;
        }
        const bool split = keep_start_component();
        if (kept_lost_) {
            why = "cavity correction would remove a tetrahedron of the crossing the point splits";
            return false;
        }
        if (r == Pass::kChanged || split) continue;
        if (!drop_interior_vertices()) return true;
    }
}

// Each boundary face coned to p: the cavity tetrahedron with p in place of
// the vertex opposite the face (same side, so the orientation is kept).
std::vector<std::array<VertexId, 4>> Cavity::star() const {
    std::vector<std::array<VertexId, 4>> fresh;
    for (const Face& b : boundary()) {
        const VertexId* v = m_.vertices(b.t);
        std::array<VertexId, 4> s = {v[0], v[1], v[2], v[3]};
        s[static_cast<std::size_t>(b.f)] = pid_;
        fresh.push_back(s);
    }
    return fresh;
}

ProtectedInsertResult run(TetMesh& m, VertexId p, TetId start, const BlockedFace& blocked,
                          const std::vector<TetId>* seed, bool keep_seed) {
    ProtectedInsertResult res;
    if (p >= m.vertex_count()) {
        res.why = "p is not a vertex of the mesh's coordinates";
        return res;
    }
    Cavity c(m, p, start, blocked);
    if (!c.check_start(res.why)) return res;
    if (seed == nullptr) c.grow();
    else if (!c.seed(*seed, res.why)) return res;
    if (seed != nullptr && keep_seed) c.keep_seed();
    res.initial_cavity = c.size();
    const bool corrected = c.correct(res.why);
    res.removed = c.removed();
    res.added = c.added();
    if (!corrected) return res;
    const mesh::ReplaceResult r = mesh::replace_tets(m, c.tets(), c.star(), &res.created);
    if (r != mesh::ReplaceResult::kDone) {
        res.why = std::string("replace_tets refused the star: ") + mesh::to_string(r);
        res.created.clear();
        return res;
    }
    res.ok = true;
    return res;
}

}  // namespace

ProtectedInsertResult insert_protected(TetMesh& m, VertexId p, TetId start, const BlockedFace& blocked) {
    return run(m, p, start, blocked, nullptr, false);
}

ProtectedInsertResult insert_protected_in_cavity(TetMesh& m, VertexId p, TetId start,
                                                 const std::vector<TetId>& cavity, const BlockedFace& blocked,
                                                 bool keep_seed) {
    return run(m, p, start, blocked, &cavity, keep_seed);
}

}  // namespace cbr::recover
