#include "mesh/surgery.hpp"

#include <algorithm>
#include <cstdint>

#include "geom/plane_side.hpp"
#include "geom/predicates.hpp"
#include "mesh/key_table.hpp"
#include "mesh/slot_marks.hpp"

namespace cbr::mesh {
namespace {

using Tet = std::array<VertexId, 4>;

enum FaceKind : std::uint8_t { kFreshFace = 0, kBoundaryFace = 1, kConstraintFace = 2 };

// One face of the region, keyed by its sorted vertex ids. Its orientation
// is the parity of the permutation that sorts the vertices as listed by
// kFaceVertices (normal into the tetrahedron that lists it): a boundary
// face of `old` and the fresh face replacing it both point into the region
// (same parity); two fresh tetrahedra sharing a face list it with
// opposite normals (opposite parity).
struct FaceEntry {
    std::array<VertexId, 3> key;
    std::uint64_t head, tail;  // the sorted key packed (key[0]; key[1], key[2]): fast to compare
    FacetRef ref;         // fresh: 4 * (index in fresh) + face; boundary: the outside half-facet
    std::uint8_t kind;    // FaceKind
    std::uint8_t parity;  // 1 when the sorting permutation is odd
    std::uint8_t marked;  // boundary: the old face's constraint mark
};

// By vertex set only: a group's entries may come in any order (connect_group
// does not depend on it), so nothing finer is worth comparing.
bool entry_less(const FaceEntry& a, const FaceEntry& b) {
    return a.head != b.head ? a.head < b.head : a.tail < b.tail;
}

std::uint8_t sort3(std::array<VertexId, 3>& k) {
    std::uint8_t odd = 0;
    if (k[0] > k[1]) { std::swap(k[0], k[1]); odd ^= 1; }
    if (k[1] > k[2]) { std::swap(k[1], k[2]); odd ^= 1; }
    if (k[0] > k[1]) { std::swap(k[0], k[1]); odd ^= 1; }
    return odd;
}

FaceEntry make_entry(const VertexId* v, int f, FaceKind kind, FacetRef ref, bool marked) {
    FaceEntry e;
    e.key = {v[kFaceVertices[f][0]], v[kFaceVertices[f][1]], v[kFaceVertices[f][2]]};
    e.parity = sort3(e.key);
    e.head = e.key[0];
    e.tail = (std::uint64_t{e.key[1]} << 32) | e.key[2];
    e.ref = ref;
    e.kind = kind;
    e.marked = marked ? 1 : 0;
    return e;
}

// The checked fresh set and how its faces connect.
struct Plan {
    std::vector<Tet> tets;              // ghosts with kGhostVertex at position 3
    std::vector<FacetRef> partner;      // per fresh half-facet 4j+f: see `outside`
    std::vector<std::uint8_t> outside;  // 1: partner is an outside half-facet; 0: fresh 4k+g
    std::vector<std::uint8_t> marks;    // per fresh tetrahedron: bit f = face f constrained
};

bool valid_old(const TetMesh& m, const std::vector<TetId>& old, std::vector<TetId>& sorted) {
    if (old.empty()) return false;
    sorted = old;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
    for (TetId t : sorted)
        if (t >= m.slot_count() || m.is_free(t)) return false;
    return true;
}

bool is_old(const std::vector<TetId>& sorted, TetId t) {
    return std::binary_search(sorted.begin(), sorted.end(), t);
}

// Moves the ghost vertex at position `ghost` (0..2) to position 3 by an
// even permutation (two transpositions), which keeps the orientation.
void move_ghost_last(Tet& t, int ghost) {
    std::swap(t[static_cast<std::size_t>(ghost)], t[3]);
    std::swap(t[static_cast<std::size_t>((ghost + 1) % 3)], t[static_cast<std::size_t>((ghost + 2) % 3)]);
}

// Checks ids and moves kGhostVertex to position 3 (move_ghost_last).
bool normalise_fresh(const TetMesh& m, const std::vector<Tet>& fresh, std::vector<Tet>& out) {
    if (fresh.empty()) return false;
    out = fresh;
    for (Tet& t : out) {
        int ghost = -1;
        for (int i = 0; i < 4; ++i) {
            if (t[i] == kGhostVertex) {
                if (ghost >= 0) return false;
                ghost = i;
            } else if (t[i] >= m.vertex_count()) {
                return false;
            }
            for (int j = 0; j < i; ++j)
                if (t[j] == t[i]) return false;
        }
        if (ghost >= 0 && ghost != 3) move_ghost_last(t, ghost);
    }
    return true;
}

// The boundary faces of `old`, its interior constraint faces (listed from
// both sides) and every face of `fresh`.
std::vector<FaceEntry> collect_faces(const TetMesh& m, const std::vector<TetId>& old,
                                     const std::vector<TetId>& sorted_old, const std::vector<Tet>& fresh) {
    std::vector<FaceEntry> faces;
    faces.reserve(4 * (old.size() + fresh.size()));
    for (TetId t : old) {
        for (int f = 0; f < 4; ++f) {
            const FacetRef out = m.neighbor(t, f);
            if (!is_old(sorted_old, facet_tet(out)))
                faces.push_back(make_entry(m.vertices(t), f, kBoundaryFace, out, m.is_constrained(t, f)));
            else if (m.is_constrained(t, f))
                faces.push_back(make_entry(m.vertices(t), f, kConstraintFace, 0, true));
        }
    }
    for (std::size_t j = 0; j < fresh.size(); ++j)
        for (int f = 0; f < 4; ++f)
            faces.push_back(make_entry(fresh[j].data(), f, kFreshFace, make_facet(static_cast<TetId>(j), f), false));
    return faces;
}

void set_partner(Plan& plan, FacetRef mine, FacetRef other, bool outside, bool marked) {
    plan.partner[mine] = other;
    plan.outside[mine] = outside ? 1 : 0;
    if (marked) plan.marks[facet_tet(mine)] |= static_cast<std::uint8_t>(1u << facet_face(mine));
}

// One group of entries with the same vertex set, in any order (the verdict
// and the links only count and pair them). Valid groups: one boundary face
// and one fresh face of the same orientation, or two fresh faces of
// opposite ones.
ReplaceResult connect_group(const FaceEntry* begin, const FaceEntry* end, Plan& plan) {
    const FaceEntry* fresh[2] = {nullptr, nullptr};
    int n_fresh = 0;
    const FaceEntry* boundary = nullptr;
    bool constraint = false;
    for (const FaceEntry* e = begin; e != end; ++e) {
        if (e->kind == kFreshFace) {
            if (n_fresh == 2) return ReplaceResult::kNotTiling;
            fresh[n_fresh++] = e;
        } else if (e->kind == kBoundaryFace) {
            if (boundary) return ReplaceResult::kNotTiling;
            boundary = e;
        } else {
            constraint = true;
        }
    }
    if (boundary) {
        if (n_fresh != 1 || fresh[0]->parity != boundary->parity) return ReplaceResult::kNotTiling;
        set_partner(plan, fresh[0]->ref, boundary->ref, true, boundary->marked != 0);
        return ReplaceResult::kDone;
    }
    if (n_fresh == 2) {
        if (fresh[0]->parity == fresh[1]->parity) return ReplaceResult::kNotTiling;
        set_partner(plan, fresh[0]->ref, fresh[1]->ref, false, constraint);
        set_partner(plan, fresh[1]->ref, fresh[0]->ref, false, constraint);
        return ReplaceResult::kDone;
    }
    // One unshared fresh face inside the region, or a constraint face of
    // `old` that no fresh tetrahedron has.
    return n_fresh == 1 ? ReplaceResult::kNotTiling : ReplaceResult::kRemovesConstraint;
}

// Sorts the faces, checks the tiling and the constraints, fills the links.
ReplaceResult match_faces(std::vector<FaceEntry>& faces, Plan& plan) {
    std::sort(faces.begin(), faces.end(), entry_less);
    plan.partner.assign(4 * plan.tets.size(), 0);
    plan.outside.assign(4 * plan.tets.size(), 0);
    plan.marks.assign(plan.tets.size(), 0);
    bool removes_constraint = false;
    for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j].head == faces[i].head && faces[j].tail == faces[i].tail) ++j;
        const ReplaceResult r = connect_group(&faces[i], &faces[0] + j, plan);
        if (r == ReplaceResult::kNotTiling) return r;
        removes_constraint |= r == ReplaceResult::kRemovesConstraint;
        i = j;
    }
    return removes_constraint ? ReplaceResult::kRemovesConstraint : ReplaceResult::kDone;
}

