#include "mesh/surgery.hpp"

#include <algorithm>
#include <cstdint>
#include <tuple>

#include "geom/predicates.hpp"

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

bool entry_less(const FaceEntry& a, const FaceEntry& b) {
    return std::tie(a.head, a.tail, a.kind, a.ref) < std::tie(b.head, b.tail, b.kind, b.ref);
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

// Checks ids and moves kGhostVertex to position 3 by an even permutation
// (two transpositions), which keeps the orientation.
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
        if (ghost >= 0 && ghost != 3) {
            std::swap(t[ghost], t[3]);
            std::swap(t[(ghost + 1) % 3], t[(ghost + 2) % 3]);
        }
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

// One group of entries with the same vertex set (sorted by kind: fresh,
// boundary, constraint). Valid groups: one boundary face and one fresh
// face of the same orientation, or two fresh faces of opposite ones.
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

// x is on the finite side of (or on) the hull face of ghost g.
bool inside_hull_face(const TetMesh& m, const Tet& g, VertexId x) {
    return x != kGhostVertex && orient(m, g[0], g[1], g[2], x) <= 0;
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
        for (VertexId x : region)
            if (!inside_hull_face(m, g, x)) return false;
    }
    return true;
}

ReplaceResult check(const TetMesh& m, const std::vector<TetId>& old, const std::vector<Tet>& fresh, Plan& plan) {
    std::vector<TetId> sorted_old;
    if (!valid_old(m, old, sorted_old) || !normalise_fresh(m, fresh, plan.tets)) return ReplaceResult::kBadInput;
    std::vector<FaceEntry> faces = collect_faces(m, old, sorted_old, plan.tets);
    const ReplaceResult r = match_faces(faces, plan);
    if (r != ReplaceResult::kDone) return r;
    if (!positively_oriented(m, plan.tets)) return ReplaceResult::kInverted;
    if (!hull_stays_convex(m, old, plan)) return ReplaceResult::kNotConvex;
    return ReplaceResult::kDone;
}

// The old slots first, then new ones. If an allocation throws, the slots
// taken so far are flagged free again (release_tet sets the flag before it
// pushes on the free list, so even a second failure leaves the mesh valid).
std::vector<TetId> take_slots(TetMesh& m, const std::vector<TetId>& old, std::size_t count) {
    std::vector<TetId> slots;
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
    return slots;
}

void write_plan(TetMesh& m, const Plan& plan, const std::vector<TetId>& slots) {
    for (std::size_t j = 0; j < plan.tets.size(); ++j) {
        const Tet& t = plan.tets[j];
        m.set_vertices(slots[j], t[0], t[1], t[2], t[3]);
        m.clear_mark(slots[j], 0xFF);
        for (int f = 0; f < 4; ++f) m.set_constrained(slots[j], f, ((plan.marks[j] >> f) & 1u) != 0);
    }
    for (std::size_t j = 0; j < plan.tets.size(); ++j) {
        for (int f = 0; f < 4; ++f) {
            const std::size_t half = 4 * j + static_cast<std::size_t>(f);
            const FacetRef r = plan.partner[half];
            if (plan.outside[half])
                m.link(make_facet(slots[j], f), r);
            else
                m.set_neighbor(slots[j], f, make_facet(slots[facet_tet(r)], facet_face(r)));
        }
    }
}

}  // namespace

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
    if (created) {
        created->clear();
        created->reserve(plan.tets.size());
    }
    const std::vector<TetId> slots = take_slots(m, old, plan.tets.size());
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
    return ReplaceResult::kDone;
}

}  // namespace cbr::mesh
