#include "recover/constraint_faces.hpp"

#include <algorithm>

#include "mesh/chunks.hpp"
#include "mesh/huge_pages.hpp"
#include "mesh/vertex_buckets.hpp"

namespace cbr::recover {
namespace {

// The three ids in increasing order. Called for every face of the mesh
// (facets_of_mesh: igea's 1.7 million), so three comparisons instead of a
// call of std::sort.
Triangle sorted(mesh::VertexId a, mesh::VertexId b, mesh::VertexId c) {
    const mesh::VertexId lo = std::min(a, b), hi = std::max(a, b);
    return {std::min(lo, c), std::max(lo, std::min(hi, c)), std::max(hi, c)};
}

// Files the triangles of `tris` that `keep` accepts under their smallest id
// (below n): entries [first[x], first[x + 1]) hold (middle, largest, index)
// of those whose smallest id is x. Entry is ConstraintFaces::Entry or a
// struct with the same members.
template <class Entry, class Keep>
void file_by_smallest(std::size_t n, const std::vector<Triangle>& tris, Keep keep, std::vector<std::uint32_t>& first,
                      std::vector<Entry>& entries) {
    first = mesh::bucket_starts<std::uint32_t>(n, [&](auto file) {
        for (const Triangle& t : tris)
            if (keep(t)) file(std::min({t[0], t[1], t[2]}));
    });
    mesh::resize_huge(entries, first[n]);
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < tris.size(); ++i) {
        if (!keep(tris[i])) continue;
        const Triangle k = sorted(tris[i][0], tris[i][1], tris[i][2]);
        entries[fill[k[0]]++] = Entry{k[1], k[2], static_cast<std::uint32_t>(i)};
    }
}

// Calls visit(t, f, k) once for every face of m without the ghost vertex
// whose lower slot of two is in [begin, end): face f of live tetrahedron
// t, that lower slot, k its vertices in increasing order.
template <class Visit>
void for_each_finite_face(const mesh::TetMesh& m, mesh::TetId begin, mesh::TetId end, Visit visit) {
    for (mesh::TetId t = begin; t < end; ++t) {
        if (m.is_free(t)) continue;
        const mesh::VertexId* v = m.vertices(t);
        for (int f = 0; f < 4; ++f) {
            if (mesh::facet_tet(m.neighbor(t, f)) < t) continue;  // each face once
            const Triangle k = sorted(v[mesh::kFaceVertices[f][0]], v[mesh::kFaceVertices[f][1]],
                                      v[mesh::kFaceVertices[f][2]]);
            if (k[2] != mesh::kGhostVertex) visit(t, f, k);  // the ghost is the largest id
        }
    }
}

// Marks face f of t and its other side as a constraint face.
void mark_constrained(mesh::TetMesh& m, mesh::TetId t, int f) {
    const mesh::FacetRef across = m.neighbor(t, f);
    m.set_constrained(t, f, true);
    m.set_constrained(mesh::facet_tet(across), mesh::facet_face(across), true);
}

// Whether `facet` is a face of a live tetrahedron with the vertices of t.
bool holds(const mesh::TetMesh& m, mesh::FacetRef facet, const Triangle& t) {
    const mesh::TetId tet = mesh::facet_tet(facet);
    if (tet >= m.slot_count() || m.is_free(tet)) return false;
    const mesh::VertexId* v = m.vertices(tet);
    const int* k = mesh::kFaceVertices[mesh::facet_face(facet)];
    return sorted(v[k[0]], v[k[1]], v[k[2]]) == sorted(t[0], t[1], t[2]);
}

// Whether every facet of `found` (one per triangle of faces, or kNoFacet)
// holds its triangle.
bool all_hold(const mesh::TetMesh& m, const ConstraintFaces& faces, const std::vector<mesh::FacetRef>& found) {
    if (found.size() != faces.size()) return false;
    for (std::size_t i = 0; i < found.size(); ++i)
        if (found[i] != kNoFacet && !holds(m, found[i], faces.triangle(i))) return false;
    return true;
}

}  // namespace

ConstraintFaces::ConstraintFaces(std::vector<Triangle> triangles, std::vector<std::int32_t> labels)
    : triangles_(std::move(triangles)), labels_(std::move(labels)) {
    labels_.resize(triangles_.size(), 0);
    std::size_t n = 0;
    for (const Triangle& t : triangles_) n = std::max<std::size_t>(n, std::max({t[0], t[1], t[2]}) + std::size_t{1});
    file_by_smallest(n, triangles_, [](const Triangle&) { return true; }, first_, entries_);
    index_edges(n);
}

