// Medit .mesh reader (ASCII; .meshb is not supported).
//
// A sequence of keywords, each followed by its data, free-form:
//   MeshVersionFormatted <1|2>   Dimension <3>
//   Vertices <n>       n x (x y z ref)
//   Triangles <n>      n x (i j k ref), 1-based; ref becomes the label
//   Quadrilaterals <n> n x (i j k l ref): polygons (rejected or fanned)
//   Tetrahedra <n>     n x (a b c d ref): kept for read_medit_volume
//   End
// Any other section (Edges, Corners, Ridges, Normals, ...) is skipped: its
// data are the numeric tokens up to the next keyword. Keywords match
// case-insensitively; '#' starts a comment. Vertices must come before the
// elements that use them. Elements are numbered from 0 in messages, per
// section ("triangle 0" is the first of Triangles).
#include <array>
#include <cstdint>
#include <vector>

#include "io/face_builder.hpp"
#include "io/readers.hpp"
#include "io/text_cursor.hpp"

namespace cbr::io::detail {

namespace {

bool is_keyword(std::string_view tok) {
    const char c = tok.empty() ? '\0' : tok[0];
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
        if (lower(a[i]) != lower(b[i])) return false;
    }
    return true;
}

Status read_ref(TextCursor& cur, std::int32_t& ref) {
    std::int64_t r = 0;
    if (auto st = cur.to_int(cur.token(), "reference", r); !st) return st;
    if (r < INT32_MIN || r > INT32_MAX) return cur.fail("reference " + std::to_string(r) + " does not fit in 32 bits");
    ref = static_cast<std::int32_t>(r);
    return {};
}

// Reads `n` 1-based vertex indices into ids as 0-based.
Status read_ids(TextCursor& cur, std::int64_t nv, std::size_t n, std::int64_t* ids) {
    for (std::size_t k = 0; k < n; ++k) {
        std::int64_t i = 0;
        if (auto st = cur.to_int(cur.token(), "vertex index", i); !st) return st;
        if (i < 1 || i > nv) {
            return cur.fail("vertex index " + std::to_string(i) + " is out of range (the file has " +
                            std::to_string(nv) + " vertices, numbered from 1)");
        }
        ids[k] = i - 1;
    }
    return {};
}

Status read_count(TextCursor& cur, const char* what, std::size_t min_bytes_each, std::int64_t& n) {
    if (auto st = cur.to_int(cur.token(), what, n); !st) return st;
    return cur.check_count(n, min_bytes_each, what);
}

}  // namespace

Status read_medit(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh,
                  MeditVolumePart* volume) {
    TextCursor cur(path, text);
    std::int64_t nv = -1;  // -1: no Vertices section yet
    std::string_view tok = cur.token();
    if (tok.empty()) return cur.fail("empty file: expected MeshVersionFormatted");

    while (!tok.empty()) {
        if (!is_keyword(tok)) return cur.fail("expected a keyword, found " + quote_token(tok));
        cur.clear_context();
        const std::string_view key = tok;
        tok = {};
        if (iequals(key, "End")) break;
        const bool tri = iequals(key, "Triangles"), quad = iequals(key, "Quadrilaterals");
        const bool tet = iequals(key, "Tetrahedra");
        if (iequals(key, "MeshVersionFormatted")) {
            std::int64_t version = 0;
            if (auto st = cur.to_int(cur.token(), "mesh version", version); !st) return st;
        } else if (iequals(key, "Dimension")) {
            std::int64_t dim = 0;
            if (auto st = cur.to_int(cur.token(), "dimension", dim); !st) return st;
            if (dim != 3) return cur.fail("dimension " + std::to_string(dim) + " is not supported (only 3)");
        } else if (iequals(key, "Vertices")) {
            if (nv >= 0) return cur.fail("a second Vertices section");
            if (auto st = read_count(cur, "vertex count", 8, nv); !st) return st;  // "0 0 0 0\n"
            mesh.xyz.reserve(static_cast<std::size_t>(nv) * 3);
            if (volume) volume->vertex_refs.reserve(static_cast<std::size_t>(nv));
            for (std::int64_t i = 0; i < nv; ++i) {
                cur.set_context("vertex", i);
                static const char* const kNames[3] = {"x coordinate", "y coordinate", "z coordinate"};
                for (const char* name : kNames) {
                    double v = 0.0;
                    if (auto st = cur.to_double(cur.token(), name, v); !st) return st;
                    mesh.xyz.push_back(v);
                }
                std::int32_t ref = 0;
                if (auto st = read_ref(cur, ref); !st) return st;
                if (volume) volume->vertex_refs.push_back(ref);
            }
        } else if (tri || quad || tet) {
            if (nv < 0) return cur.fail(std::string(key) + " before Vertices (not supported)");
            const std::size_t corners = tri ? 3 : 4;
            std::int64_t n = 0;
            if (auto st = read_count(cur, "element count", 2 * (corners + 1), n); !st) return st;
            std::array<std::int64_t, 4> ids{};
            for (std::int64_t e = 0; e < n; ++e) {
                cur.set_context(tet ? "tetrahedron" : tri ? "triangle" : "quadrilateral", e);
                std::int32_t ref = 0;
                if (auto st = read_ids(cur, nv, corners, ids.data()); !st) return st;
                if (auto st = read_ref(cur, ref); !st) return st;
                if (tet) {
                    if (volume) {
                        volume->tets.insert(volume->tets.end(), ids.begin(), ids.end());
                        volume->tet_refs.push_back(ref);
                    }
                } else {
                    if (!append_face(mesh, ids.data(), corners, ref, opt.triangulate_polygons)) {
                        return cur.fail(polygon_rejected(corners));
                    }
                }
            }
        } else {
            // Unknown section: skip its numbers.
            for (tok = cur.token(); !tok.empty() && !is_keyword(tok); tok = cur.token()) {
            }
            continue;
        }
        tok = cur.token();
    }
    cur.clear_context();
    if (nv < 0) return cur.fail("no Vertices section");
    return {};
}

}  // namespace cbr::io::detail