int orient(const TetMesh& m, VertexId a, VertexId b, VertexId c, VertexId d) {
    return geom::orient3d(m.point(a), m.point(b), m.point(c), m.point(d));
}

bool positively_oriented(const TetMesh& m, const std::vector<Tet>& tets) {
    for (const Tet& t : tets)
        if (t[3] != kGhostVertex && orient(m, t[0], t[1], t[2], t[3]) <= 0) return false;
    return true;
}

// The finite vertices of `old`, each once.
std::vector<VertexId> finite_vertices(const TetMesh& m, const std::vector<TetId>& old) {
    std::vector<VertexId> v;
    v.reserve(4 * old.size());
    for (TetId t : old)
        for (int i = 0; i < 4; ++i)
            if (m.vertex(t, i) != kGhostVertex) v.push_back(m.vertex(t, i));
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
}

// The vertex opposite the face that fresh half-facet `half` shares with its
// partner (fresh or outside).
VertexId far_vertex(const TetMesh& m, const Plan& plan, std::size_t half) {
    const FacetRef r = plan.partner[half];
    return plan.outside[half] ? m.vertex(facet_tet(r), facet_face(r)) : plan.tets[facet_tet(r)][facet_face(r)];
}

// x is on the finite side of (or on) the hull face of ghost g. A vertex of
// the face is on it: answered without orient3d, whose filter cannot decide
// a degenerate tetrahedron and would run the exact stage.
bool inside_hull_face(const TetMesh& m, const Tet& g, VertexId x) {
    if (x == g[0] || x == g[1] || x == g[2]) return true;
    return x != kGhostVertex && orient(m, g[0], g[1], g[2], x) <= 0;
}

