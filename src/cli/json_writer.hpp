// A small JSON writer for the command's reports (--json FILE): objects,
// arrays, strings, integers, doubles, booleans and null, indented by two
// spaces. Doubles are printed with "%.17g" (they read back to the same
// bits); a NaN or an infinity, which JSON cannot represent, becomes null.
// Strings are escaped (", \, control characters); UTF-8 passes through
// unchanged, and a byte that is not part of valid UTF-8 (a file name in
// another encoding) becomes U+FFFD, so that the file is always valid JSON.
//
// The caller keeps the structure well formed (a key before each member of
// an object, none in an array); the writer only places commas and newlines.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/status.hpp"

namespace cbr::cli {

class JsonWriter {
public:
    JsonWriter& begin_object();
    JsonWriter& end_object();
    JsonWriter& begin_array();
    JsonWriter& end_array();
    JsonWriter& key(std::string_view name);

    JsonWriter& string(std::string_view s);
    JsonWriter& integer(std::int64_t v);
    JsonWriter& number(double v);
    JsonWriter& boolean(bool v);
    JsonWriter& null();

    // The document so far (complete once every object and array is closed),
    // ending in a newline when complete.
    const std::string& text() const { return text_; }

private:
    void before_value();
    void open(char bracket);
    void close(char bracket);
    void newline();
    void put_string(std::string_view s);  // quoted and escaped

    std::string text_;
    std::vector<int> members_;  // per open object/array: members written so far
    bool after_key_ = false;
};

// Writes `text` to `path` through a temporary file renamed over it when
// complete (never a partial file under `path`).
io::Status write_text_file(const std::string& path, const std::string& text) noexcept;

}  // namespace cbr::cli
