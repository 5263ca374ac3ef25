// Whole-mesh validity checks, exact: run after every operation in tests,
// and once at the end of the library's own algorithms.
#pragma once

#include <string>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace cbr::mesh {

struct CheckReport {
    std::vector<std::string> errors;  // first few problems found, readable
    std::size_t error_count = 0;      // all problems found
    bool ok() const { return error_count == 0; }
    void add(std::string message);
};

// Combinatorics and geometry: vertex ids in range, neighbour links
// symmetric and across the same three vertices, every finite tetrahedron
// positively oriented (exact), ghosts well formed and the hull closed (a
// triangulated sphere: V - E + F = 2), every vertex used. `threads`: how
// many threads may share the work (mesh/chunks.hpp); the report is the
// same whatever their number.
CheckReport check_mesh(const TetMesh& m, int threads = 1);

// check_mesh, plus: every face locally Delaunay under the symbolic
// perturbation (interior faces by insphere_sos, hull faces by the ghost
// conflict test), which proves the whole mesh Delaunay.
CheckReport check_delaunay(const TetMesh& m);

}  // namespace cbr::mesh