// inside_hull_face for every finite vertex in `region`, the face's plane
// set up once for the exact stage (PlaneSide).
bool region_inside_hull_face(const TetMesh& m, const Tet& g, const std::vector<VertexId>& region) {
    geom::PlaneSide side(m.point(g[0]), m.point(g[1]), m.point(g[2]));
    for (VertexId x : region) {
        if (x == g[0] || x == g[1] || x == g[2]) continue;  // on the face (see inside_hull_face)
        if (side(m.point(x)) > 0) return false;
    }
    return true;
}

// The convexity rule for fresh ghosts (see surgery.hpp). Hull edges
// between two unchanged ghosts are not touched; every hull edge of a fresh
// ghost is checked from that ghost. The region's vertices are tested
// against every fresh hull face: G * V orientation tests for G fresh
// ghosts, which only regions at the hull have, and few (a flip: at most 4).
bool hull_stays_convex(const TetMesh& m, const std::vector<TetId>& old, const Plan& plan) {
    std::vector<VertexId> region;
    bool region_known = false;
    for (std::size_t j = 0; j < plan.tets.size(); ++j) {
        const Tet& g = plan.tets[j];
        if (g[3] != kGhostVertex) continue;
        if (far_vertex(m, plan, 4 * j + 3) == kGhostVertex) return false;  // hull face between two ghosts
        for (std::size_t f = 0; f < 3; ++f)
            if (!inside_hull_face(m, g, far_vertex(m, plan, 4 * j + f))) return false;
        if (!region_known) {
            region = finite_vertices(m, old);
            region_known = true;
        }
        if (!region_inside_hull_face(m, g, region)) return false;
    }
    return true;
}

// The part of the convexity rule that a scored ring (ShellGeometry::
// kScoredRing) does not imply: a fresh ghost's hull face borders a finite
// tetrahedron, and the far vertex of each hull face next to it outside the
// shell is on the inner side. The region's vertices were scored against
// every fresh ghost, and so were the far vertices of fresh neighbours:
// across a face through the ghost vertex, a fresh neighbour's far vertex is
// a finite vertex of the region.
bool hull_stays_convex_outside_region(const TetMesh& m, const Plan& plan) {
    for (std::size_t j = 0; j < plan.tets.size(); ++j) {
        const Tet& g = plan.tets[j];
        if (g[3] != kGhostVertex) continue;
        if (far_vertex(m, plan, 4 * j + 3) == kGhostVertex) return false;  // hull face between two ghosts
        for (std::size_t f = 0; f < 3; ++f)
            if (plan.outside[4 * j + f] && !inside_hull_face(m, g, far_vertex(m, plan, 4 * j + f))) return false;
    }
    return true;
}

// The checks that follow the face matching.
ReplaceResult check_geometry(const TetMesh& m, const std::vector<TetId>& old, const Plan& plan) {
    if (!positively_oriented(m, plan.tets)) return ReplaceResult::kInverted;
    if (!hull_stays_convex(m, old, plan)) return ReplaceResult::kNotConvex;
    return ReplaceResult::kDone;
}

ReplaceResult check(const TetMesh& m, const std::vector<TetId>& old, const std::vector<Tet>& fresh, Plan& plan) {
    std::vector<TetId> sorted_old;
    if (!valid_old(m, old, sorted_old) || !normalise_fresh(m, fresh, plan.tets)) return ReplaceResult::kBadInput;
    std::vector<FaceEntry> faces = collect_faces(m, old, sorted_old, plan.tets);
    const ReplaceResult r = match_faces(faces, plan);
    if (r != ReplaceResult::kDone) return r;
    return check_geometry(m, old, plan);
}

// The old slots first, then new ones. If an allocation throws, the slots
// taken so far are flagged free again (release_tet sets the flag before it
// pushes on the free list, so even a second failure leaves the mesh valid).
void take_slots(TetMesh& m, const std::vector<TetId>& old, std::size_t count, std::vector<TetId>& slots) {
    slots.reserve(count);
    slots.assign(old.begin(), old.begin() + static_cast<std::ptrdiff_t>(std::min(old.size(), count)));
    try {
        while (slots.size() < count) slots.push_back(m.allocate_tet());
    } catch (...) {
        for (std::size_t i = old.size(); i < slots.size(); ++i) {
            try {
                m.release_tet(slots[i]);
            } catch (...) {  // the slot is flagged free already: leaked, not live
            }
        }
        throw;
    }
}

// Each fresh slot written whole (set_tet: one journal check), then the
// outside neighbours' links back.
void write_plan(TetMesh& m, const Plan& plan, const std::vector<TetId>& slots) {
    for (std::size_t j = 0; j < plan.tets.size(); ++j) {
        FacetRef n[4];
        for (int f = 0; f < 4; ++f) {
            const std::size_t half = 4 * j + static_cast<std::size_t>(f);
            const FacetRef r = plan.partner[half];
            n[f] = plan.outside[half] ? r : make_facet(slots[facet_tet(r)], facet_face(r));
        }
        m.set_tet(slots[j], plan.tets[j].data(), n, plan.marks[j]);
    }
    for (std::size_t j = 0; j < plan.tets.size(); ++j)
        for (int f = 0; f < 4; ++f) {
            const std::size_t half = 4 * j + static_cast<std::size_t>(f);
            if (plan.outside[half]) {
                const FacetRef r = plan.partner[half];
                m.set_neighbor(facet_tet(r), facet_face(r), make_facet(slots[j], f));
            }
        }
}

