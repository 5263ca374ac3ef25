// Tetrahedral mesh storage: flat arrays, 32-bit indices (geogram / HXT
// style). Per tetrahedron: 4 vertex ids and 4 neighbour half-facet
// references in one 32-byte record (two per cache line: the Delaunay walk
// and cavity search read both for every tetrahedron they visit, and a
// record is one cache miss where separate arrays were two), plus one byte
// of flags in an array of its own; 33 bytes in all.
//
// Anatomy of tetrahedron t = (v0, v1, v2, v3), positively oriented, i.e.
// orient3d(v0, v1, v2, v3) > 0 (see cbr.h for the convention):
//
//                 v3
//                /|\            face f is the triangle opposite vertex f;
//               / | \           kFaceVertices[f] lists it in the order
//              /  |  \          whose normal points *into* t, toward v_f:
//             /   |   \           face 0 = (v1, v3, v2)
//           v0 ---|--- v2         face 1 = (v0, v2, v3)
//             \   |   /           face 2 = (v0, v3, v1)
//              \  |  /            face 3 = (v0, v1, v2)
//               \ | /           so orient3d(face f..., v_f) > 0.
//                \|/
//                 v1
//
// Neighbours: neighbor(t, f) = 4 * t' + f' is the half-facet of the
// tetrahedron t' across face f of t; face f of t is face f' of t'.
// Every tetrahedron has four neighbours: the hull is closed by ghost
// tetrahedra (v0, v1, v2, kGhostVertex), whose infinite vertex is always
// at position 3 and lies on the positive side of (v0, v1, v2), outside the
// hull. Face 3 of a ghost is its hull face.
//
// Flags byte: bit 0 "free" (slot on the free list), bits 1-2 scratch marks
// for algorithms (cleared by whoever sets them), bits 4-7 reserved for
// per-face constraint marks (boundary recovery).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/large_array.hpp"

namespace cbr::mesh {

using VertexId = std::uint32_t;
using TetId = std::uint32_t;
using FacetRef = std::uint32_t;  // 4 * tet + face

inline constexpr VertexId kGhostVertex = 0xFFFFFFFFu;
inline constexpr TetId kNoTet = 0xFFFFFFFFu;
// 4 * tet + face must fit in 32 bits.
inline constexpr std::size_t kMaxTets = std::size_t{1} << 30;
// Vertex ids stay below kGhostVertex; the C API promises 2^31 - 2.
inline constexpr std::size_t kMaxVertices = (std::size_t{1} << 31) - 2;

inline constexpr int kFaceVertices[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};

inline constexpr std::uint8_t kFlagFree = 1u << 0;
inline constexpr std::uint8_t kFlagMarkA = 1u << 1;
inline constexpr std::uint8_t kFlagMarkB = 1u << 2;
inline constexpr std::uint8_t kFlagConstraintFace0 = 1u << 4;  // bits 4..7: faces 0..3

inline FacetRef make_facet(TetId t, int f) { return 4 * t + static_cast<FacetRef>(f); }
inline TetId facet_tet(FacetRef r) { return r >> 2; }
inline int facet_face(FacetRef r) { return static_cast<int>(r & 3u); }

class TetMesh {
public:
    // --- vertices -------------------------------------------------------
    std::size_t vertex_count() const { return coords_.size() / 3; }
    const double* point(VertexId v) const { return &coords_[3 * std::size_t{v}]; }
    // Appends points (3 doubles each); returns the id of the first.
    VertexId add_points(const double* xyz, std::size_t count);
    void truncate_vertices(std::size_t count);
    const LargeArray<double>& coordinates() const { return coords_; }
    // Moves vertex v to xyz (3 doubles): Steiner point repositioning (§6).
    // The caller keeps every tetrahedron incident to v positively oriented.
    void set_point(VertexId v, const double* xyz) {
        for (std::size_t k = 0; k < 3; ++k) coords_[3 * std::size_t{v} + k] = xyz[k];
    }

    // --- tetrahedra -------------------------------------------------------
    // Number of slots, including free ones; ids run over [0, slot_count()).
    std::size_t slot_count() const { return flags_.size(); }
    std::size_t free_count() const { return free_.size(); }
    std::size_t live_count() const { return slot_count() - free_count(); }

    VertexId vertex(TetId t, int i) const { return tets_[t].v[i]; }
    const VertexId* vertices(TetId t) const { return tets_[t].v; }
    FacetRef neighbor(TetId t, int f) const { return tets_[t].n[f]; }
    bool is_free(TetId t) const { return (flags_[t] & kFlagFree) != 0; }
    bool is_ghost(TetId t) const { return tets_[t].v[3] == kGhostVertex; }
    std::uint8_t flags(TetId t) const { return flags_[t]; }

