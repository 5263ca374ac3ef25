#include "refine/field_refiner.hpp"

#include <algorithm>
#include <cmath>

#include "geom/predicates.hpp"
#include "mesh/slot_marks.hpp"

namespace cbr::refine {

using mesh::facet_tet;
using mesh::kFaceVertices;
using mesh::TetId;
using mesh::VertexId;

namespace {

// A fallback midpoint must be at least this fraction of its edge's length
// away from the constraint faces around it.
constexpr double kMinSurfaceGap = 0.1;

// Quality refinement stops at tetrahedra whose circumradius is below this
// fraction of the local size (see meets_quality).
constexpr double kMinQualityRadius = 0.5;

// A circumcentre nearer than this fraction of the circumradius to a vertex
// of its cavity is refused (see try_circumcentre).
constexpr double kMinCircumcentreGap = 0.1;

// Slivers: a radius ratio below this fails the quality bound whatever the
// radius-edge ratio says (a sliver can have a fine radius-edge ratio), and
// gets its centroid when its circumcentre is refused, if the star is at
// least kSliverGain times better.
constexpr double kSliverQuality = 0.1;
constexpr double kSliverGain = 2.0;

}  // namespace

// Also "met" when the circumradius is already below kMinQualityRadius times
// the local size: a circumcentre there would sit closer than that to the
// corners, and near small input angles (which the surface keeps) such
// insertions cascade without end (the classic limit of Delaunay
// refinement; TetGen's -Y meshes stop there too).
bool FieldRefiner::meets_quality(TetId t) const {
    const VertexId* v = m_.vertices(t);
    const double* p[4] = {m_.point(v[0]), m_.point(v[1]), m_.point(v[2]), m_.point(v[3])};
    if (radius_edge_ratio(p[0], p[1], p[2], p[3]) <= c_.options.quality_bound &&
        radius_ratio(p[0], p[1], p[2], p[3]) >= kSliverQuality)
        return true;
    Point cc;
    if (!circumcentre(p[0], p[1], p[2], p[3], cc)) return false;
    const double h = 0.25 * (c_.size.at(v[0]) + c_.size.at(v[1]) + c_.size.at(v[2]) + c_.size.at(v[3]));
    const double r = kMinQualityRadius * h;
    return squared_distance(cc.data(), p[0]) < r * r;
}

// p's (Bowyer-Watson) cavity, grown from start the way insert_protected
// grows it (insphere_sos conflicts, never across a constraint face), and
// what its boundary says: whether p lies in the diametral ball of a
// constraint face (it encroaches), its smallest distance to their planes
// (counted where its projection falls within the face's circumcircle),
// and, when asked, the smallest quality of the star (every boundary face
// coned to p; -1 when p does not see a boundary face strictly, where the
// §5.1 correction would change the cavity). Stops early once `refusal`
// holds: most candidates near a thin CAD wall encroach, and their
// cavities are the largest.
FieldRefiner::Probe FieldRefiner::probe(TetId start, const double* p, bool want_star, const Refusal& refusal) {
    Probe out;
    std::vector<TetId>& cavity = probe_cavity_;
    mesh::SlotMarks& marks = inserter_.shared_marks();
    marks.new_round(m_.slot_count());
    cavity.assign(1, start);
    marks.set(start, kTested | kInCavity);
    for (std::size_t i = 0; i < cavity.size(); ++i) {
        const TetId t = cavity[i];
        for (int f = 0; f < 4; ++f) {
            if (m_.is_constrained(t, f)) {
                measure_constraint_face(t, f, p, out);
                if ((refusal.encroaching && out.encroaches) || out.gap < refusal.min_gap) return out;
                continue;
            }
            const TetId n = facet_tet(m_.neighbor(t, f));
            if (m_.is_ghost(n)) {
                out.reusable = false;  // the insertion's growth tests ghosts
                if (half_) {
                    out.foreign = foreign_ = true;
                    return out;
                }
                continue;
            }
            if (marks.has(n, kTested)) continue;
            marks.set(n, kTested);
            const VertexId* w = m_.vertices(n);
            if (geom::insphere_sos(m_.point(w[0]), m_.point(w[1]), m_.point(w[2]), m_.point(w[3]), p) > 0) {
                // In half mode n's corners may be read (n shares a face
                // with the half's t), not n's neighbours unless it is the
                // half's.
                if (!claimed(n)) {
                    out.foreign = foreign_ = true;
                    return out;
                }
                cavity.push_back(n);
                marks.set(n, kInCavity);
            }
        }
    }
    for (const TetId t : cavity) {
        const VertexId* v = m_.vertices(t);
        for (int f = 0; f < 4; ++f) {
            const bool constrained = m_.is_constrained(t, f);
            const bool inner = marks.has(facet_tet(m_.neighbor(t, f)), kInCavity);
            if (constrained && inner) out.reusable = false;
            if (!constrained && inner) continue;  // interior face
            ++out.boundary_faces;
            const int* k = kFaceVertices[f];
            const double* a = m_.point(v[k[0]]);
            const double* b = m_.point(v[k[1]]);
            const double* c = m_.point(v[k[2]]);
            for (const double* corner : {a, b, c}) out.nearest2 = std::min(out.nearest2, squared_distance(p, corner));
            if (want_star && out.star_quality >= 0) {
                if (geom::orient3d(a, b, c, p) <= 0) out.star_quality = -1;
                else out.star_quality = std::min(out.star_quality, radius_ratio(a, b, c, p));
                if (out.star_quality <= refusal.min_star_quality) return out;
            }
        }
    }
    return out;
}

// Whether p encroaches on constraint face f of t (lies in its diametral
// ball), and its distance to the face's plane where p's projection falls
// within the face's circumcircle, folded into `out`.
void FieldRefiner::measure_constraint_face(TetId t, int f, const double* p, Probe& out) const {
    const VertexId* v = m_.vertices(t);
    const int* k = kFaceVertices[f];
    const double* a = m_.point(v[k[0]]);
    const double* b = m_.point(v[k[1]]);
    const double* c = m_.point(v[k[2]]);
    Point centre;
    double r2 = 0;
    if (!triangle_circumsphere(a, b, c, centre, r2)) return;
    const double d2 = squared_distance(p, centre.data());
    if (d2 < r2) out.encroaches = true;
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const double h = (n[0] * (p[0] - a[0]) + n[1] * (p[1] - a[1]) + n[2] * (p[2] - a[2])) / std::sqrt(nn);
    if (d2 - h * h < r2) out.gap = std::min(out.gap, std::fabs(h));
}

// A sliver (radius ratio under kSliverQuality) whose circumcentre was
// refused: its centroid, when the star it would make is strictly better
// than the sliver (checked on the cavity before inserting: there is no
// undo).
bool FieldRefiner::try_centroid(TetId t) {
    const VertexId* v = m_.vertices(t);
    const double* q[4] = {m_.point(v[0]), m_.point(v[1]), m_.point(v[2]), m_.point(v[3])};
    const double old_q = radius_ratio(q[0], q[1], q[2], q[3]);
    if (old_q >= kSliverQuality) return false;
    Point g;
    for (int k = 0; k < 3; ++k) g[k] = 0.25 * (q[0][k] + q[1][k] + q[2][k] + q[3][k]);
    const Location loc = locate(t, g.data());
    if (loc.where != Located::kInside) return false;
    Refusal refusal;
    refusal.encroaching = true;
    refusal.min_star_quality = kSliverGain * old_q;
    const Probe pr = probe(loc.tet, g.data(), true, refusal);
    if (pr.foreign) return false;
    if (pr.encroaches || pr.star_quality <= kSliverGain * old_q) return false;
    return insert(g, loc.tet, pr);
}

// Inserts p (found in `start`), whose cavity `probed` describes: when the
// probe's cavity is the one the insertion would grow, it is handed over
// instead of grown again (same set of tetrahedra, so the same star).
bool FieldRefiner::insert(const Point& p, TetId start, const Probe& probed) {
    if (half_) return insert_in_half(p, start, probed);
    const std::int32_t region = c_.region(start);
    const double h = c_.size.for_new_point(m_, start, p.data());
    const VertexId id = m_.add_points(p.data(), 1);
    const recover::ProtectedInsertResult& res = probed.reusable
                                                    ? inserter_.insert_in_cavity(m_, id, start, probe_cavity_)
                                                    : inserter_.insert(m_, id, start);
    if (!res.ok) {
        m_.truncate_vertices(id);
        return false;
    }
    c_.add_vertex(h);
    if (border_only_) border_only_->push_back(border_plane_.half_of(p.data()));
    record(res, region);
    return true;
}

// insert in half mode: the point takes the round's next id (its
// coordinates, field value and label written there) and its cavity must be
// the probe's, all the half's; the correction may not take in a
// tetrahedron that is not (the claim blocks its faces). Any failure leaves
// the tetrahedron to the border's refinement, which tries it again whole.
bool FieldRefiner::insert_in_half(const Point& p, TetId start, const Probe& probed) {
    if (!probed.reusable) {
        foreign_ = true;
        return false;
    }
    HalfRound& round = *half_;
    // The star takes boundary_faces slots and frees the cavity's; the
    // correction may take in a few tetrahedra more.
    if (round.next_id == round.end_id || round.pool->size() + probe_cavity_.size() < probed.boundary_faces + kSlotMargin) {
        starved_ = true;
        return false;
    }
    const std::int32_t region = c_.region(start);
    const double h = c_.size.for_new_point(m_, start, p.data());
    const VertexId id = round.next_id;
    m_.set_point(id, p.data());
    const recover::ProtectedInsertResult& res = inserter_.insert_in_cavity(
        m_, id, start, probe_cavity_, [this](TetId t, int) { return !claimed(t); });
    if (!res.ok) {
        foreign_ = true;
        return false;
    }
    ++round.next_id;
    (*round.label)[id] = round.half;
    c_.size.set(id, h);
    record(res, region);
    return true;
}

void FieldRefiner::record(const recover::ProtectedInsertResult& res, std::int32_t region) {
    stats_.cavity_tets += res.initial_cavity + res.added - res.removed;
    for (TetId t : res.created) {
        c_.set_region(t, region);
        push(t);
    }
    ++stats_.field_points;
    if (log_) {
        TetChange change;
        change.replaced = res.cavity;
        for (TetId t : res.created) change.made.push_back({m_.vertex(t, 0), m_.vertex(t, 1), m_.vertex(t, 2), m_.vertex(t, 3)});
        log_->push_back(std::move(change));
    }
}

bool FieldRefiner::try_circumcentre(TetId t) {
    const VertexId* v = m_.vertices(t);
    Point cc;
    if (!circumcentre(m_.point(v[0]), m_.point(v[1]), m_.point(v[2]), m_.point(v[3]), cc)) return false;
    const Location loc = locate(t, cc.data());
    if (loc.where != Located::kInside && loc.where != Located::kOnFace) return false;
    Refusal refusal;
    refusal.encroaching = true;
    const Probe pr = probe(loc.tet, cc.data(), false, refusal);
    if (pr.foreign) return false;
    if (pr.encroaches) return false;
    // In a Delaunay cavity no vertex is nearer to the circumcentre than the
    // circumradius; the cavity correction and the protected faces can
    // leave one much nearer, and a point there makes needles and slivers
    // that nothing removes later (common3d-fandisk: two field points 5e-6
    // apart, at a local size of 0.05).
    const double r2 = squared_distance(cc.data(), m_.point(v[0]));
    if (pr.nearest2 < kMinCircumcentreGap * kMinCircumcentreGap * r2) return false;
    return insert(cc, loc.tet, pr);
}

bool FieldRefiner::try_edge_midpoint(TetId t) {
    const VertexId* v = m_.vertices(t);
    int bi = -1, bj = -1;
    double worst = 1;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            if (c_.edge_within_size(v[i], v[j])) continue;
            const double bound = kEdgeFactor * c_.edge_size(v[i], v[j]);
            const double excess = std::sqrt(squared_distance(m_.point(v[i]), m_.point(v[j]))) / bound;
            if (excess > worst) worst = excess, bi = i, bj = j;
        }
    if (bi < 0) return false;
    const double* a = m_.point(v[bi]);
    const double* b = m_.point(v[bj]);
    const Point mid = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
    const Location loc = locate(t, mid.data());
    if (loc.where != Located::kInside && loc.where != Located::kOnFace) return false;
    // Too close to the surface: splitting again and again toward a face
    // that cannot be split would only make flat elements.
    const double length = std::sqrt(squared_distance(a, b));
    Refusal refusal;
    refusal.min_gap = kMinSurfaceGap * length;
    const Probe pr = probe(loc.tet, mid.data(), false, refusal);
    if (pr.foreign) return false;
    if (pr.gap < kMinSurfaceGap * length) return false;
    return insert(mid, loc.tet, pr);
}

