#include "mesh/mesh_check.hpp"

#include <algorithm>
#include <sstream>
#include <vector>

#include "geom/predicates.hpp"
#include "mesh/chunks.hpp"

namespace cbr::mesh {
namespace {

constexpr std::size_t kMaxReported = 10;

// Face f of t and face g of n have the same three vertices: each vertex of
// the first is a vertex of n other than its apex n[g] (three distinct
// vertices of n other than one: exactly the face g).
bool same_face(const TetMesh& m, TetId t, int f, TetId n, int g) {
    const VertexId* vn = m.vertices(n);
    for (int k = 0; k < 3; ++k) {
        const VertexId x = m.vertex(t, kFaceVertices[f][k]);
        bool found = false;
        for (int i = 0; i < 4; ++i) found = found || (i != g && vn[i] == x);
        if (!found) return false;
    }
    return true;
}

std::string tet_name(const TetMesh& m, TetId t) {
    std::ostringstream s;
    s << "tet " << t << " (";
    for (int i = 0; i < 4; ++i) {
        const VertexId v = m.vertex(t, i);
        if (i) s << ' ';
        if (v == kGhostVertex) s << "ghost"; else s << v;
    }
    s << ')';
    return s.str();
}

// p in conflict with ghost (a, b, c, oo): the kernel's test, restated.
bool ghost_conflict(const TetMesh& m, TetId g, const double* p) {
    const double* a = m.point(m.vertex(g, 0));
    const double* b = m.point(m.vertex(g, 1));
    const double* c = m.point(m.vertex(g, 2));
    const int side = geom::orient3d(a, b, c, p);
    return side > 0 || (side == 0 && geom::incircle_coplanar_sos(a, b, c, p) > 0);
}

void check_links(const TetMesh& m, TetId t, CheckReport& r) {
    for (int f = 0; f < 4; ++f) {
        const FacetRef out = m.neighbor(t, f);
        const TetId n = facet_tet(out);
        if (n >= m.slot_count() || m.is_free(n)) {
            r.add(tet_name(m, t) + ": face " + std::to_string(f) + " links to a missing tetrahedron");
            continue;
        }
        if (m.neighbor(n, facet_face(out)) != make_facet(t, f))
            r.add(tet_name(m, t) + ": face " + std::to_string(f) + " link is not symmetric");
        else if (!same_face(m, t, f, n, facet_face(out)))
            r.add(tet_name(m, t) + " and " + tet_name(m, n) + " are linked across different faces");
    }
}

void check_shape(const TetMesh& m, TetId t, std::vector<char>& used, CheckReport& r) {
    const VertexId* v = m.vertices(t);
    for (int i = 0; i < 4; ++i) {
        if (v[i] == kGhostVertex && i == 3) continue;
        if (v[i] >= m.vertex_count()) {
            r.add(tet_name(m, t) + ": vertex id out of range");
            return;
        }
        used[v[i]] = 1;
    }
    if (m.is_ghost(t)) {
        if (m.is_ghost(facet_tet(m.neighbor(t, 3))))
            r.add(tet_name(m, t) + ": ghost whose hull face borders another ghost");
        return;
    }
    if (geom::orient3d(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3])) <= 0)
        r.add(tet_name(m, t) + " is not positively oriented");
}

// What one chunk of the slots found: its problems in slot order, and its
// share of the counts and of the marks that the whole check needs.
struct ChunkCheck {
    CheckReport report;
    std::vector<char> used, on_hull;  // per vertex
    std::size_t ghosts = 0, live = 0;
};

void check_slots(const TetMesh& m, TetId begin, TetId end, ChunkCheck& c) {
    c.used.assign(m.vertex_count(), 0);
    c.on_hull.assign(m.vertex_count(), 0);
    for (TetId t = begin; t < end; ++t) {
        if (m.is_free(t)) continue;
        ++c.live;
        check_shape(m, t, c.used, c.report);
        check_links(m, t, c.report);
        if (m.is_ghost(t)) {
            ++c.ghosts;
            for (int i = 0; i < 3; ++i) {
                const VertexId v = m.vertex(t, i);
                if (v < c.on_hull.size()) c.on_hull[v] = 1;
            }
        }
    }
}

}  // namespace

void CheckReport::add(std::string message) {
    if (errors.size() < kMaxReported) errors.push_back(std::move(message));
    ++error_count;
}

CheckReport check_mesh(const TetMesh& m, int threads) {
    const std::size_t slots = m.slot_count();
    std::vector<ChunkCheck> chunk(chunk_count(slots, threads));
    run_chunks(slots, chunk.size(), [&](std::size_t k, std::size_t begin, std::size_t end) {
        check_slots(m, static_cast<TetId>(begin), static_cast<TetId>(end), chunk[k]);
    });
    // Merged in slot order: the problems listed are the first ones of a
    // single pass.
    CheckReport r;
    std::size_t ghosts = 0, live = 0;
    std::vector<char>& used = chunk[0].used;
    std::vector<char>& on_hull = chunk[0].on_hull;
    for (std::size_t k = 0; k < chunk.size(); ++k) {
        const ChunkCheck& c = chunk[k];
        for (const std::string& e : c.report.errors) r.add(e);
        r.error_count += c.report.error_count - c.report.errors.size();  // those it found but did not list
        ghosts += c.ghosts;
        live += c.live;
        if (k == 0) continue;
        for (std::size_t v = 0; v < used.size(); ++v) {
            used[v] |= c.used[v];
            on_hull[v] |= c.on_hull[v];
        }
    }
    if (live == 0) return r;
    // The hull is a closed triangulated sphere: F faces, 3F/2 edges.
    const long long V = std::count(on_hull.begin(), on_hull.end(), 1);
    const long long F = static_cast<long long>(ghosts);
    if (F % 2 != 0 || V - 3 * F / 2 + F != 2)
        r.add("hull is not a closed sphere: " + std::to_string(V) + " vertices, " + std::to_string(F) + " faces");
    for (std::size_t v = 0; v < used.size(); ++v)
        if (!used[v]) r.add("vertex " + std::to_string(v) + " is in no tetrahedron");
    return r;
}

CheckReport check_delaunay(const TetMesh& m) {
    CheckReport r = check_mesh(m);
    if (!r.ok()) return r;
    for (TetId t = 0; t < m.slot_count(); ++t) {
        if (m.is_free(t)) continue;
        for (int f = 0; f < 4; ++f) {
            const FacetRef out = m.neighbor(t, f);
            const TetId n = facet_tet(out);
            if (n < t) continue;  // each face once
            const VertexId apex_n = m.vertex(n, facet_face(out));
            const VertexId apex_t = m.vertex(t, f);
            bool violated = false;
            if (!m.is_ghost(t) && !m.is_ghost(n)) {
                const VertexId* v = m.vertices(t);
                violated = geom::insphere_sos(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3]),
                                              m.point(apex_n)) >= 0;
            } else {
                if (m.is_ghost(t) && apex_n != kGhostVertex) violated |= ghost_conflict(m, t, m.point(apex_n));
                if (m.is_ghost(n) && apex_t != kGhostVertex) violated |= ghost_conflict(m, n, m.point(apex_t));
            }
            if (violated) r.add("face between " + tet_name(m, t) + " and " + tet_name(m, n) + " is not locally Delaunay");
        }
    }
    return r;
}

}  // namespace cbr::mesh