// Each triangle's three edges under their smaller vertex, then each
// vertex's list sorted and its repeats (an edge of two or more triangles)
// dropped, the lists closed up in place.
void ConstraintFaces::index_edges(std::size_t n) {
    const std::vector<std::uint32_t> start = mesh::bucket_starts<std::uint32_t>(n, [&](auto file) {
        for (const Triangle& t : triangles_)
            for (int k = 0; k < 3; ++k) file(std::min(t[k], t[(k + 1) % 3]));
    });
    edge_ends_.resize(3 * triangles_.size());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const Triangle& t : triangles_)
        for (int k = 0; k < 3; ++k) {
            const mesh::VertexId a = t[k], b = t[(k + 1) % 3];
            edge_ends_[fill[std::min(a, b)]++] = std::max(a, b);
        }
    edge_first_.assign(n + 1, 0);
    std::size_t kept = 0;
    for (std::size_t v = 0; v < n; ++v) {
        const auto begin = edge_ends_.begin() + start[v], end = edge_ends_.begin() + start[v + 1];
        std::sort(begin, end);
        for (auto e = begin; e != end; ++e)
            if (e == begin || *e != *(e - 1)) edge_ends_[kept++] = *e;
        edge_first_[v + 1] = static_cast<std::uint32_t>(kept);
    }
    edge_ends_.resize(kept);
    edge_ends_.shrink_to_fit();
}

bool ConstraintFaces::has_edge(mesh::VertexId a, mesh::VertexId b) const {
    if (a > b) std::swap(a, b);
    if (std::size_t{a} + 1 >= edge_first_.size()) return false;
    const auto begin = edge_ends_.begin() + edge_first_[a], end = edge_ends_.begin() + edge_first_[a + 1];
    // Mostly a handful; the hub of a fanned CAD cap has hundreds.
    if (end - begin <= 16) return std::find(begin, end, b) != end;
    return std::binary_search(begin, end, b);
}

std::size_t ConstraintFaces::find(mesh::VertexId a, mesh::VertexId b, mesh::VertexId c) const {
    const Triangle k = sorted(a, b, c);
    if (std::size_t{k[0]} + 1 >= first_.size()) return npos;
    for (std::uint32_t e = first_[k[0]]; e < first_[k[0] + 1]; ++e)
        if (entries_[e].middle == k[1] && entries_[e].largest == k[2]) return entries_[e].index;
    return npos;
}

std::size_t ConstraintFaces::vertex_count() const {
    std::vector<char> used(first_.empty() ? 0 : first_.size() - 1, 0);
    std::size_t count = 0;
    for (const Triangle& t : triangles_)
        for (mesh::VertexId v : t)
            if (!used[v]) {
                used[v] = 1;
                ++count;
            }
    return count;
}

std::vector<std::size_t> mark_present_faces(mesh::TetMesh& m, const ConstraintFaces& faces,
                                            const std::vector<mesh::FacetRef>* found) {
    // igea: the scan of its 1.7 million faces was 4% of `cbr recover`, the
    // same scan as the surface check's just before.
    const bool usable = found != nullptr && all_hold(m, faces, *found);
    const std::vector<mesh::FacetRef> scanned =
        usable ? std::vector<mesh::FacetRef>{} : facets_of_mesh(m, faces.triangles());
    const std::vector<mesh::FacetRef>& facet = usable ? *found : scanned;
    std::vector<std::size_t> missing;
    for (std::size_t i = 0; i < facet.size(); ++i) {
        if (facet[i] == kNoFacet) missing.push_back(i);
        else mark_constrained(m, mesh::facet_tet(facet[i]), mesh::facet_face(facet[i]));
    }
    return missing;
}

std::vector<mesh::FacetRef> facets_of_mesh(const mesh::TetMesh& m, const std::vector<Triangle>& tris, int threads) {
    std::vector<mesh::FacetRef> facet(tris.size(), kNoFacet);
    // The triangles with distinct ids of m, filed under their smallest id
    // (as ConstraintFaces files them; a triangle given twice is filed
    // twice), then every face of the mesh looked up once, in storage order.
    const std::size_t n = m.vertex_count();
    const auto own = [n](const Triangle& t) {
        return t[0] < n && t[1] < n && t[2] < n && t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
    };
    struct Filed {
        mesh::VertexId middle, largest;
        std::uint32_t index;
    };
    std::vector<std::uint32_t> first;
    std::vector<Filed> entries;
    file_by_smallest(n, tris, own, first, entries);
    // Each chunk of the slots lists what it found; the lists are applied in
    // slot order, as one pass would have written them.
    struct Found {
        std::uint32_t index;
        mesh::FacetRef facet;
    };
    const std::size_t slots = m.slot_count();
    std::vector<std::vector<Found>> found(mesh::chunk_count(slots, threads));
    mesh::run_chunks(slots, found.size(), [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        for_each_finite_face(m, static_cast<mesh::TetId>(begin), static_cast<mesh::TetId>(end),
                             [&](mesh::TetId t, int f, const Triangle& k) {
                                 for (std::uint32_t e = first[k[0]]; e < first[k[0] + 1]; ++e)
                                     if (entries[e].middle == k[1] && entries[e].largest == k[2])
                                         found[chunk].push_back({entries[e].index, mesh::make_facet(t, f)});
                             });
    });
    for (const std::vector<Found>& list : found)
        for (const Found& x : list) facet[x.index] = x.facet;
    return facet;
}

}  // namespace cbr::recover
