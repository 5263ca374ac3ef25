// PLY reader (ascii, binary_little_endian, binary_big_endian).
//
// The header declares elements in file order, each with a count and
// properties (scalar, or `list COUNT_TYPE ITEM_TYPE name`). Used here:
//   element vertex: properties x, y, z (any numeric type; float/double
//                   values widen exactly; ascii text is parsed exactly,
//                   whatever type the header declares)
//   element face:   list vertex_indices (or vertex_index), 0-based
//   element tristrips: list vertex_indices, -1 restarts a strip; strips
//                   are expanded with alternating orientation and their
//                   degenerate (joining) triangles dropped
// Every other element and property is read and skipped. Before each element
// is read, its count times the smallest record size is checked against the
// bytes left, so a corrupt count cannot trigger a huge allocation.
#include <cmath>
#include <cstring>
#include <vector>

#include "io/face_builder.hpp"
#include "io/readers.hpp"
#include "io/text_cursor.hpp"

namespace cbr::io::detail {

namespace {

enum class Type { i8, u8, i16, u16, i32, u32, f32, f64, invalid };

Type type_from_name(std::string_view n) {
    if (n == "char" || n == "int8") return Type::i8;
    if (n == "uchar" || n == "uint8") return Type::u8;
    if (n == "short" || n == "int16") return Type::i16;
    if (n == "ushort" || n == "uint16") return Type::u16;
    if (n == "int" || n == "int32") return Type::i32;
    if (n == "uint" || n == "uint32") return Type::u32;
    if (n == "float" || n == "float32") return Type::f32;
    if (n == "double" || n == "float64") return Type::f64;
    return Type::invalid;
}

std::size_t type_size(Type t) {
    switch (t) {
        case Type::i8: case Type::u8: return 1;
        case Type::i16: case Type::u16: return 2;
        case Type::i32: case Type::u32: case Type::f32: return 4;
        case Type::f64: return 8;
        case Type::invalid: break;
    }
    return 0;
}

bool is_integer(Type t) { return t != Type::f32 && t != Type::f64; }

struct Property {
    std::string name;
    Type type = Type::invalid;        // scalar type, or list item type
    Type count_type = Type::invalid;  // list count type; invalid = scalar
    bool is_list() const { return count_type != Type::invalid; }
};

struct Element {
    std::string name;
    std::int64_t count = 0;
    std::vector<Property> props;
};

enum class Encoding { ascii, little, big };

struct Header {
    Encoding encoding = Encoding::ascii;
    std::vector<Element> elements;
    std::size_t body_offset = 0;
    std::size_t body_line = 0;
};

Status parse_header(TextCursor& cur, Header& h) {
    if (cur.token() != "ply") return cur.fail("not a PLY file (the first line must be 'ply')");
    cur.skip_line();
    bool have_format = false;
    for (;;) {
        if (!cur.start_record()) return cur.fail("file ends inside the header (no end_header)");
        const std::string_view key = cur.field();
        if (key == "end_header") break;
        if (key == "comment" || key == "obj_info") {
        } else if (key == "format") {
            const std::string_view enc = cur.field();
            if (enc == "ascii") h.encoding = Encoding::ascii;
            else if (enc == "binary_little_endian") h.encoding = Encoding::little;
            else if (enc == "binary_big_endian") h.encoding = Encoding::big;
            else return cur.fail("unknown PLY format " + quote_token(enc));
            have_format = true;
        } else if (key == "element") {
            Element e;
            e.name = std::string(cur.field());
            if (auto st = cur.to_int(cur.field(), "element count", e.count); !st) return st;
            if (e.count < 0) return cur.fail("element count " + std::to_string(e.count) + " is negative");
            h.elements.push_back(std::move(e));
        } else if (key == "property") {
            if (h.elements.empty()) return cur.fail("property before any element");
            Property p;
            std::string_view t = cur.field();
            if (t == "list") {
                p.count_type = type_from_name(cur.field());
                if (p.count_type == Type::invalid || !is_integer(p.count_type)) {
                    return cur.fail("list count type must be an integer type");
                }
                t = cur.field();
            }
            p.type = type_from_name(t);
            if (p.type == Type::invalid) return cur.fail("unknown property type " + quote_token(t));
            p.name = std::string(cur.field());
            if (p.name.empty()) return cur.fail("property without a name");
            h.elements.back().props.push_back(std::move(p));
        } else {
            return cur.fail("unexpected " + quote_token(key) + " in the PLY header");
        }
        cur.skip_line();
    }
    if (!have_format) return cur.fail("the header has no 'format' line");
    cur.skip_line();  // the body starts right after "end_header\n"
    h.body_offset = cur.offset();
    h.body_line = cur.line();
    return {};
}

// Values of the body, ascii or binary, with the same interface.
class Body {
public:
    Body(const std::string& path, std::string_view text, const Header& h)
        : path_(path), cur_(path, text, '\0'), text_(text), enc_(h.encoding), pos_(h.body_offset) {
        cur_.seek(h.body_offset, h.body_line);
    }

