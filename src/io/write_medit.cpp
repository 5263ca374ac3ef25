// Medit .mesh writer (ASCII, MeshVersionFormatted 2 = double precision).
//
//   MeshVersionFormatted 2
//   Dimension 3
//   Vertices    n, then "x y z ref"      ref = 1 for a Steiner point, else 0
//   Tetrahedra  n, then "a b c d ref"    ref = region
//   Triangles   n, then "a b c ref"      ref = label
//   End
// Indices are 1-based. Empty sections are left out.
#include "io/text_writer.hpp"
#include "io/writers.hpp"

namespace cbr::io::detail {

namespace {

void put_elements(TextWriter& w, const char* keyword, const std::vector<std::int64_t>& ids, std::size_t corners,
                  const std::vector<std::int32_t>& refs) {
    if (refs.empty()) return;
    w.put(keyword).put('\n').put_int(static_cast<std::int64_t>(refs.size())).put('\n');
    for (std::size_t e = 0; e < refs.size(); ++e) {
        for (std::size_t k = 0; k < corners; ++k) w.put_int(ids[e * corners + k] + 1).put(' ');
        w.put_int(refs[e]).put('\n');
    }
}

}  // namespace

Status write_medit(const std::string& path, const VolumeMesh& mesh) {
    TextWriter w;
    if (auto st = w.open(path); !st) return st;
    w.put("MeshVersionFormatted 2\n\nDimension 3\n\n");

    const std::size_t np = mesh.num_points();
    if (np > 0) {
        w.put("Vertices\n").put_int(static_cast<std::int64_t>(np)).put('\n');
        for (std::size_t i = 0; i < np; ++i) {
            const int ref = !mesh.is_steiner.empty() && mesh.is_steiner[i] != 0 ? 1 : 0;
            w.put_double(mesh.xyz[3 * i]).put(' ').put_double(mesh.xyz[3 * i + 1]).put(' ');
            w.put_double(mesh.xyz[3 * i + 2]).put(' ').put_int(ref).put('\n');
        }
        w.put('\n');
    }
    put_elements(w, "Tetrahedra", mesh.tets, 4, mesh.tet_regions);
    put_elements(w, "Triangles", mesh.tris, 3, mesh.tri_labels);
    w.put("\nEnd\n");
    return w.commit();
}

}  // namespace cbr::io::detail
