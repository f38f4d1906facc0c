// SPDX-License-Identifier: MIT
// Extreme radius about an axis (see radius.hpp).
//
// The radius is R = max over unit w perpendicular to the axis of the support function
// h(w) = w . s(w): the farthest point's distance from the axis is its largest component along
// such a w. Distance from a line is convex in x, so over a polytope its maximum is at a vertex,
// and over a cylinder or cone at a point of a rim circle (or the apex).
#include "shapes/radius.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kairos {
namespace {

// Squared distance of x from the line through the origin along unit u, without cancellation
// trouble for points near the axis: the squared length of the rejection x - (x.u) u. Maxima are
// taken over it and rooted once (the square root is monotone: the same result bit for bit).
double squared_distance_from_axis(Vec3 x, Vec3 u) {
    const Vec3 off = x - dot(x, u) * u;
    return dot(off, off);
}

// The larger distance from the axis of the two rim circles of radius r at heights +-h (axis
// z). For a rim point p, |p|^2 = r^2 + h^2 and p.u = r s cos(theta - phi) +- h u_z with
// s = |u_xy|, so the smallest |p.u| over the rim is max(0, h |u_z| - r s).
double rim_radius(double r, double h, Vec3 u) {
    const double s = std::hypot(u.x, u.y);
    const double nearest = std::max(0.0, h * std::fabs(u.z) - r * s);
    return std::sqrt(std::max(0.0, r * r + h * h - nearest * nearest));
}

// Upper bound from K support samples in the plane perpendicular to u (docs/algorithms.md §4): the
// farthest point p* of the shape's projection lies within pi/K of some sample w_k, and
// h(w_k) >= w_k . p* >= R cos(pi/K).
double sampled_radius(const Shape& s, Vec3 u) {
    // An orthonormal pair (e1, e2) spanning the plane perpendicular to u.
    const Vec3 helper = std::fabs(u.x) < 0.57 ? Vec3{1, 0, 0} : (std::fabs(u.y) < 0.57 ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    const Vec3 e1 = normalized_or(cross(u, helper), {1, 0, 0});
    const Vec3 e2 = cross(u, e1);
    double best = 0;
    for (int k = 0; k < kRadiusSamples; ++k) {
        const double angle = 2 * std::numbers::pi * k / kRadiusSamples;
        const Vec3 w = std::cos(angle) * e1 + std::sin(angle) * e2;
        best = std::max(best, dot(w, support(s, w)));
    }
    // Rounding in the samples is far below the 0.12 % slack; add a relative ulp-scale margin.
    return best / std::cos(std::numbers::pi / kRadiusSamples) * (1 + 1e-12);
}

}  // namespace

double extreme_radius(const Shape& s, Vec3 u) {
    u = normalized_or(u, {0, 0, 1});
    switch (s.kind()) {
        case ShapeKind::Point:
            return 0;
        case ShapeKind::Segment:
            return static_cast<const SegmentShape&>(s).half_length * std::hypot(u.x, u.y);
        case ShapeKind::Sphere:
            return static_cast<const SphereShape&>(s).radius;
        case ShapeKind::Box: {
            // Opposite corners lie equally far from an axis through the centre (negation is
            // exact, so bit for bit): four corners, and one square root for the largest.
            const Vec3 h = static_cast<const BoxShape&>(s).half_extents;
            double best = 0;
            for (int corner = 0; corner < 4; ++corner) {
                const Vec3 c{corner & 1 ? h.x : -h.x, corner & 2 ? h.y : -h.y, h.z};
                best = std::max(best, squared_distance_from_axis(c, u));
            }
            return std::sqrt(best);
        }
        case ShapeKind::Capsule: {
            const auto& c = static_cast<const CapsuleShape&>(s);
            return c.half_height * std::hypot(u.x, u.y) + c.radius;
        }
        case ShapeKind::Cylinder: {
            const auto& c = static_cast<const CylinderShape&>(s);
            return rim_radius(c.radius, c.half_height, u);
        }
        case ShapeKind::Cone: {
            const auto& c = static_cast<const ConeShape&>(s);
            return std::max(c.half_height * std::hypot(u.x, u.y), rim_radius(c.radius, c.half_height, u));
        }
        case ShapeKind::ConvexHull: {
            double best = 0;
            for (const Vec3& v : static_cast<const ConvexHullShape&>(s).vertices)
                best = std::max(best, squared_distance_from_axis(v, u));
            return std::sqrt(best);
        }
        case ShapeKind::HullOfTwo: {
            const auto& h = static_cast<const HullOfTwoShape&>(s);
            return std::max(extreme_radius(*h.a, u), extreme_radius(*h.b, u));
        }
        case ShapeKind::MinkowskiSum: {
            // Both the triangle inequality and the sampled bound are upper bounds: keep the tighter.
            const auto& m = static_cast<const MinkowskiSumShape&>(s);
            return std::min(extreme_radius(*m.a, u) + extreme_radius(*m.b, u), sampled_radius(s, u));
        }
        case ShapeKind::Transformed:
            return sampled_radius(s, u);
        case ShapeKind::Disk:
            // The rim circle always has a point whose component along u is 0: its distance R.
            return static_cast<const DiskShape&>(s).radius;
    }
    return sampled_radius(s, u);
}

}  // namespace kairos
