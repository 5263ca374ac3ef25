// Exit codes of the cbr command (documented in `cbr --help` and README,
// "The cbr command"), and the mapping from libcbr's status codes.
#pragma once

#include <cbr/cbr.h>

#include "io/status.hpp"

namespace cbr::cli {

constexpr int kExitOk = 0;        // success
constexpr int kExitUsage = 1;     // bad command line
constexpr int kExitInput = 2;     // invalid input: unparsable file, or a surface that cannot be recovered
constexpr int kExitRecovery = 3;  // boundary recovery failed
constexpr int kExitIo = 4;        // a file missing, unreadable, unwritable, or of unknown extension
constexpr int kExitInternal = 5;  // a bug or out of memory

inline int exit_code_for(int status) {
    switch (status) {
        case CBR_OK: return kExitOk;
        case CBR_ERR_INVALID_ARGUMENT: return kExitUsage;
        case CBR_ERR_INVALID_INPUT: return kExitInput;
        case CBR_ERR_RECOVERY_FAILED: return kExitRecovery;
        case CBR_ERR_IO: return kExitIo;
        default: return kExitInternal;
    }
}

// The name of an exit code in the JSON reports ("status"): stable.
inline const char* exit_status_name(int code) {
    switch (code) {
        case kExitOk: return "ok";
        case kExitUsage: return "usage";
        case kExitInput: return "invalid_input";
        case kExitRecovery: return "recovery_failed";
        case kExitIo: return "io_error";
        default: return "internal_error";
    }
}

// Exit code for a failed read or write of a file.
inline int exit_code_for(io::ErrorKind kind) {
    switch (kind) {
        case io::ErrorKind::parse_error:
        case io::ErrorKind::invalid_mesh: return kExitInput;
        case io::ErrorKind::not_found:
        case io::ErrorKind::unreadable:
        case io::ErrorKind::unknown_extension:
        case io::ErrorKind::write_error: return kExitIo;
        default: return kExitInternal;
    }
}

}  // namespace cbr::cli
