#include "delaunay/kernel.hpp"

#include "mesh/errors.hpp"

namespace cbr::delaunay {

using mesh::FacetRef;
using mesh::kFaceVertices;
using mesh::kGhostVertex;
using mesh::TetId;
using mesh::VertexId;

namespace {
constexpr std::uint8_t kInCavity = mesh::kFlagMarkA;
constexpr std::uint8_t kRejected = mesh::kFlagMarkB;
}  // namespace

void Kernel::build_first_tet(VertexId a, VertexId b, VertexId c, VertexId d) {
    const TetId t = m_.allocate_tet();
    m_.set_vertices(t, a, b, c, d);
    TetId ghosts[4];
    for (int f = 0; f < 4; ++f) {
        // kFaceVertices[f] faces into t; the ghost needs it facing out.
        const VertexId* v = m_.vertices(t);
        const VertexId x = v[kFaceVertices[f][0]], y = v[kFaceVertices[f][1]], z = v[kFaceVertices[f][2]];
        ghosts[f] = m_.allocate_tet();
        m_.set_vertices(ghosts[f], x, z, y, kGhostVertex);
        m_.link(mesh::make_facet(t, f), mesh::make_facet(ghosts[f], 3));
    }
    // Ghosts f and h share the edge of t's vertices other than f and h;
    // in ghost f that face is opposite t's vertex h.
    for (int f = 0; f < 4; ++f)
        for (int h = f + 1; h < 4; ++h)
            m_.link(mesh::make_facet(ghosts[f], index_in(ghosts[f], m_.vertex(t, h))),
                    mesh::make_facet(ghosts[h], index_in(ghosts[h], m_.vertex(t, f))));
    hint_ = t;
}

TetId Kernel::locate(const double* p) {
    TetId t = hint_;
    if (m_.is_free(t)) t = 0;
    while (m_.is_free(t)) ++t;
    if (m_.is_ghost(t)) t = mesh::facet_tet(m_.neighbor(t, 3));
    int came_from = -1;
    // The visibility walk terminates in a Delaunay triangulation
    // (Edelsbrunner's acyclicity theorem); the bound only guards against a
    // corrupted mesh turning into a hang.
    const std::size_t max_steps = m_.slot_count() + 16;
    for (std::size_t step = 0; step < max_steps; ++step) {
        if (m_.is_ghost(t)) return t;
        const VertexId* v = m_.vertices(t);
        const int start = static_cast<int>(next_random() & 3u);
        int exit_face = -1;
        for (int k = 0; k < 4; ++k) {
            const int f = (start + k) & 3;
            if (f == came_from) continue;
            const double* a = m_.point(v[kFaceVertices[f][0]]);
            const double* b = m_.point(v[kFaceVertices[f][1]]);
            const double* c = m_.point(v[kFaceVertices[f][2]]);
            if (geom::orient3d(a, b, c, p, counters_) < 0) {
                exit_face = f;
                break;
            }
        }
        if (exit_face < 0) return t;
        const FacetRef across = m_.neighbor(t, exit_face);
        t = mesh::facet_tet(across);
        came_from = mesh::facet_face(across);
    }
    throw InternalError("point location did not terminate");
}

bool Kernel::in_conflict(TetId t, const double* p) {
    const VertexId* v = m_.vertices(t);
    const double* a = m_.point(v[0]);
    const double* b = m_.point(v[1]);
    const double* c = m_.point(v[2]);
    if (v[3] == kGhostVertex) {
        // Conflict with a ghost: p strictly outside its hull face, or in its
        // plane and inside the face's (perturbed) circumcircle.
        const int side = geom::orient3d(a, b, c, p, counters_);
        if (side != 0) return side > 0;
        return geom::incircle_coplanar_sos(a, b, c, p, counters_) > 0;
    }
    return geom::insphere_sos(a, b, c, m_.point(v[3]), p, counters_) > 0;
}

void Kernel::grow_cavity(TetId start, const double* p) {
    cavity_.clear();
    rejected_.clear();
    boundary_.clear();
    stack_.clear();
    m_.set_mark(start, kInCavity);
    cavity_.push_back(start);
    stack_.push_back(start);
    while (!stack_.empty()) {
        const TetId t = stack_.back();
        stack_.pop_back();
        for (int f = 0; f < 4; ++f) {
            const FacetRef out = m_.neighbor(t, f);
            const TetId n = mesh::facet_tet(out);
            if (m_.has_mark(n, kInCavity)) continue;
            if (!m_.has_mark(n, kRejected)) {
                if (in_conflict(n, p)) {
                    m_.set_mark(n, kInCavity);
                    cavity_.push_back(n);
                    stack_.push_back(n);
                    continue;
                }
                m_.set_mark(n, kRejected);
                rejected_.push_back(n);
            }
            boundary_.push_back({t, f, out});
        }
    }
    for (TetId t : rejected_) m_.clear_mark(t, kRejected);
}

void Kernel::fill_cavity(VertexId p) {
    // Each boundary face, seen from its cavity tetrahedron t, becomes the
    // tetrahedron t with p in place of the vertex opposite the face: p is
    // on the same side of the face as that vertex (the cavity is
    // star-shaped from p), so the orientation is kept. The old t keeps a
    // link to its replacement across that face until the links are made.
    constexpr FacetRef kUnlinked = 0xFFFFFFFFu;
    new_tets_.clear();
    for (const BoundaryFacet& bf : boundary_) {
        const TetId nt = m_.allocate_tet();
        const VertexId* v = m_.vertices(bf.tet);
        m_.set_vertices(nt, v[0], v[1], v[2], v[3]);
        m_.set_vertex(nt, bf.face, p);
        for (int g = 0; g < 4; ++g) m_.set_neighbor(nt, g, kUnlinked);
        m_.link(mesh::make_facet(nt, bf.face), bf.out);
        m_.set_neighbor(bf.tet, bf.face, mesh::make_facet(nt, bf.face));
        new_tets_.push_back(nt);
    }
    if (!link_star_by_table()) {
        for (std::size_t i = 0; i < boundary_.size(); ++i) {
            const BoundaryFacet& bf = boundary_[i];
            for (int g = 0; g < 4; ++g)
                if (g != bf.face && m_.neighbor(new_tets_[i], g) == kUnlinked)
                    m_.link(mesh::make_facet(new_tets_[i], g), partner_across_edge(bf.tet, bf.face, g));
        }
    }
    for (TetId t : cavity_) m_.release_tet(t);
    hint_ = new_tets_.back();
}

// The new tetrahedra meet across faces through p. Read in kFaceVertices
// order, every boundary triangle of the cavity has its normal pointing
// into the cavity, so all are oriented alike and the neighbour across the
// directed edge a -> b of one triangle holds the edge as b -> a. With small
// local numbers for the boundary vertices, a table of directed edges pairs
// them: three passes, no search, hardly a data-dependent branch (the
// pivoting of partner_across_edge cost a quarter of the insertion time).
// False, with nothing changed, when the cavity has more boundary vertices
// than local numbers.
bool Kernel::link_star_by_table() {
    if (vertex_local_.size() < m_.vertex_count()) vertex_local_.resize(m_.vertex_count(), kNoLocal);
    int count = 0, ghost_local = -1;
    local_vertices_.clear();
    triangle_locals_.resize(3 * boundary_.size());
    bool fits = true;
    for (std::size_t i = 0; i < boundary_.size() && fits; ++i) {
        const BoundaryFacet& bf = boundary_[i];
        const VertexId* v = m_.vertices(bf.tet);
        for (int k = 0; k < 3; ++k) {
            const VertexId x = v[kFaceVertices[bf.face][k]];
            int local;
            if (x == kGhostVertex) {
                if (ghost_local < 0) ghost_local = count++;
                local = ghost_local;
            } else {
                std::uint8_t& l = vertex_local_[x];
                if (l == kNoLocal) {
                    l = static_cast<std::uint8_t>(count++);
                    local_vertices_.push_back(x);
                }
                local = l;
            }
            triangle_locals_[3 * i + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(local);
        }
        fits = count < kNoLocal;
    }
    const auto stride = static_cast<std::size_t>(count);
    if (fits) {
        edge_table_.resize(stride * stride);
        for (int pass = 0; pass < 2; ++pass)
            for (std::size_t i = 0; i < boundary_.size(); ++i) {
                const int f = boundary_[i].face;
                const std::uint8_t* l = &triangle_locals_[3 * i];
                for (int k = 0; k < 3; ++k) {
                    const std::size_t a = l[k], b = l[(k + 1) % 3];
                    const int opposite = kFaceVertices[f][(k + 2) % 3];  // the new face holds p, a, b
                    if (pass == 0)
                        edge_table_[a * stride + b] = mesh::make_facet(new_tets_[i], opposite);
                    else
                        m_.set_neighbor(new_tets_[i], opposite, edge_table_[b * stride + a]);
                }
            }
    }
    for (VertexId x : local_vertices_) vertex_local_[x] = kNoLocal;
    return fits;
}

// The new tetrahedron built on boundary face f of cavity tetrahedron t
// meets its neighbour through face g, which holds p and the edge E of the
// two vertices at positions other than f and g. That neighbour is built on
// the next boundary face around E: turn around E through the cavity,
// starting across face g of t, until a face whose far side is a new
// tetrahedron. At each step `cur` holds E, x (on the face just entered) and
// y (opposite the face to cross next).
FacetRef Kernel::partner_across_edge(TetId t, int f, int g) const {
    TetId cur = t;
    VertexId x = m_.vertex(t, f), y = m_.vertex(t, g);
    for (;;) {
        const FacetRef across = m_.neighbor(cur, index_in(cur, y));
        const TetId next = mesh::facet_tet(across);
        if (!m_.has_mark(next, kInCavity)) {
            // next = cur with y replaced by p: the shared face (p, E) is
            // opposite x.
            return mesh::make_facet(next, index_in(cur, x));
        }
        y = x;
        x = m_.vertex(next, mesh::facet_face(across));
        cur = next;
    }
}

int Kernel::index_in(TetId t, VertexId v) const {
    // v is a vertex of t, so exactly one term is 1: no data-dependent
    // branch (a chain of tests here mispredicted about half the time).
    const VertexId* w = m_.vertices(t);
    return (w[1] == v) + 2 * (w[2] == v) + 3 * (w[3] == v);
}

VertexId Kernel::coincident_vertex(TetId t, const double* p) const {
    if (m_.is_ghost(t)) return kGhostVertex;
    for (int i = 0; i < 4; ++i) {
        if (geom::same_point(m_.point(m_.vertex(t, i)), p)) return m_.vertex(t, i);
    }
    return kGhostVertex;
}

VertexId Kernel::insert(VertexId p) {
    const double* xyz = m_.point(p);
    const TetId t = locate(xyz);
    // A point equal to a vertex lies in the closed tetrahedra around that
    // vertex only, so the walk ends in one of them.
    const VertexId twin = coincident_vertex(t, xyz);
    if (twin != kGhostVertex) return twin;
    // t contains p (or, for a ghost, sees it strictly outside): t is in
    // conflict without any test, since a closed tetrahedron minus its
    // vertices lies inside the open circumball.
    grow_cavity(t, xyz);
    fill_cavity(p);
    return kGhostVertex;
}

}  // namespace cbr::delaunay