// Carries out a checked plan: slots, tetrahedra and links, surplus old
// slots freed; `created` (optional) gets the slots in the order of the plan.
void apply_plan(TetMesh& m, const std::vector<TetId>& old, const Plan& plan, std::vector<TetId>& slots,
                std::vector<TetId>* created) {
    if (created) {
        created->clear();
        created->reserve(plan.tets.size());
    }
    take_slots(m, old, plan.tets.size(), slots);
    // From here on nothing throws but the free list's growth, and a slot
    // that fails to go on it is flagged free already (leaked, not live):
    // the replacement is complete either way.
    write_plan(m, plan, slots);
    for (std::size_t i = slots.size(); i < old.size(); ++i) {
        try {
            m.release_tet(old[i]);
        } catch (...) {
        }
    }
    if (created) created->assign(slots.begin(), slots.end());
}

// --- the cone of a new point (ConeReplacer) ---------------------------------

// The faces through p, found by the boundary edge they stand on: an
// open-addressing table keyed by the edge's sorted vertex pair.
struct EdgeSlot {
    std::uint64_t key = 0;  // 0: empty (a key is never 0: its two ids differ)
    FacetRef first = 0;     // the first cone half-facet on this edge (4 * cone + face)
    std::uint8_t parity = 0;  // that face's orientation parity (as in FaceEntry)
    std::uint8_t count = 0;   // cone faces on this edge so far
};

constexpr std::uint8_t kInOld = 1;  // ConeReplacer's mark: listed in `old`

}  // namespace

struct ConeReplacer::Scratch {
    Plan plan;
    SlotMarks own_marks;
    SlotMarks* in_old = &own_marks;  // per slot: kInOld (ConeReplacer::share_marks)
    std::vector<EdgeSlot> edges;  // see EdgeSlot; a power of two long
    std::vector<TetId> slots;
    // What restore_last() puts back, from the last successful replace():
    // the replaced tetrahedra (vertices and neighbour links, in the order
    // of `old`), the apex, and per cone the face of `old` it stands on
    // (4 * index in `old` + face; build_cones fills it).
    std::vector<TetId> old_slots;
    std::vector<Tet> old_vertices;
    std::vector<std::array<FacetRef, 4>> old_neighbors;
    VertexId apex = kGhostVertex;
    std::vector<std::uint32_t> cone_base;
    // restore_last's scratch, per face of `old`: 1 + the constraint mark
    // for a face on the region's boundary (0 inside), and what the cone on
    // it is linked to.
    std::vector<std::uint8_t> boundary;
    std::vector<FacetRef> outside;
    std::vector<std::pair<TetId, TetId>> moved;  // (old slot, index in `old`), sorted
};

