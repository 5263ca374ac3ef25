// Interior Steiner points that unblock flips, between the flips (§5.1) and
// conforming recovery (§5.2). A Steiner point strictly off the surface is
// legal anywhere (inside or outside the domain): only points on input
// triangles are forbidden. So where a missing edge of a face that flips
// could not recover crosses many tetrahedra, a point put near the edge but
// off the surface, inserted with the protected Delaunay cavity (§5.1: no
// recovered face is ever crossed), replaces the crossed tetrahedra whose
// circumspheres hold it by its star; the flips are then tried again on
// those faces, and only what is still missing goes on to conforming
// recovery. The points go to the Steiner list, so §6 tries to suppress
// them like the others (TetGen, too, puts Steiner points in the interior
// to unblock flips).
#pragma once

#include <cstddef>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "recover/constraint_faces.hpp"

namespace cbr::recover {

// A point whose star is larger than this is not kept by default: it would
// stay a Steiner point that §6 suppression tries at a cost that grows with
// the cube of its ball (a flat fanned cylinder: one point coned to all 796
// faces, 8 s where the whole recovery took 0.9).
constexpr std::size_t kUnblockingMaxStar = 256;
// No limit on the star: recovery's retry when the limit turned points away
// and what the flips then left defeated conforming recovery (recovery.cpp).
constexpr std::size_t kUnblockingAnyStar = static_cast<std::size_t>(-1);

// Where and how near the surface the points go: one point per
// `tets_per_point` tetrahedra a missing edge meets (at most 8 per edge), and
// never nearer a missing triangle than `clearance` times the face's
// shortest edge; stars of at most `max_star` tetrahedra; see also the
// last two fields.
struct UnblockingOptions {
    std::size_t max_star = kUnblockingMaxStar;
    std::size_t tets_per_point = 8;
    double clearance = 0.1;
    // Keep the first point each target gets inserted (on the side of the
    // face most crossed tetrahedra lie on first, the farthest first),
    // whether or not the edge then meets fewer tetrahedra: recovery's last
    // try, for nearly planar regions of many input triangles, where a
    // point that only moves the crossings still gives the flips
    // tetrahedra off the plane to work with.
    bool keep_first = false;
    // Let the walk to a point pass recovered faces (a Steiner point is legal
    // anywhere off the surface; the protected cavity still never crosses
    // one). Without it, a point across a recovered face from the crossed
    // tetrahedra is not tried: on a turned plate whose faces are nearly
    // all recovered, that is every point near the last missing edges.
    bool walk_through_recovered = false;
};
// Denser and nearer the surface: recovery's retry when the default points
// left faces that defeated conforming recovery. On turned prisms with
// fanned caps (nearly flat layers of thin tetrahedra) they let the flips
// recover what conforming recovery failed on: 3 of the 273 turned copies
// that failed in every retry before recover so (recovery.cpp).
constexpr UnblockingOptions kDenseUnblocking{kUnblockingMaxStar, 4, 0.05, false};
// Denser still, as near: one point every 2 tetrahedra a missing edge
// meets (recovery's last try, kept where they do not cut).
constexpr UnblockingOptions kDensestUnblocking{kUnblockingMaxStar, 2, 0.05, false};

struct UnblockingResult {
    std::size_t kept = 0;              // points kept (appended to the Steiner list)
    std::size_t refused_for_star = 0;  // points that helped but whose star was over the limit
};

// For every missing edge of the faces `missing` (indices into `faces`):
// points at decreasing distances from points of the edge along the face's
// normal, the side of the crossed tetrahedra first. A point is inserted only
// when it is strictly inside the tetrahedron the walk to it ends in (so on
// no face of the mesh, recovered faces included; the walk starts from a
// crossed tetrahedron and, unless options.walk_through_recovered, stops at
// a recovered face), on no missing triangle
// (exact) and not nearer one than options.clearance times the face's
// shortest edge; it is kept only when the edge then meets fewer
// tetrahedra (or, with options.keep_first, whatever it meets) and its star
// has at most options.max_star tetrahedra (else the mesh is restored as it
// was). Appends the points kept to `steiner`, in increasing id order.
UnblockingResult insert_unblocking_points(mesh::TetMesh& m, const ConstraintFaces& faces,
                                          const std::vector<std::size_t>& missing,
                                          std::vector<mesh::VertexId>& steiner,
                                          const UnblockingOptions& options = {});

}  // namespace cbr::recover
