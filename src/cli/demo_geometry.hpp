// The built-in example: the paper's Example 1, a box holding nine
// spherical inclusions (Du & Wang 2004, Fig. 17), as a surface
// triangulation made in code.
#pragma once

#include <cstdint>
#include <vector>

namespace cbr::cli {

struct DemoSurface {
    std::vector<double> xyz;         // 3 per point
    std::vector<std::int64_t> tris;  // 3 per triangle, 0-based
    std::vector<std::int32_t> labels;  // 1 for the box, 2..10 for the spheres
};

// Box [0, 3] x [0, 3] x [0, 1] meshed as a grid of `box_cells` per unit
// length; nine spheres of radius 0.3 at the centres of its 3 x 3 unit cells,
// each an icosahedron refined `sphere_levels` times and projected.
DemoSurface nine_sphere_box(int box_cells = 6, int sphere_levels = 2);

}  // namespace cbr::cli
