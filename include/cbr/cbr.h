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

/* Number of points in the mesh; -1 for a NULL mesh. */
CBR_API int64_t cbr_mesh_point_count(const cbr_mesh *mesh);

/* Number of tetrahedra cbr_mesh_get_tets returns; -1 for a NULL mesh.
   Fewer than 4 points, or all points coplanar, give 0. */
CBR_API int64_t cbr_mesh_tet_count(const cbr_mesh *mesh);

/* Copies the coordinates of all points, in id order, into xyz_out
   (3 * cbr_mesh_point_count doubles). The coordinates are bit-identical to
   the ones inserted. xyz_out may be NULL when there are no points. */
CBR_API int cbr_mesh_get_points(const cbr_mesh *mesh, double *xyz_out);

/* Copies the tetrahedra into tets_out (4 * cbr_mesh_tet_count point ids,
   in the index base set): the finite tetrahedra of the Delaunay
   tetrahedralization of all points, each positively oriented (see the
   orientation convention at the top of this file). tets_out may be NULL
   when there are no tetrahedra. */
CBR_API int cbr_mesh_get_tets(const cbr_mesh *mesh, int64_t *tets_out);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* CBR_H */
