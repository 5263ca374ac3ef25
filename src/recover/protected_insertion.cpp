// Protected insertion with the cavity correction of §5.1. The cavity is
// kept in the inserter's own marks and lists (no scratch marks on the
// mesh), so every failure before replace_tets leaves the mesh untouched.
//
// The cavity's state is one mark byte per slot (SlotMarks: cleared in O(1)
// per insertion) and the list of its members in the order they joined.
// Whatever depends on the order — the sweeps of the correction, the star
// and so the ids of the new tetrahedra — walks the members sorted by id
// (sorted_members), the order an ordered set of ids would give.
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
// face matching, done again when the star replaces the cavity
// (mesh::ConeReplacer: the checks of replace_tets).
#include "recover/protected_insertion.hpp"

#include <algorithm>
#include <array>

#include "geom/flat_cone.hpp"
#include "geom/predicates.hpp"
#include "mesh/errors.hpp"
#include "mesh/slot_marks.hpp"
#include "mesh/slot_pool.hpp"
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

// A face of the cavity: face f of its member t.
struct CavityFace {
    TetId t;
    int f;
    // boundary()'s order: member id, then face.
    bool operator<(const CavityFace& o) const { return t != o.t ? t < o.t : f < o.f; }
    bool operator==(const CavityFace& o) const { return t == o.t && f == o.f; }
};

}  // namespace

// What an inserter keeps from one insertion to the next (all of it is
// reset per insertion; only the allocations are kept).
struct ProtectedInserter::Scratch {
    mesh::SlotMarks tet_marks;      // per slot: the cavity's state (Cavity::kIn, ...)
    mesh::SlotMarks reached;        // per slot: keep_start_component's search
    mesh::SlotMarks vertex_marks;   // per vertex: drop_interior_vertices
    std::vector<TetId> members;     // cavity tetrahedra; may still list removed ones
    std::vector<TetId> stack;       // depth-first searches
    std::vector<CavityFace> faces;  // boundary()
    std::vector<CavityFace> to_sweep, next_sweep;  // correction_pass()
    mesh::ConeReplacer star;        // replaces the cavity by the star of p
    ProtectedInsertResult result;
    bool full_rounds = false;  // set_full_rounds
};

namespace {

enum class Pass { kStable, kChanged, kStartLost };

class Cavity {
public:
    Cavity(const TetMesh& m, VertexId p, TetId start, const BlockedFace& blocked, ProtectedInserter::Scratch& s)
        : m_(m), p_(m.point(p)), start_(start), blocked_(blocked), s_(s) {
        s_.tet_marks.new_round(m.slot_count());
        s_.members.clear();
    }

    // The seed's finite tetrahedra are never dropped by the correction (it
    // grows past a face p does not see instead, or gives up).
    void keep_seed() {
        for (TetId t : s_.members)
            if (!m_.is_ghost(t)) s_.tet_marks.set(t, kKeep);
    }

    bool check_start(std::string& why) const;
    void grow();
    bool seed(const std::vector<TetId>& tets, std::string& why);
    bool correct(std::string& why);
    // The members, sorted by id.
    const std::vector<TetId>& tets() { return sorted_members(); }
    std::size_t size() const { return count_; }
    std::size_t removed() const { return removed_; }
    std::size_t added() const { return added_; }
    // The faces between a member and a tetrahedron outside (the star's
    // faces), in the order of the members' ids.
    const std::vector<CavityFace>& boundary();

private:
    // A slot's marks (s_.tet_marks), for the current insertion.
    static constexpr std::uint8_t kIn = 1u << 0;        // in the cavity
    static constexpr std::uint8_t kRejected = 1u << 1;  // left the cavity: never again
    static constexpr std::uint8_t kKeep = 1u << 2;      // must stay (keep_seed)
    static constexpr std::uint8_t kSeen = 1u << 3;      // tested by grow()

    const double* pt(VertexId v) const { return m_.point(v); }
    TetId across(TetId t, int f) const { return facet_tet(m_.neighbor(t, f)); }
    bool in(TetId t) const { return s_.tet_marks.has(t, kIn); }
    void add(TetId t);
    const std::vector<TetId>& sorted_members();
    bool is_protected(TetId t, int f) const;
    bool can_join(TetId n) const;
    bool can_take_in(TetId t, int f, TetId n) const;
    bool nearly_flat(TetId t, int f) const;
    bool in_conflict(TetId t) const;
    int face_sign(TetId t, int f) const;
    void note_new_boundary_of_added(TetId n);
    void note_new_boundary_of_removed(TetId t);
    void remove(TetId t);
    Pass correction_pass();
    bool keep_start_component();
    bool drop_interior_vertices();
    std::size_t vertex_slot(VertexId v) const { return v == kGhostVertex ? m_.vertex_count() : v; }

