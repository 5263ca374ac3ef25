// Gmsh .msh 4.1 ASCII writer.
//
//   $MeshFormat     4.1 0 8
//   $PhysicalNames  one per region (dim 3, "region_R") and per triangle
//                   label (dim 2, "label_L")
//   $Entities       one volume per region, one surface per label, each
//                   with its bounding box and its physical group
//   $Nodes          one block holding every point, tags 1..n
//   $Elements       one block per entity: tetrahedra (type 4) first, tags
//                   1..T, then triangles (type 2), tags T+1..
//
// Gmsh tags must be positive. A region (or label) value v becomes entity
// and physical tag v when every value of that dimension is >= 1, otherwise
// v + (1 - smallest value); the name always carries the original value.
// The volumes' bounding surfaces are not listed (not known here).
// All points sit in the first entity's node block: Gmsh and meshio accept
// nodes shared by elements of other entities.
#include <algorithm>
#include <limits>
#include <vector>

#include "io/text_writer.hpp"
#include "io/writers.hpp"

namespace cbr::io::detail {

namespace {

// The elements of one dimension grouped by value (region or label).
struct Groups {
    std::vector<std::int32_t> values;  // distinct, sorted
    std::int64_t tag_shift = 0;        // tag = value + tag_shift
    std::vector<std::size_t> start;    // elements of group g: order[start[g] .. start[g+1])
    std::vector<std::size_t> order;    // element indices grouped by value
};

Groups group_by_value(const std::vector<std::int32_t>& of_element) {
    Groups g;
    g.values = of_element;
    std::sort(g.values.begin(), g.values.end());
    g.values.erase(std::unique(g.values.begin(), g.values.end()), g.values.end());
    if (!g.values.empty() && g.values.front() < 1) g.tag_shift = 1 - static_cast<std::int64_t>(g.values.front());

    // Counting sort of the elements by the rank of their value.
    std::vector<std::size_t> rank(of_element.size());
    g.start.assign(g.values.size() + 1, 0);
    for (std::size_t e = 0; e < of_element.size(); ++e) {
        rank[e] = static_cast<std::size_t>(std::lower_bound(g.values.begin(), g.values.end(), of_element[e]) -
                                           g.values.begin());
        ++g.start[rank[e] + 1];
    }
    for (std::size_t k = 0; k < g.values.size(); ++k) g.start[k + 1] += g.start[k];
    g.order.resize(of_element.size());
    std::vector<std::size_t> fill(g.start.begin(), g.start.end() - 1);
    for (std::size_t e = 0; e < of_element.size(); ++e) g.order[fill[rank[e]]++] = e;
    return g;
}

void put_bbox(TextWriter& w, const VolumeMesh& m, const Groups& g, std::size_t k,
              const std::vector<std::int64_t>& ids, std::size_t corners) {
    double lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
        lo[c] = std::numeric_limits<double>::infinity();
        hi[c] = -lo[c];
    }
    for (std::size_t i = g.start[k]; i < g.start[k + 1]; ++i) {
        for (std::size_t v = 0; v < corners; ++v) {
            const auto p = static_cast<std::size_t>(ids[g.order[i] * corners + v]);
            for (std::size_t c = 0; c < 3; ++c) {
                lo[c] = std::min(lo[c], m.xyz[3 * p + c]);
                hi[c] = std::max(hi[c], m.xyz[3 * p + c]);
            }
        }
    }
    for (double x : lo) w.put(' ').put_double(x);
    for (double x : hi) w.put(' ').put_double(x);
}

void put_entities(TextWriter& w, const VolumeMesh& m, const Groups& vol, const Groups& surf) {
    w.put("$Entities\n0 0 ").put_int(static_cast<std::int64_t>(surf.values.size())).put(' ');
    w.put_int(static_cast<std::int64_t>(vol.values.size())).put('\n');
    for (std::size_t k = 0; k < surf.values.size(); ++k) {
        const std::int64_t tag = surf.values[k] + surf.tag_shift;
        w.put_int(tag);
        put_bbox(w, m, surf, k, m.tris, 3);
        w.put(" 1 ").put_int(tag).put(" 0\n");  // one physical tag, no bounding curves
    }
    for (std::size_t k = 0; k < vol.values.size(); ++k) {
        const std::int64_t tag = vol.values[k] + vol.tag_shift;
        w.put_int(tag);
        put_bbox(w, m, vol, k, m.tets, 4);
        w.put(" 1 ").put_int(tag).put(" 0\n");  // one physical tag, no bounding surfaces
    }
    w.put("$EndEntities\n");
}

void put_element_blocks(TextWriter& w, int dim, int type, const Groups& g, const std::vector<std::int64_t>& ids,
                        std::size_t corners, std::int64_t first_tag) {
    for (std::size_t k = 0; k < g.values.size(); ++k) {
        w.put_int(dim).put(' ').put_int(g.values[k] + g.tag_shift).put(' ').put_int(type).put(' ');
        w.put_int(static_cast<std::int64_t>(g.start[k + 1] - g.start[k])).put('\n');
        for (std::size_t i = g.start[k]; i < g.start[k + 1]; ++i) {
            const std::size_t e = g.order[i];
            w.put_int(first_tag + static_cast<std::int64_t>(e));
            for (std::size_t v = 0; v < corners; ++v) w.put(' ').put_int(ids[e * corners + v] + 1);
            w.put('\n');
        }
    }
}

}  // namespace

