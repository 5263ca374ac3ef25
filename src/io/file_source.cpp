#include "io/file_source.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "mesh/huge_pages.hpp"

namespace cbr::io::detail {

namespace {

Status io_failure(const std::string& path, int err) {
    const ErrorKind kind = (err == ENOENT || err == ENOTDIR) ? ErrorKind::not_found : ErrorKind::unreadable;
    const char* what = kind == ErrorKind::not_found ? "no such file" : std::strerror(err);
    return Status::error(kind, path + ": cannot read: " + what);
}

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

std::size_t last_component_start(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? 0 : slash + 1;
}

std::size_t extension_dot(const std::string& path) {
    const std::size_t start = last_component_start(path);
    const std::size_t dot = path.find_last_of('.');
    // A leading dot names a hidden file, not an extension (".off" is a name).
    if (dot == std::string::npos || dot <= start) return std::string::npos;
    return dot;
}

}  // namespace

Status load_file(const std::string& path, std::string& data) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return io_failure(path, errno);
    if (S_ISDIR(st.st_mode)) return Status::error(ErrorKind::unreadable, path + ": cannot read: is a directory");

    std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
    if (!f) return io_failure(path, errno);

    data.clear();
    if (S_ISREG(st.st_mode) && st.st_size > 0) cbr::mesh::reserve_huge(data, static_cast<std::size_t>(st.st_size));
    // Read in chunks until EOF: also works for pipes and files that change
    // size under us.
    char chunk[1 << 16];
    for (;;) {
        const std::size_t n = std::fread(chunk, 1, sizeof chunk, f.get());
        data.append(chunk, n);
        if (n < sizeof chunk) break;
    }
    if (std::ferror(f.get())) return io_failure(path, errno != 0 ? errno : EIO);
    return {};
}

std::string lower_extension(const std::string& path) {
    const std::size_t dot = extension_dot(path);
    if (dot == std::string::npos) return {};
    std::string ext = path.substr(dot + 1);
    for (char& c : ext) {
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    return ext;
}

std::string replace_extension(const std::string& path, const std::string& ext) {
    const std::size_t dot = extension_dot(path);
    return (dot == std::string::npos ? path : path.substr(0, dot)) + ext;
}

}  // namespace cbr::io::detail