    const TetMesh& m_;
    const double* p_;
    TetId start_;
    const BlockedFace& blocked_;
    ProtectedInserter::Scratch& s_;
    std::size_t count_ = 0;  // members in the cavity now
    bool sorted_ = true;     // s_.members lists exactly the members, by id
    bool kept_lost_ = false;  // a tetrahedron marked kKeep was removed
    // correct() is running: boundary faces that a change makes go to the
    // next sweep (s_.next_sweep).
    bool sweeping_ = false;
    std::size_t removed_ = 0, added_ = 0;
    // removed_ when keep_start_component last ran (none yet: the seed may
    // be in pieces).
    std::size_t removed_at_component_check_ = static_cast<std::size_t>(-1);
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
        if (geom::same_point(pt(v[f]), p_)) {
            why = "p coincides with a vertex of the mesh";
            return false;
        }
    }
    return true;
}

// t (not a member, never rejected) joins the cavity.
void Cavity::add(TetId t) {
    s_.tet_marks.set(t, kIn);
    s_.members.push_back(t);
    ++count_;
    sorted_ = false;
    if (sweeping_) note_new_boundary_of_added(t);
}

// The faces of t that now bound the cavity (t just joined).
void Cavity::note_new_boundary_of_added(TetId t) {
    for (int f = 0; f < 4; ++f)
        if (!in(across(t, f))) s_.next_sweep.push_back({t, f});
}

// The members' faces toward t (t just left).
void Cavity::note_new_boundary_of_removed(TetId t) {
    for (int f = 0; f < 4; ++f) {
        const mesh::FacetRef r = m_.neighbor(t, f);
        if (in(facet_tet(r))) s_.next_sweep.push_back({facet_tet(r), facet_face(r)});
    }
}

// Drops the removed tetrahedra from the list and sorts it: the order in
// which the correction sweeps the boundary and the star is listed.
const std::vector<TetId>& Cavity::sorted_members() {
    if (!sorted_) {
        std::vector<TetId>& list = s_.members;
        list.erase(std::remove_if(list.begin(), list.end(), [this](TetId t) { return !in(t); }), list.end());
        std::sort(list.begin(), list.end());
        sorted_ = true;
    }
    return s_.members;
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
    std::vector<TetId>& stack = s_.stack;
    stack.assign(1, start_);
    s_.tet_marks.set(start_, kSeen);
    add(start_);
    while (!stack.empty()) {
        const TetId t = stack.back();
        stack.pop_back();
        for (int f = 0; f < 4; ++f) {
            const TetId n = across(t, f);
            // can_join only gets stricter as the cavity grows: one test each.
            if (is_protected(t, f) || s_.tet_marks.has(n, kSeen)) continue;
            s_.tet_marks.set(n, kSeen);
            if (in_conflict(n) && can_join(n)) {
                add(n);
                stack.push_back(n);
            }
        }
    }
}

bool Cavity::seed(const std::vector<TetId>& tets, std::string& why) {
    for (TetId t : tets) {
        if (t >= m_.slot_count() || m_.is_free(t) || in(t)) {
            why = "initial cavity: a tetrahedron is not live or is listed twice";
            return false;
        }
        add(t);
    }
    if (!in(start_)) {
        why = "initial cavity does not contain start";
        return false;
    }
    for (TetId t : s_.members)
        for (int f = 0; f < 4; ++f)
            if (in(across(t, f)) && is_protected(t, f)) {
                why = "initial cavity contains a protected face";
                return false;
            }
    return true;
}

// The faces of the members whose other side is not a member, by member id
// then face.
const std::vector<CavityFace>& Cavity::boundary() {
    std::vector<CavityFace>& out = s_.faces;
    out.clear();
    for (TetId t : sorted_members())
        for (int f = 0; f < 4; ++f)
            if (!in(across(t, f))) out.push_back({t, f});
    return out;
}

// t leaves the cavity for good (its id stays in s_.members until the next
// sorted_members()).
void Cavity::remove(TetId t) {
    if (s_.tet_marks.has(t, kKeep)) kept_lost_ = true;
    s_.tet_marks.clear(t, kIn);
    s_.tet_marks.set(t, kRejected);
    --count_;
    sorted_ = false;
    ++removed_;
    if (sweeping_) note_new_boundary_of_removed(t);
}