Status write_gmsh(const std::string& path, const VolumeMesh& mesh) {
    const Groups vol = group_by_value(mesh.tet_regions);
    const Groups surf = group_by_value(mesh.tri_labels);
    const auto np = static_cast<std::int64_t>(mesh.num_points());
    const auto nt = static_cast<std::int64_t>(mesh.num_tets());
    const auto nf = static_cast<std::int64_t>(mesh.num_triangles());

    TextWriter w;
    if (auto st = w.open(path); !st) return st;
    w.put("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");

    w.put("$PhysicalNames\n").put_int(static_cast<std::int64_t>(vol.values.size() + surf.values.size())).put('\n');
    for (const std::int32_t v : surf.values) {
        w.put("2 ").put_int(v + surf.tag_shift).put(" \"label_").put_int(v).put("\"\n");
    }
    for (const std::int32_t v : vol.values) {
        w.put("3 ").put_int(v + vol.tag_shift).put(" \"region_").put_int(v).put("\"\n");
    }
    w.put("$EndPhysicalNames\n");

    put_entities(w, mesh, vol, surf);

    // Every node in one block, on the first volume (or surface) entity.
    const bool have_entity = !vol.values.empty() || !surf.values.empty();
    const std::int64_t nodes = have_entity ? np : 0;
    w.put("$Nodes\n").put_int(nodes > 0 ? 1 : 0).put(' ').put_int(nodes).put(' ');
    w.put_int(nodes > 0 ? 1 : 0).put(' ').put_int(nodes).put('\n');
    if (nodes > 0) {
        if (!vol.values.empty()) w.put("3 ").put_int(vol.values[0] + vol.tag_shift);
        else w.put("2 ").put_int(surf.values[0] + surf.tag_shift);
        w.put(" 0 ").put_int(np).put('\n');
        for (std::int64_t i = 1; i <= np; ++i) w.put_int(i).put('\n');
        for (std::int64_t i = 0; i < np; ++i) {
            const auto p = static_cast<std::size_t>(i);
            w.put_double(mesh.xyz[3 * p]).put(' ').put_double(mesh.xyz[3 * p + 1]).put(' ');
            w.put_double(mesh.xyz[3 * p + 2]).put('\n');
        }
    }
    w.put("$EndNodes\n");

    const std::int64_t ne = nt + nf;
    w.put("$Elements\n").put_int(static_cast<std::int64_t>(vol.values.size() + surf.values.size())).put(' ');
    w.put_int(ne).put(' ').put_int(ne > 0 ? 1 : 0).put(' ').put_int(ne).put('\n');
    put_element_blocks(w, 3, 4, vol, mesh.tets, 4, 1);
    put_element_blocks(w, 2, 2, surf, mesh.tris, 3, nt + 1);
    w.put("$EndElements\n");
    return w.commit();
}

}  // namespace cbr::io::detail