namespace {

// The cones over the boundary faces of `old` (by tetrahedron of `old`, then
// face) in plan.tets, each cone's face on the boundary linked to the
// outside with its constraint mark, and per cone the face it stands on in
// `cone_base` (4 * index in `old` + face); `interior_constraint` tells
// whether a constraint face lies between two tetrahedra of `old`. False
// when replace_tets would reject the input (kBadInput). `old` is marked
// in_old.
bool build_cones(const TetMesh& m, const std::vector<TetId>& old, VertexId p, const SlotMarks& in_old, Plan& plan,
                 std::vector<std::uint32_t>& cone_base, bool& interior_constraint) {
    plan.tets.clear();
    plan.partner.clear();
    plan.outside.clear();
    plan.marks.clear();
    cone_base.clear();
    interior_constraint = false;
    for (std::size_t k = 0; k < old.size(); ++k) {
        const TetId t = old[k];
        const VertexId* v = m.vertices(t);
        for (int f = 0; f < 4; ++f) {
            if (in_old.has(facet_tet(m.neighbor(t, f)), kInOld)) {
                interior_constraint |= m.is_constrained(t, f);
                continue;
            }
            Tet cone = {v[0], v[1], v[2], v[3]};
            for (int i = 0; i < 4; ++i)
                if (i != f && cone[static_cast<std::size_t>(i)] == p) return false;  // a repeated vertex
            cone[static_cast<std::size_t>(f)] = p;
            plan.tets.push_back(cone);
            cone_base.push_back(static_cast<std::uint32_t>(4 * k + static_cast<std::size_t>(f)));
            const std::uint8_t mark = m.is_constrained(t, f) ? static_cast<std::uint8_t>(1u << f) : 0;
            for (int g = 0; g < 4; ++g) {
                plan.partner.push_back(g == f ? m.neighbor(t, f) : 0);
                plan.outside.push_back(g == f ? 1 : 0);
            }
            plan.marks.push_back(mark);
        }
    }
    return !plan.tets.empty();
}

// Links the faces through p: each stands on an edge of the boundary, and
// the region is tiled only if every such edge carries exactly two of them,
// of opposite orientations (what match_faces checks on their sorted
// triples). Returns kDone or kNotTiling.
ReplaceResult link_faces_through_apex(Plan& plan, VertexId p, std::vector<EdgeSlot>& table) {
    std::size_t size = 16;
    while (size < 6 * plan.tets.size()) size *= 2;  // 3 faces per cone; at most half full
    table.assign(size, EdgeSlot{});
    const std::size_t mask = size - 1;
    std::size_t unpaired = 0;
    for (std::size_t j = 0; j < plan.tets.size(); ++j) {
        const Tet& cone = plan.tets[j];
        const int apex = static_cast<int>(std::find(cone.begin(), cone.end(), p) - cone.begin());
        for (int g = 0; g < 4; ++g) {
            if (g == apex) continue;  // the boundary face, linked already
            std::array<VertexId, 3> sorted = {cone[kFaceVertices[g][0]], cone[kFaceVertices[g][1]],
                                              cone[kFaceVertices[g][2]]};
            const std::uint8_t parity = sort3(sorted);
            // The edge: the face's vertices other than p, at the cone
            // positions x < y other than apex and g (they sum to 6).
            const int x = apex != 0 && g != 0 ? 0 : apex != 1 && g != 1 ? 1 : 2;
            const int y = 6 - apex - g - x;
            const std::uint64_t k = edge_key(cone[static_cast<std::size_t>(x)], cone[static_cast<std::size_t>(y)]);
            std::size_t i = static_cast<std::size_t>((k * 0x9E3779B97F4A7C15ull) >> 32) & mask;
            while (table[i].key != 0 && table[i].key != k) i = (i + 1) & mask;
            EdgeSlot& e = table[i];
            const FacetRef half = make_facet(static_cast<TetId>(j), g);
            if (e.key == 0) {
                e = {k, half, parity, 1};
                ++unpaired;
                continue;
            }
            if (++e.count > 2 || e.parity == parity) return ReplaceResult::kNotTiling;
            plan.partner[half] = e.first;
            plan.partner[e.first] = half;
            --unpaired;
        }
    }
    return unpaired == 0 ? ReplaceResult::kDone : ReplaceResult::kNotTiling;
}

// --- the shell transformation (ShellReplacer) --------------------------------

// An edge of the ring polygon (a side or a chord), keyed by its two ring
// indices: how many triangles have used it so far, and for the first one,
// its direction and the faces through it of its two cones.
struct RingEdgeUse {
    FacetRef above = 0;  // the face of the cone to v through the edge
    FacetRef below = 0;  // the face of the cone to u through the edge
    std::uint8_t uses = 0;
    bool ascending = false;  // traversed from the smaller ring index to the larger
};

// Three distinct ring indices in range (a cone with distinct vertex ids).
bool valid_indices(const RingTriangle& tri, int n) {
    for (int i : tri)
        if (i < 0 || i >= n) return false;
    return tri[0] != tri[1] && tri[1] != tri[2] && tri[2] != tri[0];
}

// Distinct indices in cyclic ring order.
bool in_ring_order(const RingTriangle& tri) {
    const int i = tri[0], j = tri[1], k = tri[2];
    return (i < j && j < k) || (j < k && k < i) || (k < i && i < j);
}

// Position of x in t (x is one of its vertices).
int position(const Tet& t, VertexId x) {
    int i = 0;
    while (i < 3 && t[static_cast<std::size_t>(i)] != x) ++i;
    return i;
}

// t with a ghost vertex moved to position 3, as normalise_fresh does.
Tet with_ghost_last(Tet t) {
    for (int i = 0; i < 3; ++i)
        if (t[static_cast<std::size_t>(i)] == kGhostVertex) move_ghost_last(t, i);
    return t;
}

// The cones of the ring triangles in plan.tets (to v, then to u, per
// triangle; ghosts normalised), links and marks cleared. False when there
// is none or a triangle is not three distinct ring indices.
bool cone_ring(VertexId u, VertexId v, const Shell& s, const std::vector<RingTriangle>& triangles, Plan& plan) {
    const int n = static_cast<int>(s.size());
    plan.tets.clear();
    for (const RingTriangle& tri : triangles) {
        if (!valid_indices(tri, n)) return false;
        const VertexId a = s.ring[static_cast<std::size_t>(tri[0])], b = s.ring[static_cast<std::size_t>(tri[1])],
                       c = s.ring[static_cast<std::size_t>(tri[2])];
        plan.tets.push_back(with_ghost_last({a, b, c, v}));
        plan.tets.push_back(with_ghost_last({a, c, b, u}));
    }
    plan.partner.assign(4 * plan.tets.size(), 0);
    plan.outside.assign(4 * plan.tets.size(), 0);
    plan.marks.assign(plan.tets.size(), 0);
    return !plan.tets.empty();
}

// Links a ring side's two new faces to the old faces of shell tetrahedron
// `t` opposite u and v, which they replace, with their constraint marks.
void link_to_shell_side(const TetMesh& m, VertexId u, VertexId v, TetId t, FacetRef above, FacetRef below,
                        Plan& plan) {
    const int fu = vertex_index(m, t, u), fv = vertex_index(m, t, v);
    set_partner(plan, above, m.neighbor(t, fu), true, m.is_constrained(t, fu));
    set_partner(plan, below, m.neighbor(t, fv), true, m.is_constrained(t, fv));
}

// Links every face of the cones (cone_ring) and checks that the triangles
// tile the ring polygon, which is what match_faces would find: each ring
// side is used by one triangle, each chord by two, in opposite directions
// (a triangle in ring order is positively oriented in the polygon, so
// these make a triangulation). Returns kDone or kNotTiling.
ReplaceResult link_ring_cones(const TetMesh& m, VertexId u, VertexId v, const Shell& s,
                              const std::vector<RingTriangle>& triangles, Plan& plan,
                              std::vector<RingEdgeUse>& edges) {
    const int n = static_cast<int>(s.size());
    if (triangles.size() + 2 != s.size()) return ReplaceResult::kNotTiling;
    edges.assign(s.size() * s.size(), RingEdgeUse{});
    std::size_t open_chords = 0;
    for (std::size_t q = 0; q < triangles.size(); ++q) {
        const RingTriangle& tri = triangles[q];
        if (!in_ring_order(tri)) return ReplaceResult::kNotTiling;  // its cones face the wrong way
        const TetId above = static_cast<TetId>(2 * q), below = above + 1;  // the cones to v and to u
        const Tet& cone_v = plan.tets[above];
        const Tet& cone_u = plan.tets[below];
        // The triangle itself: the face the two cones share.
        set_partner(plan, make_facet(above, position(cone_v, v)), make_facet(below, position(cone_u, u)), false, false);
        set_partner(plan, make_facet(below, position(cone_u, u)), make_facet(above, position(cone_v, v)), false, false);
        for (int e = 0; e < 3; ++e) {
            const int x = tri[static_cast<std::size_t>(e)], y = tri[static_cast<std::size_t>((e + 1) % 3)];
            const VertexId opposite = s.ring[static_cast<std::size_t>(tri[static_cast<std::size_t>((e + 2) % 3)])];
            const FacetRef face_v = make_facet(above, position(cone_v, opposite));
            const FacetRef face_u = make_facet(below, position(cone_u, opposite));
            RingEdgeUse& use = edges[static_cast<std::size_t>(std::min(x, y) * n + std::max(x, y))];
            if (y == (x + 1) % n) {  // a side, from shell tetrahedron x
                if (use.uses++ != 0) return ReplaceResult::kNotTiling;
                link_to_shell_side(m, u, v, s.tets[static_cast<std::size_t>(x)], face_v, face_u, plan);
            } else if (use.uses == 0) {  // a chord, first seen
                use = {face_v, face_u, 1, x < y};
                ++open_chords;
            } else {  // a chord, second seen: the two triangles share its faces
                if (use.uses++ != 1 || use.ascending == (x < y)) return ReplaceResult::kNotTiling;
                set_partner(plan, face_v, use.above, false, false);
                set_partner(plan, use.above, face_v, false, false);
                set_partner(plan, face_u, use.below, false, false);
                set_partner(plan, use.below, face_u, false, false);
                --open_chords;
            }
        }
    }
    return open_chords == 0 ? ReplaceResult::kDone : ReplaceResult::kNotTiling;
}

// A face between two tetrahedra of the shell (through u and v) is
// constrained: no cone has it.
bool shell_has_interior_constraint(const TetMesh& m, VertexId u, VertexId v, const Shell& s) {
    for (TetId t : s.tets)
        for (int f = 0; f < 4; ++f)
            if (m.vertex(t, f) != u && m.vertex(t, f) != v && m.is_constrained(t, f)) return true;
    return false;
}

}  // namespace

