#include "io/status.hpp"

namespace cbr::io {

const char* error_kind_name(ErrorKind kind) {
    switch (kind) {
        case ErrorKind::none: return "none";
        case ErrorKind::not_found: return "not_found";
        case ErrorKind::unreadable: return "unreadable";
        case ErrorKind::unknown_extension: return "unknown_extension";
        case ErrorKind::parse_error: return "parse_error";
        case ErrorKind::invalid_mesh: return "invalid_mesh";
        case ErrorKind::write_error: return "write_error";
        case ErrorKind::out_of_memory: return "out_of_memory";
    }
    return "unknown";
}

}  // namespace cbr::io
