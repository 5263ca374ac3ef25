// Buffered text output into a temporary file that replaces the target only
// when complete ("write to a temp file, then rename"): the temporary file is
// created next to the target (same directory, hence same file system, so
// rename() is atomic) as ".NAME.tmp-PID-N", and removed again if anything
// fails or the writer is destroyed before publish().
//
// Numbers are formatted with std::to_chars: integers exactly, doubles in the
// shortest form that parses back to the same bits.
#pragma once

#include <charconv>
#include <cstdint>
#include <cstring>
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

    // Creates the temporary file for `final_path`; the put functions
    // below write only after it succeeded.
    Status open(const std::string& final_path);

    // The writers call these once or more per number: inline, each with
    // one check for room (igea's Medit file: 2.7 million integers).
    TextWriter& put(std::string_view s) {
        if (s.size() > buf_.size() - used_) return put_long(s);
        std::memcpy(buf_.data() + used_, s.data(), s.size());
        used_ += s.size();
        return *this;
    }
    TextWriter& put(char c) {
        reserve_room(1);
        buf_[used_++] = c;
        return *this;
    }
    TextWriter& put_int(std::int64_t v) {
        reserve_room(kIntRoom);
        return advance_to(std::to_chars(buf_.data() + used_, buf_.data() + buf_.size(), v).ptr);
    }
    TextWriter& put_double(double v) {
        reserve_room(kDoubleRoom);
        return advance_to(std::to_chars(buf_.data() + used_, buf_.data() + buf_.size(), v).ptr);
    }

    // Flushes and closes the temporary file (it stays hidden).
    Status finish();
    // Renames the finished temporary file to the final path.
    Status publish();
    // finish() then publish().
    Status commit();

    const std::string& final_path() const { return final_; }

private:
    static constexpr std::size_t kIntRoom = 24;     // "-9223372036854775808" is 20
    static constexpr std::size_t kDoubleRoom = 32;  // "-1.2345678901234567e-308" is 24

    TextWriter& put_long(std::string_view s);  // a string that does not fit in what is left
    TextWriter& advance_to(const char* end) {
        used_ = static_cast<std::size_t>(end - buf_.data());
        return *this;
    }
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
