/*
 * libcbr — constrained boundary recovery for 3D Delaunay meshing.
 *
 * This header is the whole public interface (ABI) of libcbr.so. It is C99,
 * includes only <stddef.h> and <stdint.h>, and is callable from C, C++ and,
 * through the module in capi/fortran/cbr.f90, from Fortran.
 *
 * Conventions (they hold for every function below):
 *
 *  - Every function that can fail returns an int status: CBR_OK (0) or one of
 *    the negative CBR_ERR_* codes. The numbers are fixed forever.
 *  - A call that fails changes nothing in the handle, and
 *    cbr_mesh_last_error() then returns a message naming the culprit (which
 *    argument, which point index, ...).
 *  - No exception, abort, exit or print ever leaves the library. Running out
 *    of memory is reported as CBR_ERR_OUT_OF_MEMORY.
 *  - The caller owns its arrays: the library copies input in and output out.
 *    To read a result, ask for its count, allocate, then call the getter.
 *  - Indices (point ids) are int64_t at the boundary, 0-based by default,
 *    1-based for every id in and out after
 *    cbr_mesh_set_param(mesh, CBR_PARAM_INDEX_BASE, 1) (Fortran style).
 *  - Handles are independent: two threads may use two handles at the same
 *    time. One handle must not be used by two threads at the same time.
 *  - Options and results are read and written through enumerated keys, never
 *    through structs, so that new keys can be added without breaking
 *    binaries linked against an older version.
 *
 * Orientation convention: a tetrahedron (a, b, c, d) is positively oriented
 * when det[b-a, c-a, d-a] > 0, i.e. its signed volume
 * ((b-a) x (c-a)) . (d-a) / 6 is positive: seen from d, the triangle a, b, c
 * turns counterclockwise. This is the convention of VTK, Gmsh and Medit.
 */
#ifndef CBR_H
#define CBR_H

#include <stddef.h>
#include <stdint.h>

/* ------------------------------------------------------------------------ */
/* Version                                                                  */
/* ------------------------------------------------------------------------ */

#define CBR_VERSION_MAJOR 0
#define CBR_VERSION_MINOR 1
#define CBR_VERSION_PATCH 0

/* ------------------------------------------------------------------------ */
/* Symbol export                                                            */
/* ------------------------------------------------------------------------ */

#if defined(_WIN32)
#  if defined(CBR_BUILDING_LIBRARY)
#    define CBR_API __declspec(dllexport)
#  else
#    define CBR_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__) && __GNUC__ >= 4
#  define CBR_API __attribute__((visibility("default")))
#else
#  define CBR_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* Status codes (fixed forever; new codes are only ever added)              */
/* ------------------------------------------------------------------------ */

/* Success. */
#define CBR_OK 0
/* The call itself is wrong: a NULL pointer, a negative count, an unknown
   key, a parameter value out of its range. */
#define CBR_ERR_INVALID_ARGUMENT (-1)
/* The data is wrong: a NaN, infinite or out-of-range coordinate, two
   identical points, an invalid surface. The message names the indices. */
#define CBR_ERR_INVALID_INPUT (-2)
/* Memory could not be allocated; the handle is unchanged. */
#define CBR_ERR_OUT_OF_MEMORY (-3)
/* Boundary recovery could not recover every face; the message names them. */
#define CBR_ERR_RECOVERY_FAILED (-4)
/* A file could not be read or written. */
#define CBR_ERR_IO (-5)
/* A bug in libcbr: an internal consistency check failed. Please report it
   with the message. */
#define CBR_ERR_INTERNAL (-6)

/* ------------------------------------------------------------------------ */
/* Parameter keys for cbr_mesh_set_param / cbr_mesh_get_param               */
/* (numbers fixed forever; new keys are only ever added)                    */
/* ------------------------------------------------------------------------ */

/* Base of every point id passed in or returned: 0 (default, C) or 1
   (Fortran). Changing it later reinterprets the ids of later calls only;
   stored data is not affected. */
#define CBR_PARAM_INDEX_BASE 1
/* After cbr_mesh_recover_faces: 0 (default) makes cbr_mesh_tet_count and
   cbr_mesh_get_tets return the tetrahedra of the bounded regions only (what
   a solver meshes), and the point getters (cbr_mesh_point_count,
   cbr_mesh_get_points, cbr_mesh_steiner_count, cbr_mesh_steiner_points)
   leave out the added points that only the exterior uses (Steiner points
   outside the domain, the corners of an enclosing box): the caller's
   points keep their ids, the added points that the returned tetrahedra use
   follow in their order, so every returned point after the caller's is a
   vertex of a returned tetrahedron. 1 returns the exterior (region 0) and
   every point. The getters read it when they run; the ids of added points
   differ between the two when the exterior has points of its own. */