// A guard against runaway refinement: 10x the number of points an ideal
// mesh of the field would have (about one point per 5 tetrahedra), plus a
// margin.
std::size_t FieldRefiner::point_cap() const {
    double ideal_tets = 0;
    for (TetId t = 0; t < m_.slot_count(); ++t) {
        if (!c_.in_domain(t)) continue;
        const VertexId* v = m_.vertices(t);
        const double* a = m_.point(v[0]);
        double h = c_.size.at(v[0]);
        for (int i = 1; i < 4; ++i) h = std::min(h, c_.size.at(v[i]));
        const double six_v = six_volume(a, m_.point(v[1]), m_.point(v[2]), m_.point(v[3]));
        // regular tetrahedron of edge h: volume h^3 / (6 sqrt 2)
        ideal_tets += (six_v / 6) / (h * h * h / 8.48528137423857);
    }
    return static_cast<std::size_t>(std::min(2.0 * ideal_tets + 1000.0, 1.0e9));
}

bool FieldRefiner::refine_entry(const Entry& e) {
    foreign_ = starved_ = false;
    const bool size_ok = c_.tet_within_size(e.t);
    if (size_ok && meets_quality(e.t)) return false;
    if (try_circumcentre(e.t)) return true;
    if (foreign_ || starved_) return false;
    if (!size_ok && try_edge_midpoint(e.t)) {
        ++stats_.size_fallbacks;
        return true;
    }
    if (foreign_ || starved_) return false;
    if (try_centroid(e.t)) return true;
    if (!foreign_ && !starved_) ++stats_.rejected;
    return false;
}

