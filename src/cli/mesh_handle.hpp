// Owns a cbr_mesh for the length of a command.
#pragma once

#include <cbr/cbr.h>

namespace cbr::cli {

struct MeshHandle {
    cbr_mesh* mesh = nullptr;
    MeshHandle() = default;
    MeshHandle(const MeshHandle&) = delete;
    MeshHandle& operator=(const MeshHandle&) = delete;
    ~MeshHandle() { cbr_mesh_destroy(mesh); }
};

}  // namespace cbr::cli
