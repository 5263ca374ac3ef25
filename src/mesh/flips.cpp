#include "mesh/flips.hpp"

#include <string>

#include "geom/predicates.hpp"
#include "mesh/errors.hpp"

namespace cbr::mesh {
namespace {

using Tet = std::array<VertexId, 4>;

bool live(const TetMesh& m, TetId t) { return t < m.slot_count() && !m.is_free(t); }

bool is_protected(const EdgeProtect& protect, VertexId u, VertexId v) { return protect && protect(u, v); }

// A flip builds a tiling of its region by construction: replace_tets
// refusing it as such is a bug, not a configuration.
FlipResult checked(ReplaceResult r) {
    switch (r) {
        case ReplaceResult::kDone: return FlipResult::kDone;
        case ReplaceResult::kRemovesConstraint: return FlipResult::kRemovesConstraint;
        case ReplaceResult::kInverted: return FlipResult::kInverted;
        case ReplaceResult::kNotConvex: return FlipResult::kNotConvex;
        case ReplaceResult::kBadInput:
        case ReplaceResult::kNotTiling: break;
    }
    throw InternalError(std::string("flip: replace_tets refused the flip's own tiling: ") + to_string(r));
}

// The shell of uv from t, when t is live and contains both.
bool shell_from(const TetMesh& m, TetId t, VertexId u, VertexId v, Shell& s) {
    return live(m, t) && shell(m, u, v, t, s);
}

bool valid_triangles(const Shell& s, const std::vector<RingTriangle>& triangles) {
    const int n = static_cast<int>(s.size());
    if (n < 3 || triangles.size() != s.size() - 2) return false;
    for (const RingTriangle& tri : triangles)
        for (int i : tri)
            if (i < 0 || i >= n) return false;
    return true;
}

// Reused storage: flip recovery removes edges millions of times, and the
// shell's vectors alone were a tenth of its instructions in allocation.
// One thread_local object: each one costs a TLS look-up per call.
struct FlipScratch {
    Shell shell;
    std::vector<RingTriangle> triangles;
    // replace_tets for the flips' own ring triangulations of a current
    // shell, by the shell's structure.
    ShellReplacer replacer;
    // replace_tets for the 2-3 flip, by the flip's structure.
    TwoThreeReplacer two_three;
};

FlipScratch& flip_scratch() {
    thread_local FlipScratch scratch;
    return scratch;
}

// Index d in {0, 1} of the ring diagonal (r_d, r_d+2) coplanar with uv, or -1.
int coplanar_diagonal(const TetMesh& m, VertexId u, VertexId v, const Shell& s) {
    if (u == kGhostVertex || v == kGhostVertex) return -1;
    for (int d = 0; d < 2; ++d) {
        const VertexId a = s.ring[static_cast<std::size_t>(d)], b = s.ring[static_cast<std::size_t>(d + 2)];
        if (a == kGhostVertex || b == kGhostVertex) continue;
        if (geom::orient3d(m.point(u), m.point(v), m.point(a), m.point(b)) == 0) return d;
    }
    return -1;
}

}  // namespace

const char* to_string(FlipResult r) {
    switch (r) {
        case FlipResult::kDone: return "done";
        case FlipResult::kNotApplicable: return "not applicable";
        case FlipResult::kProtectedEdge: return "protected edge";
        case FlipResult::kNoValidTriangulation: return "no valid triangulation";
        case FlipResult::kRemovesConstraint: return "would remove a constraint face";
        case FlipResult::kInverted: return "inverted tetrahedron";
        case FlipResult::kNotConvex: return "hull would not stay convex";
    }
    return "?";
}

FlipResult flip23(TetMesh& m, TetId t, int f, const EdgeProtect& /*protect*/, std::vector<TetId>* created) {
    if (!live(m, t) || f < 0 || f > 3) return FlipResult::kNotApplicable;
    // abc (face f) points into t, toward d; e is on the other side
    // (Definition 5.6): (a, b, e, d), (b, c, e, d), (c, a, e, d).
    return checked(flip_scratch().two_three.replace(m, t, f, created));
}

FlipResult flip32(TetMesh& m, TetId t, VertexId u, VertexId v, const EdgeProtect& protect,
                  std::vector<TetId>* created) {
    Shell s;
    if (!shell_from(m, t, u, v, s) || s.size() != 3) return FlipResult::kNotApplicable;
    if (is_protected(protect, u, v)) return FlipResult::kProtectedEdge;
    return checked(flip_scratch().replacer.replace(m, u, v, s, {{0, 1, 2}}, ShellGeometry::kUnchecked, created));
}

FlipResult flip44(TetMesh& m, TetId t, VertexId u, VertexId v, const EdgeProtect& protect,
                  std::vector<TetId>* created) {
    Shell s;
    if (!shell_from(m, t, u, v, s) || s.size() != 4) return FlipResult::kNotApplicable;
    const int d = coplanar_diagonal(m, u, v, s);
    if (d < 0) return FlipResult::kNotApplicable;
    if (is_protected(protect, u, v)) return FlipResult::kProtectedEdge;
    const std::vector<RingTriangle> triangles = {{d, d + 1, d + 2}, {d, d + 2, (d + 3) % 4}};
    return checked(flip_scratch().replacer.replace(m, u, v, s, triangles, ShellGeometry::kUnchecked, created));
}

FlipResult remove_edge(TetMesh& m, TetId t, VertexId u, VertexId v, const EdgeProtect& protect,
                       std::vector<TetId>* created) {
    FlipScratch& scratch = flip_scratch();
    if (!shell_from(m, t, u, v, scratch.shell)) return FlipResult::kNotApplicable;
    return remove_edge(m, u, v, scratch.shell, protect, created);
}

FlipResult remove_edge(TetMesh& m, VertexId u, VertexId v, const Shell& s, const EdgeProtect& protect,
                       std::vector<TetId>* created) {
    if (s.size() < 3 || s.size() > kMaxRemovalShell) return FlipResult::kNotApplicable;
    if (is_protected(protect, u, v)) return FlipResult::kProtectedEdge;
    FlipScratch& scratch = flip_scratch();
    if (!best_ring_triangulation(m, u, v, s, scratch.triangles)) return FlipResult::kNoValidTriangulation;
    return checked(scratch.replacer.replace(m, u, v, s, scratch.triangles, ShellGeometry::kScoredRing, created));
}

FlipResult transform_shell(TetMesh& m, VertexId u, VertexId v, const Shell& shell,
                           const std::vector<RingTriangle>& triangles, std::vector<TetId>* created) {
    if (!valid_triangles(shell, triangles)) return FlipResult::kNotApplicable;
    // Definition 5.8: each ring triangle coned to v and (reversed) to u,
    // matched by the shell's structure (nothing checked beforehand).
    const ReplaceResult r =
        flip_scratch().replacer.replace(m, u, v, shell, triangles, ShellGeometry::kUnchecked, created);
    if (r == ReplaceResult::kBadInput || r == ReplaceResult::kNotTiling) return FlipResult::kNotApplicable;
    return checked(r);
}

}  // namespace cbr::mesh
