// §5.1 Edge-added-point and face-added-point splitting, as one mechanism.
//
// An added point e lies on the surface: on an input edge (then every input
// triangle with that edge has a fan of sub-faces around e) or inside one
// triangle (one closed fan). The fans cut Ball(e) into wedges — two for a
// face point or a manifold edge, k for an edge of k triangles. Splitting
// removes e and puts one Steiner point s_W strictly inside each wedge W:
// each fan's polygon (its outer vertices P1 ... Pn) is triangulated
// without e, and W is rebuilt as the cone from s_W over its boundary — the
// faces of Ball(e) opposite e in W, and the polygon triangles on W's side.
//
// For a face point this is the paper's ball transformation (the polygon
// triangulated, coned to P and to its mirror P*); for an edge point on a
// manifold edge, its cap transformation (P1 Pn becomes an edge, cones to
// e and e*), except that both triangles at the edge are treated at once
// instead of giving up the neighbour's conforming recovery (§5.2 says the
// paper does): the surface stays a union of sub-faces after every split,
// so the splits can run in any order and each removes exactly one added
// point (Lemmas 1-2). When every added point is split, every input
// triangle is a union of sub-faces with only its corners as vertices:
// itself.
//
// Placement (the paper's perturbation by epsilon, §5.1): s_W = e + eps d_W,
// where d_W, the sum of the unit normals of W's fans pointing into W, lies
// inside W near e (for a reflex wedge it points into the region that sees
// both fans: the mirror side). eps is taken in the middle of the range
// that keeps every tetrahedron of the cone positively oriented (estimated,
// then tested exactly on the rounded s_W; smaller ones after). A wedge made of ghost
// tetrahedra (e on the hull) gets no point: the polygon triangles become
// hull faces. When no point near e sees the whole wedge (or only one
// extremely close to the surface does), the wedge grows instead: it takes
// in the tetrahedra beyond every far face a target point does not see, so
// the target cones the grown region (§5.1's cavity correction, driven by
// the point); earlier Steiner points inside it are absorbed. An exterior
// wedge that borders the convex hull (a nearly planar face of the surface
// on the hull: a rotated CAD cylinder's cap) may grow past the hull too,
// its point then a new hull vertex outside the old hull.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/surface_points.hpp"
#include "recover/tet_owners.hpp"

namespace cbr::recover {

class PointSplitting {
public:
    // `incident`: one tetrahedron per vertex, kept up to date.
    PointSplitting(mesh::TetMesh& m, SurfacePoints& points, std::vector<mesh::TetId>& incident)
        : m_(m), points_(points), incident_(incident) {}

    // Splits added point e; appends the Steiner points made to `steiner`.
    // e then belongs to no tetrahedron. False (why(); mesh unchanged) when
    // the fans around e are not as described or no placement works.
    bool split(mesh::VertexId e, std::vector<mesh::VertexId>& steiner);
    const std::string& why() const { return why_; }
    // Steiner points made so far (some may have been absorbed since by a
    // later split's grown wedge).
    std::size_t made() const { return made_; }

private:
    // A point e + eps d strictly inside the wedge bounded by `bounds`
    // (normals inward), in s; false when none is found.
    bool place_in_wedge(const double* pe, const double* d, const std::vector<std::array<mesh::VertexId, 3>>& bounds,
                        double shortest, std::array<double, 3>& s) const;
    bool place_by_growing(int w, const double* pe, const double* d, const std::vector<std::array<mesh::VertexId, 3>>& poly,
                          double shortest, const TetOwners& ball_wedge,
                          std::vector<mesh::FacetRef>& links, TetOwners& taken,
                          std::array<double, 3>& s) const;
    std::array<mesh::VertexId, 3> face_vertices(mesh::FacetRef r) const;
    bool absorbable(mesh::VertexId v) const;
    bool keeps_region_vertices(int w, const std::vector<std::array<mesh::VertexId, 3>>& poly,
                               const std::vector<mesh::FacetRef>& links, const TetOwners& taken) const;
    bool keeps_vertices(const std::vector<mesh::TetId>& old, const std::vector<std::array<mesh::VertexId, 4>>& fresh,
                        mesh::VertexId e, std::vector<mesh::VertexId>& absorbed) const;
    using CrossTest = std::function<bool(const double*, const double*, const double*)>;
    void grow_wedge(int w, const TetOwners& ball_wedge, std::vector<mesh::FacetRef>& links,
                    TetOwners& taken, const CrossTest& cross, std::size_t limit,
                    const double* beyond_hull = nullptr) const;
    bool sees_hull_face(mesh::TetId g, const double* p) const;
    bool keeps_far_face(mesh::FacetRef r, const double* p) const;
    bool fail(std::string why) {
        why_ = std::move(why);
        return false;
    }

    mesh::TetMesh& m_;
    SurfacePoints& points_;
    std::vector<mesh::TetId>& incident_;
    std::string why_;
    std::size_t made_ = 0;
};

}  // namespace cbr::recover