#define CBR_PARAM_KEEP_EXTERIOR 2
/* Options of cbr_mesh_refine (full mesh generation, the paper's section 6).
   They are read when cbr_mesh_refine runs. */
/* Target edge length H of the tetrahedra: 0 (default) = the sizing field
   derived from the surface (at each surface vertex the mean length of its
   input edges, interpolated inside); H > 0 = the smaller of H and the
   surface field, or H alone when CBR_PARAM_REFINE_SIZE_FROM_SURFACE is 0.
   Range: 0, or finite and > 0. */
#define CBR_PARAM_REFINE_SIZE 3
/* Size grading g: the sizing field is made to vary by at most g per unit
   length along the mesh edges, h(v) <= h(u) + g |uv|. Default 0.5; range
   [0.01, 100]. */
#define CBR_PARAM_REFINE_GRADING 4
/* Quality bound B: a tetrahedron whose circumradius exceeds B times its
   shortest edge (radius-edge ratio, TetGen's -q) gets a point at its
   circumcentre when that point is inside its region and not too close to
   the surface. Default 1.414; range [1, 1000]. */
#define CBR_PARAM_REFINE_QUALITY_BOUND 5
/* Optimisation passes after the insertion of points (each: quality flips,
   then smoothing of the non-input interior points); 0 = no optimisation.
   Default 3; an integer in [0, 100]. */
#define CBR_PARAM_REFINE_PASSES 6
/* 1 (default): the sizing field uses the surface (see
   CBR_PARAM_REFINE_SIZE); 0: H alone (CBR_PARAM_REFINE_SIZE must then be
   > 0 when cbr_mesh_refine runs). 0 or 1. */
#define CBR_PARAM_REFINE_SIZE_FROM_SURFACE 7
/* Size growth r away from the surface: a point inserted inside takes the
   larger of the field interpolated there and min over the corners c of its
   tetrahedron of h(c) + r |pc|, so the tetrahedra coarsen by r per unit
   length towards the inside (fewer tetrahedra; the shape bound still
   applies). 0: the surface field interpolated, the inside meshed at the
   surface's resolution. Default 0.3 (about 1.3x the tetrahedra of TetGen
   -pYq1.414 on the benchmark surfaces); range [0, 100]. */
#define CBR_PARAM_REFINE_GROWTH 8
/* Option of cbr_mesh_recover_faces: 1 (default) = before any Steiner point
   is added, flip searches go to their deepest round (edge removals nested
   8 levels, 40,000 a face): fewer Steiner points, more time on surfaces
   whose faces flips find hard (on the 37 shared benchmark surfaces, 150
   Steiner points inside the domain; with 0, 161 for 6.9% fewer
   instructions; on 180 turned copies of them, 266 and 291, all
   recovered either way). 0 = without that round.
   0 or 1. */
#define CBR_PARAM_RECOVERY_DEEP_FLIPS 9
/* Option of cbr_mesh_recover_faces: 1 (default) = after a failure on the
   Delaunay mesh of the points, recovery is attempted again inside an
   enclosing box, then from other flip states, outside the box and inside
   it (see cbr_mesh_recover_faces; up to six attempts in all, so a failure
   takes several times as long as one attempt). 0 = the first attempt's
   failure is reported at once. 0 or 1. */
#define CBR_PARAM_RECOVERY_RETRIES 10
/* Threads the library may use, for the passes that only read the whole
   mesh (the exact validity checks that end cbr_mesh_recover_faces and
   cbr_mesh_refine, the lookup of the input triangles among the faces of
   the mesh, Table II) and for the field points, smoothing sweeps and
   quality flips of cbr_mesh_refine (two halves of the mesh at once):
   1 (default) = the calling thread alone; n > 1 = up to n threads at a
   time, started and joined within the call; 0 = as many as the hardware
   runs at once. Every result is the same, bit for bit, whatever the
   value. An integer within [0, 256]. */
#define CBR_PARAM_THREADS 11

/* ------------------------------------------------------------------------ */
/* Opaque handle                                                            */
/* ------------------------------------------------------------------------ */

/* A mesh: a set of points and the tetrahedralization built on them. */
typedef struct cbr_mesh cbr_mesh;

