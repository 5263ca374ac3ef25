#include "recover/surface_points.hpp"

#include <algorithm>

#include "mesh/errors.hpp"
#include "mesh/key_table.hpp"

namespace cbr::recover {

using mesh::VertexId;

SurfacePoints::SurfacePoints(const ConstraintFaces& faces, std::size_t vertex_count)
    : faces_(faces), corner_first_(vertex_count + 1, 0), first_new_(static_cast<VertexId>(vertex_count)) {
    for (std::size_t i = 0; i < faces_.size(); ++i)
        for (VertexId v : faces_.triangle(i)) ++corner_first_[v + 1];
    for (std::size_t v = 0; v < vertex_count; ++v) corner_first_[v + 1] += corner_first_[v];
    corner_faces_.resize(corner_first_.back());
    std::vector<std::uint32_t> fill(corner_first_.begin(), corner_first_.end() - 1);
    for (std::size_t i = 0; i < faces_.size(); ++i) {
        const Triangle& t = faces_.triangle(i);
        for (int k = 0; k < 3; ++k) corner_faces_[fill[t[k]]++] = static_cast<std::uint32_t>(i);
    }
}

SurfacePoints::Added& SurfacePoints::record(VertexId p) {
    if (p < first_new_) throw InternalError("SurfacePoints: an input point cannot be an added point");
    if (p - first_new_ >= added_.size()) added_.resize(p - first_new_ + 1);
    return added_[p - first_new_];
}

void SurfacePoints::add_edge_point(VertexId p, VertexId a, VertexId b) {
    record(p) = Added{a, b, npos, true};
    order_.push_back(p);
}

void SurfacePoints::add_face_point(VertexId p, std::size_t face) {
    record(p) = Added{0, 0, face, true};
    order_.push_back(p);
}

void SurfacePoints::remove(VertexId p) {
    if (find_added(p)) added_[p - first_new_].live = false;
}

bool SurfacePoints::on_edge(VertexId v, VertexId* a, VertexId* b, std::size_t* face) const {
    const Added* found = find_added(v);
    if (!found) throw InternalError("SurfacePoints::on_edge: not an added point");
    const Added& x = *found;
    if (x.face != npos) {
        if (face) *face = x.face;
        return false;
    }
    if (a) *a = x.a;
    if (b) *b = x.b;
    return true;
}

void SurfacePoints::faces_of(VertexId v, std::vector<std::size_t>& out) const {
    out.clear();
    if (const Added* x = find_added(v)) {
        if (x->face != npos) out.push_back(x->face);
        else
            for (std::uint32_t f : faces_of_edge(x->a, x->b)) out.push_back(f);
        return;
    }
    if (v + 1 >= corner_first_.size()) return;
    for (std::uint32_t k = corner_first_[v]; k < corner_first_[v + 1]; ++k) out.push_back(corner_faces_[k]);
}

bool SurfacePoints::belongs_to(VertexId v, std::size_t face) const {
    const Triangle& t = faces_.triangle(face);
    if (v == t[0] || v == t[1] || v == t[2]) return true;
    const Added* found = find_added(v);
    if (!found) return false;
    const Added& x = *found;
    if (x.face != npos) return x.face == face;
    const auto corner = [&](VertexId c) { return c == t[0] || c == t[1] || c == t[2]; };
    return corner(x.a) && corner(x.b);
}

std::size_t SurfacePoints::common_face(VertexId x, VertexId y, VertexId z) const {
    if (x == mesh::kGhostVertex || y == mesh::kGhostVertex || z == mesh::kGhostVertex) return npos;
    // Candidates from the vertex with the fewest triangles: an added point
    // has one or a few, a corner its whole umbrella.
    const VertexId pick = is_added(x) ? x : is_added(y) ? y : z;
    faces_of(pick, candidates_);
    for (std::size_t f : candidates_)
        if (belongs_to(x, f) && belongs_to(y, f) && belongs_to(z, f)) return f;
    return npos;
}

// An edge holding three distinct points holds at least one added point
// (it has only two ends): the edge of any added edge point among them is
// the only candidate.
bool SurfacePoints::on_one_edge(VertexId x, VertexId y, VertexId z) const {
    for (const VertexId v : {x, y, z}) {
        const Added* found = find_added(v);
        if (!found || found->face != npos) continue;
        const Added& e = *found;
        const auto on = [&](VertexId w) {
            if (w == e.a || w == e.b) return true;
            const Added* other = find_added(w);
            return other && other->face == npos && mesh::edge_key(other->a, other->b) == mesh::edge_key(e.a, e.b);
        };
        return on(x) && on(y) && on(z);
    }
    return false;
}

bool SurfacePoints::is_chain_link(VertexId x, VertexId y) const {
    // The input edge both would lie on: that of an added edge point among
    // them, or xy itself.
    std::uint64_t edge = mesh::edge_key(x, y);
    for (const VertexId v : {x, y}) {
        const Added* found = find_added(v);
        if (found && found->face == npos) edge = mesh::edge_key(found->a, found->b);
    }
    const auto it = chains_.find(edge);
    if (it == chains_.end()) return false;
    const std::vector<VertexId>& c = it->second;
    for (std::size_t i = 0; i + 1 < c.size(); ++i)
        if ((c[i] == x && c[i + 1] == y) || (c[i] == y && c[i + 1] == x)) return true;
    return false;
}

std::vector<std::uint32_t> SurfacePoints::faces_of_edge(VertexId a, VertexId b) const {
    // The triangles at a that also have b: a's umbrella is short.
    std::vector<std::uint32_t> out;
    if (a + 1 >= corner_first_.size()) return out;
    for (std::uint32_t k = corner_first_[a]; k < corner_first_[a + 1]; ++k) {
        const Triangle& t = faces_.triangle(corner_faces_[k]);
        if (t[0] == b || t[1] == b || t[2] == b) out.push_back(corner_faces_[k]);
    }
    return out;
}

std::vector<VertexId> SurfacePoints::chain(VertexId a, VertexId b) const {
    const auto it = chains_.find(mesh::edge_key(a, b));
    if (it == chains_.end()) return {};
    std::vector<VertexId> c = it->second;
    if (c.front() != a) std::reverse(c.begin(), c.end());
    return c;
}

void SurfacePoints::set_chain(VertexId a, VertexId b, std::vector<VertexId> chain) {
    if (chain.front() != std::min(a, b)) std::reverse(chain.begin(), chain.end());
    chains_[mesh::edge_key(a, b)] = std::move(chain);
}

void SurfacePoints::remove_from_chain(VertexId p) {
    const Added* found = find_added(p);
    if (!found) throw InternalError("SurfacePoints::remove_from_chain: not an added point");
    const Added& x = *found;
    auto& c = chains_.at(mesh::edge_key(x.a, x.b));
    c.erase(std::find(c.begin(), c.end(), p));
}

}  // namespace cbr::recover
