// SPDX-License-Identifier: MIT
// Rim slides: a Newton step for GJK on pairs with a curved rim (cylinders, cones).
//
// Plain GJK converges on a rim by halving the arc between its last two points (the new point's
// tangent is parallel to their chord), so the gap falls about fourfold per support call, and a
// cylinder's side (two rims at one angle) or a rim against an edge needs every point of the
// simplex at the right angle. The rims' radii of curvature, known in closed form, predict the
// direction whose support is the nearest point; each simplex point then slides along its own rim
// (a cylinder's top or bottom, a cone's base; vertices and apexes stay) to that direction's
// angle. Slid points are points of A - B, so the estimate stays an upper bound; the next support
// call along the new estimate gives the lower bound as before, so the stopping rule is unchanged
// (docs/algorithms.md §2, "Rim slides").
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>

#include "gjk/loop_rules.hpp"
#include "gjk/simplex.hpp"
#include "gjk/support_kernels.hpp"
#include "math/math.hpp"

namespace kairos::gjk_detail {

// How a support point moves as the call's direction turns: by rho * dtheta along the unit tangent
// t (rho = 0: it does not move: a vertex, an apex, or a direction so near a revolution shape's
// axis that its cap decides).
struct Rim {
    double rho = 0;
    Vec3 t{};
};

// The feature a support point lies on: a revolution shape's rim at local z = `z` (a cylinder's
// +-h, a cone's base -h), or none that slides (rim false: a vertex, an apex, a general shape's
// point).
struct Feature {
    bool rim = false;
    double z = 0;
};

// A direction's angle about a revolution shape's axis (shape-local): the unit radial direction
// and the rim's curvature there. Not valid within 1e-4 rad of the axis, where the rim's point
// swings by more than 1e4 radii per radian: the cap decides, and no model helps.
struct Angle {
    bool valid = false;
    double x = 0, y = 0;
    Rim rim;
};

template <class S>
inline Angle angle_of(const S&, Vec3) {
    return {};
}
template <class S>
inline Feature feature_of(const S&, Vec3) {
    return {};
}
inline Angle angle_of(const kernels::RevolutionSupport& s, Vec3 d) {
    const double q2 = d.x * d.x + d.y * d.y, dd = dot(d, d);
    if (!(q2 > 1e-8 * dd) || !(dd < 1e300)) return {};
    const double q = std::sqrt(q2), inv = 1 / q;
    const double x = d.x * inv, y = d.y * inv;
    return {true, x, y, {s.radius * std::sqrt(dd) * inv, {-y, x, 0}}};
}
// The feature of the support along d (the kernel's own choice, shape.hpp's cylinder_support and
// cone_support).
inline Feature feature_of(const kernels::RevolutionSupport& s, Vec3 d) {
    if (!s.cone) return {true, toward(d.z, s.half_height)};
    const double q = std::sqrt(d.x * d.x + d.y * d.y);
    if (d.z * s.half_height >= s.radius * q - d.z * s.half_height) return {};
    return {true, -s.half_height};
}
template <class S>
inline Vec3 rim_point(const S&, Feature, const Angle&) {
    return {};  // never called: only rims slide
}
inline Vec3 rim_point(const kernels::RevolutionSupport& s, Feature f, const Angle& g) {
    return {s.radius * g.x, s.radius * g.y, f.z};
}

// A simplex point's model: its two support points' features and rims (A's frame, the pair's
// scale). Set lazily from the call's direction, or by a slide.
struct PointModel {
    Feature fa, fb;
    Rim ra, rb;
};

// Per simplex slot: the direction of the call that found the point, and its model once made.
struct SlotModels {
    Vec3 dir[4];
    PointModel m[4];
    bool ready[4] = {false, false, false, false};
    void set_call(int slot, Vec3 d) {
        dir[slot] = d;
        ready[slot] = false;
    }
};

template <class Pair>
inline Rim to_pair_frame_b(const Pair& pair, Rim r) {
    r.rho *= pair.scale;
    r.t = pair.r * r.t;
    return r;
}

// The model of the point found along d (A's support along -d, B's along d in A's frame).
template <class Pair>
inline PointModel call_model(const Pair& pair, Vec3 d) {
    const Vec3 da = -d, db = mul_transpose(pair.r, d);
    PointModel m;
    m.fa = feature_of(pair.sa, da);
    m.fb = feature_of(pair.sb, db);
    if (m.fa.rim) {
        m.ra = angle_of(pair.sa, da).rim;
        m.ra.rho *= pair.scale;
    }
    if (m.fb.rim) m.rb = to_pair_frame_b(pair, angle_of(pair.sb, db).rim);
    return m;
}

// Adds weight * rho t t^T to the symmetric matrix m (rows xx, yy, zz, xy, xz, yz).
inline void add_rim(double (&m)[6], double weight, const Rim& r) {
    const double k = weight * r.rho;
    m[0] += k * r.t.x * r.t.x;
    m[1] += k * r.t.y * r.t.y;
    m[2] += k * r.t.z * r.t.z;
    m[3] += k * r.t.x * r.t.y;
    m[4] += k * r.t.x * r.t.z;
    m[5] += k * r.t.y * r.t.z;
}

// The direction whose support the model puts nearest, for the simplex `s` (coordinates up to
// date; v = s.v); kappa about ||v||. False when no rim turns or the step leaves the model's reach.
//
// Model: as the direction turns to u, point i moves to w_i - R_i (u - u_i), R_i the sum of
// rho t t^T over its two support points' rims (positive semidefinite: the radii of A - B add;
// R_i u_i = 0, a support depends on the direction only). The point with v's coordinates then
// moves to v - R u, R = sum of lambda_i R_i, and points along u when
//     v - R u = kappa u,  i.e.  u = (R + kappa I)^-1 v,
// kappa = u . (v - R u), about the distance. Along directions no rim turns (vertices, edges, flat
// faces: R zero) u keeps v's component, plain GJK's choice; on a sphere's patch u is the centre's
// direction, to second order in the arc the simplex spans.
template <class Pair>
bool bent_direction(const Pair& pair, const Simplex& s, SlotModels& sm, double kappa, Vec3& out) {
    double m[6] = {0, 0, 0, 0, 0, 0};
    bool any = false;
    for (unsigned r = s.bits; r; r &= r - 1) {
        const int i = std::countr_zero(r);
        if (!sm.ready[i]) sm.m[i] = call_model(pair, sm.dir[i]), sm.ready[i] = true;
        const PointModel& p = sm.m[i];
        if (p.ra.rho > 0) add_rim(m, s.lambda[i], p.ra), any = true;
        if (p.rb.rho > 0) add_rim(m, s.lambda[i], p.rb), any = true;
    }
    if (!any) return false;
    m[0] += kappa;
    m[1] += kappa;
    m[2] += kappa;
    // Symmetric positive definite (R semidefinite, kappa > 0): the inverse by cofactors, up to
    // the positive factor 1 / det (only the direction counts).
    const double c0 = m[1] * m[2] - m[5] * m[5], c1 = m[4] * m[5] - m[3] * m[2], c2 = m[3] * m[5] - m[4] * m[1];
    const double c3 = m[0] * m[2] - m[4] * m[4], c4 = m[3] * m[4] - m[0] * m[5], c5 = m[0] * m[1] - m[3] * m[3];
    const double det = m[0] * c0 + m[3] * c1 + m[4] * c2;
    if (!(det > 0) || !std::isfinite(det)) return false;
    const Vec3 v = s.v;
    const Vec3 u{c0 * v.x + c1 * v.y + c2 * v.z, c1 * v.x + c3 * v.y + c4 * v.z, c2 * v.x + c4 * v.y + c5 * v.z};
    // Within about 25 degrees of v; farther, the linear model is not to be trusted.
    const double uv = dot(u, v);
    if (!(uv > 0) || !(uv * uv > 0.8 * dot(u, u) * dot(v, v))) return false;
    out = u;
    return true;
}

// Slides the simplex's rim points to the bent direction's angles (vertices and apexes stay) and
// keeps the result when its points' affine hull's nearest point lies inside it (coordinates >= 0)
// and is nearer than ||v|| by more than rounding (vv = ||v||^2). Points that land together (the
// two ends of a bracket on one rim) merge. True when kept; otherwise s is as it was.
// Slides run at tolerances below this: a slide costs about as much as a plain step, and at looser
// tolerances GJK stops after a few halvings of the arc (at 1e-6 the slides' 6.5 calls per query
// took 8 % longer than plain GJK's 10.9 on bench_gjk's cylinder/cone pairs).
inline constexpr double kSlideTolerance = 1e-7;
// A merge's arc allowance: chord^2 <= kMergeArc * ||v|| * rho (chord theta rho, error rho theta^2 / 2
// against the distance ||v||): a tilt below about 1e-3 rad.
inline constexpr double kMergeArc = 1e-3;

template <class Pair>
bool slide_simplex(const Pair& pair, Simplex& s, SlotModels& sm, double vv, double lower_sq, double lower_w_sq) {
    Vec3 u;
    if (!bent_direction(pair, s, sm, std::sqrt(vv), u)) return false;
    const Vec3 ua = -u, ub = mul_transpose(pair.r, u);
    const Angle ga = angle_of(pair.sa, ua), gb = angle_of(pair.sb, ub);
    if (!ga.valid && !gb.valid) return false;
    const Rim rim_a{ga.rim.rho * pair.scale, ga.rim.t}, rim_b = to_pair_frame_b(pair, gb.rim);
    const unsigned old_bits = s.bits;
    RawVec3s<4> oy, oa, ob;
    unsigned bits = 0;
    for (unsigned r = old_bits; r; r &= r - 1) {
        const int i = std::countr_zero(r);
        oy[i] = s.y[i], oa[i] = s.pa[i], ob[i] = s.pb[i];
    }
    for (unsigned r = old_bits; r; r &= r - 1) {
        const int i = std::countr_zero(r);
        const PointModel& p = sm.m[i];  // made by bent_direction
        if (ga.valid && p.fa.rim) s.pa[i] = pair.scale * rim_point(pair.sa, p.fa, ga);
        if (gb.valid && p.fb.rim) s.pb[i] = pair.scale * (pair.r * rim_point(pair.sb, p.fb, gb) + pair.t);
        s.y[i] = s.pa[i] - s.pb[i];
        bool dup = false, wide = false;
        for (unsigned q = bits; q; q &= q - 1) {
            const int k = std::countr_zero(q);
            if (!(s.y[k] == s.y[i])) continue;
            dup = true;
            // A merge trusts the Newton step with the bracket's whole arc, whose error (about
            // rho theta^2 for an arc theta wide) tilts the merged point's direction by that over
            // the distance: past a few degrees its support can land across the rim, and GJK has
            // lost the bracket. Merging waits until the arc is narrow enough.
            const Vec3 chord = oy[i] - oy[k];
            const double rho = std::max(std::max(p.ra.rho, p.rb.rho), 1e-300);
            wide |= !(dot(chord, chord) <= kMergeArc * std::sqrt(vv) * rho);
        }
        if (wide) {
            bits = 0;
            break;
        }
        if (!dup) bits |= 1u << i;
    }
    if (bits != 0) {
        s.recompute_all(bits);
        s.set_from_subset(bits);
        bool inside = true;
        for (unsigned r = bits; r; r &= r - 1) inside &= s.lambda[std::countr_zero(r)] >= 0;
        const double nv = dot(s.v, s.v);
        // As for any step (the distance loop): a sliver's plane can pass nearer the origin than
        // its points, with coordinates that do not reproduce v, or v below the proven bound.
        if (inside && vv - nv > kNoProgress * vv && s.coordinates_reproduce_v(0x1p-60) &&
            !below_lower_bound(nv, lower_sq, lower_w_sq)) {
            for (unsigned r = bits; r; r &= r - 1) {
                const int i = std::countr_zero(r);
                PointModel& p = sm.m[i];
                if (ga.valid && p.fa.rim) p.ra = rim_a;
                if (gb.valid && p.fb.rim) p.rb = rim_b;
            }
            s.last_all = bits;
            return true;
        }
    }
    for (unsigned r = old_bits; r; r &= r - 1) {
        const int i = std::countr_zero(r);
        s.y[i] = oy[i], s.pa[i] = oa[i], s.pb[i] = ob[i];
    }
    s.recompute_all(old_bits);
    s.set_from_subset(old_bits);
    return false;
}

// The slides of one distance query: the points' models, and when to stop sliding. A slide needs a
// positive lower bound (before one the simplex may still be building a tetrahedron around the
// origin, which merging points would undo) and an estimate above 1e-6 of the simplex's size (near
// contact rounding decides, and plain GJK's rules are tuned for it). They stop for the query when
// a slide did not halve the gap vv - lower^2 by the next one (the model is off: a chord across a
// flat cap, not a bracket on a rim), or when a call returns the last call's point again (plain
// GJK would have stopped on it: the slides keep moving the simplex off it). Seeded queries (the
// motion cast's, a point or two from the last step's answer) do not slide: their near-contact
// end game is tuned on plain GJK. Nor do queries at tolerances of kSlideTolerance or looser.
template <class Pair, bool = Pair::exact>
struct Slides {
    SlotModels models;
    bool on;
    bool slid = false;
    double gap_at_slide = INFINITY;
    Vec3 last_w{};

