// SPDX-License-Identifier: MIT
// The shape cast's simplex (cast.cpp): after a clip, re-expressed about the new ray point, its
// determinants recomputed and Johnson's test run over every subset, since the closest sub-simplex
// need not hold the newest point once x has moved (the first pass runs with the point set known
// at compile time, as Simplex::add does); and its checks at the boundary.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <utility>

#include "gjk/simplex.hpp"

namespace kairos::cast_detail {

using gjk_detail::Simplex;

// The first pass with `all` known at compile time (as add() runs it): the first valid subset,
// smallest first, the empty one skipped and the full tetrahedron left to the geometric test.
template <unsigned All>
bool first_valid_proper(Simplex& s) {
    constexpr auto& table = gjk_detail::kSubsets;
    return [&]<unsigned... T>(std::integer_sequence<unsigned, T...>) {
        return (s.try_subset<table.subsets[All][T + 1], All>() || ...);
    }(std::make_integer_sequence<unsigned, table.count[All] - 1>{});
}

// Johnson's test over every subset of `all` except the full tetrahedron (its determinants must be
// current), then the backup pass: the subset with positive determinants whose affine closest
// point is nearest x.
inline Simplex::Outcome johnson_proper(Simplex& s, unsigned all) {
    static constexpr auto first = gjk_detail::per_subset([]<unsigned M>() { return &first_valid_proper<M>; });
    if (first[all & 15u](s)) return Simplex::Outcome::Reduced;
    return s.backup(all, INFINITY);
}

// After a rebuild: a flat or thin tetrahedron (Simplex::thickness; add() applies the same test)
// is replaced by the best proper sub-simplex (a flat one says nothing about x, a thin one gives
// poor coordinates for the contact point).
inline Simplex::Outcome check_full(Simplex& s) {
    if (s.thickness() == Simplex::Thickness::Solid) return Simplex::Outcome::Full;
    return johnson_proper(s, 15u);
}

// Re-expresses the simplex about the ray point x: y_i = x - (pa_i - pb_i) for its points, plus the
// point (a, b) when `add` is set; recomputes every dot product and determinant, and runs Johnson's
// test over all subsets (the closest sub-simplex need not hold the newest point once x has moved).
inline Simplex::Outcome rebuild(Simplex& s, Vec3 x, bool add, Vec3 a, Vec3 b) {
    unsigned all = s.bits;
    if (add) {
        const int slot = std::countr_zero(~all & 15u);
        s.pa[slot] = a;
        s.pb[slot] = b;
        all |= 1u << slot;
    }
    // y_i = x - p_i with p_i = a_i - b_i written exactly as the loop writes w, so a repeated
    // support point compares equal; then every norm, determinant and cached sum of the points.
    for (unsigned r = all; r; r &= r - 1) {
        const int i = std::countr_zero(r);
        s.y[i] = x - (s.pa[i] - s.pb[i]);
    }
    s.recompute_all(all);
    s.last_all = all;
    if (all == 15u && s.origin_in_tetrahedron()) {
        s.bits = 15u;
        s.v = Vec3{};
        return check_full(s);
    }
    return johnson_proper(s, all);
}

// x reached the boundary of C (a clip happened, so x is on or outside C) and the tetrahedron of
// the simplex holds it: x lies on one of its faces. The coordinates from signed volumes lose their
// digits on flat tetrahedra, so the contact point is taken from the face nearest x, with the face's
// own coordinates (all of them non-negative up to rounding); without such a face the tetrahedron's
// coordinates stay.
inline void on_boundary_face(Simplex& sx) {
    const Simplex full = sx;
    double best = INFINITY;
    unsigned best_face = 0;
    for (int drop = 0; drop < 4; ++drop) {
        const unsigned face = 15u & ~(1u << drop);
        Simplex trial = full;
        trial.set_from_subset(face);
        bool inside = true;
        for (unsigned r = face; r; r &= r - 1)
            if (!(trial.lambda[std::countr_zero(r)] >= -1e-9)) inside = false;
        const double d = dot(trial.v, trial.v);
        if (inside && d < best) {
            best = d;
            best_face = face;
        }
    }
    if (best_face == 0) return;
    sx.set_from_subset(best_face);
    sx.v = Vec3{};
}

// The barycentric coordinates of v over the kept points lie in [0, 1] up to rounding.
inline bool coordinates_sane(const Simplex& sx) {
    for (unsigned q = sx.bits; q; q &= q - 1) {
        const double l = sx.lambda[std::countr_zero(q)];
        if (!(l >= -1e-9 && l <= 1 + 1e-9)) return false;
    }
    return true;
}

}  // namespace kairos::cast_detail
