// Compass (pattern) search, as sliver removal climbs a star's point and
// smoothing moves a vertex for its ball's smallest dihedral angle: from p,
// whose value is `value`, a step of `step` along -x, +x, -y, +y, -z, +z;
// the best step that raises the value is taken, else the step halves,
// `halvings` times in all. `rate(q, to_beat)` is the value at q; anything
// at or below `to_beat` counts as no gain, so it may stop early there.
#pragma once

#include <cstddef>

#include "refine/tet_measures.hpp"

namespace cbr::refine {

template <class Rate>
void compass_search(Point& p, double& value, double step, int halvings, Rate rate) {
    for (int halved = 0; halved < halvings;) {
        Point next = p;
        double next_value = value;
        for (std::size_t axis = 0; axis < 3; ++axis)
            for (double sign : {-1.0, 1.0}) {
                Point trial = p;
                trial[axis] += sign * step;
                const double rated = rate(trial, next_value);
                if (rated > next_value) next = trial, next_value = rated;
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
