#include "cli/recover_command.hpp"

#include <cbr/cbr.h>

#include <cstdio>
#include <string>
#include <vector>

#include "cli/exit_codes.hpp"
#include "cli/table_one.hpp"
#include "io/read_surface.hpp"
#include "io/write_volume.hpp"

namespace cbr::cli {
namespace {

constexpr int kContinue = -1;

struct RecoverArgs {
    std::string input, output;
    bool keep_exterior = false;
    bool allow_open = false;
    bool quiet = false;
};

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "usage: cbr recover IN -o OUT [--keep-exterior] [--allow-open] [-q]\n"
                 "\n"
                 "Tetrahedralizes the points of the surface IN (OFF, OBJ, STL, PLY, .smesh,\n"
                 ".poly, .mesh) and recovers every one of its triangles as a face, without\n"
                 "adding any point on the surface (Du & Wang 2004). Writes the tetrahedra of\n"
                 "the bounded regions to OUT (%s, by extension) and prints\n"
                 "the paper's Table I.\n"
                 "\n"
                 "  -o OUT           the volume mesh to write (required)\n"
                 "  --keep-exterior  also write the exterior tetrahedra (region 0)\n"
                 "  --allow-open     recover an open surface too (its faces are recovered,\n"
                 "                   but it bounds no region: use with --keep-exterior)\n"
                 "  -q               print nothing but errors\n",
                 io::volume_extensions());
}

int usage_error(const std::string& message) {
    std::fprintf(stderr, "cbr recover: %s (try cbr recover --help)\n", message.c_str());
    return kExitUsage;
}

int parse_args(int argc, char** argv, RecoverArgs& args) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-h" || a == "--help") {
            print_help(stdout);
            return kExitOk;
        }
        if (a == "-o") {
            if (++i >= argc) return usage_error("-o needs a file name");
            args.output = argv[i];
        } else if (a == "--keep-exterior") {
            args.keep_exterior = true;
        } else if (a == "--allow-open") {
            args.allow_open = true;
        } else if (a == "-q") {
            args.quiet = true;
        } else if (!a.empty() && a[0] == '-') {
            return usage_error("unknown option '" + a + "'");
        } else if (!args.input.empty()) {
            return usage_error("one input file only");
        } else {
            args.input = a;
        }
    }
    if (args.input.empty()) return usage_error("no input file");
    if (args.output.empty()) return usage_error("no output file (-o OUT)");
    if (!io::is_volume_file(args.output)) {
        std::fprintf(stderr, "cbr recover: %s: unknown output format (known: %s)\n", args.output.c_str(),
                     io::volume_extensions());
        return kExitIo;
    }
    return kContinue;
}

// The mesh as the writers want it: points, the tetrahedra returned, their
// regions, the input triangles with labels, which points are Steiner.
int collect(cbr_mesh* m, const io::SurfaceMesh& surface, io::VolumeMesh& out) {
    const std::int64_t np = cbr_mesh_point_count(m), nt = cbr_mesh_tet_count(m);
    out.xyz.resize(3 * static_cast<std::size_t>(np));
    out.tets.resize(4 * static_cast<std::size_t>(nt));
    out.tet_regions.resize(static_cast<std::size_t>(nt));
    std::vector<std::int64_t> steiner(static_cast<std::size_t>(cbr_mesh_steiner_count(m)));
    int status = cbr_mesh_get_points(m, out.xyz.data());
    if (status == CBR_OK) status = cbr_mesh_get_tets(m, out.tets.data());
    if (status == CBR_OK) status = cbr_mesh_get_tet_regions(m, out.tet_regions.data());
    if (status == CBR_OK) status = cbr_mesh_steiner_points(m, steiner.data());
    if (status != CBR_OK) return status;
    out.tris = surface.tris;
    out.tri_labels = surface.labels;
    out.tri_labels.resize(surface.tris.size() / 3, 0);
    out.is_steiner.assign(static_cast<std::size_t>(np), 0);
    for (std::int64_t s : steiner) out.is_steiner[static_cast<std::size_t>(s)] = 1;
    return CBR_OK;
}

int fail(cbr_mesh* m, int status) {
    std::fprintf(stderr, "cbr recover: %s\n", cbr_mesh_last_error(m));
    return exit_code_for(status);
}

int recover(const RecoverArgs& args, const io::SurfaceMesh& surface, cbr_mesh* m) {
    const auto np = static_cast<std::int64_t>(surface.xyz.size() / 3);
    const auto nf = static_cast<std::int64_t>(surface.tris.size() / 3);
    int status = cbr_mesh_set_param(m, CBR_PARAM_KEEP_EXTERIOR, args.keep_exterior ? 1 : 0);
    if (status == CBR_OK) status = cbr_mesh_insert_points(m, np, surface.xyz.data());
    if (status == CBR_OK)
        status = cbr_mesh_recover_faces(m, nf, surface.tris.data(), surface.labels.empty() ? nullptr : surface.labels.data());
    // Legal for the library, but rarely what a user of the command wants:
    // an open surface encloses nothing (recover_faces left its check report,
    // also when it could not recover every face).
    const std::int64_t open_edges =
        status == CBR_OK || status == CBR_ERR_RECOVERY_FAILED ? cbr_mesh_defect_count(m, CBR_DEFECT_OPEN_EDGE) : 0;
    if (open_edges > 0 && !args.allow_open) {
        std::fprintf(stderr, "cbr recover: %s is open: %lld open edges, it bounds no region (--allow-open to recover it anyway)\n",
                     args.input.c_str(), static_cast<long long>(open_edges));
        return kExitInput;
    }
    if (status != CBR_OK) {
        if (!args.quiet && status == CBR_ERR_RECOVERY_FAILED) print_table_one(m);
        return fail(m, status);
    }
    io::VolumeMesh volume;
    status = collect(m, surface, volume);
    if (status != CBR_OK) return fail(m, status);
    const io::Status written = io::write_volume(args.output, volume);
    if (!written.ok()) {
        std::fprintf(stderr, "cbr recover: %s\n", written.message.c_str());
        return exit_code_for(written.kind);
    }
    if (!args.quiet) {
        std::printf("cbr recover: %s -> %s: %zu points, %zu tetrahedra\n", args.input.c_str(), args.output.c_str(),
                    volume.num_points(), volume.num_tets());
        print_table_one(m);
    }
    return kExitOk;
}

}  // namespace

int run_recover(int argc, char** argv) {
    RecoverArgs args;
    const int parsed = parse_args(argc, argv, args);
    if (parsed != kContinue) return parsed;
    io::SurfaceMesh surface;
    const io::Status read = io::read_surface(args.input, surface);
    if (!read.ok()) {
        std::fprintf(stderr, "cbr recover: %s\n", read.message.c_str());
        return exit_code_for(read.kind);
    }
    cbr_mesh* m = nullptr;
    if (cbr_mesh_create(&m) != CBR_OK) {
        std::fprintf(stderr, "cbr recover: out of memory\n");
        return kExitInternal;
    }
    const int code = recover(args, surface, m);
    cbr_mesh_destroy(m);
    return code;
}

}  // namespace cbr::cli
