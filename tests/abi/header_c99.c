/*
 * Header test (the idea of libgit2's tests/headertest): the public header
 * alone, compiled as strict C99 with -Wall -Wextra -pedantic -Werror.
 *
 * It checks that cbr.h
 *  - is self-contained (nothing is included before it),
 *  - survives being included twice (include guard),
 *  - keeps every signature and every constant of the ABI: each function is
 *    assigned to a pointer of its frozen type (a changed signature is an
 *    incompatible-pointer error under -Werror) and each constant is checked
 *    at compile time. Changing one of these is an ABI break; if it is
 *    intended, it comes with a new major version and an update here.
 *
 * It is also linked against libcbr and run, so that the declarations are
 * known to resolve.
 */
#include <cbr/cbr.h>
#include <cbr/cbr.h>

/* C99 has no _Static_assert: a negative array size stops the build. */
#define CBR_TEST_STATIC_ASSERT(name, cond) typedef char name[(cond) ? 1 : -1]

CBR_TEST_STATIC_ASSERT(ok_is_0, CBR_OK == 0);
CBR_TEST_STATIC_ASSERT(invalid_argument_is_m1, CBR_ERR_INVALID_ARGUMENT == -1);
CBR_TEST_STATIC_ASSERT(invalid_input_is_m2, CBR_ERR_INVALID_INPUT == -2);
CBR_TEST_STATIC_ASSERT(out_of_memory_is_m3, CBR_ERR_OUT_OF_MEMORY == -3);
CBR_TEST_STATIC_ASSERT(recovery_failed_is_m4, CBR_ERR_RECOVERY_FAILED == -4);
CBR_TEST_STATIC_ASSERT(io_is_m5, CBR_ERR_IO == -5);
CBR_TEST_STATIC_ASSERT(internal_is_m6, CBR_ERR_INTERNAL == -6);
CBR_TEST_STATIC_ASSERT(param_index_base_is_1, CBR_PARAM_INDEX_BASE == 1);
CBR_TEST_STATIC_ASSERT(version_macros_are_numbers,
                       CBR_VERSION_MAJOR >= 0 && CBR_VERSION_MINOR >= 0 &&
                           CBR_VERSION_PATCH >= 0);
/* The status codes must be usable in #if (plain integer constants). */
#if CBR_ERR_INVALID_INPUT >= 0 || CBR_VERSION_MAJOR < 0
#error "cbr.h constants are not preprocessor integers"
#endif

/* The frozen signatures, one pointer each. */
static const char *(*const p_version)(void) = cbr_version;
static const char *(*const p_status_string)(int) = cbr_status_string;
static int (*const p_create)(cbr_mesh **) = cbr_mesh_create;
static void (*const p_destroy)(cbr_mesh *) = cbr_mesh_destroy;
static const char *(*const p_last_error)(const cbr_mesh *) = cbr_mesh_last_error;
static int (*const p_set_param)(cbr_mesh *, int, double) = cbr_mesh_set_param;
static int (*const p_get_param)(const cbr_mesh *, int, double *) = cbr_mesh_get_param;
static int (*const p_insert_points)(cbr_mesh *, int64_t, const double *) =
    cbr_mesh_insert_points;
static int64_t (*const p_point_count)(const cbr_mesh *) = cbr_mesh_point_count;
static int64_t (*const p_tet_count)(const cbr_mesh *) = cbr_mesh_tet_count;
static int (*const p_get_points)(const cbr_mesh *, double *) = cbr_mesh_get_points;
static int (*const p_get_tets)(const cbr_mesh *, int64_t *) = cbr_mesh_get_tets;

int main(void)
{
    /* int64_t comes from the header's own includes. */
    int64_t count;
    int failures = 0;
    cbr_mesh *mesh = NULL;

    if (p_version() == NULL || p_status_string(CBR_OK) == NULL)
        ++failures;
    /* NULL handles are answered, never dereferenced. */
    count = p_point_count(NULL) + p_tet_count(NULL);
    if (count != -2)
        ++failures;
    if (p_last_error(NULL) == NULL)
        ++failures;
    if (p_set_param(NULL, CBR_PARAM_INDEX_BASE, 1.0) != CBR_ERR_INVALID_ARGUMENT)
        ++failures;
    if (p_get_param(NULL, CBR_PARAM_INDEX_BASE, NULL) != CBR_ERR_INVALID_ARGUMENT)
        ++failures;
    if (p_insert_points(NULL, 0, NULL) != CBR_ERR_INVALID_ARGUMENT)
        ++failures;
    if (p_get_points(NULL, NULL) != CBR_ERR_INVALID_ARGUMENT ||
        p_get_tets(NULL, NULL) != CBR_ERR_INVALID_ARGUMENT)
        ++failures;
    if (p_create(&mesh) != CBR_OK || mesh == NULL)
        ++failures;
    p_destroy(mesh);
    p_destroy(NULL);
    return failures;
}
