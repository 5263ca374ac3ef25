#include "recover/constraint_faces.hpp"

#include <algorithm>
#include <unordered_set>

namespace cbr::recover {
namespace {

Triangle sorted(mesh::VertexId a, mesh::VertexId b, mesh::VertexId c) {
    Triangle t = {a, b, c};
    std::sort(t.begin(), t.end());
    return t;
}

}  // namespace

std::size_t ConstraintFaces::KeyHash::operator()(const Triangle& k) const {
    std::uint64_t h = k[0];
    h = h * 0x9E3779B97F4A7C15ull + k[1];
    h = h * 0x9E3779B97F4A7C15ull + k[2];
    return static_cast<std::size_t>(h ^ (h >> 29));
}

ConstraintFaces::ConstraintFaces(std::vector<Triangle> triangles, std::vector<std::int32_t> labels)
    : triangles_(std::move(triangles)), labels_(std::move(labels)) {
    labels_.resize(triangles_.size(), 0);
    index_.reserve(triangles_.size());
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
        const Triangle& t = triangles_[i];
        index_.emplace(sorted(t[0], t[1], t[2]), static_cast<std::uint32_t>(i));
    }
}

std::size_t ConstraintFaces::find(mesh::VertexId a, mesh::VertexId b, mesh::VertexId c) const {
    const auto it = index_.find(sorted(a, b, c));
    return it == index_.end() ? npos : it->second;
}

std::size_t ConstraintFaces::vertex_count() const {
    std::unordered_set<mesh::VertexId> used;
    for (const Triangle& t : triangles_) used.insert(t.begin(), t.end());
    return used.size();
}

std::vector<std::size_t> mark_present_faces(mesh::TetMesh& m, const ConstraintFaces& faces) {
    std::vector<char> present(faces.size(), 0);
    for (mesh::TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        for (int f = 0; f < 4; ++f) {
            const mesh::FacetRef across = m.neighbor(t, f);
            if (mesh::facet_tet(across) < t) continue;  // each face once
            const mesh::VertexId* v = m.vertices(t);
            const mesh::VertexId a = v[mesh::kFaceVertices[f][0]], b = v[mesh::kFaceVertices[f][1]],
                                 c = v[mesh::kFaceVertices[f][2]];
            if (a == mesh::kGhostVertex || b == mesh::kGhostVertex || c == mesh::kGhostVertex) continue;
            const std::size_t i = faces.find(a, b, c);
            if (i == ConstraintFaces::npos) continue;
            present[i] = 1;
            m.set_constrained(t, f, true);
            m.set_constrained(mesh::facet_tet(across), mesh::facet_face(across), true);
        }
    }
    std::vector<std::size_t> missing;
    for (std::size_t i = 0; i < present.size(); ++i)
        if (!present[i]) missing.push_back(i);
    return missing;
}

}  // namespace cbr::recover
