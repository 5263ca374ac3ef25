/*
 * Downstream test, C: compiled the way a user does,
 *     cc cube.c $(pkg-config --cflags --libs cbr)
 * against an installed libcbr, and run.
 *
 * The 8 corners of the unit cube and its centre: the corners are
 * cospherical and the centre lies strictly inside their sphere, so every
 * Delaunay tetrahedron has the centre as a vertex and the tetrahedralization
 * is the cone from the centre over the 12 hull triangles (two per face):
 * 12 tetrahedra of volume 1/12 each, whatever diagonal the symbolic
 * perturbation picks on each face.
 *
 * Exits 0 when everything matches, 1 otherwise (every mismatch is printed).
 */
#include <cbr/cbr.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;

#define CHECK(cond)                                                           \
    do {                                                                      \
        if (!(cond)) {                                                        \
            fprintf(stderr, "cube.c:%d: check failed: %s\n", __LINE__, #cond); \
            ++failures;                                                       \
        }                                                                     \
    } while (0)

static const double cube_points[9][3] = {
    {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
    {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1},
    {0.5, 0.5, 0.5}, /* id 8: the centre */
};

/* 6 * signed volume of the tetrahedron (a, b, c, d): det[b-a, c-a, d-a]. */
static double six_volume(const double *a, const double *b, const double *c,
                         const double *d)
{
    double u[3], v[3], w[3];
    int i;
    for (i = 0; i < 3; ++i) {
        u[i] = b[i] - a[i];
        v[i] = c[i] - a[i];
        w[i] = d[i] - a[i];
    }
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

static void check_version(void)
{
    char expected[64];
    const char *version = cbr_version();
    sprintf(expected, "%d.%d.%d", CBR_VERSION_MAJOR, CBR_VERSION_MINOR, CBR_VERSION_PATCH);
    CHECK(version != NULL);
    if (version != NULL && strcmp(version, expected) != 0) {
        fprintf(stderr, "cbr_version() = \"%s\" but the header says %s\n", version, expected);
        ++failures;
    }
    CHECK(cbr_status_string(CBR_OK) != NULL);
    CHECK(cbr_status_string(CBR_ERR_INVALID_INPUT) != NULL);
    CHECK(cbr_status_string(12345) != NULL);
}

static void check_cube(cbr_mesh *mesh)
{
    int64_t tets[4 * 12];
    double xyz[3 * 9];
    int64_t ntet, t;
    int k, seen[9] = {0};
    double total = 0;

    CHECK(cbr_mesh_insert_points(mesh, 9, &cube_points[0][0]) == CBR_OK);
    CHECK(cbr_mesh_point_count(mesh) == 9);
    ntet = cbr_mesh_tet_count(mesh);
    if (ntet != 12) {
        fprintf(stderr, "cbr_mesh_tet_count = %lld, expected 12\n", (long long)ntet);
        ++failures;
        return;
    }
    CHECK(cbr_mesh_get_points(mesh, xyz) == CBR_OK);
    CHECK(memcmp(xyz, cube_points, sizeof xyz) == 0); /* bit-identical */

    CHECK(cbr_mesh_get_tets(mesh, tets) == CBR_OK);
    for (t = 0; t < ntet; ++t) {
        const int64_t *v = tets + 4 * t;
        int has_centre = 0;
        double vol6;
        for (k = 0; k < 4; ++k) {
            if (v[k] < 0 || v[k] > 8) {
                fprintf(stderr, "tet %lld: id %lld out of 0..8\n", (long long)t, (long long)v[k]);
                ++failures;
                return;
            }
            seen[v[k]] = 1;
            has_centre |= v[k] == 8;
        }
        vol6 = six_volume(cube_points[v[0]], cube_points[v[1]], cube_points[v[2]],
                          cube_points[v[3]]);
        if (!has_centre || vol6 != 0.5) {
            fprintf(stderr, "tet %lld = (%lld %lld %lld %lld): 6*volume %g (expected 0.5, "
                            "positive orientation), centre %s\n",
                    (long long)t, (long long)v[0], (long long)v[1], (long long)v[2],
                    (long long)v[3], vol6, has_centre ? "present" : "missing");
            ++failures;
        }
        total += vol6 / 6;
    }
    for (k = 0; k < 9; ++k)
        CHECK(seen[k]);
    CHECK(fabs(total - 1.0) < 1e-12);
}

static void check_nan_rejected(cbr_mesh *mesh)
{
    double bad[3 * 2] = {0.25, 0.25, 0.25, 0.75, 0.0, 0.75};
    const char *message;
    bad[4] = NAN;
    CHECK(cbr_mesh_insert_points(mesh, 2, bad) == CBR_ERR_INVALID_INPUT);
    message = cbr_mesh_last_error(mesh);
    CHECK(message != NULL && message[0] != '\0');
    /* A failed call changes nothing. */
    CHECK(cbr_mesh_point_count(mesh) == 9);
    CHECK(cbr_mesh_tet_count(mesh) == 12);
}

int main(void)
{
    cbr_mesh *mesh = NULL;
    double base = -1;

    check_version();
    if (cbr_mesh_create(&mesh) != CBR_OK || mesh == NULL) {
        fprintf(stderr, "cbr_mesh_create failed\n");
        return 1;
    }
    CHECK(cbr_mesh_get_param(mesh, CBR_PARAM_INDEX_BASE, &base) == CBR_OK);
    CHECK(base == 0);
    CHECK(cbr_mesh_tet_count(mesh) == 0);
    check_cube(mesh);
    check_nan_rejected(mesh);
    cbr_mesh_destroy(mesh);
    cbr_mesh_destroy(NULL);

    if (failures != 0) {
        fprintf(stderr, "cube.c: %d check(s) failed\n", failures);
        return 1;
    }
    printf("cube.c: libcbr %s, 9 points, 12 tetrahedra, NaN rejected: OK\n", cbr_version());
    return 0;
}
