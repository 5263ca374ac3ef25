// Welding STL corners into shared vertices by EXACT coordinate equality
// (x == x' && y == y' && z == z', so +0.0 and -0.0 are the same vertex; the
// first occurrence's bits are kept). No tolerance: two points that differ in
// the last bit stay two vertices, as the surface checks must see them.
//
// An open-addressing hash table of vertex ids (linear probing, load <= 1/2)
// whose keys are the coordinates already stored in mesh.xyz.
#pragma once

#include <cstdint>
#include <vector>

#include "io/mesh_types.hpp"

namespace cbr::io::detail {

class VertexWelder {
public:
    explicit VertexWelder(SurfaceMesh& mesh) : mesh_(mesh) {}
    void reserve(std::size_t points);
    // Index of the vertex at (x, y, z), appended to mesh.xyz if new.
    std::int64_t id(double x, double y, double z);

private:
    void grow();
    std::size_t slot_of(double x, double y, double z) const;

    SurfaceMesh& mesh_;
    std::vector<std::int64_t> slots_;  // vertex id, or -1 for an empty slot
    std::size_t used_ = 0;
};

}  // namespace cbr::io::detail