void FieldRefiner::queue_seeds(const std::vector<TetId>& seeds) {
    for (TetId t : seeds)
        if (t < m_.slot_count() && !m_.is_free(t) && c_.in_domain(t)) push(t);
}

void FieldRefiner::queue_claimed(const HalfClaim& claim) {
    for (TetId t = 0; t < m_.slot_count(); ++t)
        if (c_.in_domain(t) && claim.owns(m_, t)) push(t);
}

bool FieldRefiner::run_round(HalfRound* round) {
    half_ = round;
    if (!round && cap_ == kNoCap) cap_ = point_cap();
    const std::size_t cap = round ? round->cap : cap_;
    bool left = false;
    while (!queue_.empty()) {
        const Entry e = queue_.front();
        if (!current(e)) {
            queue_.pop_front();
            continue;
        }
        if (stats_.field_points >= cap && !(c_.tet_within_size(e.t) && meets_quality(e.t))) {
            stats_.point_cap_hit = true;
            break;
        }
        refine_entry(e);
        if (starved_) {  // half mode, nothing changed: the entry waits for the next round
            left = true;
            break;
        }
        queue_.pop_front();
        if (foreign_) deferred_.push_back(e);  // half mode
    }
    half_ = nullptr;
    return left;
}

}  // namespace cbr::refine
