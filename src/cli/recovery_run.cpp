#include "cli/recovery_run.hpp"
#include "cli/mesh_handle.hpp"

#include <cbr/cbr.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "cli/check_describe.hpp"
#include "cli/exit_codes.hpp"
#include "cli/surface_margins.hpp"
#include "cli/volume_output.hpp"
#include "io/write_volume.hpp"

namespace cbr::cli {
namespace {

RecoveryOutcome failure(int exit_code, std::string message) {
    RecoveryOutcome out;
    out.exit_code = exit_code;
    out.error = std::move(message);
    return out;
}

RecoveryOutcome api_failure(const cbr_mesh* m, int status) { return failure(exit_code_for(status), cbr_mesh_last_error(m)); }

// After a failed recovery (the mesh is the Delaunay one again): where the
// surface is within rounding of degenerate (surface_margins.hpp), what
// says so, to append to the error; else "".
std::string degenerate_hint(const cbr_mesh* m, const io::SurfaceMesh& surface) {
    const SurfaceMargins margins = measure_margins(m, surface.xyz, surface.tris);
    if (!margins.nearly_degenerate()) return "";
    std::vector<std::int64_t> same_ids(surface.num_points());
    std::iota(same_ids.begin(), same_ids.end(), std::int64_t{0});
    const IdNames names{surface, same_ids};
    return " (the surface is within rounding of degenerate, where no point can be added on it: closest points " +
           describe_closest_points(margins, names) + "; flattest triangle " +
           describe_flattest_triangle(margins, names) + "; see cbr check)";
}

// The threads options.threads allows (0: the hardware's).
int thread_count(const RecoveryOptions& options) {
    if (options.threads > 0) return options.threads;
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// Writes the output on a thread of its own while this one measures Table
// II, when there is an output, a second thread is allowed and the format
// does not store the quality (which is not known yet). The file and the
// table are the same as one after the other (the writer reads the mesh,
// the measure only reads it too and fills its own array); igea after
// recovery: 0.15 s of Table II and 0.05 s of writing. False when it did
// not run (nothing done then).
bool measure_while_writing(const RecoveryOptions& options, io::VolumeMesh& volume, Steps& steps,
                           QualityReport& quality, io::Status& written) {
    if (options.output.empty() || thread_count(options) < 2 || io::volume_file_stores_quality(options.output))
        return false;
    std::thread writer;
    try {
        writer = std::thread([&] { written = io::write_volume(options.output, volume); });  // noexcept
    } catch (const std::system_error&) {
        return false;  // no thread: one after the other
    }
    steps.begin("measuring quality and writing", true);
    std::vector<double> qualities;
    try {
        quality = measure_quality(static_cast<const io::VolumeMesh&>(volume), qualities);
    } catch (...) {
        writer.join();
        throw;
    }
    writer.join();
    volume.tet_quality.swap(qualities);
    return true;
}

}  // namespace

RecoveryOutcome run_recovery(const io::SurfaceMesh& surface, const RecoveryOptions& options, Steps& steps) {
    MeshHandle h;
    int status = cbr_mesh_create(&h.mesh);
    if (status != CBR_OK) return failure(exit_code_for(status), cbr_status_string(status));
    cbr_mesh* m = h.mesh;
    const auto np = static_cast<std::int64_t>(surface.num_points());
    const auto nf = static_cast<std::int64_t>(surface.num_triangles());

    steps.begin("inserting points");
    status = cbr_mesh_set_param(m, CBR_PARAM_KEEP_EXTERIOR, options.keep_exterior ? 1 : 0);
    if (status == CBR_OK) status = cbr_mesh_set_param(m, CBR_PARAM_RECOVERY_DEEP_FLIPS, options.deep_flips ? 1 : 0);
    if (status == CBR_OK) status = cbr_mesh_set_param(m, CBR_PARAM_RECOVERY_RETRIES, options.retries ? 1 : 0);
    if (status == CBR_OK) status = cbr_mesh_set_param(m, CBR_PARAM_THREADS, options.threads);
    if (status == CBR_OK) status = cbr_mesh_insert_points(m, np, surface.xyz.data());
    if (status != CBR_OK) return api_failure(m, status);
    const std::int64_t delaunay_tets = cbr_mesh_tet_count(m);

    steps.begin("recovering");
    status = cbr_mesh_recover_faces(m, nf, surface.tris.data(), surface.labels.empty() ? nullptr : surface.labels.data());
    // Legal for the library, but rarely what a user of the command wants:
    // an open surface encloses nothing (recover_faces left its check report,
    // also when it could not recover every face).
    const std::int64_t open_edges =
        status == CBR_OK || status == CBR_ERR_RECOVERY_FAILED ? cbr_mesh_defect_count(m, CBR_DEFECT_OPEN_EDGE) : 0;
    if (open_edges > 0 && !options.allow_open) {
        return failure(kExitInput, options.input + " is open: " + std::to_string(open_edges) +
                                       " open edges, it bounds no region (--allow-open to recover it anyway)");
    }
    if (status != CBR_OK) {
        RecoveryOutcome out = api_failure(m, status);
        out.delaunay_tets = delaunay_tets;
        if (status == CBR_ERR_RECOVERY_FAILED) {
            out.has_table_one = true;
            out.table_one = read_table_one(m);
            out.error += degenerate_hint(m, surface);
        }
        return out;
    }

    RecoveryOutcome out;
    out.delaunay_tets = delaunay_tets;
    out.has_table_one = true;
    out.table_one = read_table_one(m);
    if (options.refine) {
        steps.begin("generating the mesh");
        status = cbr_mesh_set_param(m, CBR_PARAM_REFINE_SIZE, options.size);
        if (status == CBR_OK && options.growth >= 0)
            status = cbr_mesh_set_param(m, CBR_PARAM_REFINE_GROWTH, options.growth);
        if (status == CBR_OK) status = cbr_mesh_refine(m);
        if (status != CBR_OK) {
            RecoveryOutcome failed = api_failure(m, status);
            failed.delaunay_tets = delaunay_tets;
            failed.has_table_one = true;
            failed.table_one = out.table_one;
            return failed;
        }
        out.has_refine = true;
        cbr_mesh_get_stat(m, CBR_STAT_FIELD_POINTS, &out.refine.field_points);
        cbr_mesh_get_stat(m, CBR_STAT_REFINE_FLIPS, &out.refine.flips);
        cbr_mesh_get_stat(m, CBR_STAT_REFINE_OVERSIZE_TETS, &out.refine.oversize_tets);
        cbr_mesh_get_stat(m, CBR_STAT_REFINE_SECONDS, &out.refine.seconds);
    }
    steps.begin("measuring quality");
    io::VolumeMesh volume;
    status = collect_volume(m, surface, volume);
    if (status != CBR_OK) return api_failure(m, status);
    out.points = volume.num_points();
    out.tets = volume.num_tets();
    io::Status written;
    if (!measure_while_writing(options, volume, steps, out.quality, written)) {
        out.quality = measure_quality(volume);
        if (!options.output.empty()) {
            steps.begin("writing", true);
            written = io::write_volume(options.output, volume);
        }
    }
    out.has_quality = true;
    if (!options.output.empty()) {
        if (!written.ok()) {
            out.exit_code = exit_code_for(written.kind);
            out.error = written.message;
            return out;
        }
        out.written = true;
    }
    steps.end();
    return out;
}

}  // namespace cbr::cli
