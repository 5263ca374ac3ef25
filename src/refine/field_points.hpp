// Field points (Du & Wang 2004, §6 step (d)): points inserted inside the
// bounded regions until every tetrahedron meets the sizing field and the
// quality bound. Each point goes in through the constrained insertion
// kernel of recovery (recover::insert_protected: its cavity never crosses a
// constraint face), so the surface triangulation stays exactly the input.
//
// Placement: the circumcentre of the bad tetrahedron (Delaunay refinement;
// the paper couples advancing-front placement with Delaunay insertion,
// circumcentres are the simpler choice its issue allows). A circumcentre is
// refused when it lies outside the tetrahedron's region, on the surface, or
// inside the diametral ball of a constraint face of its cavity (too close to
// the surface: it would make a flat element against a face that cannot be
// split). Then a tetrahedron over the size bound gets the midpoint of its
// longest over-long non-surface edge instead (inside the region: no face
// through a non-surface edge is a constraint face), unless that midpoint is
// within a tenth of the edge's length of the surface; a sliver (radius
// ratio < 0.1) gets its centroid when the star it would make is at least
// twice as good (checked before inserting); anything else is left to the
// optimisation. Quality refinement stops where the circumradius is under
// half the local size (no cascades at small input angles).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "refine/refine_context.hpp"
#include "refine/refine_options.hpp"

namespace cbr::refine {

// For tests: the points insert_field_points put in each part of its work
// (in halves: the border's before the halves, each half's, the border's
// after them; with seeds, all count as border_after) and each insertion's
// cavity and star, in that order.
struct FieldPointsLog {
    std::size_t border_before = 0;
    std::array<std::size_t, 2> in_half{};
    std::size_t border_after = 0;
    std::vector<TetChange> insertions;
};

// Refines every tetrahedron of the bounded regions of c.m, in two halves
// (see field_points.cpp: two threads when c.options.threads allows; the
// same mesh with any number); new points are appended to the mesh
// coordinates (after the existing ones) and to c.size. With `seeds`, only
// those tetrahedra (the live ones of the bounded regions) and what their
// refinement creates, on one thread, new points in insertion order.
void insert_field_points(RefineContext& c, RefineStats& stats, const std::vector<mesh::TetId>* seeds = nullptr,
                         FieldPointsLog* log = nullptr);

}  // namespace cbr::refine
