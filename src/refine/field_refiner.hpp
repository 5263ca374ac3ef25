// One refiner of field points (field_points.hpp): a queue of tetrahedra,
// each refined when it misses the sizing field or the quality bound by a
// point at its circumcentre, the midpoint of its longest over-long edge or
// its centroid (the rules are field_points.hpp's), inserted through the
// constrained insertion kernel. insert_field_points runs one for the border
// of its two halves and one for each half; a half's runs in half mode
// (run_round): it reads and changes only the half's tetrahedra and takes
// ids and slots set aside for the round.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <limits>
#include <vector>

#include "mesh/slot_pool.hpp"
#include "recover/protected_insertion.hpp"
#include "refine/locate.hpp"
#include "refine/refine_context.hpp"
#include "refine/tet_measures.hpp"
#include "refine/vertex_halves.hpp"

namespace cbr::refine {

class FieldRefiner {
public:
    // Half mode: an insertion needs its pool to hold its star's slots beyond
    // its cavity's, plus this margin (the correction may take in a few
    // tetrahedra).
    static constexpr std::size_t kSlotMargin = 64;

    // A queued tetrahedron, with its vertices: the slot may have been reused.
    struct Entry {
        mesh::TetId t;
        std::array<mesh::VertexId, 4> v;
    };

    // What one half of the mesh works with in a round of the halves: the
    // vertices' half labels (written for its new points) and its half, the
    // vertex ids taken ahead for its points ([next_id, end_id)), its slot
    // pool and its share of the point cap.
    struct HalfRound {
        std::vector<std::uint8_t>* label = nullptr;
        std::uint8_t half = 0;
        mesh::VertexId next_id = 0, end_id = 0;
        const mesh::SlotPool* pool = nullptr;
        std::size_t cap = 0;
        HalfClaim claim() const { return {label, half}; }
    };