/* ------------------------------------------------------------------------ */
/* Library information                                                      */
/* ------------------------------------------------------------------------ */

/* The version of the library actually loaded, "MAJOR.MINOR.PATCH"
   (compare with the CBR_VERSION_* macros of the header you compiled
   against). Never NULL; static storage. */
CBR_API const char *cbr_version(void);

/* A short English description of a status code, e.g. "invalid input".
   Unknown codes give "unknown status". Never NULL; static storage. */
CBR_API const char *cbr_status_string(int status);

/* ------------------------------------------------------------------------ */
/* Handle lifetime and errors                                               */
/* ------------------------------------------------------------------------ */

/* Creates an empty mesh and stores it in *out (set to NULL on failure).
   Returns CBR_OK, CBR_ERR_INVALID_ARGUMENT (out is NULL) or
   CBR_ERR_OUT_OF_MEMORY. */
CBR_API int cbr_mesh_create(cbr_mesh **out);

/* Frees the mesh and everything it owns. NULL is accepted and ignored. */
CBR_API void cbr_mesh_destroy(cbr_mesh *mesh);

/* The message of the last call on this handle that failed, or "" if none
   failed yet. The string stays valid until the next call on the handle.
   A NULL handle gives a fixed message. Never NULL. */
CBR_API const char *cbr_mesh_last_error(const cbr_mesh *mesh);

/* ------------------------------------------------------------------------ */
/* Parameters                                                               */
/* ------------------------------------------------------------------------ */

/* Sets parameter `key` (a CBR_PARAM_* key) to `value`.
   Returns CBR_ERR_INVALID_ARGUMENT for a NULL mesh, an unknown key or a
   value outside the key's range. */
CBR_API int cbr_mesh_set_param(cbr_mesh *mesh, int key, double value);

/* Reads parameter `key` into *value.
   Returns CBR_ERR_INVALID_ARGUMENT for a NULL mesh or value, or an unknown
   key. */
CBR_API int cbr_mesh_get_param(const cbr_mesh *mesh, int key, double *value);

/* ------------------------------------------------------------------------ */
/* Points and the Delaunay tetrahedralization                               */
/* ------------------------------------------------------------------------ */

/* Inserts `count` points, given as 3*count doubles x0 y0 z0 x1 y1 z1 ...,
   and updates the Delaunay tetrahedralization of all points inserted so far.
   The points get the next ids in the order given: the first call's points
   are 0 .. count-1 (1 .. count with CBR_PARAM_INDEX_BASE = 1), the next
   call's continue from there. The tetrahedralization depends only on the
   set of points, not on how they were split into calls or ordered:
   degenerate (cospherical) configurations are resolved by a symbolic
   perturbation, so the result is unique and exact.
   Every coordinate must be finite and either 0 or of magnitude within
   [1e-40, 1e+40] (the range in which every predicate is exact).
   count = 0 is allowed (xyz may then be NULL).
   Errors (the mesh is then unchanged):
     CBR_ERR_INVALID_ARGUMENT  mesh or xyz NULL, count negative or beyond
                               the capacity of the mesh (2^31 - 2 points);
     CBR_ERR_INVALID_INPUT     a NaN, infinite or out-of-range coordinate
                               (the message gives the point index), or two
                               identical points (the message gives both ids);
     CBR_ERR_OUT_OF_MEMORY. */
CBR_API int cbr_mesh_insert_points(cbr_mesh *mesh, int64_t count, const double *xyz);

/* Number of points the getters return (after recovery, without the
   exterior's own added points unless CBR_PARAM_KEEP_EXTERIOR is set); -1
   for a NULL mesh. */
CBR_API int64_t cbr_mesh_point_count(const cbr_mesh *mesh);

/* Number of tetrahedra cbr_mesh_get_tets returns; -1 for a NULL mesh.
   Fewer than 4 points, or all points coplanar, give 0. */
CBR_API int64_t cbr_mesh_tet_count(const cbr_mesh *mesh);

/* Copies the coordinates of the points (cbr_mesh_point_count), in id order, into xyz_out
   (3 * cbr_mesh_point_count doubles). The coordinates are bit-identical to
   the ones inserted. xyz_out may be NULL when there are no points. */
CBR_API int cbr_mesh_get_points(const cbr_mesh *mesh, double *xyz_out);

/* Copies the tetrahedra into tets_out (4 * cbr_mesh_tet_count point ids,
   in the index base set): the finite tetrahedra of the Delaunay
   tetrahedralization of all points, each positively oriented (see the
   orientation convention at the top of this file). tets_out may be NULL
   when there are no tetrahedra. */
