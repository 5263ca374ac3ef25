#include "cli/json_writer.hpp"

#include <cmath>
#include <cstdio>
#include <exception>

#include "io/text_writer.hpp"

namespace cbr::cli {
namespace {

// The length of the well-formed UTF-8 sequence starting at s[i] (a byte
// >= 0x80), or 0 when it is not one (JSON text must be UTF-8).
std::size_t utf8_length(std::string_view s, std::size_t i) {
    const auto lead = static_cast<unsigned char>(s[i]);
    std::size_t n = 0;
    unsigned lo = 0x80, hi = 0xbf;  // range of the second byte
    if (lead >= 0xc2 && lead <= 0xdf) {
        n = 2;
    } else if (lead >= 0xe0 && lead <= 0xef) {
        n = 3;
        if (lead == 0xe0) lo = 0xa0;  // no overlong forms
        if (lead == 0xed) hi = 0x9f;  // no surrogates
    } else if (lead >= 0xf0 && lead <= 0xf4) {
        n = 4;
        if (lead == 0xf0) lo = 0x90;
        if (lead == 0xf4) hi = 0x8f;  // up to U+10FFFF
    } else {
        return 0;
    }
    if (i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k) {
        const auto b = static_cast<unsigned char>(s[i + k]);
        if (b < (k == 1 ? lo : 0x80u) || b > (k == 1 ? hi : 0xbfu)) return 0;
    }
    return n;
}

}  // namespace

void JsonWriter::newline() {
    text_ += '\n';
    text_.append(2 * members_.size(), ' ');
}

void JsonWriter::before_value() {
    if (after_key_) {
        after_key_ = false;
        return;
    }
    if (members_.empty()) return;
    if (members_.back()++ > 0) text_ += ',';
    newline();
}

void JsonWriter::open(char bracket) {
    before_value();
    text_ += bracket;
    members_.push_back(0);
}

void JsonWriter::close(char bracket) {
    const bool empty = members_.back() == 0;
    members_.pop_back();
    if (!empty) newline();
    text_ += bracket;
    if (members_.empty()) text_ += '\n';
}

JsonWriter& JsonWriter::begin_object() {
    open('{');
    return *this;
}

JsonWriter& JsonWriter::end_object() {
    close('}');
    return *this;
}

JsonWriter& JsonWriter::begin_array() {
    open('[');
    return *this;
}

JsonWriter& JsonWriter::end_array() {
    close(']');
    return *this;
}

JsonWriter& JsonWriter::key(std::string_view name) {
    before_value();
    put_string(name);
    text_ += ": ";
    after_key_ = true;
    return *this;
}

JsonWriter& JsonWriter::string(std::string_view s) {
    before_value();
    put_string(s);
    return *this;
}

void JsonWriter::put_string(std::string_view s) {
    text_ += '"';
    for (std::size_t i = 0; i < s.size();) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c >= 0x80) {  // a UTF-8 sequence, copied whole, or one invalid byte
            const std::size_t n = utf8_length(s, i);
            if (n == 0) {
                text_ += "\\ufffd";
                ++i;
            } else {
                text_.append(s.substr(i, n));
                i += n;
            }
            continue;
        }
        ++i;
        switch (c) {
            case '"': text_ += "\\\""; break;
            case '\\': text_ += "\\\\"; break;
            case '\n': text_ += "\\n"; break;
            case '\r': text_ += "\\r"; break;
            case '\t': text_ += "\\t"; break;
            default:
                if (c < 0x20 || c == 0x7f) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
                    text_ += buf;
                } else {
                    text_ += static_cast<char>(c);
                }
        }
    }
    text_ += '"';
}

JsonWriter& JsonWriter::integer(std::int64_t v) {
    before_value();
    text_ += std::to_string(v);
    return *this;
}

JsonWriter& JsonWriter::number(double v) {
    if (!std::isfinite(v)) return null();
    before_value();
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    text_ += buf;
    return *this;
}

JsonWriter& JsonWriter::boolean(bool v) {
    before_value();
    text_ += v ? "true" : "false";
    return *this;
}

JsonWriter& JsonWriter::null() {
    before_value();
    text_ += "null";
    return *this;
}

io::Status write_text_file(const std::string& path, const std::string& text) noexcept {
    try {
        io::detail::TextWriter w;
        if (auto st = w.open(path); !st) return st;
        w.put(text);
        return w.commit();
    } catch (const std::exception& e) {
        return io::Status::error(io::ErrorKind::write_error, path + ": " + e.what());
    }
}

}  // namespace cbr::cli