struct ShellReplacer::Scratch {
    Plan plan;
    std::vector<RingEdgeUse> edges;  // n * n for a ring of n: see RingEdgeUse
    std::vector<TetId> slots;
};

const char* to_string(ReplaceResult r) {
    switch (r) {
        case ReplaceResult::kDone: return "done";
        case ReplaceResult::kBadInput: return "bad input";
        case ReplaceResult::kNotTiling: return "fresh tetrahedra do not tile the region";
        case ReplaceResult::kRemovesConstraint: return "would remove a constraint face";
        case ReplaceResult::kInverted: return "a fresh tetrahedron is not positively oriented";
        case ReplaceResult::kNotConvex: return "the hull would not stay convex";
    }
    return "?";
}

ReplaceResult replace_tets(TetMesh& m, const std::vector<TetId>& old, const std::vector<std::array<VertexId, 4>>& fresh,
                           std::vector<TetId>* created) {
    Plan plan;
    const ReplaceResult r = check(m, old, fresh, plan);
    if (r != ReplaceResult::kDone) return r;
    std::vector<TetId> slots;
    apply_plan(m, old, plan, slots, created);
    return ReplaceResult::kDone;
}

ConeReplacer::ConeReplacer() : scratch_(std::make_unique<Scratch>()) {}
ConeReplacer::~ConeReplacer() = default;

void ConeReplacer::share_marks(SlotMarks* marks) { scratch_->in_old = marks ? marks : &scratch_->own_marks; }

