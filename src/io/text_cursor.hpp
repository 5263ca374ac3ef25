// Line-aware tokenizer over an in-memory text file, shared by the text
// readers. Tokens are runs of non-blank characters; blanks are space, tab,
// CR (so CRLF files read like LF files), vertical tab and form feed. A
// comment character (usually '#') hides the rest of its line.
//
// Two ways to read:
//  - token(): the next token wherever it is (crosses line ends);
//  - start_record() then field()...: a record that lives on one line, as in
//    OFF and TetGen files; field() returns "" at the end of that line.
//
// Numbers are parsed exactly with std::from_chars (correctly rounded, so the
// double is bit-identical to what the text denotes); NaN, infinities and
// values outside the double range are errors.
//
// Errors read "path:LINE: [record N: ]message"; set_context() names the
// record being read without building any string until an error happens.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "io/status.hpp"

namespace cbr::io::detail {

class TextCursor {
public:
    TextCursor(const std::string& path, std::string_view text, char comment = '#');

    // Skips blanks, line ends and comments up to the next token; false at
    // the end of the text.
    bool start_record();
    // Next token on the current line ("" at the end of the line or at a
    // comment). Never moves to the next line.
    std::string_view field();
    // Next token anywhere ("" at the end of the text).
    std::string_view token();
    // Skips the rest of the current line, including its line end.
    void skip_line();
    // True if the current line has no more tokens (comments do not count).
    bool line_done();

    std::size_t line() const { return line_; }
    std::size_t offset() const { return static_cast<std::size_t>(p_ - begin_); }
    std::size_t remaining_bytes() const { return static_cast<std::size_t>(end_ - p_); }
    // Moves to an absolute byte offset (used by PLY after the header).
    void seek(std::size_t offset, std::size_t line);

    // What is being read, for error messages: "vertex 12", "face 3", ...
    // (index < 0: just the kind). `kind` must be a string literal.
    void set_context(const char* kind, std::int64_t index = -1) {
        ctx_kind_ = kind;
        ctx_index_ = index;
    }
    void clear_context() { ctx_kind_ = nullptr; }

    // Builds a parse_error "path:LINE: [context: ]message".
    Status fail(const std::string& message) const;
    // Same for an earlier line, without the context: "path:LINE: message".
    Status fail_at(std::size_t line, const std::string& message) const;

    // Parse `tok` (usually just returned by field() or token()); `what`
    // names the value ("x coordinate", "vertex count").
    Status to_double(std::string_view tok, const char* what, double& value) const;
    Status to_int(std::string_view tok, const char* what, std::int64_t& value) const;

    // A count read from a header must be >= 0 and fit in the rest of the
    // file at `min_bytes_each` bytes per item; this is checked before any
    // memory is reserved for it.
    Status check_count(std::int64_t count, std::size_t min_bytes_each, const char* what) const;

private:
    void skip_blanks();  // on the current line
    std::string_view take_token();

    // Per byte value: kBlank for a blank, kStop for a line end or the
    // comment character (either ends a token): one lookup per character
    // where five to seven comparisons were (igea's 1.5 million fields).
    static constexpr std::uint8_t kBlank = 1, kStop = 2;
    std::uint8_t class_of(char c) const { return class_[static_cast<unsigned char>(c)]; }
    std::array<std::uint8_t, 256> class_{};

    const std::string& path_;
    const char* begin_;
    const char* p_;
    const char* end_;
    char comment_;
    std::size_t line_ = 1;
    const char* ctx_kind_ = nullptr;
    std::int64_t ctx_index_ = -1;
};

// The exact parsers behind to_double/to_int, also used by the PLY header.
// They accept an optional leading '+', and report anything but a complete,
// finite, in-range number.
enum class NumberError { none, empty, syntax, not_finite, out_of_range };
NumberError parse_double(std::string_view tok, double& value);
NumberError parse_int64(std::string_view tok, std::int64_t& value);

// Token shortened for messages: "abc", or the first 24 characters + "...".
std::string quote_token(std::string_view tok);

}  // namespace cbr::io::detail
