// Buffered text output into a temporary file that replaces the target only
// when complete ("write to a temp file, then rename"): the temporary file is
// created next to the target (same directory, hence same file system, so
// rename() is atomic) as ".NAME.tmp-PID-N", and removed again if anything
// fails or the writer is destroyed before publish().
//
// Numbers are formatted with std::to_chars: integers exactly, doubles in the
// shortest form that parses back to the same bits.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/status.hpp"

namespace cbr::io::detail {

class TextWriter {
public:
    TextWriter() = default;
    TextWriter(const TextWriter&) = delete;
    TextWriter& operator=(const TextWriter&) = delete;
    ~TextWriter();

    // Creates the temporary file for `final_path`.
    Status open(const std::string& final_path);

    TextWriter& put(std::string_view s);
    TextWriter& put(char c);
    TextWriter& put_int(std::int64_t v);
    TextWriter& put_double(double v);

    // Flushes and closes the temporary file (it stays hidden).
    Status finish();
    // Renames the finished temporary file to the final path.
    Status publish();
    // finish() then publish().
    Status commit();

    const std::string& final_path() const { return final_; }

private:
    void flush();
    void reserve_room(std::size_t n) {
        if (buf_.size() - used_ < n) flush();
    }
    Status failure(const char* what) const;

    std::string final_, temp_;
    int fd_ = -1;
    std::vector<char> buf_;
    std::size_t used_ = 0;
    int error_ = 0;  // first errno seen while writing
    bool published_ = false;
};

}  // namespace cbr::io::detail
