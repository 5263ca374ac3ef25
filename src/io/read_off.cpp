// OFF reader.
//
//   [ST][C][N]OFF        header keyword (optional; "4OFF", "nOFF" and
//                        "OFF BINARY" are rejected)
//   nv nf ne             counts (ne ignored), on the header line or the next
//   x y z [...]          nv vertex lines; extra values (colour, normal,
//                        texture) only with a C/N/ST header
//   n i1 ... in [...]    nf faces, 0-based; trailing values (face colour)
//                        ignored
//
// '#' starts a comment. Vertex and face records are read one per line, so a
// missing value is reported on its own line rather than silently shifting
// the rest of the file.
#include <vector>

#include "io/face_builder.hpp"
#include "io/readers.hpp"
#include "io/text_cursor.hpp"
#include "mesh/huge_pages.hpp"

namespace cbr::io::detail {

namespace {

struct OffHeader {
    bool extra_vertex_values = false;  // C, N or ST prefix
};

// Parses an [ST][C][N]OFF keyword; false if `tok` is not one.
bool parse_off_keyword(std::string_view tok, OffHeader& h, std::string& unsupported) {
    if (tok.size() < 3 || tok.substr(tok.size() - 3) != "OFF") return false;
    std::string_view prefix = tok.substr(0, tok.size() - 3);
    auto eat = [&prefix](std::string_view p) {
        if (prefix.substr(0, p.size()) != p) return false;
        prefix.remove_prefix(p.size());
        return true;
    };
    if (eat("ST")) h.extra_vertex_values = true;
    if (eat("C")) h.extra_vertex_values = true;
    if (eat("N")) h.extra_vertex_values = true;
    if (eat("4") || eat("n")) unsupported = std::string(tok) + " (not 3-dimensional)";
    return prefix.empty();
}

}  // namespace

Status read_off(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh) {
    TextCursor cur(path, text);
    OffHeader header;

    std::string_view tok = cur.token();
    if (tok.empty()) return cur.fail("empty file: expected an OFF header");
    std::string unsupported;
    if (parse_off_keyword(tok, header, unsupported)) {
        if (!unsupported.empty()) return cur.fail("unsupported OFF variant " + unsupported);
        const std::string_view next = cur.field();
        if (next == "BINARY") return cur.fail("binary OFF is not supported (convert it to ASCII OFF)");
        tok = next.empty() ? cur.token() : next;
    } else if (tok[0] < '0' || tok[0] > '9') {
        return cur.fail("expected an OFF header, found " + quote_token(tok));
    }
    // Without a keyword the file starts directly with the counts.

    std::int64_t nv = 0, nf = 0;
    if (auto st = cur.to_int(tok, "vertex count", nv); !st) return st;
    if (auto st = cur.to_int(cur.token(), "face count", nf); !st) return st;
    // Smallest records: "0 0 0\n" and "3 0 1 2\n".
    if (auto st = cur.check_count(nv, 6, "vertex count"); !st) return st;
    if (auto st = cur.check_count(nf, 8, "face count"); !st) return st;
    cur.skip_line();  // edge count, unused

    cbr::mesh::reserve_huge(mesh.xyz, static_cast<std::size_t>(nv) * 3);
    for (std::int64_t i = 0; i < nv; ++i) {
        cur.set_context("vertex", i);
        if (!cur.start_record()) {
            return cur.fail("file ends early: the header announces " + std::to_string(nv) + " vertices");
        }
        static const char* const kNames[3] = {"x coordinate", "y coordinate", "z coordinate"};
        for (const char* name : kNames) {
            double v = 0.0;
            if (auto st = cur.to_double(cur.field(), name, v); !st) return st;
            mesh.xyz.push_back(v);
        }
        if (!header.extra_vertex_values && !cur.line_done()) {
            return cur.fail("unexpected " + quote_token(cur.field()) +
                            " after the 3 coordinates (the header does not announce colours or normals)");
        }
        cur.skip_line();
    }

    cbr::mesh::reserve_huge(mesh.tris, static_cast<std::size_t>(nf) * 3);
    mesh.labels.reserve(static_cast<std::size_t>(nf));
    std::vector<std::int64_t> ids;
    for (std::int64_t f = 0; f < nf; ++f) {
        cur.set_context("face", f);
        if (!cur.start_record()) {
            return cur.fail("file ends early: the header announces " + std::to_string(nf) + " faces");
        }
        std::int64_t n = 0;
        if (auto st = cur.to_int(cur.field(), "corner count", n); !st) return st;
        if (n < 3) return cur.fail("has " + std::to_string(n) + " corners (at least 3 needed)");
        if (auto st = cur.check_count(n, 2, "corner count"); !st) return st;
        ids.resize(static_cast<std::size_t>(n));
        for (std::int64_t& id : ids) {
            if (auto st = cur.to_int(cur.field(), "vertex index", id); !st) return st;
            if (id < 0 || id >= nv) {
                return cur.fail("vertex index " + std::to_string(id) + " is out of range (the file has " +
                                std::to_string(nv) + " vertices, numbered from 0)");
            }
        }
        if (!append_face(mesh, ids.data(), ids.size(), 0, opt.triangulate_polygons)) {
            return cur.fail(polygon_rejected(ids.size()));
        }
        cur.skip_line();  // optional face colour
    }
    cur.clear_context();
    if (cur.start_record()) {
        return cur.fail("unexpected " + quote_token(cur.field()) + " after the last face (the header announces " +
                        std::to_string(nf) + " faces)");
    }
    return {};
}

}  // namespace cbr::io::detail
