// orient3d against one plane for many points: the hull checks of mesh
// surgery test every vertex of a region against each new hull face, and on
// CAD surfaces most of those points lie in the face's plane, where the
// filter cannot decide and the exact stage runs for each of them.
#pragma once

#include "geom/expansion.hpp"
#include "geom/predicates.hpp"

namespace cbr::geom {

// orient3d(a, b, c, x) for a fixed a, b, c: the same filter, then an exact
// stage that computes the plane's normal (b - a) x (c - a) once, as three
// exact 2x2 minors, and only its dot product with x - a per point, where
// orient3d's exact stage computes three minors per point. Same sign as
// orient3d, always. a, b and c are kept by pointer.
class PlaneSide {
public:
    PlaneSide(const double* a, const double* b, const double* c) : a_(a), b_(b), c_(c) {}

    int operator()(const double* x) {
        const int s = detail::orient3d_filter(a_, b_, c_, x);
        return s != 0 ? s : exact_sign(x);
    }

private:
    int exact_sign(const double* x);  // predicates.cpp

    enum class Normal : unsigned char {
        kNotYet,   // no exact stage run yet
        kExact,    // normal_ holds the exact normal
        kInexact,  // b - a or c - a is not representable: orient3d's exact stage
    };
    const double* a_;
    const double* b_;
    const double* c_;
    Normal state_ = Normal::kNotYet;
    xp::Expansion<4> normal_[3];
    // The normal in doubles, when kExact and each component is exact so.
    bool normal_in_doubles_ = false;
    double normal_doubles_[3] = {0, 0, 0};
};

}  // namespace cbr::geom