    FieldRefiner(RefineContext& c, RefineStats& stats) : c_(c), m_(c.m), stats_(stats) {}
    // Queues the live tetrahedra of `seeds` in the domain.
    void queue_seeds(const std::vector<mesh::TetId>& seeds);
    // Refines until the queue is empty or the point cap (set_cap, else
    // point_cap()) is reached.
    void run_queue() { run_round(nullptr); }
    // Half mode: queues the claim's tetrahedra in slot order.
    void queue_claimed(const HalfClaim& claim);
    // Half mode (`round` given): refines until the queue is empty, the
    // round's ids or slots run short or the round's cap is reached; an entry
    // whose refinement would read or change a tetrahedron not the half's is
    // deferred (see hand_over). Returns whether entries are left for a next
    // round.
    bool run_round(HalfRound* round);
    void queue_tet(mesh::TetId t) { push(t); }
    // Half mode: renumbers the vertex ids in the queue, the deferred entries
    // and the log by `renumber`.
    template <typename Renumber>
    void renumber_queued(Renumber renumber) {
        for (std::deque<Entry>* list : {&queue_, &deferred_})
            for (Entry& e : *list)
                for (mesh::VertexId& v : e.v) v = renumber(v);
        if (log_)
            for (TetChange& change : *log_)
                for (auto* tets : {&change.replaced, &change.made})
                    for (std::array<mesh::VertexId, 4>& corners : *tets)
                        for (mesh::VertexId& v : corners) v = renumber(v);
    }
    // Each insertion's cavity and star go to `log` (nullptr: none).
    void set_log(std::vector<TetChange>* log) { log_ = log; }
    // Half mode, between rounds: drops the entries whose tetrahedron is no
    // longer the one queued. (Its slot may be another half's in the next
    // round: no half may read it then.)
    void drop_stale() {
        queue_.erase(std::remove_if(queue_.begin(), queue_.end(), [this](const Entry& e) { return !current(e); }),
                     queue_.end());
    }
    // Half mode: appends the deferred entries, then those still queued, to
    // the queue of `to`.
    void hand_over(FieldRefiner& to) const {
        to.queue_.insert(to.queue_.end(), deferred_.begin(), deferred_.end());
        to.queue_.insert(to.queue_.end(), queue_.begin(), queue_.end());
    }
    std::size_t point_cap() const;
    void set_cap(std::size_t cap) { cap_ = cap; }
    // With `label`: queues only tetrahedra of neither half of it from here
    // on (the border's refinement before the halves') and labels its new
    // points by their side of `plane`; with nullptr, queues all again.
    void keep_to_border(std::vector<std::uint8_t>* label, const MedianPlane& plane) {
        border_only_ = label;
        border_plane_ = plane;
    }

private:
    void push(mesh::TetId t) {
        if (border_only_ && common_half(*border_only_, m_, t) != kNoHalf) return;
        const mesh::VertexId* v = m_.vertices(t);
        queue_.push_back({t, {v[0], v[1], v[2], v[3]}});
    }
    // Refines the tetrahedron of e if it needs it; false when it stays as
    // it is (refused, or left for later in half mode: foreign_, starved_).
    bool refine_entry(const Entry& e);
    // Half mode: whether t is the half's (always true otherwise).
    bool claimed(mesh::TetId t) const { return half_ == nullptr || half_->claim().owns(m_, t); }
    bool current(const Entry& e) const {
        if (m_.is_free(e.t) || !c_.in_domain(e.t)) return false;
        const mesh::VertexId* v = m_.vertices(e.t);
        return v[0] == e.v[0] && v[1] == e.v[1] && v[2] == e.v[2] && v[3] == e.v[3];
    }
    bool meets_quality(mesh::TetId t) const;
    struct Probe {
        bool encroaches = false;
        bool foreign = false;  // half mode: the cavity needs a tetrahedron not the half's (the rest is partial)
        std::size_t boundary_faces = 0;  // the star's size (when the probe ran to the end)
        double gap = std::numeric_limits<double>::infinity();
        double star_quality = 2;  // when asked
        double nearest2 = std::numeric_limits<double>::infinity();  // squared distance to the nearest cavity vertex
        // The cavity (probe_cavity_) is the one the insertion would grow:
        // no ghost met, and no constraint face between two of its members
        // (where the insertion's growth refuses a tetrahedron).
        bool reusable = true;
    };
    // What makes a caller refuse a point, so that probe() can stop as soon
    // as it is certain: the cavity meets a constraint face whose diametral
    // ball holds the point, a constraint face's plane nearer than min_gap,
    // or a star quality at or below min_star_quality. The answer that
    // refuses is then exact; the other fields are partial.
    struct Refusal {
        bool encroaching = false;
        double min_gap = 0;
        double min_star_quality = -2;
    };
    Probe probe(mesh::TetId start, const double* p, bool want_star, const Refusal& refusal);
    void measure_constraint_face(mesh::TetId t, int f, const double* p, Probe& out) const;
    bool try_centroid(mesh::TetId t);
    bool insert(const Point& p, mesh::TetId start, const Probe& probed);
    bool insert_in_half(const Point& p, mesh::TetId start, const Probe& probed);
    void record(const recover::ProtectedInsertResult& res, std::int32_t region);
    bool try_circumcentre(mesh::TetId t);
    bool try_edge_midpoint(mesh::TetId t);
    Location locate(mesh::TetId start, const double* p) {
        const HalfClaim claim = half_ ? half_->claim() : HalfClaim{};
        const Location loc = locate_in_region(c_, start, p, half_ ? &claim : nullptr);
        if (loc.where == Located::kForeign) foreign_ = true;
        return loc;
    }

    RefineContext& c_;
    mesh::TetMesh& m_;
    RefineStats& stats_;
    std::deque<Entry> queue_;
    static constexpr std::size_t kNoCap = static_cast<std::size_t>(-1);
    std::size_t cap_ = kNoCap;
    std::vector<TetChange>* log_ = nullptr;
    std::vector<std::uint8_t>* border_only_ = nullptr;  // keep_to_border
    MedianPlane border_plane_;
    // Half mode (run_round): the round, the entries left to the border's
    // refinement, and why the current entry stopped: it needed a
    // tetrahedron not the half's (foreign_) or more ids or slots than the
    // round has left (starved_).
    HalfRound* half_ = nullptr;
    std::deque<Entry> deferred_;
    bool foreign_ = false;
    bool starved_ = false;
    recover::ProtectedInserter inserter_;  // keeps its scratch storage across insertions
    // probe()'s scratch: its cavity, and per slot whether a tetrahedron
    // was tested (kTested) and is in the cavity (kInCavity), in the
    // inserter's shared marks (the insertion that follows reads the same
    // words).
    static constexpr std::uint8_t kTested = 1u << 0;
    static constexpr std::uint8_t kInCavity = 1u << 1;
    std::vector<mesh::TetId> probe_cavity_;
};

}  // namespace cbr::refine
