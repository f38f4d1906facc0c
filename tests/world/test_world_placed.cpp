// SPDX-License-Identifier: MIT
// A world of placed balls: each object is a ball wrapped by a rigid placement (a rotation and an
// offset, some placed twice over), so its centre sits off the object's origin and moves on an arc
// when the object turns. The world must find every pair's first contact as the balls' own: its
// contacts against a reference computed here for every pair, by conservative advancement on the
// exact centre distance along the long double motions (motion_reference.hpp's LMotion), with half
// steps so that a reference miss also proves the clearance. Translating and turning objects,
// pairs overlapping at the start, three steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include "math/math.hpp"
#include "oracle/motion_reference.hpp"
#include "scene_rng.hpp"
#include "shapes/shape.hpp"
#include "world/world.hpp"

namespace kairos {
namespace {

using cast_oracle::P3;
using cast_oracle::Real;

struct Release {
    void operator()(const Shape* s) const {
        if (s) s->release();
    }
};
using Owned = std::unique_ptr<const Shape, Release>;

struct PlacedBall {
    Owned shape;        // the placement the world holds
    double radius = 0;  // the ball's
    Vec3 centre;        // the ball's centre in the object's frame
    double reach = 0;   // bounding radius about the object's origin
    Pose pose;
    uint64_t id = 0;
};

Quat random_rotation(scene::Rng& rng) {
    return normalized(Quat{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
}

// The ball's centre at time t of motion m, in long double.
P3 centre_at(const motion_ref::LMotion& m, Vec3 c, Real t) {
    cast_oracle::Body body;
    m.place(body, t);
    return {body.R[0] * c.x + body.R[1] * c.y + body.R[2] * c.z + body.t.x,
            body.R[3] * c.x + body.R[4] * c.y + body.R[5] * c.z + body.t.y,
            body.R[6] * c.x + body.R[7] * c.y + body.R[8] * c.z + body.t.z};
}

}  // namespace

TEST(WorldPlaced, PlacedBallsMeetAsBalls) {
    const uint64_t seed = 2831;
    scene::Rng rng(seed);
    World world;
    std::vector<PlacedBall> balls;
    std::vector<Owned> inner;  // the first placements of the nested ones
    for (int i = 0; i < 64; ++i) {
        PlacedBall b;
        b.radius = rng.uniform(0.2, 0.6);
        Owned ball(new SphereShape(b.radius));
        const Mat3 l = to_matrix(random_rotation(rng));
        const Vec3 o = rng.in_cube(0.5);
        if (i % 3 == 2) {  // placed twice over
            Owned first(new TransformedShape(*ball, l, o));
            const Mat3 l2 = to_matrix(random_rotation(rng));
            const Vec3 o2 = rng.in_cube(0.5);
            b.shape = Owned(new TransformedShape(*first, l2, o2));
            b.centre = l2 * o + o2;
            inner.push_back(std::move(first));
        } else {
            b.shape = Owned(new TransformedShape(*ball, l, o));
            b.centre = o;
        }
        b.reach = length(b.centre) + b.radius;
        b.pose = {rng.in_cube(2.5), random_rotation(rng)};
        b.id = world.add(*b.shape, b.pose, static_cast<uint64_t>(i));
        balls.push_back(std::move(b));
    }
    int pairs_hit = 0, pairs_clear = 0, turning = 0, at_start = 0, failures = 0;
    double worst_early = 0;
    auto fail = [&](const std::string& what) {
        if (++failures <= 10) ADD_FAILURE() << what << " (seed " << seed << ")";
    };
    for (int step = 0; step < 3; ++step) {
        std::vector<Pose> ends;
        for (std::size_t i = 0; i < balls.size(); ++i) {
            Pose e = balls[i].pose;
            e.position = e.position + rng.on_sphere(rng.uniform(1, 4));
            if (i % 2 == 1)
                e.orientation = normalized(axis_angle(rng.on_sphere(1), rng.uniform(0.2, 3.0)) * e.orientation);
            ends.push_back(e);
            ASSERT_TRUE(world.move(balls[i].id, e));
        }
        world.step();
        const std::vector<Contact>& contacts = world.contacts();
        for (std::size_t i = 0; i < balls.size(); ++i) {
            for (std::size_t j = i + 1; j < balls.size(); ++j) {
                const PlacedBall &a = balls[i], &b = balls[j];
                const motion_ref::LMotion ma(a.pose, ends[i]), mb(b.pose, ends[j]);
                auto dist = [&](Real t) {
                    return oracle::norm(centre_at(mb, b.centre, t) - centre_at(ma, a.centre, t)) - Real(a.radius) -
                           Real(b.radius);
                };
                const Real speed = oracle::norm(ma.p1 - ma.p0) + ma.angle * Real(length(a.centre)) +
                                   oracle::norm(mb.p1 - mb.p0) + mb.angle * Real(length(b.centre));
                Real t = 0, smallest = dist(0);
                bool contact = false;
                for (int k = 0; k < 1000000 && t <= 1; ++k) {
                    const Real d = dist(t);
                    smallest = std::min(smallest, d);
                    if (d <= Real(1e-12)) {
                        contact = true;
                        break;
                    }
                    t += d / (2 * speed);
                }
                const uint64_t lo = std::min(a.id, b.id), hi = std::max(a.id, b.id);
                const Contact* c = nullptr;
                for (const Contact& x : contacts)
                    if (x.a == lo && x.b == hi) c = &x;
                char where[96];
                std::snprintf(where, sizeof where, "step %d pair %zu, %zu", step, i, j);
                // The world's contact distance: its tolerance (1e-10) of the smaller bounding radius.
                const double delta = 1e-10 * std::min(a.reach, b.reach);
                if (contact) {
                    ++pairs_hit;
                    if (ma.angle > 0 || mb.angle > 0) ++turning;
                    if (t == 0) ++at_start;
                    if (c == nullptr) {
                        fail(std::string("no contact where the balls meet at t = ") + std::to_string(double(t)) + ": " +
                             where);
                        continue;
                    }
                    worst_early = std::max(worst_early, double(t) - c->toi);
                    if (!(c->toi <= double(t) + 1e-9)) fail("contact late: " + std::string(where));
                    if (!(double(dist(Real(c->toi))) <= 2 * delta + 1e-9)) fail("apart at toi: " + std::string(where));
                    if (t > 0) {  // the normal from a toward b: along the centres' line at toi
                        const bool a_first = a.id == lo;
                        const P3 ca = centre_at(ma, a.centre, Real(c->toi)), cb = centre_at(mb, b.centre, Real(c->toi));
                        const P3 line = (a_first ? Real(1) : Real(-1)) * (cb - ca);
                        const Real along =
                            (Real(c->normal.x) * line.x + Real(c->normal.y) * line.y + Real(c->normal.z) * line.z) /
                            oracle::norm(line);
                        if (!(along > 1 - 1e-6L)) fail("normal off the centres' line: " + std::string(where));
                    }
                } else if (smallest / 2 > Real(1e-8)) {
                    ++pairs_clear;
                    if (c != nullptr) fail("contact where the balls stay apart: " + std::string(where));
                }
            }
        }
        for (std::size_t i = 0; i < balls.size(); ++i) balls[i].pose = ends[i];
    }
    std::printf(
        "placed balls in a world: %d pairs meet (%d turning, %d at the start), %d stay clear, the contact "
        "earliest by %.3g of the step\n",
        pairs_hit, turning, at_start, pairs_clear, worst_early);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(pairs_hit, 100) << "seed " << seed;
    EXPECT_GT(turning, 40) << "seed " << seed;
    EXPECT_GT(at_start, 5) << "seed " << seed;
    EXPECT_GT(pairs_clear, 1000) << "seed " << seed;
}

}  // namespace kairos
