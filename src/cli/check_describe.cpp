// Describing what `cbr check` found (see check_describe.hpp).
#include "cli/check_describe.hpp"

#include <cbr/cbr.h>

#include <cstdio>

namespace cbr::cli {
namespace {

// 17 significant digits: reads back as the same double.
std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

std::string short_number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", x);
    return buf;
}

std::string coordinates(const std::vector<double>& xyz, std::int64_t id) {
    const auto i = 3 * static_cast<std::size_t>(id);
    return "(" + number(xyz[i]) + ", " + number(xyz[i + 1]) + ", " + number(xyz[i + 2]) + ")";
}

std::string shared_part(const LibDefect& d, const IdNames& names) {
    if (d.pts[0] < 0) return "";
    if (d.pts[1] < 0) return " (beyond their shared point " + names.point(d.pts[0]) + ")";
    return " (beyond their shared edge " + names.point(d.pts[0]) + "-" + names.point(d.pts[1]) + ")";
}

std::string describe_defect(int key, const LibDefect& d, const IdNames& names) {
    const std::string t0 = std::to_string(d.tri[0]), t1 = std::to_string(d.tri[1]);
    switch (key) {
        case CBR_DEFECT_ID_OUT_OF_RANGE:
            return "triangle " + t0 + " uses points " + names.triangle_points(d.tri[0]) + " (the file has " +
                   std::to_string(names.surface.num_points()) + ")";
        case CBR_DEFECT_REPEATED_ID:
            return "triangle " + t0 + " uses a point twice (" + names.triangle_points(d.tri[0]) + ")";
        case CBR_DEFECT_ZERO_AREA:
            return "triangle " + t0 + " has zero area (points " + names.triangle_points(d.tri[0]) +
                   " are collinear)";
        case CBR_DEFECT_DUPLICATE_TRIANGLE:
            return "triangles " + t0 + " and " + t1 + " have the same points (" + names.triangle_points(d.tri[1]) +
                   ")";
        case CBR_DEFECT_INTERSECTION: return "triangles " + t0 + " and " + t1 + " intersect" + shared_part(d, names);
        case CBR_DEFECT_OPEN_EDGE:
            return "edge " + names.point(d.pts[0]) + "-" + names.point(d.pts[1]) + " (triangle " + t0 + ")";
        case CBR_DEFECT_NONMANIFOLD_EDGE:
            return "edge " + names.point(d.pts[0]) + "-" + names.point(d.pts[1]) + " (first triangle " + t0 + ")";
        default: return "defect of unknown kind " + std::to_string(key);
    }
}

}  // namespace

std::string IdNames::point(std::int64_t merged) const {
    const bool known = merged >= 0 && static_cast<std::size_t>(merged) < file_id.size();
    return std::to_string(known ? file_id[static_cast<std::size_t>(merged)] : merged);
}

std::string IdNames::triangle_points(std::int64_t t) const {
    const auto i = 3 * static_cast<std::size_t>(t);
    const std::vector<std::int64_t>& v = surface.tris;
    return std::to_string(v[i]) + ", " + std::to_string(v[i + 1]) + ", " + std::to_string(v[i + 2]);
}

const std::vector<DefectKindInfo>& defect_kinds() {
    static const std::vector<DefectKindInfo> kinds = {
        {CBR_DEFECT_ID_OUT_OF_RANGE, "triangles with ids out of range", "triangle with an id out of range", true},
        {CBR_DEFECT_REPEATED_ID, "triangles using a point twice", "triangle using a point twice", true},
        {CBR_DEFECT_ZERO_AREA, "zero-area triangles", "zero-area triangle", true},
        {CBR_DEFECT_DUPLICATE_TRIANGLE, "duplicate triangles", "duplicate triangle", true},
        {CBR_DEFECT_INTERSECTION, "intersecting triangle pairs", "intersecting triangle pair", true},
        {CBR_DEFECT_OPEN_EDGE, "open edges", "open edge", true},
        {CBR_DEFECT_NONMANIFOLD_EDGE, "non-manifold edges", "non-manifold edge", false},
    };
    return kinds;
}

