// Rows of the `cbr check` report: libcbr's defects (read through
// cbr_mesh_get_defect) and the command's own findings, described with the
// file's ids.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cli/check_report.hpp"
#include "cli/surface_margins.hpp"
#include "cli/surface_topology.hpp"
#include "io/mesh_types.hpp"

namespace cbr::cli {

// One listed defect as cbr_mesh_get_defect gives it.
struct LibDefect {
    std::array<std::int64_t, 2> tri{-1, -1};
    std::array<std::int64_t, 3> pts{-1, -1, -1};
};

// Names points and triangles as the file does: the checked surface has its
// duplicate points merged, so its point ids go through file_id.
struct IdNames {
    const io::SurfaceMesh& surface;
    const std::vector<std::int64_t>& file_id;  // merged id -> file id

    std::string point(std::int64_t merged) const;
    std::string triangle_points(std::int64_t t) const;  // "a, b, c" as in the file
};

struct DefectKindInfo {
    int key;            // CBR_DEFECT_*
    const char* label;  // plural
    const char* one;    // singular
    bool error;
};
// The seven CBR_DEFECT_* kinds, in key order.
const std::vector<DefectKindInfo>& defect_kinds();

ReportRow defect_row(const DefectKindInfo& kind, std::int64_t count, const std::vector<LibDefect>& listed,
                     const IdNames& names);
// Open edges are an error unless --allow-open.
void mark_open_edges(ReportRow& row, bool allow_open);
ReportRow duplicate_points_row(const DuplicatePoints& dups, const io::SurfaceMesh& surface);
ReportRow nonmanifold_vertices_row(const Topology& topo, const IdNames& names);
std::string describe_orientation(const Topology& topo, const IdNames& names);
std::string describe_box(const BoundingBox& box);
// "2.1e-14 apart: points 9 and 125 (8.6e-15 of the bounding box's
// diagonal)"; "-" when there is none.
std::string describe_closest_points(const SurfaceMargins& margins, const IdNames& names);
// "432 (points 18, 219, 218): smallest height 1.2e-15 of its longest
// edge"; "-" when there is none.
std::string describe_flattest_triangle(const SurfaceMargins& margins, const IdNames& names);

}  // namespace cbr::cli
