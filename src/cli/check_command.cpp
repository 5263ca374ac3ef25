// `cbr check IN` (see check_command.hpp). The steps:
//  1. read the surface with cbr::io (coordinates exact);
//  2. find duplicate points (exact equality) and merge each into its first
//     copy, so that libcbr can take the points (it refuses duplicates) and
//     the other checks can still run;
//  3. insert the points into a cbr_mesh and run cbr_mesh_check_faces (ids
//     out of range or repeated, zero-area and duplicate triangles,
//     intersections, open and non-manifold edges);
//  4. compute non-manifold vertices, orientation, components and the
//     bounding box here (surface_topology.hpp), and how near the surface
//     comes to degenerate (surface_margins.hpp: the closest points, from
//     the Delaunay mesh of step 3, and the flattest triangle);
//  5. print the report; exit 0 when nothing stops a recovery, else 2.
#include "cli/check_command.hpp"
#include "cli/mesh_handle.hpp"

#include <cbr/cbr.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "cli/check_describe.hpp"
#include "cli/check_report.hpp"
#include "cli/exit_codes.hpp"
#include "cli/surface_margins.hpp"
#include "cli/surface_topology.hpp"
#include "io/read_surface.hpp"

namespace cbr::cli {
namespace {

constexpr int kContinue = -1;  // a step went well: go on
constexpr std::size_t kMaxListed = 20;  // what libcbr lists of each kind

struct CheckArgs {
    std::string path;
    bool allow_open = false;
    bool triangulate = false;
    std::size_t list = 5;
};

int usage_error(const std::string& message) {
    std::fprintf(stderr, "cbr check: %s (try cbr check --help)\n", message.c_str());
    return kExitUsage;
}

bool parse_count(const char* text, std::size_t& value) {
    char* end = nullptr;
    const long n = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || n < 0 || n > static_cast<long>(kMaxListed)) return false;
    value = static_cast<std::size_t>(n);
    return true;
}

int parse_args(int argc, char** argv, CheckArgs& args) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help") {
            print_check_help(stdout);
            return kExitOk;
        }
        if (a == "--allow-open") {
            args.allow_open = true;
        } else if (a == "--triangulate") {
            args.triangulate = true;
        } else if (a == "--list") {
            if (i + 1 == argc || !parse_count(argv[i + 1], args.list))
                return usage_error("--list needs a number from 0 to 20");
            ++i;
        } else if (a.size() > 1 && a[0] == '-') {
            return usage_error("unknown option '" + a + "'");
        } else if (!args.path.empty()) {
            return usage_error("one input file only ('" + args.path + "', then '" + a + "')");
        } else {
            args.path = a;
        }
    }
    return args.path.empty() ? usage_error("no input file") : kContinue;
}

int read_input(const CheckArgs& args, io::SurfaceMesh& surface) {
    io::ReadOptions options;
    options.triangulate_polygons = args.triangulate;
    const io::Status status = io::read_surface(args.path, surface, options);
    if (status.ok()) return kContinue;
    std::fprintf(stderr, "cbr check: %s\n", status.message.c_str());
    return exit_code_for(status.kind);
}

// The surface with each duplicate point merged into its first copy.
struct Merged {
    std::vector<double> xyz;
    std::vector<std::int64_t> tris;     // ids out of range are kept as they are
    std::vector<std::int64_t> file_id;  // merged id -> id in the file
};

Merged merge_duplicates(const io::SurfaceMesh& s, const DuplicatePoints& dups) {
    const std::size_t n = s.num_points();
    std::vector<std::int64_t> merged_id(n);
    Merged m;
    for (std::size_t i = 0; i < n; ++i) {
        const auto first = static_cast<std::size_t>(dups.first_of[i]);
        if (first != i) {
            merged_id[i] = merged_id[first];  // first < i: already numbered
            continue;
        }
        merged_id[i] = static_cast<std::int64_t>(m.file_id.size());
        m.file_id.push_back(static_cast<std::int64_t>(i));
        m.xyz.insert(m.xyz.end(), s.xyz.begin() + static_cast<std::ptrdiff_t>(3 * i),
                     s.xyz.begin() + static_cast<std::ptrdiff_t>(3 * i + 3));
    }
    m.tris = s.tris;
    for (std::int64_t& id : m.tris)
        if (id >= 0 && static_cast<std::size_t>(id) < n) id = merged_id[static_cast<std::size_t>(id)];
    return m;
}