// The checks of replace_tets in its order. Its matching of sorted face
// triples reduces here to the faces through p (link_faces_through_apex):
// in a valid mesh a triangle bounds two tetrahedra, so the boundary faces
// of `old` are distinct triangles, each the face of exactly one cone with
// the same vertex order (same orientation), and none of them, nor a face
// inside `old`, contains p (in no tetrahedron).
ReplaceResult ConeReplacer::replace(TetMesh& m, const std::vector<TetId>& old, VertexId p,
                                    std::vector<TetId>* created) {
    Scratch& s = *scratch_;
    s.old_vertices.clear();  // nothing to restore unless this one is done
    if (old.empty() || p >= m.vertex_count()) return ReplaceResult::kBadInput;
    SlotMarks& in_old = *s.in_old;
    in_old.new_round(m.slot_count());
    for (TetId t : old) {
        if (t >= m.slot_count() || m.is_free(t) || in_old.has(t, kInOld)) return ReplaceResult::kBadInput;
        in_old.set(t, kInOld);
    }
    bool interior_constraint = false;
    if (!build_cones(m, old, p, in_old, s.plan, s.cone_base, interior_constraint)) return ReplaceResult::kBadInput;
    const ReplaceResult tiling = link_faces_through_apex(s.plan, p, s.edges);
    if (tiling != ReplaceResult::kDone) return tiling;
    if (interior_constraint) return ReplaceResult::kRemovesConstraint;
    const ReplaceResult r = check_geometry(m, old, s.plan);
    if (r != ReplaceResult::kDone) return r;
    remember_old(m, old, p);
    apply_plan(m, old, s.plan, s.slots, created);
    return ReplaceResult::kDone;
}

// The region as it is, before apply_plan reuses its slots (the cones'
// bases are build_cones').
void ConeReplacer::remember_old(const TetMesh& m, const std::vector<TetId>& old, VertexId p) {
    Scratch& s = *scratch_;
    s.old_slots = old;
    s.old_vertices.clear();
    s.old_neighbors.clear();
    s.apex = p;
    for (TetId t : old) {
        s.old_vertices.push_back({m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2), m.vertex(t, 3)});
        s.old_neighbors.push_back({m.neighbor(t, 0), m.neighbor(t, 1), m.neighbor(t, 2), m.neighbor(t, 3)});
    }
}

// What replace_tets(m, created, the old tetrahedra) would do, written
// directly. The star took the region's slots first, so created[i] is
// old[i] for i below both counts; replace_tets takes the star's slots in
// order, then free ones (take_slots), so tetrahedron i of `old` goes
// into slots[i], linked to the others as it was (through the slot each
// now has) and, across the region's boundary, to what the cone on that
// face is linked to now, with that face's constraint mark; the star's
// slots beyond the region's count are freed in order.
bool ConeReplacer::restore_last(TetMesh& m, const std::vector<TetId>& created, std::vector<TetId>* restored) {
    Scratch& s = *scratch_;
    const std::size_t k = s.old_vertices.size();
    if (k == 0 || created.size() != s.cone_base.size()) return false;
    s.boundary.assign(4 * k, 0);
    s.outside.resize(4 * k);
    for (std::size_t j = 0; j < created.size(); ++j) {
        const TetId cone = created[j];
        const std::uint32_t base = s.cone_base[j];
        const int f = static_cast<int>(base % 4);
        // The star as replace() left it: live, its apex where it was put.
        if (cone >= m.slot_count() || m.is_free(cone) || m.vertex(cone, f) != s.apex) return false;
        s.outside[base] = m.neighbor(cone, f);
        s.boundary[base] = m.is_constrained(cone, f) ? 2 : 1;
    }
    take_slots(m, created, k, s.slots);
    // Where the star is smaller than the region (a flat region has more
    // tetrahedra than faces), the rest of it comes back in other slots:
    // its inner links go by the old slot's index in `old`.
    s.moved.clear();
    if (created.size() < k) {
        for (std::size_t i = 0; i < k; ++i) s.moved.emplace_back(s.old_slots[i], static_cast<TetId>(i));
        std::sort(s.moved.begin(), s.moved.end());
    }
    const auto now = [&](FacetRef was) {
        if (s.moved.empty()) return was;
        const auto it = std::lower_bound(s.moved.begin(), s.moved.end(), std::make_pair(facet_tet(was), TetId{0}));
        return make_facet(s.slots[it->second], facet_face(was));
    };
    for (std::size_t i = 0; i < k; ++i) {
        FacetRef n[4];
        std::uint8_t constrained = 0;
        for (int f = 0; f < 4; ++f) {
            const std::size_t face = 4 * i + static_cast<std::size_t>(f);
            n[f] = s.boundary[face] != 0 ? s.outside[face] : now(s.old_neighbors[i][static_cast<std::size_t>(f)]);
            if (s.boundary[face] == 2) constrained |= static_cast<std::uint8_t>(1u << f);
        }
        m.set_tet(s.slots[i], s.old_vertices[i].data(), n, constrained);
    }
    for (std::size_t i = 0; i < k; ++i)
        for (int f = 0; f < 4; ++f) {
            const std::size_t face = 4 * i + static_cast<std::size_t>(f);
            if (s.boundary[face] != 0)
                m.set_neighbor(facet_tet(s.outside[face]), facet_face(s.outside[face]), make_facet(s.slots[i], f));
        }
    for (std::size_t j = k; j < created.size(); ++j) {
        try {
            m.release_tet(created[j]);
        } catch (...) {  // flagged free already: leaked, not live (as apply_plan)
        }
    }
    if (restored) restored->assign(s.slots.begin(), s.slots.end());
    s.old_vertices.clear();  // once
    return true;
}

