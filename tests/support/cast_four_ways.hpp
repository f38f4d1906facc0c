// SPDX-License-Identifier: MIT
// A ball (or a point) cast onto a shape with a closed form, seen four ways (tests of the closed
// forms, tests/casts/test_box_cast.cpp and test_capsule_cast.cpp): shape_cast in one order and
// swapped, the GJK cast of the same shapes built so that no closed form takes them, and the ball's
// centre as a ray against the shape grown by the ball's radius. GoogleTest assertions.
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "cast_test_support.hpp"

namespace cast_test {

// The angle between two directions, accurate near 0 (acos of the cosine is not below 1e-8).
inline double angle_between(kairos::Vec3 a, kairos::Vec3 b) {
    return std::atan2(kairos::length(kairos::cross(a, b)), kairos::dot(a, b));
}

// A pair's size, its relative motion's length, the rounding of its coordinates (1e-15 of the base's
// distance from the origin and the size) and a closed form's time slack at tolerance tol: tol of the
// size plus 8 roundings, over the motion.
struct PairSlack {
    double size, rlen, round_off, toi;
};
inline PairSlack slack_of(const Body& a, const Body& b, const Cast& c, kairos::Vec3 base, double tol) {
    PairSlack s;
    s.size = static_cast<double>(cast_oracle::size_of(a, b));
    s.rlen = kairos::length(c.tb - c.ta);
    s.round_off = 1e-15 * (kairos::length(base) + s.size);
    s.toi = (tol * s.size + 8 * s.round_off) / s.rlen;
    return s;
}

struct FourWays {
    kairos::CastResult r;    // shape_cast(shape, ball)
    kairos::CastResult s;    // shape_cast(ball, shape)
    kairos::CastResult g;    // the GJK cast of the same pair
    kairos::CastResult ray;  // the ball's centre against the grown shape
};

// Each verdict is the oracle's; on a hit each time is within toi_slack of the oracle's (the GJK
// cast's within gjk_slack), the swapped order's normal opposite, and when the oracle has a normal
// and check_normal is set, r's and the ray's within 1e-6 rad of it. Returns r's angle to the
// oracle's normal (0 when not compared).
inline double expect_four_ways_agree(const FourWays& f, const cast_oracle::Truth& t, double toi_slack, double gjk_slack,
                                     bool check_normal, const char* what) {
    EXPECT_EQ(f.r.hit, t.hit) << what;
    EXPECT_EQ(f.s.hit, t.hit) << what << ": the swapped order";
    EXPECT_EQ(f.g.hit, t.hit) << what << ": the GJK cast";
    EXPECT_EQ(f.ray.hit, t.hit) << what << ": the ray";
    if (!t.hit || !f.r.hit) return 0;
    const double truth = static_cast<double>(t.toi);
    EXPECT_NEAR(f.r.toi, truth, toi_slack) << what;
    EXPECT_NEAR(f.s.toi, truth, toi_slack) << what << ": the swapped order";
    EXPECT_NEAR(f.g.toi, truth, gjk_slack) << what << ": the GJK cast";
    EXPECT_NEAR(f.ray.toi, truth, toi_slack) << what << ": the ray";
    EXPECT_LE(kairos::length(f.r.normal + f.s.normal), 1e-9) << what << ": the swapped order's normal";
    const kairos::Vec3 tn{static_cast<double>(t.normal.x), static_cast<double>(t.normal.y),
                          static_cast<double>(t.normal.z)};
    if (!(kairos::length(tn) > 0.5) || !check_normal) return 0;  // the oracle gives none when ambiguous
    EXPECT_LE(angle_between(f.r.normal, tn), 1e-6) << what;
    EXPECT_LE(angle_between(f.ray.normal, tn), 1e-6) << what << ": the ray's normal";
    return angle_between(f.r.normal, tn);
}

}  // namespace cast_test
