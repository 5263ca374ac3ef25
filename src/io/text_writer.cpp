#include "io/text_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace cbr::io::detail {

namespace {

// Large enough that writing costs a system call per 64 KB (igea's 27 MB
// Medit file: 0.06 s either way); small enough that zeroing it is not
// most of a small run: a megabyte took 240 page faults, about 2.5 ms of a
// cube's 8.5 ms `cbr recover` on the benchmark VM (6 ms now).
constexpr std::size_t kBufferBytes = 1 << 16;

std::string temp_name_for(const std::string& final_path) {
    static std::atomic<unsigned> counter{0};
    const std::size_t slash = final_path.find_last_of('/');
    const std::size_t start = slash == std::string::npos ? 0 : slash + 1;
    return final_path.substr(0, start) + "." + final_path.substr(start) + ".tmp-" + std::to_string(::getpid()) + "-" +
           std::to_string(counter.fetch_add(1));
}

}  // namespace

TextWriter::~TextWriter() {
    if (fd_ >= 0) ::close(fd_);
    if (!temp_.empty() && !published_) ::unlink(temp_.c_str());
}

Status TextWriter::open(const std::string& final_path) {
    final_ = final_path;
    for (int attempt = 0; attempt < 100; ++attempt) {
        temp_ = temp_name_for(final_path);
        // 0666 minus the umask: the permissions a plain fopen would give.
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ >= 0 || errno != EEXIST) break;
    }
    if (fd_ < 0) {
        const int err = errno;
        temp_.clear();
        return Status::error(ErrorKind::write_error, final_ + ": cannot create a file in its directory: " +
                                                         std::strerror(err));
    }
    buf_.resize(kBufferBytes);
    used_ = 0;
    return {};
}

void TextWriter::flush() {
    std::size_t done = 0;
    while (done < used_ && error_ == 0 && fd_ >= 0) {
        const ssize_t n = ::write(fd_, buf_.data() + done, used_ - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            error_ = errno;
        } else {
            done += static_cast<std::size_t>(n);
        }
    }
    used_ = 0;
}

TextWriter& TextWriter::put_long(std::string_view s) {
    flush();
    if (buf_.empty()) return *this;  // not open: nothing is written
    for (std::size_t i = 0; i < s.size(); i += buf_.size()) {
        const std::string_view part = s.substr(i, buf_.size());
        std::memcpy(buf_.data(), part.data(), part.size());
        used_ = part.size();
        if (used_ == buf_.size()) flush();
    }
    return *this;
}

Status TextWriter::failure(const char* what) const {
    return Status::error(ErrorKind::write_error, final_ + ": " + what + ": " + std::strerror(error_));
}

Status TextWriter::finish() {
    if (fd_ < 0) return Status::error(ErrorKind::write_error, final_ + ": not open");
    flush();
    if (::close(fd_) != 0 && error_ == 0) error_ = errno;
    fd_ = -1;
    if (error_ != 0) return failure("cannot write");
    return {};
}

Status TextWriter::publish() {
    if (::rename(temp_.c_str(), final_.c_str()) != 0) {
        error_ = errno;
        return failure("cannot replace the file");
    }
    published_ = true;
    return {};
}

Status TextWriter::commit() {
    if (auto st = finish(); !st) return st;
    return publish();
}

}  // namespace cbr::io::detail
