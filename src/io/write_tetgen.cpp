// TetGen writer: three files sharing one base name, numbered from 1 (as
// TetGen writes them without -z).
//
//   base.node  <#points> 3 <#attributes> 0, then "i x y z [is_steiner]"
//              (one attribute, 0/1, when Steiner flags are given)
//   base.ele   <#tets> 4 1, then "i a b c d region"
//   base.face  <#triangles> 1, then "i a b c label"
//
// The three files are completed under temporary names first and renamed
// only when all three are complete; if a rename fails, the files already
// renamed are removed so that no inconsistent set is left.
#include <cstdio>

#include "io/file_source.hpp"
#include "io/text_writer.hpp"
#include "io/writers.hpp"

namespace cbr::io::detail {

namespace {

void put_node(TextWriter& w, const VolumeMesh& m) {
    const std::size_t np = m.num_points();
    const bool flags = !m.is_steiner.empty();
    w.put_int(static_cast<std::int64_t>(np)).put(" 3 ").put(flags ? '1' : '0').put(" 0\n");
    for (std::size_t i = 0; i < np; ++i) {
        w.put_int(static_cast<std::int64_t>(i + 1)).put(' ');
        w.put_double(m.xyz[3 * i]).put(' ').put_double(m.xyz[3 * i + 1]).put(' ').put_double(m.xyz[3 * i + 2]);
        if (flags) w.put(' ').put(m.is_steiner[i] != 0 ? '1' : '0');
        w.put('\n');
    }
}

void put_elements(TextWriter& w, const std::vector<std::int64_t>& ids, std::size_t corners,
                  const std::vector<std::int32_t>& values, const char* header_tail) {
    w.put_int(static_cast<std::int64_t>(values.size())).put(header_tail);
    for (std::size_t e = 0; e < values.size(); ++e) {
        w.put_int(static_cast<std::int64_t>(e + 1));
        for (std::size_t k = 0; k < corners; ++k) w.put(' ').put_int(ids[e * corners + k] + 1);
        w.put(' ').put_int(values[e]).put('\n');
    }
}

}  // namespace

Status write_tetgen(const std::string& path, const VolumeMesh& mesh) {
    const std::string ext = lower_extension(path);
    const std::string base = ext.empty() ? path : replace_extension(path, "");

    TextWriter files[3];
    const char* const kExt[3] = {".node", ".ele", ".face"};
    for (int k = 0; k < 3; ++k) {
        if (auto st = files[k].open(base + kExt[k]); !st) return st;
    }
    put_node(files[0], mesh);
    put_elements(files[1], mesh.tets, 4, mesh.tet_regions, " 4 1\n");
    put_elements(files[2], mesh.tris, 3, mesh.tri_labels, " 1\n");
    for (TextWriter& f : files) {
        if (auto st = f.finish(); !st) return st;
    }
    for (int k = 0; k < 3; ++k) {
        if (auto st = files[k].publish(); !st) {
            for (int j = 0; j < k; ++j) std::remove(files[j].final_path().c_str());
            return st;
        }
    }
    return {};
}

}  // namespace cbr::io::detail
