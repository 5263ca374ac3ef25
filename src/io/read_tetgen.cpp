// TetGen .smesh / .poly reader: the points and the facets, as a surface.
//
// Part 1, points:  <#points> <dim = 3> <#attributes> <boundary markers 0|1>
//                  then <id> <x> <y> <z> [attributes] [marker] per line.
//                  A point count of 0 means "points are in the .node file
//                  with the same base name", which has the same layout.
//                  Facets name points by id; the first point's id (0 or 1,
//                  usually) is the base, as in TetGen.
// Part 2, facets:  <#facets> <boundary markers 0|1>
//   .smesh: one line per facet: <#corners> <c1> ... <cn> [marker]
//   .poly:  <#polygons> [#holes] [marker], then one line per polygon
//           <#corners> <c1> ... <cn>, then one line per hole point.
//           Polygons of 1 or 2 corners (points and segments constrained in
//           the facet) are not surface triangles and are skipped; facets
//           with holes are rejected (they need a constrained 2D
//           triangulation, not a fan).
// Each triangle is labelled with its facet's boundary marker (0 without
// markers). The hole and region lists after the facets are not read.
#include <cstdint>
#include <vector>

#include "io/face_builder.hpp"
#include "io/file_source.hpp"
#include "io/readers.hpp"
#include "io/text_cursor.hpp"

