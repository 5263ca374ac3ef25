// The sizing field of full mesh generation (Du & Wang 2004, §6: "a sizing
// field is given or can be derived from the surface triangulation by
// interpolation"): a target edge length stored per vertex, interpolated
// linearly (barycentric) inside tetrahedra; every point inserted stores the
// value interpolated where it was inserted.
#pragma once

#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/constraint_faces.hpp"
#include "refine/refine_options.hpp"

namespace cbr::refine {

class SizingField {
public:
    // Builds the per-vertex field of m (every vertex present). At a surface
    // vertex: the mean length of its input edges (the surface is never
    // split, so the field there is the surface's), graded among surface
    // vertices over the edges of m: h(v) <= h(u) + grading |uv|
    // (Dijkstra). Elsewhere: the graded value capped by H
    // (options.target_size > 0), or H alone when !size_from_surface.
    SizingField(const mesh::TetMesh& m, const recover::ConstraintFaces& faces, const RefineOptions& options);

    double at(mesh::VertexId v) const { return h_[v]; }
    // Barycentric interpolation of the four corner values of tetrahedron t
    // at p (clamped to the corner range when p is slightly outside t).
    double interpolate(const mesh::TetMesh& m, mesh::TetId t, const double* p) const;
    // The value a point inserted at p inside t gets: the interpolated value
    // (raised by the growth rule when RefineOptions::growth > 0) capped by
    // H, or H alone.
    double for_new_point(const mesh::TetMesh& m, mesh::TetId t, const double* p) const;
    // The interior rule applied to a value: capped by H, or H alone.
    double interior(double value) const { return constant_ ? cap_ : (value < cap_ ? value : cap_); }
    // Appends the value of a new vertex (ids must follow in order).
    void add(double h) { h_.push_back(h); }
    // For ids taken ahead (the field points in halves): sets the value of
    // vertex v < size(), and drops the values from id `count` on.
    void set(mesh::VertexId v, double h) { h_[v] = h; }
    void truncate(std::size_t count) { h_.resize(count); }
    std::size_t size() const { return h_.size(); }

private:
    std::vector<double> h_;
    double cap_ = 0;         // H, or +inf
    bool constant_ = false;  // H alone off the surface
    double growth_ = 0;      // RefineOptions::growth
};

}  // namespace cbr::refine