// The last error of `mesh` without the name of the function.
std::string api_message(const cbr_mesh* mesh) {
    const std::string m = cbr_mesh_last_error(mesh);
    const std::size_t colon = m.find(": ");
    return m.compare(0, 4, "cbr_") == 0 && colon != std::string::npos ? m.substr(colon + 2) : m;
}

int api_failure(const std::string& path, int status, const std::string& message) {
    std::fprintf(stderr, "cbr check: %s: %s\n", path.c_str(), message.c_str());
    return status == CBR_ERR_INVALID_INPUT ? kExitInput : kExitInternal;
}

// Inserts the merged points into a new handle. On failure (a NaN or an
// out-of-range coordinate) the message must name the file's ids: the
// file's points are then inserted as they are into another handle, which
// fails on the same point (libcbr checks coordinates before duplicates).
int insert_points(const std::string& path, const io::SurfaceMesh& s, const Merged& m, MeshHandle& h) {
    int status = cbr_mesh_create(&h.mesh);
    if (status != CBR_OK) return api_failure(path, status, cbr_status_string(status));
    status = cbr_mesh_insert_points(h.mesh, static_cast<std::int64_t>(m.file_id.size()), m.xyz.data());
    if (status == CBR_OK) return kContinue;
    if (m.file_id.size() == s.num_points()) return api_failure(path, status, api_message(h.mesh));
    MeshHandle again;
    if (cbr_mesh_create(&again.mesh) != CBR_OK ||
        cbr_mesh_insert_points(again.mesh, static_cast<std::int64_t>(s.num_points()), s.xyz.data()) == CBR_OK)
        return api_failure(path, status, api_message(h.mesh));
    return api_failure(path, status, api_message(again.mesh));
}

int check_faces(const std::string& path, const Merged& m, const MeshHandle& h) {
    const int status = cbr_mesh_check_faces(h.mesh, static_cast<std::int64_t>(m.tris.size() / 3), m.tris.data());
    if (status == CBR_OK || status == CBR_ERR_INVALID_INPUT) return kContinue;  // the report is in the handle
    std::fprintf(stderr, "cbr check: %s: %s\n", path.c_str(), api_message(h.mesh).c_str());
    return kExitInternal;
}

std::vector<LibDefect> listed_defects(const cbr_mesh* mesh, int kind) {
    std::vector<LibDefect> out(static_cast<std::size_t>(std::max<std::int64_t>(cbr_mesh_defect_listed(mesh, kind), 0)));
    for (std::size_t i = 0; i < out.size(); ++i)
        cbr_mesh_get_defect(mesh, kind, static_cast<std::int64_t>(i), out[i].tri.data(), out[i].pts.data());
    return out;
}

CheckReport build_report(const CheckArgs& args, const io::SurfaceMesh& s, const Merged& m,
                         const DuplicatePoints& dups, const cbr_mesh* mesh) {
    const Topology topo = analyse_topology(m.xyz, m.tris, kMaxListed);
    const IdNames names{s, m.file_id};
    CheckReport r;
    r.path = args.path;
    r.points = static_cast<std::int64_t>(s.num_points());
    r.triangles = static_cast<std::int64_t>(s.num_triangles());
    r.bounding_box = describe_box(bounding_box(s.xyz));
    if (dups.count > 0) r.merge_note = "the checks below merge each duplicate point into its first copy";
    r.rows.push_back(duplicate_points_row(dups, s));
    for (const DefectKindInfo& kind : defect_kinds()) {
        ReportRow row = defect_row(kind, cbr_mesh_defect_count(mesh, kind.key), listed_defects(mesh, kind.key), names);
        if (kind.key == CBR_DEFECT_OPEN_EDGE) mark_open_edges(row, args.allow_open);
        r.rows.push_back(std::move(row));
    }
    r.rows.push_back(nonmanifold_vertices_row(topo, names));
    r.orientation = describe_orientation(topo, names);
    r.components = topo.components;
    r.unreferenced_points = static_cast<std::int64_t>(m.file_id.size()) - topo.used_points;
    const SurfaceMargins margins = measure_margins(mesh, m.xyz, m.tris);
    r.closest_points = describe_closest_points(margins, names);
    r.flattest_triangle = describe_flattest_triangle(margins, names);
    if (margins.nearly_degenerate())
        r.degenerate_note = "within rounding of degenerate there: recovery adds no point on the surface, and it "
                            "can fail where the points it needs between such close parts do not exist in double "
                            "precision";
    return r;
}

