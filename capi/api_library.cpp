// Library-wide functions: version and status descriptions.
#include <cbr/cbr.h>

#define CBR_STRINGIFY_(x) #x
#define CBR_STRINGIFY(x) CBR_STRINGIFY_(x)

extern "C" {

CBR_API const char* cbr_version(void) {
    return CBR_STRINGIFY(CBR_VERSION_MAJOR) "." CBR_STRINGIFY(CBR_VERSION_MINOR) "." CBR_STRINGIFY(CBR_VERSION_PATCH);
}

CBR_API const char* cbr_status_string(int status) {
    switch (status) {
        case CBR_OK: return "ok";
        case CBR_ERR_INVALID_ARGUMENT: return "invalid argument";
        case CBR_ERR_INVALID_INPUT: return "invalid input";
        case CBR_ERR_OUT_OF_MEMORY: return "out of memory";
        case CBR_ERR_RECOVERY_FAILED: return "boundary recovery failed";
        case CBR_ERR_IO: return "input/output error";
        case CBR_ERR_INTERNAL: return "internal error";
        default: return "unknown status";
    }
}

}  // extern "C"
