// The commands that read a surface and write a volume mesh, `cbr recover`
// and `cbr mesh`: one argument parser and one run; `mesh` adds refinement
// (cbr_mesh_refine) after the recovery, and its --size option.
#pragma once

#include <cstdio>

namespace cbr::cli {

struct VolumeCommand {
    const char* name;                  // "recover", "mesh"
    void (*print_help)(std::FILE*);    // the command's --help
    bool refine;                       // refinement after recovery; accepts --size H
};

int run_volume_command(int argc, char** argv, const VolumeCommand& command);

}  // namespace cbr::cli
