// STL reader, ASCII and binary.
//
// Binary: 80-byte header, uint32 triangle count n, then n records of 50
// bytes (normal, 3 corners as little-endian float32, uint16 attribute). The
// file must be exactly 84 + 50 n bytes long. Floats widen to doubles
// exactly.
//
// ASCII: solid NAME / facet normal ... / outer loop / vertex x y z (3 times,
// or more for a polygon) / endloop / endfacet / ... / endsolid. Several
// solids may follow one another; each triangle is labelled with the index
// of its solid (0, 1, ...). Keywords are matched case-insensitively.
//
// Binary or ASCII? Many binary files also start with "solid" in their
// header, so that word alone does not decide: a file is ASCII if it starts
// with "solid" and its next keyword after the name line is "facet" or
// "endsolid"; otherwise it is binary and its size must match the count.
//
// Corners are welded into vertices by exact equality (vertex_welder.hpp);
// normals are ignored.
#include <cmath>
#include <cstring>
#include <vector>

#include "io/face_builder.hpp"
#include "io/readers.hpp"
#include "io/text_cursor.hpp"
#include "io/vertex_welder.hpp"

namespace cbr::io::detail {

namespace {

constexpr std::size_t kHeaderBytes = 84;
constexpr std::size_t kRecordBytes = 50;

bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        char c = a[i];
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
        if (c != b[i]) return false;
    }
    return true;
}

std::uint32_t le_u32(const char* p) {
    const auto* b = reinterpret_cast<const unsigned char*>(p);
    return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
           static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

float le_f32(const char* p) {
    const std::uint32_t u = le_u32(p);
    float f = 0.0F;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

bool looks_ascii(const std::string& path, std::string_view text) {
    TextCursor cur(path, text.substr(0, 1024), '\0');
    if (!iequals(cur.token(), "solid")) return false;
    cur.skip_line();  // the solid's name
    const std::string_view next = cur.token();
    return iequals(next, "facet") || iequals(next, "endsolid");
}

Status read_binary(const std::string& path, std::string_view text, SurfaceMesh& mesh) {
    const std::uint64_t n = le_u32(text.data() + 80);
    VertexWelder welder(mesh);
    welder.reserve(static_cast<std::size_t>(n / 2 + 3));
    mesh.tris.reserve(static_cast<std::size_t>(n) * 3);
    mesh.labels.assign(static_cast<std::size_t>(n), 0);
    for (std::uint64_t t = 0; t < n; ++t) {
        const char* rec = text.data() + kHeaderBytes + t * kRecordBytes + 12;  // skip the normal
        for (int c = 0; c < 3; ++c) {
            double p[3];
            for (int k = 0; k < 3; ++k) {
                p[k] = static_cast<double>(le_f32(rec + 12 * c + 4 * k));
                if (!std::isfinite(p[k])) {
                    return Status::error(ErrorKind::parse_error,
                                         path + ": triangle " + std::to_string(t) + " has a non-finite coordinate");
                }
            }
            mesh.tris.push_back(welder.id(p[0], p[1], p[2]));
        }
    }
    return {};
}

Status read_ascii(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh) {
    TextCursor cur(path, text, '\0');
    VertexWelder welder(mesh);
    std::vector<std::int64_t> corners;
    std::int64_t facet = 0;
    std::int32_t solid = -1;
    bool in_solid = false, in_facet = false;

    for (std::string_view tok = cur.token(); !tok.empty(); tok = cur.token()) {
        if (iequals(tok, "solid") && !in_solid) {
            in_solid = true;
            ++solid;
            cur.skip_line();  // name
            continue;
        }
        if (!in_solid) return cur.fail("expected 'solid', found " + quote_token(tok));
        if (iequals(tok, "facet") && !in_facet) {
            in_facet = true;
            corners.clear();
            cur.set_context("facet", facet);
            cur.skip_line();  // "normal nx ny nz"
        } else if (iequals(tok, "outer") && in_facet) {
            cur.skip_line();  // "loop"
        } else if (iequals(tok, "vertex") && in_facet) {
            double p[3];
            static const char* const kNames[3] = {"x coordinate", "y coordinate", "z coordinate"};
            for (int k = 0; k < 3; ++k) {
                if (auto st = cur.to_double(cur.field(), kNames[k], p[k]); !st) return st;
            }
            corners.push_back(welder.id(p[0], p[1], p[2]));
        } else if (iequals(tok, "endloop") && in_facet) {
            // nothing: the facet ends at endfacet
        } else if (iequals(tok, "endfacet") && in_facet) {
            if (corners.size() < 3) {
                return cur.fail("has " + std::to_string(corners.size()) + " vertices (at least 3 needed)");
            }
            if (!append_face(mesh, corners.data(), corners.size(), solid, opt.triangulate_polygons)) {
                return cur.fail(polygon_rejected(corners.size()));
            }
            in_facet = false;
            cur.clear_context();
            ++facet;
        } else if (iequals(tok, "endsolid") && !in_facet) {
            in_solid = false;
            cur.skip_line();  // name
        } else {
            return cur.fail("unexpected " + quote_token(tok) + (in_facet ? " inside a facet" : ""));
        }
    }
    if (in_facet) return cur.fail("file ends inside a facet (truncated file?)");
    if (solid < 0) return cur.fail("empty file: expected 'solid'");
    // A missing final "endsolid" after complete facets is tolerated.
    return {};
}

}  // namespace

Status read_stl(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh) {
    if (looks_ascii(path, text)) return read_ascii(path, text, opt, mesh);
    if (text.size() < kHeaderBytes) {
        return Status::error(ErrorKind::parse_error, path + ": not an STL file: not ASCII STL, and " +
                                                         std::to_string(text.size()) +
                                                         " bytes are too few for a binary STL header (84)");
    }
    const std::uint64_t n = le_u32(text.data() + 80);
    const std::uint64_t expected = kHeaderBytes + n * kRecordBytes;
    if (text.size() != expected) {
        return Status::error(ErrorKind::parse_error,
                             path + ": not ASCII STL, and as binary STL its header announces " + std::to_string(n) +
                                 " triangles (" + std::to_string(expected) + " bytes) but the file has " +
                                 std::to_string(text.size()) + " bytes (truncated or corrupt)");
    }
    return read_binary(path, text, mesh);
}

}  // namespace cbr::io::detail
