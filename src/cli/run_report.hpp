// The JSON report of a run (`--json FILE` of cbr recover, cbr mesh and cbr demo):
// what was asked, what happened, and the rows of Table I and Table II.
// Key names are stable (scripts read them); new keys may be added.
//
//   {
//     "cbr_version": "0.1.0",
//     "command": "recover",
//     "input": "in.off",
//     "output": "out.mesh",            null when no mesh was written
//     "options": {"keep_exterior": false, "allow_open": false,
//                 "triangulate": false, "deep_flips": true, "retries": true,
//                 "threads": 0, "size": null, "growth": null},
//                                      as given on the command line (or the
//                                      defaults): threads 0 = the hardware's;
//                                      size and growth null unless cbr mesh
//                                      was given --size / --growth
//     "status": "ok",                  ok | invalid_input | recovery_failed |
//                                      io_error | internal_error
//     "exit_code": 0,
//     "error": null,                   the stderr line when status is not ok
//     "mesh": {"points": 8, "tetrahedra": 6},              null unless recovered
//     "table_one": {"total_vertices": 8, "boundary_vertices": 8,
//                   "missing_faces": 4, "recovered_by_flips": 4,
//                   "conforming_points": 0, "steiner_generated": 0,
//                   "steiner_remaining": 0, "steiner_inside": 0,
//                   "region_count": 2,
//                   "delaunay_seconds": ..., "recovery_seconds": ...,
//                   "total_seconds": ...},               null before recovery ran
//     "refine": {"field_points": ..., "flips": ..., "oversize_tets": 0,
//                "seconds": ...},
//                                                        null unless cbr mesh refined
//     "table_two": {"tetrahedra": 6, "quality_average": ..., "quality_min": ...,
//                   "percent_above_0_4": ..., "percent_below_0_1": ...,
//                   "bad_touching_steiner": 0, "dihedral_min_degrees": ...,
//                   "dihedral_max_degrees": ...,
//                   "regions": [{"region": 1, "tetrahedra": ..., ...}, ...]}
//                                                        null unless recovered
//   }
//
// Counts are integers; times, qualities, percentages and angles are doubles
// ("%.17g"), null when undefined (no tetrahedron). "regions" has one entry
// per region (same keys as table_two, plus "region") when there are
// several, and is empty otherwise.
#pragma once

#include <string>

#include "cli/recovery_run.hpp"
#include "cli/steps.hpp"
#include "io/status.hpp"

namespace cbr::cli {

struct RunDescription {
    std::string command;  // "recover", "demo"
    // How the run was asked for: its input, its output (empty: none) and
    // the options of "options".
    RecoveryOptions options;
    bool triangulate = false;  // --triangulate (a reading option)
};

std::string run_report_json(const RunDescription& run, const RecoveryOutcome& outcome);

// Writes run_report_json() to `path` (temporary file, then rename).
io::Status write_run_report(const std::string& path, const RunDescription& run, const RecoveryOutcome& outcome);

// The end of a run of cbr recover or cbr demo, once its report is on
// stdout: the JSON report written when `json_path` is not empty, the error
// line on stderr (the outcome's, then the report's), the timing line
// (CBR_TIMING=1). Returns the exit code: the outcome's, or the I/O error of
// the report when the run itself succeeded.
int finish_run(const RunDescription& run, const std::string& json_path, const RecoveryOutcome& outcome, Steps& steps);

}  // namespace cbr::cli