CBR_API int cbr_mesh_get_tets(const cbr_mesh *mesh, int64_t *tets_out);

/* ------------------------------------------------------------------------ */
/* Constrained boundary recovery (Du & Wang 2004)                           */
/* ------------------------------------------------------------------------ */

/* Statistic keys for cbr_mesh_get_stat (numbers fixed forever): the rows of
   the paper's Table I. Counts are returned as doubles. */
#define CBR_STAT_TOTAL_VERTICES 1          /* points in the mesh, Steiner points included */
#define CBR_STAT_BOUNDARY_VERTICES 2       /* distinct points used by the input triangles */
#define CBR_STAT_MISSING_FACES 3           /* input triangles not faces of the Delaunay mesh */
#define CBR_STAT_FACES_RECOVERED_BY_FLIPS 4
#define CBR_STAT_CONFORMING_POINTS 5       /* points added on the surface in conforming recovery (all split off later) */
#define CBR_STAT_STEINER_GENERATED 6       /* Steiner points created off the surface */
#define CBR_STAT_STEINER_REMAINING 7       /* Steiner points left after suppression */
#define CBR_STAT_DELAUNAY_SECONDS 8
#define CBR_STAT_RECOVERY_SECONDS 9
#define CBR_STAT_TOTAL_SECONDS 10
#define CBR_STAT_REGION_COUNT 11           /* regions, the exterior (region 0) included */
/* Steiner points that are vertices of tetrahedra of bounded regions
   (region > 0): those the caller's mesh contains. CBR_STAT_STEINER_REMAINING
   also counts the Steiner points of the exterior (region 0), which
   cbr_mesh_get_tets and the point getters drop unless
   CBR_PARAM_KEEP_EXTERIOR is set. The
   paper's Table I counts the points inside the domain. */
#define CBR_STAT_STEINER_INSIDE 12
/* Keys 13-19 are reserved for recovery. After cbr_mesh_refine (0 before),
   over the tetrahedra of the bounded regions: the rows of the paper's
   Table II, with the quality q = 3 r_in / r_circ (radius ratio, 1 for the
   regular tetrahedron, 0 for a flat one). */
#define CBR_STAT_QUALITY_AVERAGE 20
#define CBR_STAT_QUALITY_MIN 21
#define CBR_STAT_PERCENT_ABOVE_0_4 22      /* % of tetrahedra with q > 0.4 */
#define CBR_STAT_PERCENT_BELOW_0_1 23      /* % of tetrahedra with q < 0.1 */
#define CBR_STAT_BAD_TOUCHING_STEINER 24   /* tetrahedra with q < 0.1 and a Steiner corner */
#define CBR_STAT_DIHEDRAL_MIN 25           /* degrees */
#define CBR_STAT_DIHEDRAL_MAX 26           /* degrees */
#define CBR_STAT_FIELD_POINTS 27           /* points inserted by cbr_mesh_refine */
#define CBR_STAT_REFINE_FLIPS 28           /* quality flips done by cbr_mesh_refine */
#define CBR_STAT_REFINE_SECONDS 29
#define CBR_STAT_REFINE_TETS 30            /* tetrahedra of the bounded regions after refinement */
/* Tetrahedra of the bounded regions that cbr_mesh_refine left over its size
   bound (see cbr_mesh_refine): 0 when every tetrahedron meets it. */
#define CBR_STAT_REFINE_OVERSIZE_TETS 31