struct TwoThreeReplacer::Scratch {
    Plan plan;
    std::vector<TetId> old;  // {t, n}
    std::vector<TetId> slots;
};

TwoThreeReplacer::TwoThreeReplacer() : scratch_(std::make_unique<Scratch>()) {}
TwoThreeReplacer::~TwoThreeReplacer() = default;

// The checks of replace_tets in its order. With no ghost among the five
// vertices, and t and n sharing only face f, the region's boundary is the
// six other faces of t and n, each the face of one fresh tetrahedron with
// the same orientation, and the three faces through de are shared by two
// fresh ones: the tiling holds by construction; face f, inside the region,
// is a face of no fresh tetrahedron.
ReplaceResult TwoThreeReplacer::replace(TetMesh& m, TetId t, int f, std::vector<TetId>* created) {
    Scratch& s = *scratch_;
    if (t >= m.slot_count() || m.is_free(t) || f < 0 || f > 3) return ReplaceResult::kBadInput;
    const FacetRef across = m.neighbor(t, f);
    const TetId n = facet_tet(across);
    const VertexId* tv = m.vertices(t);
    const VertexId base[3] = {tv[kFaceVertices[f][0]], tv[kFaceVertices[f][1]], tv[kFaceVertices[f][2]]};
    const VertexId d = tv[f], e = m.vertex(n, facet_face(across));
    Plan& plan = s.plan;
    plan.tets.assign({{base[0], base[1], e, d}, {base[1], base[2], e, d}, {base[2], base[0], e, d}});
    s.old.assign({t, n});
    bool general = n == t || d == kGhostVertex || e == kGhostVertex;
    for (int i = 0; i < 4; ++i) general = general || (i != f && facet_tet(m.neighbor(t, i)) == n);
    for (VertexId x : base) general = general || x == kGhostVertex;
    if (general) return replace_tets(m, s.old, plan.tets, created);
    if (m.is_free(n)) return ReplaceResult::kBadInput;
    if (m.is_constrained(t, f)) return ReplaceResult::kRemovesConstraint;
    if (!positively_oriented(m, plan.tets)) return ReplaceResult::kInverted;
    plan.partner.assign(12, 0);
    plan.outside.assign(12, 0);
    plan.marks.assign(3, 0);
    for (TetId j = 0; j < 3; ++j) {
        // Fresh tetrahedron j stands on base edge (j, j+1); its face
        // opposite e is t's face opposite the third base vertex, its face
        // opposite d is n's.
        const VertexId third = base[(j + 2) % 3];
        const int in_t = vertex_index(m, t, third), in_n = vertex_index(m, n, third);
        set_partner(plan, make_facet(j, 2), m.neighbor(t, in_t), true, m.is_constrained(t, in_t));
        set_partner(plan, make_facet(j, 3), m.neighbor(n, in_n), true, m.is_constrained(n, in_n));
        // Its face opposite base vertex j (position 0) is the next one's
        // face opposite base vertex j+2 (position 1): base vertex j+1, e, d.
        const TetId next = (j + 1) % 3;
        set_partner(plan, make_facet(j, 0), make_facet(next, 1), false, false);
        set_partner(plan, make_facet(next, 1), make_facet(j, 0), false, false);
    }
    apply_plan(m, s.old, plan, s.slots, created);
    return ReplaceResult::kDone;
}

ShellReplacer::ShellReplacer() : scratch_(std::make_unique<Scratch>()) {}
ShellReplacer::~ShellReplacer() = default;

// The checks of replace_tets in its order. In a valid mesh the shell's
// tetrahedra are live and distinct, their boundary faces are the 2n faces
// opposite u and v (a triangle bounds two tetrahedra, and the one outside
// has neither u nor v in place of the other), the faces between them go
// through uv, which no cone has, and a cone has distinct vertex ids (u, v
// and distinct ring vertices).
ReplaceResult ShellReplacer::replace(TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                                     const std::vector<RingTriangle>& triangles, ShellGeometry geometry,
                                     std::vector<TetId>* created) {
    Scratch& s = *scratch_;
    if (!cone_ring(u, v, shell, triangles, s.plan)) return ReplaceResult::kBadInput;
    const ReplaceResult tiling = link_ring_cones(m, u, v, shell, triangles, s.plan, s.edges);
    if (tiling != ReplaceResult::kDone) return tiling;
    if (shell_has_interior_constraint(m, u, v, shell)) return ReplaceResult::kRemovesConstraint;
    if (geometry == ShellGeometry::kUnchecked) {
        const ReplaceResult r = check_geometry(m, shell.tets, s.plan);
        if (r != ReplaceResult::kDone) return r;
    } else if (!hull_stays_convex_outside_region(m, s.plan)) {
        return ReplaceResult::kNotConvex;
    }
    apply_plan(m, shell.tets, s.plan, s.slots, created);
    return ReplaceResult::kDone;
}

}  // namespace cbr::mesh
