// Compass (pattern) search, as sliver removal climbs a star's point and
// smoothing moves a vertex for its ball's smallest dihedral angle: from p,
// whose value is `value`, a step of `step` in each direction of the
// stencil; the best step that raises the value is taken, else the step
// halves, `halvings` times in all. `rate(q, to_beat)` is the value at q;
// anything at or below `to_beat` counts as no gain, so it may stop early
// there.
//
// Stencils: kAxes, the 6 directions -x, +x, -y, +y, -z, +z; kCube, the 26
// directions to the other points of a 3 x 3 x 3 grid (unit length). A
// smallest angle over many tetrahedra is a ridge wherever two of them tie,
// and a ridge that runs obliquely to the axes stops the axes at once
// (thingiverse-mouth: a field point whose ball's smallest angle, 1.75 deg,
// no axis step raises, while a diagonal one climbs to 3.4).
#pragma once

#include <cmath>
#include <cstddef>

#include "refine/tet_measures.hpp"

namespace cbr::refine {

enum class Stencil { kAxes, kCube };

template <class Rate>
void compass_search(Point& p, double& value, double step, int halvings, Rate rate, Stencil stencil = Stencil::kAxes) {
    for (int halved = 0; halved < halvings;) {
        Point next = p;
        double next_value = value;
        const auto try_step = [&](int dx, int dy, int dz, double length) {
            const Point trial = {p[0] + dx * length, p[1] + dy * length, p[2] + dz * length};
            const double rated = rate(trial, next_value);
            if (rated > next_value) next = trial, next_value = rated;
        };
        if (stencil == Stencil::kAxes) {
            for (int axis = 0; axis < 3; ++axis)
                for (int sign : {-1, 1})
                    try_step(axis == 0 ? sign : 0, axis == 1 ? sign : 0, axis == 2 ? sign : 0, step);
        } else {
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dz = -1; dz <= 1; ++dz) {
                        const int squared = dx * dx + dy * dy + dz * dz;
                        if (squared > 0) try_step(dx, dy, dz, step / std::sqrt(static_cast<double>(squared)));
                    }
        }
        if (next_value > value) {
            p = next;
            value = next_value;
        } else {
            step /= 2;
            ++halved;
        }
    }
}

}  // namespace cbr::refine