/* Recovers the `count` triangles `tris` (3*count point ids, index base as
   set) as faces of the tetrahedralization of the points inserted so far,
   without adding any point on them, then classifies the regions. labels
   (one per triangle) may be NULL. Call it once per mesh, after the last
   cbr_mesh_insert_points.
   On success every input triangle is a face, no tetrahedron is inverted or
   flat and no Steiner point lies on an input triangle; regions are the
   connected sets of tetrahedra separated by input triangles: 0 outside,
   then 1, 2, ... numbered by the smallest input triangle on their boundary
   (and its side), so the numbering depends on the input only.
   Within an attempt, where the interior Steiner points that unblock the
   flips leave faces that the later steps cannot complete, it starts again
   from the mesh the flips left with other such points (of any star size,
   then denser and nearer the faces).
   When recovery fails on the Delaunay mesh of the points, it is tried again
   with the eight corners of a cube around the points added (every input
   triangle then lies away from the convex hull, where nearly planar faces
   of turned CAD parts leave no room; this recovers most first failures);
   if that succeeds, the corners are the first Steiner points (ids right
   after the caller's points, with CBR_PARAM_KEEP_EXTERIOR set), in the
   exterior. If it fails too, recovery
   starts again from the Delaunay mesh with other budgets for the deepest
   flip round (10,000, then 30,000 edge removals a face; only with
   CBR_PARAM_RECOVERY_DEEP_FLIPS at 1): the flips decide where the later
   steps start, and on nearly flat parts one start fails where another
   succeeds. Last, those budgets are tried inside the cube. The statistics
   are those of the attempt that succeeded (of the first one after a
   failure). A failing recovery runs every attempt, so it takes several
   times as long as a successful one.
   Errors (the mesh is then unchanged):
     CBR_ERR_INVALID_ARGUMENT  NULL mesh, NULL tris with count > 0, negative
                               count, or called twice;
     CBR_ERR_INVALID_INPUT     an invalid surface (see cbr_mesh_check_faces,
                               which runs first and whose report stays: the
                               message names the triangles), or no volume
                               (all points coplanar, or fewer than 4);
     CBR_ERR_RECOVERY_FAILED   some triangles could not be recovered; the
                               message names them (the statistics of the
                               attempt remain readable).
   Open surfaces and non-manifold edges are legal. */
CBR_API int cbr_mesh_recover_faces(cbr_mesh *mesh, int64_t count, const int64_t *tris, const int32_t *labels);

/* Number of Steiner points (points added by recovery, all off the
   surface; after cbr_mesh_refine, those it kept) that the getters return
   (see CBR_PARAM_KEEP_EXTERIOR); -1 for a NULL mesh. Their ids follow the
   input points'. */
CBR_API int64_t cbr_mesh_steiner_count(const cbr_mesh *mesh);

/* Copies the ids of the Steiner points (cbr_mesh_steiner_count of them, in
   the index base as set) into ids_out (may be NULL when there are none). */
CBR_API int cbr_mesh_steiner_points(const cbr_mesh *mesh, int64_t *ids_out);

/* Copies the region of each tetrahedron, in the order of cbr_mesh_get_tets
   (cbr_mesh_tet_count values), into regions_out. Before recovery every
   tetrahedron is in region 0. */
CBR_API int cbr_mesh_get_tet_regions(const cbr_mesh *mesh, int32_t *regions_out);

/* Reads statistic `key` (a CBR_STAT_* key) into *value; 0 before the step
   that sets it has run. CBR_ERR_INVALID_ARGUMENT for a NULL mesh or value
   or an unknown key. */
CBR_API int cbr_mesh_get_stat(const cbr_mesh *mesh, int key, double *value);

/* ------------------------------------------------------------------------ */
/* Full mesh generation (Du & Wang 2004, section 6)                         */
/* ------------------------------------------------------------------------ */

/* Fills the bounded regions of a recovered mesh with points and improves
   its elements: a sizing field (CBR_PARAM_REFINE_SIZE, _GRADING,
   _SIZE_FROM_SURFACE, _GROWTH), field points inserted until the
   tetrahedra meet it and the quality bound (CBR_PARAM_REFINE_QUALITY_BOUND)
   as far as points may go (see below), then optimisation passes
   (CBR_PARAM_REFINE_PASSES: quality flips, smoothing). The surface stays
   exactly the input: every input triangle stays a face, no point is
   added on it and no input point moves; the exterior (region 0) is not
   refined; regions keep their numbers. The size bound: every
   edge of a tetrahedron of a bounded region that is not an input edge is
   at most 1.5 (h(u) + h(v)) / 2 long, h being the sizing field at its
   ends, or, from an input point u into the interior, at most 1.25 times
   the largest circumradius of the input triangles at u (no point may be
   added on the surface, so no tetrahedron on a large input triangle can
   be small; a domain that lies within that reach of its surface can thus
   keep few points, see README "Known limitations"). Tetrahedra stay over
   it where refinement may not split them: their circumcentre is refused
   (outside their region, or encroaching on an input triangle) and so is
   the midpoint of their most over-long edge (nearer the surface than a
   tenth of that edge), as on walls far thinner than their triangles are
   long; CBR_STAT_REFINE_OVERSIZE_TETS counts those over it at the end.
   New points get the next ids, after the points inserted so far (and
   recovery's Steiner points); the Steiner points of recovery may move
   (smoothing, relocation) or, where one keeps an element with q < 0.1,
   be suppressed: cbr_mesh_steiner_count and cbr_mesh_steiner_points then
   report those left, and the ids after the caller's points close up
   (Steiner points left, then the new points; the caller's ids never
   change). Statistics: CBR_STAT_QUALITY_AVERAGE ...
   CBR_STAT_REFINE_OVERSIZE_TETS. It may be called again (it refines
   further, with the parameters then set).
   Errors (the mesh is then unchanged):
     CBR_ERR_INVALID_ARGUMENT  NULL mesh; cbr_mesh_recover_faces has not
                               succeeded on this mesh; no size (surface
                               field off and CBR_PARAM_REFINE_SIZE 0);
     CBR_ERR_OUT_OF_MEMORY;
     CBR_ERR_INTERNAL          a check of the result failed (a bug). */