int check(const CheckArgs& args) {
    io::SurfaceMesh s;
    int code = read_input(args, s);
    if (code != kContinue) return code;
    if (s.num_triangles() == 0) {
        std::fprintf(stderr, "cbr check: %s: no triangles: nothing to recover\n", args.path.c_str());
        return kExitInput;
    }
    const DuplicatePoints dups = find_duplicate_points(s.xyz, kMaxListed);
    const Merged m = merge_duplicates(s, dups);
    MeshHandle h;
    if ((code = insert_points(args.path, s, m, h)) != kContinue) return code;
    if ((code = check_faces(args.path, m, h)) != kContinue) return code;
    const CheckReport report = build_report(args, s, m, dups, h.mesh);
    print_report(stdout, report, args.list);
    const std::string summary = error_summary(report);
    if (summary.empty()) return kExitOk;
    std::fflush(stdout);  // the report first, then the error line
    std::fprintf(stderr, "cbr check: %s: not usable for boundary recovery: %s\n", args.path.c_str(), summary.c_str());
    return kExitInput;
}

}  // namespace

void print_check_help(std::FILE* out) {
    std::fprintf(out,
                 "usage: cbr check IN [--allow-open] [--triangulate] [--list N]\n"
                 "\n"
                 "Reads the surface IN and reports, with indices, what would stop a boundary\n"
                 "recovery -- checked exactly: duplicate points, triangles with a point id out\n"
                 "of range or used twice, zero-area triangles, duplicate triangles, triangles\n"
                 "that intersect other than in a shared point or edge, and open edges (edges\n"
                 "of one triangle only). Reported for information (legal input: regions\n"
                 "meeting along an edge or at a point): non-manifold edges and vertices; also\n"
                 "the orientation (consistent or not; outward or inward when closed), the\n"
                 "connected components, the bounding box, and how near the surface comes to\n"
                 "degenerate: its two closest points and its flattest triangle, with a note\n"
                 "when either is within 1e-13 of its scale (recovery adds no point on the\n"
                 "surface and can fail there). Ids are 0-based, in file order.\n"
                 "Formats (by extension): %s.\n"
                 "Coordinates are read exactly.\n"
                 "\n"
                 "options:\n"
                 "  --allow-open   accept open surfaces: report open edges but do not count\n"
                 "                 them as errors (recovery itself does not need a closed\n"
                 "                 surface; a volume mesh of the inside does)\n"
                 "  --triangulate  split faces with more than 3 corners into triangle fans\n"
                 "                 (otherwise such a face is a parse error)\n"
                 "  --list N       show the first N of each kind (default 5, at most 20)\n"
                 "  -h, --help     this text\n"
                 "\n"
                 "exit codes: 0 usable for recovery; 1 usage; 2 invalid input (one of the\n"
                 "errors above, no triangle at all, a coordinate that is NaN or out of range,\n"
                 "or a file that does not parse: the message gives the line); 4 I/O (missing\n"
                 "or unreadable file, unknown extension); 5 internal error.\n",
                 io::surface_extensions());
}

int run_check(int argc, char** argv) {
    try {
        CheckArgs args;
        const int code = parse_args(argc, argv, args);
        return code != kContinue ? code : check(args);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "cbr check: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "cbr check: internal error: %s\n", e.what());
    }
    return kExitInternal;
}

}  // namespace cbr::cli