    Slides(bool seeded, double tolerance) : on(!seeded && tolerance < kSlideTolerance) {}

    // A call returned w (every call, before it is added).
    void called(Vec3 w) {
        if (!on) return;
        if (slid && w == last_w) on = false;
        last_w = w;
    }
    // The call along v is about to go into the simplex (its first free slot).
    void adding(unsigned prev_bits, Vec3 v) {
        if (on) models.set_call(std::countr_zero(~prev_bits & 15u) & 3, v);
    }
    // After a step that shortened the estimate to vv: true when a slide shortened it further (s.v).
    bool after_step(const Pair& pair, Simplex& s, double vv, double lower_num, double lower_den, Vec3 lower_w) {
        const double gap = vv - lower_num / lower_den;
        if (slid && !(gap <= 0.5 * gap_at_slide)) on = false;
        if (!on || !(lower_num > 0) || !(vv > 1e-12 * s.max_norm_sq())) return false;
        if (!slide_simplex(pair, s, models, vv, lower_num / lower_den, dot(lower_w, lower_w))) return false;
        slid = true;
        gap_at_slide = gap;
        return true;
    }
};
// Pairs whose supports are all exact (polytopes, points, segments) have no rim: nothing to keep.
template <class Pair>
struct Slides<Pair, true> {
    static constexpr bool on = false;
    Slides(bool, double) {}
    void called(Vec3) {}
    void adding(unsigned, Vec3) {}
    bool after_step(const Pair&, Simplex&, double, double, double, Vec3) { return false; }
};

}  // namespace kairos::gjk_detail
