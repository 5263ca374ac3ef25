// Wavefront OBJ reader: only geometry and faces.
//
//   v x y z [w | r g b]   a vertex; values after z are ignored
//   f c1 c2 c3 ...        a face; each corner is i, i/t, i//n or i/t/n with
//                         i 1-based, or negative = relative to the last
//                         vertex defined so far (-1 = the latest)
//
// Every other statement (vt, vn, g, o, s, usemtl, mtllib, l, p, ...) is
// skipped. A line ending in '\' continues on the next line. A face may name
// a vertex defined further down (positive index); such forward references
// are checked once the whole file is read.
#include <vector>

#include "io/face_builder.hpp"
#include "io/readers.hpp"
#include "io/text_cursor.hpp"

namespace cbr::io::detail {

namespace {

// field() that follows '\' line continuations.
std::string_view obj_field(TextCursor& cur) {
    std::string_view tok = cur.field();
    while (tok == "\\" && cur.line_done()) {
        cur.skip_line();
        tok = cur.field();
    }
    return tok;
}

// The largest forward reference seen, checked at the end of the file.
struct ForwardRef {
    std::int64_t id = -1;  // 0-based
    std::int64_t face = 0;
    std::size_t line = 0;
};

}  // namespace

Status read_obj(const std::string& path, std::string_view text, const ReadOptions& opt, SurfaceMesh& mesh) {
    TextCursor cur(path, text);
    std::vector<std::int64_t> ids;
    std::int64_t face = 0;
    ForwardRef forward;

    while (cur.start_record()) {
        const std::string_view key = cur.field();
        if (key == "v") {
            cur.set_context("vertex", static_cast<std::int64_t>(mesh.xyz.size() / 3));
            static const char* const kNames[3] = {"x coordinate", "y coordinate", "z coordinate"};
            for (const char* name : kNames) {
                double v = 0.0;
                if (auto st = cur.to_double(obj_field(cur), name, v); !st) return st;
                mesh.xyz.push_back(v);
            }
        } else if (key == "f") {
            cur.set_context("face", face);
            const auto nv = static_cast<std::int64_t>(mesh.xyz.size() / 3);
            ids.clear();
            for (std::string_view c = obj_field(cur); !c.empty(); c = obj_field(cur)) {
                // Only the vertex index (before the first '/') matters.
                std::int64_t i = 0;
                if (auto st = cur.to_int(c.substr(0, c.find('/')), "vertex index", i); !st) return st;
                if (i == 0) return cur.fail("vertex index 0 is invalid (OBJ indices start at 1)");
                const std::int64_t id = i > 0 ? i - 1 : nv + i;
                if (id < 0) {
                    return cur.fail("relative vertex index " + std::to_string(i) + " points before the first vertex (" +
                                    std::to_string(nv) + " vertices defined so far)");
                }
                if (id >= nv && id > forward.id) forward = {id, face, cur.line()};
                ids.push_back(id);
            }
            if (ids.size() < 3) return cur.fail("has " + std::to_string(ids.size()) + " corners (at least 3 needed)");
            if (!append_face(mesh, ids.data(), ids.size(), 0, opt.triangulate_polygons)) {
                return cur.fail(polygon_rejected(ids.size()));
            }
            ++face;
        }
        cur.clear_context();
        // Anything else on the line (w, colours, other statements) is skipped,
        // including continuation lines.
        while (!cur.line_done()) obj_field(cur);
        cur.skip_line();
    }

    const auto nv = static_cast<std::int64_t>(mesh.xyz.size() / 3);
    if (forward.id >= nv) {
        return cur.fail_at(forward.line, "face " + std::to_string(forward.face) + ": vertex index " +
                                             std::to_string(forward.id + 1) + " is out of range (the file has " +
                                             std::to_string(nv) + " vertices)");
    }
    return {};
}

}  // namespace cbr::io::detail
