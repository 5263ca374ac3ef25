// The input surface as constraints: triangles in mesh (internal) vertex
// ids with their labels, looked up by vertex set.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::recover {

using Triangle = std::array<mesh::VertexId, 3>;

class ConstraintFaces {
public:
    static constexpr std::size_t npos = ~std::size_t{0};

    ConstraintFaces() = default;
    // Triangles must be valid (distinct ids, no duplicate triangle): the
    // surface check runs first.
    ConstraintFaces(std::vector<Triangle> triangles, std::vector<std::int32_t> labels);

    std::size_t size() const { return triangles_.size(); }
    const Triangle& triangle(std::size_t i) const { return triangles_[i]; }
    const std::vector<Triangle>& triangles() const { return triangles_; }
    std::int32_t label(std::size_t i) const { return labels_[i]; }
    // Index of the triangle with vertices {a, b, c} in any order, or npos.
    std::size_t find(mesh::VertexId a, mesh::VertexId b, mesh::VertexId c) const;
    // Number of distinct vertices used by the triangles.
    std::size_t vertex_count() const;
    // Whether ab (either order) is an edge of an input triangle. Vertices
    // that no triangle uses (Steiner points, field points, the ghost
    // vertex) have none.
    bool has_edge(mesh::VertexId a, mesh::VertexId b) const;

private:
    void index_edges(std::size_t n);  // n: above every vertex id used
    // Lookup by smallest vertex: the triangles whose smallest vertex is x
    // are entries [first_[x], first_[x + 1]), as (middle, largest, index).
    // Two per vertex on average, and mesh faces met in storage order have
    // nearby vertex ids (the points are inserted along a Hilbert curve), so
    // the lookup of the constrained faces in storage order (regions.cpp)
    // stays in cache, where a hash table would miss on nearly every face;
    // facets_of_mesh files the triangles the same way.
    struct Entry {
        mesh::VertexId middle, largest;
        std::uint32_t index;
    };
    std::vector<Triangle> triangles_;
    std::vector<std::int32_t> labels_;
    std::vector<std::uint32_t> first_;
    std::vector<Entry> entries_;
    // The edges the same way: those whose smaller vertex is x have their
    // larger ends in edge_ends_[edge_first_[x], edge_first_[x + 1]),
    // ascending, each once. Flip recovery asks for every edge it would
    // remove, refinement for every edge it would flip or split; a hash set
    // of the edges (the lookup before) was rebuilt by each of them, and on
    // a surface of a million triangles its growth alone was 5% of the
    // recovery.
    std::vector<std::uint32_t> edge_first_;
    std::vector<mesh::VertexId> edge_ends_;
};

// No facet: facets_of_mesh's answer for a triangle that is not a face.
inline constexpr mesh::FacetRef kNoFacet = ~mesh::FacetRef{0};

// Marks, on both sides, every mesh face that is an input triangle as a
// constraint face, and returns the indices of the input triangles that are
// not faces of the mesh, in increasing order: from facets_of_mesh of
// faces' triangles on m, or from `found` when given, that same answer
// computed on m as it is now (the surface check's, just before; each facet
// is checked to hold its triangle, and if one does not, facets_of_mesh
// runs after all).
std::vector<std::size_t> mark_present_faces(mesh::TetMesh& m, const ConstraintFaces& faces,
                                            const std::vector<mesh::FacetRef>* found = nullptr);

// Per triangle of `tris` (any ids, unchecked): the facet of a live
// tetrahedron of m that holds it (the lower slot of the two), or kNoFacet
// (also for an id m does not have, the ghost vertex's included, or a
// repeated id). Changes nothing. `threads`: how many threads may share the
// scan of the mesh's faces (mesh/chunks.hpp); the same answer with any.
std::vector<mesh::FacetRef> facets_of_mesh(const mesh::TetMesh& m, const std::vector<Triangle>& tris,
                                           int threads = 1);

}  // namespace cbr::recover
