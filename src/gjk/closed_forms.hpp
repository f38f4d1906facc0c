// SPDX-License-Identifier: MIT
// Closed forms for the pairs whose cores are points or segments (spheres, capsules, points and
// segments among themselves), and for a point core against a box, a cylinder or a cone (a sphere
// and one of those): the closest points with no GJK iteration. Internal.
#pragma once

#include "gjk/support_kernels.hpp"
#include "math/math.hpp"

#include <cmath>

namespace kairos::closed_form {

// Closest points of segment P = {s e_z : |s| <= ha} (A's core, in A's frame) and segment
// Q = {c + u d : |u| <= hb} (B's core in A's frame; d unit, c its centre). ha or hb 0 makes a point.
struct SegmentPair {
    Vec3 p, q;    // closest points on P and Q
    double s, u;  // their parameters: p = s e_z, q = c + u d
};

inline double clamp_to(double x, double h) { return x < -h ? -h : (x > h ? h : x); }

// The squared distance |c + u d - s e_z|^2 is convex in (s, u). Its minimiser over the rectangle:
// s from the unconstrained minimum (the lines' common perpendicular) clamped to P, u the point of
// Q nearest p(s) clamped to Q, and when that clamp acted, s again as the point of P nearest q(u)
// (Ericson, Real-Time Collision Detection §5.1.9, in this frame). The unconstrained s is
// s = c.z - d.z (d.x c.x + d.y c.y) / (d.x^2 + d.y^2): both factors are of the order of the sine
// of the angle between the segments and are computed without cancellation, so for nearly parallel
// segments s is off by about eps |c| / sin along a valley whose slope is sin: the distance stays
// within about eps |c| (the textbook (c.z - b d.c) / (1 - b^2) cancels to eps |c| / sin^2, which
// put the distance off by eps |c| / sin, 1e-7 at a tilt of 1e-9). For parallel segments (and a
// point A) s starts at 0, and the two projections that follow find a closest pair. d need not be
// exactly unit.
inline SegmentPair closest_points(double ha, Vec3 c, Vec3 d, double hb) {
    const double across = d.x * d.x + d.y * d.y;  // |e_z x d|^2
    const double dd = across + d.z * d.z;
    double s = 0;
    if (across > 0 && ha > 0) s = clamp_to(c.z - d.z * ((d.x * c.x + d.y * c.y) / across), ha);
    const double u_free = (s * d.z - dot(d, c)) / dd;
    const double u = clamp_to(u_free, hb);
    if (u != u_free || across == 0) s = clamp_to(c.z + u * d.z, ha);
    return {{0, 0, s}, c + u * d, s, u};
}

// Separation of P and Q along unit n: min over Q of n.x - max over P of n.x.
inline double separation(Vec3 n, double ha, Vec3 c, Vec3 d, double hb) {
    return dot(n, c) - hb * std::fabs(dot(n, d)) - ha * std::fabs(n.z);
}

struct Axis {
    Vec3 n;      // unit, from P toward Q
    double sep;  // separation(n): a lower bound of the distance, to rounding
};

// The unit axis from P toward Q given n0 = unit_of(q - p), chosen to prove the separation. n0
// alone is tilted by the rounding of the subtraction (eps |c| absolute, far
// above the gap when the segments nearly touch), and a tilt t toward a segment's direction widens
// its shadow by h t, so it would not separate them. The exact axis is perpendicular to each
// segment whose closest point is interior (and to both when they are parallel, where any point of
// the overlap is closest): the candidates are n0 with its component along e_z, along d, or both
// taken out, and the one that separates best is kept.
inline Axis separating_axis(double ha, Vec3 c, Vec3 d, double hb, Vec3 n0) {
    Axis best{n0, separation(n0, ha, c, d, hb)};
    auto consider = [&](Vec3 n) {
        const double m = dot(n, n);
        if (!(m > 0.25)) return;  // (nearly) nothing left of the gap's direction
        n = (1 / std::sqrt(m)) * n;
        const double sep = separation(n, ha, c, d, hb);
        if (sep > best.sep) best = {n, sep};
    };
    if (hb > 0) consider(n0 - dot(n0, d) * d);
    if (ha > 0) {
        const Vec3 na{n0.x, n0.y, 0};
        consider(na);
        // Along d made orthogonal to e_z as well (the segments' common perpendicular).
        const Vec3 dd{d.x, d.y, 0};
        const double l2 = dot(dd, dd);
        if (hb > 0 && l2 > 0) consider(na - (dot(na, dd) / l2) * dd);
    }
    return best;
}

// Nearest point of the box |x_i| <= h_i to t (its own frame): t clamped. Exact: a coordinate
// within its slab is copied, so a face's gap vector has exact zeros across the face, and every
// non-zero component of t - p has the sign of its side: t - p separates whatever its rounding.
inline Vec3 box_nearest(Vec3 h, Vec3 t) { return {clamp_to(t.x, h.x), clamp_to(t.y, h.y), clamp_to(t.z, h.z)}; }

// A cone's slant in its axial section (rho, z), from the rim (r, -h) to the apex (0, h): the
// outward unit normal (across, up) = (2h, r) / length, formed from r and 2h over the larger of
// them (of subnormal ones, a cone 5e-324 wide, the hypotenuse itself has a few bits, and the
// normal came out as (1, 0.5)); its parts first, as products of two lengths underflow below 1e-154.
struct Slant {
    double across, up, length;
    // The section point's room to the slant's line, >= 0 on the axis's side.
    double room(double rho, double z, double h) const { return up * (h - z) - across * rho; }
};
inline Slant slant_of(double r, double h) {
    const double big = std::fmax(2 * h, r), a = 2 * h / big, b = r / big, m = std::hypot(a, b);
    return {a / m, b / m, m * big};
}

// A cylinder's or cone's dimensions; s is one of them.
struct Revolution {
    bool cone;
    double radius, half_height;
};
inline Revolution revolution_of(const Shape& s) {
    if (s.kind() == ShapeKind::Cone) {
        const auto& c = static_cast<const ConeShape&>(s);
        return {true, c.radius, c.half_height};
    }
    const auto& c = static_cast<const CylinderShape&>(s);
    return {false, c.radius, c.half_height};
}

// A point's place about a solid's axis: its distance from the axis and the radial unit (over the
// larger part first: t / rho, of subnormal parts, was (1 1 0); zero on the axis). The nearest
// point from outside and the depth from inside both start here.
struct Section {
    double rho;
    Planar radial;
};
inline Section section_of(Vec3 t) { return {std::hypot(t.x, t.y), radial_unit(t.x, t.y)}; }

// Nearest point to t (its own frame) of a solid cylinder (radius r, |z| <= h) or cone (apex
// (0, 0, h), base disk of radius r at z = -h): t itself inside. It lies in the axial half-plane
// through t (turning a point of the solid about the axis into that half-plane brings it no
// farther), where the section is a rectangle or a right triangle with a leg on the axis, and t is
// never beyond that leg. Below a cone's base plane the nearest point is on the base disk or its
// rim (the side's normals point up); above it, outside, on the slant from the apex to the rim.
// The radial part is t's scaled by the section point's radius over t's, exactly 1 when only z
// moves. unit: the outward normal there toward t, zero inside: a side's, slant's or end's own
// normal, else (a rim, the apex) the section's gap direction. A direction taken from t - p would
// carry the rounding of p (a point 1e-12 off a cylinder's side got an axis 1e-4 rad off its
// normal, which then did not show the gap).
inline Vec3 revolution_nearest(bool cone, double r, double h, Vec3 t, Vec3& unit) {
    const Section section = section_of(t);
    const double rho = section.rho;
    double pr = rho < r ? rho : r, pz = clamp_to(t.z, h);  // the section's point: (radius, z)
    double nr = rho - pr, nz = t.z - pz;                   // the section's outward direction (gap)
    if (cone && t.z > -h) {
        // The slant's outward unit normal (across, up) and unit direction from the apex (up, -across).
        const Slant slant = slant_of(r, h);
        const double across = slant.across, up = slant.up, l = slant.length;
        if (slant.room(rho, t.z, h) >= 0) {
            pr = rho, pz = t.z, nr = 0, nz = 0;  // inside
        } else {
            const double s = up * rho + across * (h - t.z);  // the foot's distance from the apex
            const bool on_slant = s > 0 && s < l;
            if (s <= 0)
                pr = 0, pz = h;
            else if (s >= l)
                pr = r, pz = -h;
            else
                pr = s * up, pz = h - s * across;
            nr = on_slant ? across : rho - pr;
            nz = on_slant ? up : t.z - pz;
            // At the rim or the apex the gap's direction must stay on its side of the slant's
            // normal (its normal cone's edge): a gap near rounding can turn it past, and there the
            // support jumps to the far end of the slant (the axis then showed no gap; a point
            // 1e-12 of the size off a cone's rim at 1e4 missed by 8e-4 of the size).
            const double past = nr * up - nz * across;  // < 0 beyond the slant's normal from the rim
            if (!on_slant && (s >= l ? past < 0 : past > 0)) nr = across, nz = up;
        }
    }
    // The gap's direction too over its larger part first.
    const Planar radial = section.radial, gap = radial_unit(nr, nz);
    unit = gap.x * Vec3{radial.x, radial.y, 0} + Vec3{0, 0, gap.y};
    const double k = rho > 0 ? pr / rho : 0;
    return {k * t.x, k * t.y, pz};
}

// |a| without overflow or underflow of its square (the cores may lie 1e100 apart, or 1e-200).
inline double safe_length(Vec3 a) {
    const double nn = dot(a, a);
    if (nn > 1e-200 && nn < 1e200) return std::sqrt(nn);
    const double m = max_abs(a);
    return m > 0 ? m * length(a / m) : 0.0;
}

// a / |a| for a non-zero a, formed from a / max|a_i| (exact to rounding, about 1): a / |a| with
// |a| itself subnormal (cores 1e-321 apart) rounds |a| to a few bits and is not unit (found by
// fuzzing the world).
inline Vec3 unit_of(Vec3 a) {
    const Vec3 b = a / max_abs(a);
    return (1 / std::sqrt(dot(b, b))) * b;
}

// First lambda in [0, 1] at which s + lambda r lies within `radius` of the origin (a ray against a
// ball), 0 when s starts within, -1 when never. Works at the scale of max(|s|, radius) (a power of
// two, exact) with r's direction and length apart, so no square over- or underflows. The entry is
// the smaller root of lambda'^2 - 2 m lambda' + (|s|^2 - radius^2) = 0 in the distance lambda'
// along the unit direction (m = -s.u, the closest approach), taken as the product of the roots
// over the larger one: no cancellation, unlike m - sqrt(m^2 - ...).
//
// `offset` is the entry point relative to the centre, at the working scale (only its direction is
// meant): w - h u, the closest approach's offset w less the half chord h along u. Formed so
// rather than as s + lambda r, whose rounding (eps |s|) is all there is of it when the radius is
// far below |s| (a point cast onto a ball 1e-250 wide: a normal along the motion, found by fuzzing).
// Zero when the radius is 0 and the ray passes through the centre.
struct BallEntry {
    double lambda = -1;
    Vec3 offset;
};
inline BallEntry ball_entry(Vec3 s, Vec3 r, double radius) {
    BallEntry e;
    const double sc = kernels::pair_scale(s, {radius, 0, 0});
    s = sc * s;
    const double rad = sc * radius;
    const double ss = dot(s, s), rr = rad * rad;
    if (ss <= rr) {
        e.lambda = 0;
        e.offset = s;
        return e;
    }
    // r's direction and length apart, each from r / max|r_i| (a subnormal |r| carries few bits).
    const double rm = max_abs(r);
    if (!(rm > 0)) return e;
    const Vec3 rn = r / rm;
    const double rn_len = std::sqrt(dot(rn, rn));
    const Vec3 u = (1 / rn_len) * rn;
    const double m = -dot(s, u);       // distance along u to the closest approach
    if (!(m > 0)) return e;            // moving away (and not inside)
    // The closest approach's offset, made square to u again: s + m u keeps eps |s| along u, which
    // exceeds the radius when a tiny ball lies far from the ray's start, and would tilt the entry
    // normal to follow the motion (found by fuzzing: radius 1e-15 at 4 units).
    Vec3 w = s + m * u;
    w -= dot(w, u) * u;
    const double ww = dot(w, w);
    if (ww > rr) return e;
    const double h = std::sqrt((rad - std::sqrt(ww)) * (rad + std::sqrt(ww)));
    const double along = (std::sqrt(ss) - rad) * (std::sqrt(ss) + rad) / (m + h);  // scaled distance
    const double lambda = ((along / sc) / rm) / rn_len;  // |r| = rm * rn_len
    if (!(lambda <= 1)) return e;
    e.lambda = lambda;
    e.offset = w - h * u;
    return e;
}

// The nearest point to t of a box, cylinder or cone (a point core's partner in a closed form),
// and the outward unit normal there toward t (zero inside).
inline Vec3 solid_nearest(const Shape& s, Vec3 t, Vec3& unit) {
    if (s.kind() == ShapeKind::Box) {
        const Vec3 p = box_nearest(static_cast<const BoxShape&>(s).half_extents, t);
        unit = safe_length(t - p) > 0 ? unit_of(t - p) : Vec3{};
        return p;
    }
    const Revolution v = revolution_of(s);
    return revolution_nearest(v.cone, v.radius, v.half_height, t, unit);
}

}  // namespace kairos::closed_form
