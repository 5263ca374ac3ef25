// Header test, C++ side: cbr.h alone, compiled as C++17 with
// -Wall -Wextra -pedantic -Werror. Checks that the header is valid C++, that
// its declarations get C linkage (extern "C"), and that the signatures and
// constants of the ABI are the frozen ones (see header_c99.c).
#include <cbr/cbr.h>
#include <cbr/cbr.h>

#include <type_traits>

static_assert(CBR_OK == 0, "status codes are fixed forever");
static_assert(CBR_ERR_INVALID_ARGUMENT == -1, "status codes are fixed forever");
static_assert(CBR_ERR_INVALID_INPUT == -2, "status codes are fixed forever");
static_assert(CBR_ERR_OUT_OF_MEMORY == -3, "status codes are fixed forever");
static_assert(CBR_ERR_RECOVERY_FAILED == -4, "status codes are fixed forever");
static_assert(CBR_ERR_IO == -5, "status codes are fixed forever");
static_assert(CBR_ERR_INTERNAL == -6, "status codes are fixed forever");
static_assert(CBR_PARAM_INDEX_BASE == 1, "parameter keys are fixed forever");

#define CBR_TEST_SIGNATURE(fn, ...)                                          \
    static_assert(std::is_same<decltype(&fn), __VA_ARGS__>::value,            \
                  #fn " changed signature: that breaks the ABI")

CBR_TEST_SIGNATURE(cbr_version, const char *(*)());
CBR_TEST_SIGNATURE(cbr_status_string, const char *(*)(int));
CBR_TEST_SIGNATURE(cbr_mesh_create, int (*)(cbr_mesh **));
CBR_TEST_SIGNATURE(cbr_mesh_destroy, void (*)(cbr_mesh *));
CBR_TEST_SIGNATURE(cbr_mesh_last_error, const char *(*)(const cbr_mesh *));
CBR_TEST_SIGNATURE(cbr_mesh_set_param, int (*)(cbr_mesh *, int, double));
CBR_TEST_SIGNATURE(cbr_mesh_get_param, int (*)(const cbr_mesh *, int, double *));
CBR_TEST_SIGNATURE(cbr_mesh_insert_points,
                   int (*)(cbr_mesh *, int64_t, const double *));
CBR_TEST_SIGNATURE(cbr_mesh_point_count, int64_t (*)(const cbr_mesh *));
CBR_TEST_SIGNATURE(cbr_mesh_tet_count, int64_t (*)(const cbr_mesh *));
CBR_TEST_SIGNATURE(cbr_mesh_get_points, int (*)(const cbr_mesh *, double *));
CBR_TEST_SIGNATURE(cbr_mesh_get_tets, int (*)(const cbr_mesh *, int64_t *));

// The handle is opaque: users hold a pointer, never see the layout (a
// public struct would make its size and fields part of the ABI).
template <class T, class = void> struct is_complete : std::false_type {};
template <class T>
struct is_complete<T, decltype(void(sizeof(T)))> : std::true_type {};
static_assert(!is_complete<cbr_mesh>::value, "cbr_mesh must stay opaque");

// C linkage (the extern "C" block of the header) is checked by linking this
// program against libcbr: C++-mangled names would not resolve.

int main()
{
    cbr_mesh *mesh = nullptr;
    if (cbr_mesh_create(&mesh) != CBR_OK || mesh == nullptr)
        return 1;
    const int64_t n = cbr_mesh_point_count(mesh);
    cbr_mesh_destroy(mesh);
    return n == 0 ? 0 : 1;
}
