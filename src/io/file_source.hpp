// Loading a whole input file into memory, and file-name helpers. Reading the
// file at once lets every parser validate header counts against the real
// size before reserving memory, and is fast (one read per file).
#pragma once

#include <string>

#include "io/status.hpp"

namespace cbr::io::detail {

// Reads `path` into `data`. not_found if it does not exist, unreadable if it
// cannot be opened or read (permissions, a directory, an I/O error).
Status load_file(const std::string& path, std::string& data);

// Lower-case extension without the dot ("STL" -> "stl"); "" if none. Only
// the last component of the path counts ("dir.v2/mesh" has none).
std::string lower_extension(const std::string& path);

// `path` with its extension (if any) replaced by `ext` (given with its dot).
std::string replace_extension(const std::string& path, const std::string& ext);

}  // namespace cbr::io::detail