    void set_vertices(TetId t, VertexId a, VertexId b, VertexId c, VertexId d);
    // Writes slot t whole, as a replacement fills it: vertices, neighbours
    // and flags, where the faces whose bit f is set in `constrained` are
    // constraint faces and every other flag (free, scratch marks) is
    // cleared. The neighbours' links back are left to the caller.
    void set_tet(TetId t, const VertexId v[4], const FacetRef n[4], std::uint8_t constrained) {
        before_change(t);
        TetRecord& r = tets_[t];
        for (int i = 0; i < 4; ++i) {
            r.v[i] = v[i];
            r.n[i] = n[i];
        }
        flags_[t] = static_cast<std::uint8_t>((constrained & 0xFu) << 4);
    }
    void set_vertex(TetId t, int i, VertexId v) {
        before_change(t);
        tets_[t].v[i] = v;
    }
    // Makes the two half-facets neighbours of each other.
    void link(FacetRef a, FacetRef b) {
        before_change(facet_tet(a));
        before_change(facet_tet(b));
        tets_[facet_tet(a)].n[facet_face(a)] = b;
        tets_[facet_tet(b)].n[facet_face(b)] = a;
    }
    void set_neighbor(TetId t, int f, FacetRef r) {
        before_change(t);
        tets_[t].n[f] = r;
    }
    void set_mark(TetId t, std::uint8_t mark) {
        before_change(t);
        flags_[t] |= mark;
    }
    void clear_mark(TetId t, std::uint8_t mark) {
        before_change(t);
        flags_[t] &= static_cast<std::uint8_t>(~mark);
    }
    bool has_mark(TetId t, std::uint8_t mark) const { return (flags_[t] & mark) != 0; }

    // Face f of t is a recovered constraint face (marked on both sides).
    bool is_constrained(TetId t, int f) const { return (flags_[t] & constraint_bit(f)) != 0; }
    void set_constrained(TetId t, int f, bool on) {
        before_change(t);
        if (on) flags_[t] |= constraint_bit(f);
        else flags_[t] &= static_cast<std::uint8_t>(~constraint_bit(f));
    }

    // A tetrahedron slot: a free one if any, else a new one at the end (on
    // a thread with a SlotPool for this mesh: the pool's, slot_pool.hpp).
    // Throws std::length_error beyond kMaxTets, std::bad_alloc when out of
    // memory. Vertices and neighbours are left for the caller to set.
    TetId allocate_tet();
    void release_tet(TetId t);
    // Capacity hint so that growth reallocates rarely.
    void reserve_tets(std::size_t count);
    void clear_tets();
    // Renumbers the tetrahedra: `order` lists every live slot once, and
    // order[i] becomes slot i (neighbour references follow); free slots
    // are dropped. Not journaled.
    void reorder_tets(const std::vector<TetId>& order);

    // --- undo journal ---------------------------------------------------
    // While the journal is open, the first change to each tetrahedron slot
    // (record or flags) saves what the slot held, and the free list's
    // entries that allocation takes below where it stood are kept:
    // undo_journal() then puts the slots, flags and free list back exactly
    // as they were when the journal was opened, and drops the slots
    // appended since. What it costs is proportional to the slots changed,
    // where a copy of the mesh costs its size (flip recovery's rollback of
    // a failed search). Points are not journaled: no point may be added,
    // removed or moved while it is open.
    void open_journal();
    // Back to the mesh as it was at open_journal(); the journal stays open
    // and empty.
    void undo_journal();
    void close_journal();
    bool journal_open() const { return journal_open_; }

private:
    friend class SlotPool;
    static std::uint8_t constraint_bit(int f) { return static_cast<std::uint8_t>(kFlagConstraintFace0 << f); }

    struct alignas(32) TetRecord {
        VertexId v[4];
        FacetRef n[4];
    };
    static_assert(sizeof(TetRecord) == 32, "two tetrahedra per cache line");

    // A slot as it was when the journal was opened.
    struct SavedSlot {
        TetRecord record;
        TetId slot;
        std::uint8_t flags;
    };
    void before_change(TetId t) {
        if (journal_open_ && t < journal_.slot_count && journal_.stamp[t] != journal_.epoch) save_slot(t);
    }
    void save_slot(TetId t);

    LargeArray<double> coords_;
    LargeArray<TetRecord> tets_;
    LargeArray<std::uint8_t> flags_;
    std::vector<TetId> free_;
    // SlotPools taken from this mesh and not yet given back: while 0,
    // allocation does not look for the calling thread's pool (Delaunay
    // and recovery allocate in their inner loops).
    std::size_t slot_pools_ = 0;
    bool journal_open_ = false;
    struct Journal {
        std::uint32_t epoch = 0;            // one per open_journal()
        LargeArray<std::uint32_t> stamp;    // per slot: the epoch it was saved in
        std::vector<SavedSlot> saved;
        std::size_t slot_count = 0;         // slots when opened; later ones are dropped
        std::size_t free_low = 0;           // the free list's lowest size since
        std::vector<TetId> free_taken;      // its entries taken below where it stood, in order
    } journal_;
};

// The mesh's journal for one scope: opened here unless one is open
// already (then the caller's journal covers the changes and owns() is
// false), closed at the end of the scope however it ends.
class JournalScope {
public:
    explicit JournalScope(TetMesh& m) : m_(m), owns_(!m.journal_open()) {
        if (owns_) m_.open_journal();
    }
    ~JournalScope() {
        if (owns_) m_.close_journal();
    }
    JournalScope(const JournalScope&) = delete;
    JournalScope& operator=(const JournalScope&) = delete;
    bool owns() const { return owns_; }

private:
    TetMesh& m_;
    const bool owns_;
};

}  // namespace cbr::mesh