ReportRow defect_row(const DefectKindInfo& kind, std::int64_t count, const std::vector<LibDefect>& listed,
                     const IdNames& names) {
    ReportRow row{kind.label, kind.one, count, {}, kind.error, {}};
    for (const LibDefect& d : listed) row.listed.push_back(describe_defect(kind.key, d, names));
    return row;
}

void mark_open_edges(ReportRow& row, bool allow_open) {
    row.error = !allow_open;
    if (row.count == 0) return;
    row.note = allow_open ? "(allowed by --allow-open)" : "(the surface is open; --allow-open accepts it)";
}

ReportRow duplicate_points_row(const DuplicatePoints& dups, const io::SurfaceMesh& surface) {
    ReportRow row{"duplicate points", "duplicate point", dups.count, {}, true, {}};
    for (const IdPair& p : dups.listed)
        row.listed.push_back("points " + std::to_string(p[0]) + " and " + std::to_string(p[1]) + " are identical " +
                             coordinates(surface.xyz, p[0]));
    return row;
}

ReportRow nonmanifold_vertices_row(const Topology& topo, const IdNames& names) {
    ReportRow row{"non-manifold vertices", "non-manifold vertex", topo.nonmanifold_vertices, {}, false, {}};
    for (const std::int64_t v : topo.nonmanifold_listed)
        row.listed.push_back("point " + names.point(v) + " (its triangles form separate fans)");
    return row;
}

std::string describe_orientation(const Topology& topo, const IdNames& names) {
    if (!topo.consistent()) {
        const IdPair& e = topo.misoriented_listed.front();
        return "NOT consistent: " + std::to_string(topo.misoriented_edges) +
               " edges where neighbouring triangles run the same way (first: edge " + names.point(e[0]) + "-" +
               names.point(e[1]) + ")";
    }
    if (!topo.closed()) return "consistent (the surface is open: no inside or outside)";
    const std::string volume = "signed volume " + short_number(topo.signed_volume);
    if (topo.shells > 1 && topo.open_shells == 0) {
        const std::int64_t flat = topo.shells - topo.outward_shells - topo.inward_shells;
        return "consistent; " + std::to_string(topo.shells) + " closed shells: " +
               std::to_string(topo.outward_shells) + " with outward normals, " + std::to_string(topo.inward_shells) +
               " with INWARD normals" + (flat > 0 ? ", " + std::to_string(flat) + " flat" : "") + " (" + volume + ")";
    }
    const std::string overall = topo.shells > 1 ? " overall" : "";
    if (topo.signed_volume > 0) return "consistent, outward normals" + overall + " (" + volume + ")";
    if (topo.signed_volume < 0) return "consistent, INWARD normals" + overall + " (" + volume + ")";
    return "consistent, zero enclosed volume";
}

std::string describe_box(const BoundingBox& box) {
    if (box.empty) return "empty";
    std::string s;
    for (std::size_t k = 0; k < 3; ++k)
        s += (k > 0 ? " x [" : "[") + short_number(box.lo[k]) + ", " + short_number(box.hi[k]) + "]";
    return s;
}

std::string describe_closest_points(const SurfaceMargins& margins, const IdNames& names) {
    const ClosestPoints& closest = margins.closest;
    if (!closest.found) return "-";
    std::string s = short_number(closest.distance) + " apart: points " + names.point(closest.a) + " and " +
                    names.point(closest.b);
    if (margins.diagonal > 0)
        s += " (" + short_number(closest.distance / margins.diagonal) + " of the bounding box's diagonal)";
    return s;
}

std::string describe_flattest_triangle(const SurfaceMargins& margins, const IdNames& names) {
    const FlattestTriangle& flattest = margins.flattest;
    if (!flattest.found) return "-";
    return std::to_string(flattest.triangle) + " (points " + names.triangle_points(flattest.triangle) +
           "): smallest height " + short_number(flattest.height_ratio) + " of its longest edge";
}

}  // namespace cbr::cli