CBR_API int cbr_mesh_refine(cbr_mesh *mesh);

/* Reads the Table II statistic `key` of one bounded region alone: over the
   tetrahedra that cbr_mesh_get_tet_regions puts in `region` (1 to
   CBR_STAT_REGION_COUNT - 1), after cbr_mesh_refine. The keys:
   CBR_STAT_QUALITY_AVERAGE to CBR_STAT_DIHEDRAL_MAX, and
   CBR_STAT_REFINE_TETS (the region's tetrahedra); cbr_mesh_get_stat gives
   them over all bounded regions. 0 before cbr_mesh_refine.
   CBR_ERR_INVALID_ARGUMENT for a NULL mesh or value, another key, or a
   region that is not a bounded region of the recovered mesh (before
   cbr_mesh_recover_faces, none is). */
CBR_API int cbr_mesh_get_region_stat(const cbr_mesh *mesh, int32_t region, int key, double *value);

/* ------------------------------------------------------------------------ */
/* Surface checks                                                           */
/* ------------------------------------------------------------------------ */

/* Defect kinds found by cbr_mesh_check_faces (numbers fixed forever).
   The first five make a surface unusable for boundary recovery; open and
   non-manifold edges are legal (an open surface, two domains sharing a
   face) and reported for information. */
#define CBR_DEFECT_ID_OUT_OF_RANGE 1    /* a triangle names a point id that does not exist */
#define CBR_DEFECT_REPEATED_ID 2        /* a triangle uses one point twice */
#define CBR_DEFECT_ZERO_AREA 3          /* a triangle's three points are collinear */
#define CBR_DEFECT_DUPLICATE_TRIANGLE 4 /* two triangles with the same three points */
#define CBR_DEFECT_INTERSECTION 5       /* two triangles meet other than in a shared vertex or edge */
#define CBR_DEFECT_OPEN_EDGE 6          /* an edge used by one triangle only (information) */
#define CBR_DEFECT_NONMANIFOLD_EDGE 7   /* an edge used by more than two triangles (information) */

/* Checks `count` triangles (3*count point ids, index base as set) against
   the points of the mesh, exactly, and keeps the report in the handle
   (replacing the previous one). Returns CBR_OK when the surface has none of
   the first five defects, CBR_ERR_INVALID_INPUT when it has (the message
   names the first ones, e.g. "triangles 12 and 873 intersect (not in a
   shared vertex or edge)"), CBR_ERR_INVALID_ARGUMENT for a NULL mesh or
   tris with count > 0, or a negative count. Costs about O(n log n). */
CBR_API int cbr_mesh_check_faces(cbr_mesh *mesh, int64_t count, const int64_t *tris);

/* Number of defects of kind `kind` (a CBR_DEFECT_* key) in the last report:
   all of them, although only the first few are listed (see
   cbr_mesh_get_defect). 0 before any check; -1 for a NULL mesh or an
   unknown kind. */
CBR_API int64_t cbr_mesh_defect_count(const cbr_mesh *mesh, int kind);

/* Number of listed defects of kind `kind` (at most 20, the first in a fixed
   order: the report is deterministic); -1 for a NULL mesh or unknown kind. */
CBR_API int64_t cbr_mesh_defect_listed(const cbr_mesh *mesh, int kind);

/* The i-th listed defect of kind `kind` (0 <= i < cbr_mesh_defect_listed,
   in the index base as set): triangles_out receives 2 triangle indices (the
   second is -1 when a defect involves one triangle), points_out 3 point ids
   (-1 where not applicable: an edge defect gives 2). Either may be NULL. */
CBR_API int cbr_mesh_get_defect(const cbr_mesh *mesh, int kind, int64_t i, int64_t *triangles_out,
                                int64_t *points_out);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* CBR_H */
