// What `cbr recover`, `cbr mesh` and `cbr demo` share: a surface in memory
// through libcbr (Delaunay, boundary recovery, for `cbr mesh` full mesh
// generation), the result collected, its quality
// measured (Table II) and, when asked, written. Nothing is printed here:
// the outcome says what happened, and the command prints it once the
// progress line is gone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "cli/quality.hpp"
#include "cli/steps.hpp"
#include "cli/table_one.hpp"
#include "io/mesh_types.hpp"

namespace cbr::cli {

struct RecoveryOptions {
    std::string input;   // the input's name, for messages
    std::string output;  // the volume mesh to write; empty: none
    bool keep_exterior = false;
    bool allow_open = false;  // accept a surface with open edges
    bool deep_flips = true;   // CBR_PARAM_RECOVERY_DEEP_FLIPS
    bool retries = true;      // CBR_PARAM_RECOVERY_RETRIES
    // `cbr mesh`: after recovery, cbr_mesh_refine (full mesh generation)
    // with CBR_PARAM_REFINE_SIZE = size (0: from the surface).
    bool refine = false;
    double size = 0;
    double growth = -1;  // CBR_PARAM_REFINE_GROWTH; < 0: the library's default
    // CBR_PARAM_THREADS (0: as many as the hardware runs at once); with
    // more than one, the output file is also written while Table II is
    // measured (every format but .vtu, which stores the quality).
    int threads = 0;
};

// What cbr_mesh_refine reports (its CBR_STAT_* keys).
struct RefineSummary {
    double field_points = 0, flips = 0, seconds = 0;
    double oversize_tets = 0;  // left over the size bound (CBR_STAT_REFINE_OVERSIZE_TETS)
};

struct RecoveryOutcome {
    int exit_code = 0;   // kExit* (exit_codes.hpp)
    std::string error;   // one line for stderr, empty on success
    bool has_table_one = false;  // recovery ran (to the end, or failed on faces)
    TableOne table_one;
    bool has_refine = false;     // refinement ran and succeeded
    RefineSummary refine;
    bool has_quality = false;    // recovery (and refinement, when asked) succeeded
    QualityReport quality;
    std::int64_t delaunay_tets = 0;     // tetrahedra of the Delaunay mesh (all, before recovery)
    std::size_t points = 0, tets = 0;   // of the recovered mesh
    bool written = false;               // options.output was written
};

RecoveryOutcome run_recovery(const io::SurfaceMesh& surface, const RecoveryOptions& options, Steps& steps);

}  // namespace cbr::cli
