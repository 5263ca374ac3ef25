// The Bowyer-Watson insertion kernel: locate a point by walking, grow the
// cavity of tetrahedra whose (perturbed) circumsphere contains it, and
// replace the cavity by the star of the point.
#pragma once

#include <cstdint>
#include <vector>

#include "geom/predicates.hpp"
#include "mesh/tet_mesh.hpp"

namespace cbr::delaunay {

class Kernel {
public:
    Kernel(mesh::TetMesh& mesh, geom::PredicateCounters* counters) : m_(mesh), counters_(counters) {}

    // Builds the first tetrahedron (a, b, c, d), which must be positively
    // oriented, and the four ghosts that close its hull.
    void build_first_tet(mesh::VertexId a, mesh::VertexId b, mesh::VertexId c, mesh::VertexId d);

    // Inserts vertex p (its coordinates already stored in the mesh). When p
    // has the same coordinates as a vertex already in the mesh, nothing is
    // changed and that vertex is returned; otherwise kGhostVertex.
    mesh::VertexId insert(mesh::VertexId p);

    // Starting tetrahedron of the next walk.
    void set_hint(mesh::TetId t) { hint_ = t; }
    void set_seed(std::uint64_t seed) { rng_ = seed | 1u; }

    // The tetrahedron that contains p (closed), or a ghost whose hull face
    // p lies strictly outside of.
    mesh::TetId locate(const double* p);

private:
    struct BoundaryFacet {
        mesh::TetId tet;     // cavity tetrahedron
        int face;            // its face on the cavity boundary
        mesh::FacetRef out;  // half-facet of the tetrahedron outside
    };

    bool in_conflict(mesh::TetId t, const double* p);
    void grow_cavity(mesh::TetId start, const double* p);
    void fill_cavity(mesh::VertexId p);
    mesh::VertexId coincident_vertex(mesh::TetId t, const double* p) const;
    bool link_star_by_table();
    mesh::FacetRef partner_across_edge(mesh::TetId t, int f, int g) const;
    int index_in(mesh::TetId t, mesh::VertexId v) const;
    std::uint32_t next_random() {
        rng_ ^= rng_ << 13;
        rng_ ^= rng_ >> 7;
        rng_ ^= rng_ << 17;
        return static_cast<std::uint32_t>(rng_);
    }

    mesh::TetMesh& m_;
    geom::PredicateCounters* counters_;
    mesh::TetId hint_ = 0;
    std::uint64_t rng_ = 0x2545F4914F6CDD1Dull;
    std::vector<mesh::TetId> cavity_, rejected_, stack_;
    std::vector<BoundaryFacet> boundary_;
    std::vector<mesh::TetId> new_tets_;
    // link_star_by_table's scratch: a local number per vertex (kNoLocal
    // between insertions: 1 byte per vertex), the locals of each boundary
    // triangle, the directed-edge table.
    static constexpr std::uint8_t kNoLocal = 0xFF;
    std::vector<std::uint8_t> vertex_local_, triangle_locals_;
    std::vector<mesh::VertexId> local_vertices_;
    std::vector<mesh::FacetRef> edge_table_;
};

}  // namespace cbr::delaunay