// One sweep of §5.1 step 2 over the boundary faces: Det > 0 keep; Det < 0
// drop the cavity tetrahedron; Det = 0 — or a cone flat to within rounding
// (nearly_flat), whatever its sign — take in the one beyond (unless the
// face is protected, or that tetrahedron was rejected or would enclose a
// protected face: then keep the face if Det > 0, else drop the cavity
// tetrahedron).
//
// A sweep acts on the boundary as it was when the sweep began, face by
// face in the order of boundary() (member id, then face). A face that p
// sees and that is not flat is kept, and stays kept as long as it bounds
// the cavity (its sign is the same every time), so a sweep only needs the
// other faces: those that became boundary faces since the last sweep
// (add and remove note them) and the flat visible ones that could not take
// in the tetrahedron beyond (that may change as the cavity shrinks). The
// first sweep takes the whole boundary. Same decisions in the same order
// as sweeping the whole boundary each time: on a nearly cospherical
// surface every point's Delaunay cavity is most of the mesh (a fanned
// cylinder: 7,000 tetrahedra, 35-50 sweeps), and each sweep sorted it.
Pass Cavity::correction_pass() {
    std::vector<CavityFace>& faces = s_.to_sweep;
    if (!sweeping_ || s_.full_rounds) {
        boundary();
        faces.swap(s_.faces);
        sweeping_ = true;
    } else {
        faces.swap(s_.next_sweep);
        std::sort(faces.begin(), faces.end());
        faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    }
    s_.next_sweep.clear();
    bool changed = false;
    for (const CavityFace& b : faces) {
        const TetId n = across(b.t, b.f);
        if (!in(b.t) || in(n)) continue;  // not a boundary face (now)
        const int s = face_sign(b.t, b.f);
        // Coplanar, or flat to within rounding (either sign): take in the
        // tetrahedron beyond if it may join; else a visible face stays.
        const bool flat = s == 0 || nearly_flat(b.t, b.f);
        if (s > 0 && !flat) continue;
        if (flat && can_take_in(b.t, b.f, n)) {
            add(n);
            ++added_;
            changed = true;
            continue;
        }
        if (s > 0) {
            s_.next_sweep.push_back(b);  // flat and visible: may take in n later
            continue;
        }
        changed = true;
        if (b.t == start_) return Pass::kStartLost;
        if (s_.tet_marks.has(b.t, kKeep) && can_take_in(b.t, b.f, n)) {
            // p is behind a face of a tetrahedron that must stay (only
            // rounding puts it there: the seed is the crossing p splits):
            // take in the one beyond instead. (If it cannot join, remove()
            // records the loss and correct() gives up.)
            add(n);
            ++added_;
            continue;
        }
        remove(b.t);
    }
    return changed ? Pass::kChanged : Pass::kStable;
}

bool Cavity::can_take_in(TetId t, int f, TetId n) const {
    return !is_protected(t, f) && !s_.tet_marks.has(n, kRejected) && can_join(n);
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
    // Tetrahedra that joined since the last check each joined across a
    // face of a member: only a removal can split the cavity.
    if (removed_ == removed_at_component_check_ && !s_.full_rounds) return false;
    mesh::SlotMarks& reached = s_.reached;
    constexpr std::uint8_t kReached = 1;
    reached.new_round(m_.slot_count());
    reached.set(start_, kReached);
    std::size_t count = 1;
    std::vector<TetId>& stack = s_.stack;
    stack.assign(1, start_);
    while (!stack.empty()) {
        const TetId t = stack.back();
        stack.pop_back();
        for (int f = 0; f < 4; ++f) {
            const TetId n = across(t, f);
            if (!in(n) || reached.has(n, kReached)) continue;
            reached.set(n, kReached);
            ++count;
            stack.push_back(n);
        }
    }
    if (count == count_) {
        removed_at_component_check_ = removed_;
        return false;
    }
    for (TetId t : s_.members)  // remove() leaves the list as it is
        if (in(t) && !reached.has(t, kReached)) remove(t);
    removed_at_component_check_ = removed_;
    return true;
}

