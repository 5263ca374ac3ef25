// The result of every reader and writer: no exception ever leaves cbr_io.
// A failed call returns a Status whose message is one line, naming the file
// (and, for text formats, the line: "path:12: ...").
#pragma once

#include <string>
#include <utility>

namespace cbr::io {

enum class ErrorKind {
    none = 0,
    not_found,          // the input file does not exist
    unreadable,         // exists but cannot be opened/read (permissions, a directory, I/O error)
    unknown_extension,  // no reader/writer for this file name
    parse_error,        // malformed content (with line number for text formats)
    invalid_mesh,       // writer given inconsistent arrays (sizes, indices, NaN)
    write_error,        // the output could not be created, written or renamed
    out_of_memory,
};

struct Status {
    ErrorKind kind = ErrorKind::none;
    std::string message;  // empty when ok

    bool ok() const { return kind == ErrorKind::none; }
    explicit operator bool() const { return ok(); }

    static Status success() { return {}; }
    static Status error(ErrorKind k, std::string msg) { return {k, std::move(msg)}; }
};

// Short stable name of a kind ("parse_error", ...), for logs and tests.
const char* error_kind_name(ErrorKind kind);

}  // namespace cbr::io
