#include "io/text_cursor.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

namespace cbr::io::detail {

namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// std::from_chars rejects a leading '+', which some writers emit.
std::string_view strip_plus(std::string_view tok) {
    if (tok.size() > 1 && tok[0] == '+' && tok[1] != '-' && tok[1] != '+') tok.remove_prefix(1);
    return tok;
}

}  // namespace

NumberError parse_double(std::string_view tok, double& value) {
    if (tok.empty()) return NumberError::empty;
    tok = strip_plus(tok);
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec == std::errc::result_out_of_range) return NumberError::out_of_range;
    if (ec != std::errc() || ptr != tok.data() + tok.size()) return NumberError::syntax;
    if (!std::isfinite(v)) return NumberError::not_finite;  // "nan", "inf" parse fine otherwise
    value = v;
    return NumberError::none;
}

NumberError parse_int64(std::string_view tok, std::int64_t& value) {
    if (tok.empty()) return NumberError::empty;
    tok = strip_plus(tok);
    std::int64_t v = 0;
    const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec == std::errc::result_out_of_range) return NumberError::out_of_range;
    if (ec != std::errc() || ptr != tok.data() + tok.size()) return NumberError::syntax;
    value = v;
    return NumberError::none;
}

std::string quote_token(std::string_view tok) {
    constexpr std::size_t kMax = 24;
    std::string out = "'";
    out.append(tok.substr(0, kMax));
    if (tok.size() > kMax) out += "...";
    out += "'";
    return out;
}

TextCursor::TextCursor(const std::string& path, std::string_view text, char comment)
    : path_(path), begin_(text.data()), p_(text.data()), end_(text.data() + text.size()),
      comment_(comment) {
    for (int c = 0; c < 256; ++c) {
        const char ch = static_cast<char>(c);
        class_[static_cast<std::size_t>(c)] =
            static_cast<std::uint8_t>((is_blank(ch) ? kBlank : 0) | (ch == '\n' || ch == comment_ ? kStop : 0));
    }
}

void TextCursor::skip_blanks() {
    while (p_ != end_ && (class_of(*p_) & kBlank) != 0) ++p_;
    if (p_ != end_ && *p_ == comment_) {
        while (p_ != end_ && *p_ != '\n') ++p_;
    }
}

bool TextCursor::start_record() {
    for (;;) {
        skip_blanks();
        if (p_ == end_) return false;
        if (*p_ != '\n') return true;
        ++p_;
        ++line_;
    }
}

std::string_view TextCursor::take_token() {
    const char* b = p_;
    while (p_ != end_ && (class_of(*p_) & (kBlank | kStop)) == 0) ++p_;
    return {b, static_cast<std::size_t>(p_ - b)};
}

std::string_view TextCursor::field() {
    skip_blanks();
    if (p_ == end_ || *p_ == '\n') return {};
    return take_token();
}

std::string_view TextCursor::token() {
    if (!start_record()) return {};
    return take_token();
}

void TextCursor::skip_line() {
    while (p_ != end_ && *p_ != '\n') ++p_;
    if (p_ != end_) {
        ++p_;
        ++line_;
    }
}

bool TextCursor::line_done() {
    skip_blanks();
    return p_ == end_ || *p_ == '\n';
}

void TextCursor::seek(std::size_t offset, std::size_t line) {
    p_ = begin_ + offset;
    line_ = line;
}

Status TextCursor::fail(const std::string& message) const {
    // At the end of a file that ends with a line end, name the last line
    // rather than the empty one after it.
    const bool after_last_line = p_ == end_ && p_ != begin_ && p_[-1] == '\n' && line_ > 1;
    std::string m = path_ + ":" + std::to_string(after_last_line ? line_ - 1 : line_) + ": ";
    if (ctx_kind_ != nullptr) {
        m += ctx_kind_;
        if (ctx_index_ >= 0) m += " " + std::to_string(ctx_index_);
        m += ": ";
    }
    m += message;
    return Status::error(ErrorKind::parse_error, std::move(m));
}

Status TextCursor::fail_at(std::size_t line, const std::string& message) const {
    return Status::error(ErrorKind::parse_error, path_ + ":" + std::to_string(line) + ": " + message);
}

Status TextCursor::to_double(std::string_view tok, const char* what, double& value) const {
    switch (parse_double(tok, value)) {
        case NumberError::none: return {};
        case NumberError::empty:
            return fail(std::string("expected ") + what + ", found " +
                        (p_ == end_ ? "the end of the file" : "the end of the line"));
        case NumberError::syntax:
            return fail(std::string("expected ") + what + ", found " + quote_token(tok));
        case NumberError::not_finite:
            return fail(std::string(what) + " " + quote_token(tok) + " is not a finite number");
        case NumberError::out_of_range:
            return fail(std::string(what) + " " + quote_token(tok) + " is outside the range of double");
    }
    return fail("internal error");
}

Status TextCursor::to_int(std::string_view tok, const char* what, std::int64_t& value) const {
    switch (parse_int64(tok, value)) {
        case NumberError::none: return {};
        case NumberError::empty:
            return fail(std::string("expected ") + what + ", found " +
                        (p_ == end_ ? "the end of the file" : "the end of the line"));
        case NumberError::syntax:
        case NumberError::not_finite:
            return fail(std::string("expected ") + what + " (an integer), found " + quote_token(tok));
        case NumberError::out_of_range:
            return fail(std::string(what) + " " + quote_token(tok) + " is too large");
    }
    return fail("internal error");
}

Status TextCursor::check_count(std::int64_t count, std::size_t min_bytes_each, const char* what) const {
    if (count < 0) return fail(std::string(what) + " " + std::to_string(count) + " is negative");
    const std::size_t room = remaining_bytes() / (min_bytes_each == 0 ? 1 : min_bytes_each);
    if (static_cast<std::uint64_t>(count) > room) {
        return fail(std::string(what) + " " + std::to_string(count) +
                    " cannot fit in the rest of the file (" + std::to_string(remaining_bytes()) +
                    " bytes): truncated file or corrupt header");
    }
    return {};
}

}  // namespace cbr::io::detail