// A vertex of the cavity on no boundary face would vanish from the mesh:
// drop its cavity tetrahedra other than start (start's faces through it
// then become boundary faces). True when something was dropped.
bool Cavity::drop_interior_vertices() {
    mesh::SlotMarks& marks = s_.vertex_marks;
    constexpr std::uint8_t kOnBoundary = 1u << 0;
    constexpr std::uint8_t kLost = 1u << 1;
    marks.new_round(m_.vertex_count() + 1);  // + 1: the infinite vertex (vertex_slot)
    for (const CavityFace& b : boundary())
        for (int i = 0; i < 3; ++i) marks.set(vertex_slot(m_.vertex(b.t, kFaceVertices[b.f][i])), kOnBoundary);
    bool any_lost = false;
    for (TetId t : s_.members) {  // exactly the members: boundary() sorted them
        for (int i = 0; i < 4; ++i) {
            const std::size_t v = vertex_slot(m_.vertex(t, i));
            if (!marks.has(v, kOnBoundary)) {
                marks.set(v, kLost);
                any_lost = true;
            }
        }
    }
    if (!any_lost) return false;
    for (TetId t : s_.members) {  // remove() leaves the list as it is
        if (t == start_ || !in(t)) continue;
        for (int i = 0; i < 4; ++i)
            if (marks.has(vertex_slot(m_.vertex(t, i)), kLost)) {
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

}  // namespace

ProtectedInserter::ProtectedInserter() : scratch_(std::make_unique<Scratch>()) {
    // The star is built right after the cavity is marked, on the same slots.
    scratch_->star.share_marks(&scratch_->tet_marks);
}
ProtectedInserter::~ProtectedInserter() = default;

const ProtectedInsertResult& ProtectedInserter::run(TetMesh& m, VertexId p, TetId start, const BlockedFace& blocked,
                                                    const std::vector<TetId>* seed, bool keep_seed) {
    ProtectedInsertResult& res = scratch_->result;
    res.ok = false;
    res.why.clear();
    res.created.clear();
    res.cavity.clear();
    res.initial_cavity = res.removed = res.added = 0;
    if (p >= m.vertex_count()) {
        res.why = "p is not a vertex of the mesh's coordinates";
        return res;
    }
    Cavity c(m, p, start, blocked, *scratch_);
    if (!c.check_start(res.why)) return res;
    if (seed == nullptr) c.grow();
    else if (!c.seed(*seed, res.why)) return res;
    if (seed != nullptr && keep_seed) c.keep_seed();
    res.initial_cavity = c.size();
    const bool corrected = c.correct(res.why);
    res.removed = c.removed();
    res.added = c.added();
    if (!corrected) return res;
    // On a thread with a slot pool (mesh/slot_pool.hpp), the star must fit
    // in the cavity's slots and the pool's: an empty pool throws halfway
    // through a replacement.
    if (const mesh::SlotPool* pool = mesh::SlotPool::in_use(m)) {
        if (c.boundary().size() > c.size() + pool->size()) {
            res.why = "the thread's slot pool cannot hold the star";
            return res;
        }
    }
    // The star of p: each boundary face coned to p, i.e. its cavity
    // tetrahedron with p in place of the vertex opposite the face (same
    // side, so the orientation is kept), listed by tetrahedron (sorted
    // ids) then face.
    res.cavity.clear();
    for (TetId t : c.tets()) res.cavity.push_back({m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)});
    const mesh::ReplaceResult r = scratch_->star.replace(m, c.tets(), p, &res.created);
    if (r != mesh::ReplaceResult::kDone) {
        res.why = std::string("replace_tets refused the star: ") + mesh::to_string(r);
        res.created.clear();
        return res;
    }
    res.ok = true;
    return res;
}

void ProtectedInserter::set_full_rounds(bool full) { scratch_->full_rounds = full; }

mesh::SlotMarks& ProtectedInserter::shared_marks() { return scratch_->tet_marks; }

const ProtectedInsertResult& ProtectedInserter::last() const { return scratch_->result; }

bool ProtectedInserter::undo_last(TetMesh& m, VertexId p, std::vector<TetId>& restored) {
    const ProtectedInsertResult& r = scratch_->result;
    if (!r.ok || std::size_t{p} + 1 != m.vertex_count() || !scratch_->star.restore_last(m, r.created, &restored))
        throw InternalError("protected insertion: the cavity of an undone point could not be put back");
    m.truncate_vertices(p);
    return r.created.size() >= r.cavity.size();
}

const ProtectedInsertResult& ProtectedInserter::insert(TetMesh& m, VertexId p, TetId start,
                                                       const BlockedFace& blocked) {
    return run(m, p, start, blocked, nullptr, false);
}

const ProtectedInsertResult& ProtectedInserter::insert_in_cavity(TetMesh& m, VertexId p, TetId start,
                                                                 const std::vector<TetId>& cavity,
                                                                 const BlockedFace& blocked, bool keep_seed) {
    return run(m, p, start, blocked, &cavity, keep_seed);
}

ProtectedInsertResult insert_protected(TetMesh& m, VertexId p, TetId start, const BlockedFace& blocked) {
    return ProtectedInserter().insert(m, p, start, blocked);
}

ProtectedInsertResult insert_protected_in_cavity(TetMesh& m, VertexId p, TetId start,
                                                 const std::vector<TetId>& cavity, const BlockedFace& blocked,
                                                 bool keep_seed) {
    return ProtectedInserter().insert_in_cavity(m, p, start, cavity, blocked, keep_seed);
}

}  // namespace cbr::recover