    void set_context(const char* kind, std::int64_t index) {
        cur_.set_context(kind, index);
        kind_ = kind;
        index_ = index;
    }

    std::size_t remaining() const {
        return enc_ == Encoding::ascii ? cur_.remaining_bytes() : text_.size() - pos_;
    }

    // Smallest size of one value: its binary size, or 2 bytes ("0 ") in ascii.
    std::size_t value_bytes(Type t) const { return enc_ == Encoding::ascii ? 2 : type_size(t); }

    // Smallest size of one record of `e` (lists counted as empty).
    std::size_t min_record_bytes(const Element& e) const {
        std::size_t n = 0;
        for (const Property& p : e.props) n += value_bytes(p.is_list() ? p.count_type : p.type);
        return n == 0 ? 1 : n;
    }

    Status check_count(std::int64_t count, std::size_t bytes_each, const char* what) {
        // In ascii the very last value needs no separator after it: +1.
        const std::size_t room = remaining() + (enc_ == Encoding::ascii ? 1 : 0);
        if (static_cast<std::uint64_t>(count) <= room / bytes_each) return {};
        return fail(std::string(what) + " " + std::to_string(count) + " cannot fit in the rest of the file (" +
                    std::to_string(remaining()) + " bytes): truncated file or corrupt header");
    }

    Status number(Type t, double& v) {
        if (enc_ == Encoding::ascii) return cur_.to_double(cur_.token(), "value", v);
        if (text_.size() - pos_ < type_size(t)) return fail("file ends in the middle of the element (truncated)");
        v = decode(t);
        if (!std::isfinite(v)) return fail("non-finite value");
        return {};
    }

    Status integer(Type t, const char* what, std::int64_t& v) {
        if (enc_ == Encoding::ascii) return cur_.to_int(cur_.token(), what, v);
        if (!is_integer(t)) return fail(std::string(what) + " has a floating-point type");
        if (text_.size() - pos_ < type_size(t)) return fail("file ends in the middle of the element (truncated)");
        v = static_cast<std::int64_t>(decode(t));
        return {};
    }

    Status fail(const std::string& msg) const {
        if (enc_ == Encoding::ascii) return cur_.fail(msg);
        return Status::error(ErrorKind::parse_error, path_ + ": " + kind_ + " " + std::to_string(index_) + ": " + msg);
    }

private:
    // Reads one binary value at pos_ (caller checked the size).
    double decode(Type t) {
        unsigned char b[8];
        const std::size_t n = type_size(t);
        std::memcpy(b, text_.data() + pos_, n);
        pos_ += n;
        const bool swap = enc_ == Encoding::big;  // x86 and ARM Linux are little-endian
        if (swap) {
            for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
        }
        switch (t) {
            case Type::i8: { std::int8_t x; std::memcpy(&x, b, 1); return x; }
            case Type::u8: return b[0];
            case Type::i16: { std::int16_t x; std::memcpy(&x, b, 2); return x; }
            case Type::u16: { std::uint16_t x; std::memcpy(&x, b, 2); return x; }
            case Type::i32: { std::int32_t x; std::memcpy(&x, b, 4); return x; }
            case Type::u32: { std::uint32_t x; std::memcpy(&x, b, 4); return x; }
            case Type::f32: { float x; std::memcpy(&x, b, 4); return static_cast<double>(x); }
            case Type::f64: { double x; std::memcpy(&x, b, 8); return x; }
            case Type::invalid: break;
        }
        return 0.0;
    }

