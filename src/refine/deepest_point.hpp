// The deepest point of a bounded intersection of half-spaces (its
// Chebyshev centre: the centre of the largest ball inside it), by a small
// linear program. Sliver removal uses it as a candidate point for a star
// whose kernel is a thin sliver of space that fixed candidates miss.
//
// Floating point throughout: the result is only a candidate, judged
// exactly by the caller before it is used.
#pragma once

#include <vector>

#include "refine/tet_measures.hpp"

namespace cbr::refine {

// Half-space {x : normal . x >= offset}; the normal need not be unit.
struct HalfSpace {
    Point normal;
    double offset;
};

// Writes the point of the intersection of `spaces` farthest from all their
// planes into `deepest`, starting from `inside`, a point inside all of
// them (on their planes at worst). False when the program does not reach
// an optimum (unbounded, or too many steps): `deepest` is then unchanged.
bool deepest_point(const std::vector<HalfSpace>& spaces, const Point& inside, Point& deepest);

}  // namespace cbr::refine