namespace cbr::io::detail {

namespace {

// Optional trailing integer field (default when absent).
Status optional_int(TextCursor& cur, const char* what, std::int64_t fallback, std::int64_t& v) {
    const std::string_view tok = cur.field();
    if (tok.empty()) {
        v = fallback;
        return {};
    }
    return cur.to_int(tok, what, v);
}

Status to_label(TextCursor& cur, std::int64_t marker, std::int32_t& label) {
    if (marker < INT32_MIN || marker > INT32_MAX) return cur.fail("boundary marker " + std::to_string(marker) + " does not fit in 32 bits");
    label = static_cast<std::int32_t>(marker);
    return {};
}

// Reads the point list header and points. count == 0 (when allowed) is
// reported back so that the caller reads the .node file.
Status read_points(TextCursor& cur, SurfaceMesh& mesh, std::int64_t& first_id, std::int64_t& count) {
    cur.set_context("point list header");
    if (!cur.start_record()) return cur.fail("empty file: expected the point list header");
    if (auto st = cur.to_int(cur.field(), "point count", count); !st) return st;
    std::int64_t dim = 3;
    if (auto st = optional_int(cur, "dimension", 3, dim); !st) return st;
    if (dim != 3) return cur.fail("dimension " + std::to_string(dim) + " is not supported (only 3)");
    if (auto st = cur.check_count(count, 8, "point count"); !st) return st;  // "1 0 0 0\n"
    cur.skip_line();

    mesh.xyz.reserve(static_cast<std::size_t>(count) * 3);
    for (std::int64_t i = 0; i < count; ++i) {
        cur.set_context("point", i);
        if (!cur.start_record()) return cur.fail("file ends early: the header announces " + std::to_string(count) + " points");
        std::int64_t id = 0;
        if (auto st = cur.to_int(cur.field(), "point id", id); !st) return st;
        if (i == 0) first_id = id;
        static const char* const kNames[3] = {"x coordinate", "y coordinate", "z coordinate"};
        for (const char* name : kNames) {
            double v = 0.0;
            if (auto st = cur.to_double(cur.field(), name, v); !st) return st;
            mesh.xyz.push_back(v);
        }
        cur.skip_line();  // attributes, marker
    }
    return {};
}

// Reads one polygon "<n> <c1> ... <cn>" (the rest of the line is left to
// the caller) into ids, 0-based.
Status read_polygon(TextCursor& cur, std::int64_t first_id, std::int64_t nv, std::vector<std::int64_t>& ids) {
    std::int64_t n = 0;
    if (auto st = cur.to_int(cur.field(), "corner count", n); !st) return st;
    if (n < 0) return cur.fail("corner count " + std::to_string(n) + " is negative");
    if (auto st = cur.check_count(n, 2, "corner count"); !st) return st;
    ids.resize(static_cast<std::size_t>(n));
    for (std::int64_t& id : ids) {
        std::int64_t raw = 0;
        if (auto st = cur.to_int(cur.field(), "point id", raw); !st) return st;
        id = raw - first_id;
        if (id < 0 || id >= nv) {
            return cur.fail("point id " + std::to_string(raw) + " is out of range (points are numbered " +
                            std::to_string(first_id) + ".." + std::to_string(first_id + nv - 1) + ")");
        }
    }
    return {};
}

Status add_polygon(TextCursor& cur, const std::vector<std::int64_t>& ids, std::int32_t label, const ReadOptions& opt,
                   SurfaceMesh& mesh) {
    if (ids.size() < 3) return cur.fail("has " + std::to_string(ids.size()) + " corners (at least 3 needed)");
    if (!append_face(mesh, ids.data(), ids.size(), label, opt.triangulate_polygons)) {
        return cur.fail(polygon_rejected(ids.size()));
    }
    return {};
}

Status read_facets(TextCursor& cur, bool poly, std::int64_t first_id, const ReadOptions& opt, SurfaceMesh& mesh) {
    const auto nv = static_cast<std::int64_t>(mesh.xyz.size() / 3);
    cur.set_context("facet list header");
    if (!cur.start_record()) return cur.fail("file ends before the facet list");
    std::int64_t nf = 0, markers = 0;
    if (auto st = cur.to_int(cur.field(), "facet count", nf); !st) return st;
    if (auto st = optional_int(cur, "boundary marker flag", 0, markers); !st) return st;
    if (auto st = cur.check_count(nf, 8, "facet count"); !st) return st;  // "3 1 2 3\n"
    cur.skip_line();

    std::vector<std::int64_t> ids;
    for (std::int64_t f = 0; f < nf; ++f) {
        cur.set_context("facet", f);
        if (!cur.start_record()) return cur.fail("file ends early: the header announces " + std::to_string(nf) + " facets");
        std::int32_t label = 0;
        std::int64_t marker = 0;
        if (!poly) {
            if (auto st = read_polygon(cur, first_id, nv, ids); !st) return st;
            if (markers != 0) {
                if (auto st = optional_int(cur, "boundary marker", 0, marker); !st) return st;
            }
            if (auto st = to_label(cur, marker, label); !st) return st;
            if (auto st = add_polygon(cur, ids, label, opt, mesh); !st) return st;
            cur.skip_line();
            continue;
        }
        std::int64_t npolys = 0, nholes = 0;
        if (auto st = cur.to_int(cur.field(), "polygon count", npolys); !st) return st;
        if (auto st = optional_int(cur, "hole count", 0, nholes); !st) return st;
        if (markers != 0) {
            if (auto st = optional_int(cur, "boundary marker", 0, marker); !st) return st;
        }
        if (auto st = to_label(cur, marker, label); !st) return st;
        if (nholes != 0) {
            return cur.fail("has " + std::to_string(nholes) +
                            " holes: facets with holes are not supported (they need a constrained triangulation)");
        }
        if (auto st = cur.check_count(npolys, 2, "polygon count"); !st) return st;
        cur.skip_line();
        for (std::int64_t k = 0; k < npolys; ++k) {
            if (!cur.start_record()) return cur.fail("file ends inside the facet");
            if (auto st = read_polygon(cur, first_id, nv, ids); !st) return st;
            if (ids.size() >= 3) {
                if (auto st = add_polygon(cur, ids, label, opt, mesh); !st) return st;
            }
            cur.skip_line();
        }
    }
    return {};
}

}  // namespace

Status read_tetgen(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh) {
    const bool poly = lower_extension(path) == "poly";
    TextCursor cur(path, text);
    std::int64_t first_id = 0, count = 0;
    if (auto st = read_points(cur, mesh, first_id, count); !st) return st;

    if (count == 0) {
        // The points live in the sibling .node file.
        const std::string node_path = replace_extension(path, ".node");
        std::string node_text;
        if (auto st = load_file(node_path, node_text); !st) {
            return Status::error(st.kind, path + ":1: the point count is 0, so the points come from the .node file: " +
                                              st.message);
        }
        TextCursor node_cur(node_path, node_text);
        if (auto st = read_points(node_cur, mesh, first_id, count); !st) return st;
    }
    return read_facets(cur, poly, first_id, opt, mesh);
}

}  // namespace cbr::io::detail