    const std::string& path_;
    TextCursor cur_;
    std::string_view text_;
    Encoding enc_;
    std::size_t pos_;
    const char* kind_ = "element";
    std::int64_t index_ = 0;
};

bool is_index_list(const Element& e, const Property& p) {
    if (!p.is_list()) return false;
    if (e.name == "face") return p.name == "vertex_indices" || p.name == "vertex_index";
    return e.name == "tristrips" && p.name == "vertex_indices";
}

// Expands one triangle strip (with -1 restarts) into triangles.
void append_strip(const std::vector<std::int64_t>& strip, SurfaceMesh& mesh) {
    std::size_t start = 0;
    for (std::size_t i = 0; i <= strip.size(); ++i) {
        if (i < strip.size() && strip[i] >= 0) continue;
        for (std::size_t k = start; k + 2 < i; ++k) {
            std::int64_t a = strip[k], b = strip[k + 1];
            const std::int64_t c = strip[k + 2];
            if ((k - start) % 2 == 1) std::swap(a, b);
            if (a == b || b == c || a == c) continue;  // strip joints
            const std::int64_t t[3] = {a, b, c};
            append_face(mesh, t, 3, 0, false);
        }
        start = i + 1;
    }
}

Status read_element(Body& body, const Element& e, std::int64_t num_vertices, const ReadOptions& opt,
                    SurfaceMesh& mesh) {
    const bool is_vertex = e.name == "vertex";
    std::vector<int> coord_of(e.props.size());  // property -> coordinate 0..2, or -1
    for (std::size_t i = 0; i < e.props.size(); ++i) {
        const std::string& n = e.props[i].name;
        coord_of[i] = !is_vertex || e.props[i].is_list() ? -1 : n == "x" ? 0 : n == "y" ? 1 : n == "z" ? 2 : -1;
    }
    const char* kind = is_vertex ? "vertex" : e.name == "face" ? "face" : e.name == "tristrips" ? "strip" : "element";
    body.set_context(kind, 0);
    if (auto st = body.check_count(e.count, body.min_record_bytes(e), "element count"); !st) return st;
    if (is_vertex) mesh.xyz.resize(static_cast<std::size_t>(e.count) * 3);

    std::vector<std::int64_t> ids;
    for (std::int64_t r = 0; r < e.count; ++r) {
        body.set_context(kind, r);
        for (std::size_t i = 0; i < e.props.size(); ++i) {
            const Property& p = e.props[i];
            if (!p.is_list()) {
                double v = 0.0;
                if (auto st = body.number(p.type, v); !st) return st;
                if (coord_of[i] >= 0) mesh.xyz[static_cast<std::size_t>(r) * 3 + static_cast<std::size_t>(coord_of[i])] = v;
                continue;
            }
            std::int64_t n = 0;
            if (auto st = body.integer(p.count_type, "list length", n); !st) return st;
            if (n < 0) return body.fail("negative list length " + std::to_string(n));
            if (auto st = body.check_count(n, body.value_bytes(p.type), "list length"); !st) return st;
            const bool wanted = is_index_list(e, p);
            if (wanted) ids.resize(static_cast<std::size_t>(n));
            for (std::int64_t k = 0; k < n; ++k) {
                if (!wanted) {
                    double skipped = 0.0;
                    if (auto st = body.number(p.type, skipped); !st) return st;
                    continue;
                }
                std::int64_t& id = ids[static_cast<std::size_t>(k)];
                if (auto st = body.integer(p.type, "vertex index", id); !st) return st;
                const bool restart = e.name == "tristrips" && id == -1;
                if (!restart && (id < 0 || id >= num_vertices)) {
                    return body.fail("vertex index " + std::to_string(id) + " is out of range (the file has " +
                                     std::to_string(num_vertices) + " vertices, numbered from 0)");
                }
            }
            if (!wanted) continue;
            if (e.name == "tristrips") {
                append_strip(ids, mesh);
            } else if (ids.size() < 3) {
                return body.fail("has " + std::to_string(ids.size()) + " corners (at least 3 needed)");
            } else if (!append_face(mesh, ids.data(), ids.size(), 0, opt.triangulate_polygons)) {
                return body.fail(polygon_rejected(ids.size()));
            }
        }
    }
    return {};
}

}  // namespace

Status read_ply(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh) {
    TextCursor header_cur(path, text, '\0');
    Header h;
    if (auto st = parse_header(header_cur, h); !st) return st;

    // Header problems are reported on the end_header line.
    const std::size_t end_line = h.body_line > 1 ? h.body_line - 1 : 1;
    const Element* vertex = nullptr;
    for (const Element& e : h.elements) {
        if (e.name == "vertex") vertex = &e;
    }
    if (vertex == nullptr) return header_cur.fail_at(end_line, "the header declares no 'vertex' element");
    for (const char* c : {"x", "y", "z"}) {
        bool found = false;
        for (const Property& p : vertex->props) found = found || (!p.is_list() && p.name == c);
        if (!found) {
            return header_cur.fail_at(end_line, std::string("the vertex element has no scalar property '") + c + "'");
        }
    }

    Body body(path, text, h);
    for (const Element& e : h.elements) {
        if (auto st = read_element(body, e, vertex->count, opt, mesh); !st) {
            mesh = SurfaceMesh{};
            return st;
        }
    }
    return {};
}

}  // namespace cbr::io::detail
