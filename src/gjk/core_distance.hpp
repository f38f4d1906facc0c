// SPDX-License-Identifier: MIT
// The distance between the cores of two shapes (each shape less the radius folded out of it:
// a sphere's centre, a capsule's segment, a rounded box's box), for the signed distance. Internal.
#pragma once

#include <cstdint>

#include "gjk/gjk.hpp"
#include "gjk/polytope.hpp"
#include "gjk/support_kernels.hpp"
#include "gjk/termination.hpp"
#include "math/math.hpp"

namespace kairos {

// In A's local frame, at the caller's scale.
struct CoreDistance {
    double distance = 0;     // >= 0; 0 when the cores overlap or touch within rounding
    Vec3 point_a, point_b;   // the cores' closest points (apart)
    Vec3 unit;               // from A's core toward B's (apart); zero when unknown
    Vec3 center_offset;      // B's origin in A's frame
    bool overlap = false;
    // A support call proved a positive lower bound of the gap (see LocalDistance::bounded).
    bool bounded = false;
    uint32_t iterations = 0;
    Termination termination = Termination::None;
};

// Whether a GJK loop's gap may hide an overlap (overlap_behind_rounding_stop): a rounding rule
// stopped it (no progress, or no valid sub-simplex) and no support call bounded the gap from below.
inline bool unproven_rounding_stop(bool bounded, Termination termination) {
    return !bounded && (termination == Termination::JohnsonFailed || termination == Termination::NoProgress);
}

// A box, cylinder or cone core (solid_core); with a point core (a ball's centre, a point), either order: their
// distance and the point's depth inside have closed forms (closed_forms.hpp, penetration.cpp).
inline bool solid_core(const kernels::CoreOf& c) {
    return c.core == kernels::Core::Box || c.core == kernels::Core::Revolution;
}
inline bool point_and_solid(const kernels::CoreOf& ca, const kernels::CoreOf& cb) {
    return (ca.core == kernels::Core::Point && solid_core(cb)) || (solid_core(ca) && cb.core == kernels::Core::Point);
}

// Whether core_distance has a closed form for the pair (points and segments among themselves,
// point_and_solid).
bool closed_form_cores(const kernels::CoreOf& ca, const kernels::CoreOf& cb);

// The closed forms for the pairs that have them, else GJK on the cores with no margin (held, may
// be null: its final tetrahedron when the cores overlap).
CoreDistance core_distance(const kernels::CoreOf& ca, const Transform& pose_a, const kernels::CoreOf& cb,
                           const Transform& pose_b, double tolerance, uint32_t max_iterations,
                           HeldTetrahedron* held = nullptr);

// GJK's gap between shapes without radii (or between the cores of shapes with radii) when a
// rounding rule stopped it (unproven_rounding_stop) is no verdict when its own axis (unit, A's
// frame) shows the shapes overlapping by more than rounding: 2^-46 of the offset plus the support
// point, a few units in the last place of the support value. Faces tilted 1e-9 against each
// other, 1e-12 apart at one end, made A - B a slab of nearly coplanar facets: GJK stopped 2e-11
// of the size "apart", along an axis on which the boxes overlapped by 2e-10, for boxes a vertex
// of which lay 1.2e-10 inside the other (and 1e-13 "apart" for a vertex 1e-12 inside). The
// expansion then decides: a depth past the same rounding is the overlap, with its normal (A's
// frame); else depth 0. iterations: its support calls.
epa_detail::CoreDepth overlap_behind_rounding_stop(const kernels::CoreOf& ca, const Transform& pose_a,
                                                   const kernels::CoreOf& cb, const Transform& pose_b, Vec3 axis,
                                                   double tolerance);

}  // namespace kairos
