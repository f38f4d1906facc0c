// SPDX-License-Identifier: MIT
// How a GJK-based query ended: shared by the distance and intersection loops, the casts, the
// motion cast and the C boundary.
#pragma once

#include <cstdint>

namespace kairos {

// Which rule ended an iteration. Values equal the public KAIROS_TERMINATION_* (checked at the C
// boundary), so they are never renumbered.
enum class Termination : int32_t {
    None = 0,
    RelativeError = 1,    // ||v||^2 - v.w <= tolerance * ||v||^2: distance within the tolerance
    NearContact = 2,      // ||v||^2 <= kNearContact * max ||y||^2: touching within rounding
    FullSimplex = 3,      // the simplex holds the origin (or, for rounded shapes, the cores are
                          // closer than the sum of the radii): the shapes intersect
    JohnsonFailed = 4,    // no valid sub-simplex, and the backup pass did not improve; or the
                          // sub-simplex found lies below the proven lower bound: last estimate
    RepeatedSupport = 5,  // the support point was already a vertex of the last step's simplex
    NoProgress = 6,       // ||v||^2 decreased by no more than machine epsilon (relative)
    MaxIterations = 7,    // the iteration guard
    Separated = 8,        // intersection test: a separating axis was found
    Hit = 9,              // casts only
};

}  // namespace kairos
