// SPDX-License-Identifier: MIT
// The distance loop's start from a seed (gjk.hpp, DistanceSeed) and the seed it leaves: the
// previous query's simplex points re-placed at the new poses. Internal to gjk.cpp.
#pragma once

#include <bit>

#include "gjk/gjk.hpp"
#include "gjk/simplex.hpp"
#include "gjk/support_kernels.hpp"

namespace kairos::gjk_detail {

// Fills s with the seed's points at the pair's poses, through Johnson's steps as support points
// would go, after adopting the scale of the first one (set_scale: the pair, the points and the
// margin). s is left empty when there is no seed, a point is not finite, or the simplex holds or
// touches the origin: the loop then starts afresh, and decides an intersection from support
// points only.
template <class Pair, class SetScale>
void seed_simplex(Pair& pair, const DistanceSeed& seed, Simplex& s, SetScale&& set_scale) {
    const int n = seed.count < 0 ? 0 : (seed.count > 4 ? 4 : seed.count);
    if (n == 0) return;
    Vec3 a[4], b[4];
    for (int i = 0; i < n; ++i) {
        a[i] = seed.a[i];
        b[i] = pair.r * seed.b[i] + pair.t;
        if (!is_finite(a[i]) || !is_finite(b[i])) return;
    }
    Vec3 w0 = a[0] - b[0];
    set_scale(a[0], b[0], w0);
    for (int i = 1; i < n; ++i)
        if (pair.scale != 1) a[i] = pair.scale * a[i], b[i] = pair.scale * b[i];
    for (int i = 0; i < n; ++i) {
        const Vec3 w = a[i] - b[i];
        if (s.bits != 0 && s.contains(w)) continue;
        const Simplex::Outcome o = s.add(w, a[i], b[i], s.bits != 0 ? dot(s.v, s.v) : INFINITY);
        if (o == Simplex::Outcome::Full || o == Simplex::Outcome::Failed) {
            s.bits = 0;
            s.last_all = 0;
            return;
        }
    }
    if (!(dot(s.v, s.v) > kNearContact * s.max_norm_sq())) {
        s.bits = 0;
        s.last_all = 0;
    }
}

// The seed s leaves: its points at the caller's scale, B's taken back to B's frame.
template <class Pair>
void save_seed(const Pair& pair, const Simplex& s, bool intersecting, DistanceSeed& seed) {
    seed.count = 0;
    if (intersecting) return;
    const double inv = 1 / pair.scale;
    for (unsigned r = s.bits; r; r &= r - 1) {
        const int i = std::countr_zero(r);
        seed.a[seed.count] = inv * s.pa[i];
        seed.b[seed.count] = mul_transpose(pair.r, inv * s.pb[i] - pair.t);
        ++seed.count;
    }
}

}  // namespace kairos::gjk_detail
