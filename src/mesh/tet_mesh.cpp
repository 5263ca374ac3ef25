#include "mesh/tet_mesh.hpp"

#include <stdexcept>

namespace cbr::mesh {

VertexId TetMesh::add_points(const double* xyz, std::size_t count) {
    const std::size_t first = vertex_count();
    if (count > kMaxVertices - first) throw std::length_error("too many points");
    coords_.insert(coords_.end(), xyz, xyz + 3 * count);
    return static_cast<VertexId>(first);
}

void TetMesh::truncate_vertices(std::size_t count) {
    if (count < vertex_count()) coords_.resize(3 * count);
}

void TetMesh::set_vertices(TetId t, VertexId a, VertexId b, VertexId c, VertexId d) {
    VertexId* v = tets_[t].v;
    v[0] = a;
    v[1] = b;
    v[2] = c;
    v[3] = d;
}

TetId TetMesh::allocate_tet() {
    if (!free_.empty()) {
        const TetId t = free_.back();
        free_.pop_back();
        flags_[t] = 0;
        return t;
    }
    const std::size_t t = flags_.size();
    if (t >= kMaxTets) throw std::length_error("the mesh would exceed 2^30 tetrahedra");
    tets_.emplace_back();
    flags_.push_back(0);
    return static_cast<TetId>(t);
}

void TetMesh::release_tet(TetId t) {
    flags_[t] = kFlagFree;
    free_.push_back(t);
}

void TetMesh::reserve_tets(std::size_t count) {
    if (count > kMaxTets) count = kMaxTets;
    tets_.reserve(count);
    flags_.reserve(count);
}

void TetMesh::clear_tets() {
    tets_.clear();
    flags_.clear();
    free_.clear();
}

}  // namespace cbr::mesh
