// SPDX-License-Identifier: MIT
// Rigidly placed shapes (shapes/shape.hpp, unwrap_rigid) where the placement could break them:
// line cores (capsules and segments) at scales 1e-150 to 1e90 and 1e8 of their size from the
// origin; boxes face to face, touching, 1e-12 to 1e-2 apart and overlapping, with parallel and
// nearly parallel faces; and placed balls carried by motions that turn, where the placement's
// offset makes the ball's centre move on an arc. Truths: the line cores' distance from their
// endpoints mapped in long double (closest segment points), the boxes' from the brute-force
// polytope oracle on the mapped vertices, the motions' first contact by conservative advancement
// on the exact ball/ball distance along the long double motion (motion_reference.hpp's LMotion).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "casts/cast.hpp"
#include "gjk/gjk.hpp"
#include "gjk/penetration.hpp"
#include "gjk_test_support.hpp"
#include "motion/motion_cast.hpp"
#include "oracle/motion_reference.hpp"
#include "rigid_placement_support.hpp"
#include "shapes/shape.hpp"

using namespace kairos;
using gjk_test::random_quat;
using gjk_test::random_unit;
using oracle::P3;
using oracle::Real;
using rigid_test::map;
using rigid_test::placement_rotation;

namespace {

Vec3 to_vec(P3 p) { return {double(p.x), double(p.y), double(p.z)}; }
Vec3 unit(Vec3 v) { return (1 / length(v)) * v; }
Vec3 unit_perpendicular(Vec3 v, std::mt19937_64& rng) {
    for (;;) {
        const Vec3 w = random_unit(rng);
        const Vec3 p = w - dot(w, v) * v;
        if (length(p) > 0.1) return unit(p);
    }
}
}  // namespace

// Placed capsules and segments (one of each pair placed twice over) at scales 1e-150 to 1e90 and
// 1 or 1e8 of their size from the origin, gaps from -0.99 of the radii through touching to 1e-12
// ... 1 of them, crossing, skew and parallel axes, both argument orders. The pair is built so the
// cores' closest points are interior, but the truth is recomputed from the mapped endpoints.
TEST(RigidPlacement, PlacedLineCoresAtExtremeScalesAndFarAway) {
    const uint64_t seed = 2811;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const double gaps[] = {-0.99, -0.5, -1e-6, 0, 1e-12, 1e-9, 1e-6, 1e-2, 0.3, 1};
    int cases = 0, failures = 0, overlapping = 0, parallel = 0;
    double worst = 0;
    for (double size : {1e-150, 1e-6, 1.0, 1e4, 1e90}) {
        for (double far : {1.0, 1e8}) {
            for (int i = 0; i < 120; ++i) {
                const double ha = size * (0.2 + std::fabs(u(rng))), hb = size * (0.2 + std::fabs(u(rng)));
                // Segments (radius 0) in a fifth of the cases on each side.
                const double ra = i % 5 == 1 ? 0 : size * (0.1 + std::fabs(u(rng)));
                const double rb = i % 5 == 2 ? 0 : size * (0.1 + std::fabs(u(rng)));
                CapsuleShape cap_a(ra, ha), cap_b(rb, hb);
                SegmentShape seg_a(ha), seg_b(hb);
                const Shape& child_a = ra > 0 ? static_cast<const Shape&>(cap_a) : seg_a;
                const Shape& child_b = rb > 0 ? static_cast<const Shape&>(cap_b) : seg_b;
                const Mat3 la = placement_rotation(rng, i % 3), lb = placement_rotation(rng, i / 3 % 3);
                const Vec3 oa = size * Vec3{u(rng), u(rng), u(rng)}, ob = size * Vec3{u(rng), u(rng), u(rng)};
                const Mat3 lb2 = placement_rotation(rng, 2);
                const Vec3 ob2 = size * Vec3{u(rng), u(rng), u(rng)};
                TransformedShape a(child_a, la, oa), inner(child_b, lb, ob), nested(inner, lb2, ob2);
                const bool nest = i % 2 == 1;
                const Shape& b = nest ? static_cast<const Shape&>(nested) : inner;
                const Mat3 lb_all = nest ? lb2 * lb : lb;        // B's child frame in B's frame
                const Vec3 ob_all = nest ? lb2 * ob + ob2 : ob;  // B's child centre in B's frame
                const Transform pa = make_transform(far * size * Vec3{u(rng), u(rng), u(rng)}, random_quat(rng));
                const Vec3 axis_a = unit(pa.rotation * (la * Vec3{0, 0, 1}));
                // B's rotation: random, or making its axis A's (parallel cores) in a quarter of the cases.
                const bool par = i % 4 == 0;
                const Mat3 rbm = par ? pa.rotation * la * transpose(lb_all) : to_matrix(random_quat(rng));
                const Vec3 axis_b = unit(rbm * (lb_all * Vec3{0, 0, 1}));
                const Vec3 c = cross(axis_a, axis_b);
                const Vec3 n = length(c) > 1e-3 ? unit(c) : unit_perpendicular(axis_a, rng);
                const double gap = gaps[i % 10] * (ra + rb + (ra + rb > 0 ? 0 : size));
                const Vec3 near_a = pa.apply(oa) + 0.8 * u(rng) * ha * axis_a;
                const Vec3 centre_b = near_a + (ra + rb + gap) * n + 0.8 * u(rng) * hb * axis_b;
                const Transform pb{rbm, centre_b - rbm * ob_all};
                // Truth from the doubles the queries see: the mapped endpoints, long double.
                P3 a0 = map(pa.rotation, map(la, {0, 0, -ha}, oa), pa.translation);
                P3 a1 = map(pa.rotation, map(la, {0, 0, ha}, oa), pa.translation);
                P3 b0 = nest ? map(lb2, map(lb, {0, 0, -hb}, ob), ob2) : map(lb, {0, 0, -hb}, ob);
                P3 b1 = nest ? map(lb2, map(lb, {0, 0, hb}, ob), ob2) : map(lb, {0, 0, hb}, ob);
                b0 = map(pb.rotation, b0, pb.translation);
                b1 = map(pb.rotation, b1, pb.translation);
                P3 ca, cb;
                cast_oracle::closest_segments(a0, a1, b0, b1, ca, cb);
                const Real cores = oracle::norm(cb - ca);
                const double truth = double(cores - Real(ra) - Real(rb));
                const double reach = ra + rb + ha + hb + max_abs(pa.translation) + max_abs(pb.translation);
                const double tol = 1e-13 * reach;
                ++cases;
                if (truth < 0) ++overlapping;
                if (par) ++parallel;
                auto fail = [&](const char* rule, double got) {
                    if (++failures <= 8)
                        ADD_FAILURE() << rule << ": got " << got << ", truth " << truth << " (tol " << tol << "); size "
                                      << size << " far " << far << " case " << i << " seed " << seed;
                };
                for (int order = 0; order < 2; ++order) {
                    const Shape& x = order == 0 ? static_cast<const Shape&>(a) : b;
                    const Shape& y = order == 0 ? b : static_cast<const Shape&>(a);
                    const Transform& px = order == 0 ? pa : pb;
                    const Transform& py = order == 0 ? pb : pa;
                    const DistanceResult s = signed_distance(x, px, y, py, 1e-10, 256);
                    worst = std::max(worst, std::fabs(s.distance - truth) / reach);
                    if (!(std::fabs(s.distance - truth) <= tol)) fail("signed distance", s.distance);
                    if (s.iterations != 1) fail("signed distance iterations", s.iterations);
                    if (cores > Real(1e-3) * Real(size)) {
                        const P3 toward = (Real(order == 0 ? 1 : -1) / cores) * (cb - ca);
                        const Real along =
                            Real(s.axis.x) * toward.x + Real(s.axis.y) * toward.y + Real(s.axis.z) * toward.z;
                        if (!(along > 1 - 1e-9L)) fail("signed distance axis . closest points", double(along));
                    }
                    const DistanceResult d = gjk_distance(x, px, y, py, 1e-10, 256);
                    if (!(std::fabs(d.distance - std::fmax(truth, 0.0)) <= tol)) fail("distance", d.distance);
                    Vec3 sep{};
                    const bool hit = gjk_intersect(x, px, y, py, sep, nullptr);
                    if (std::fabs(truth) > tol && hit != (truth < 0)) fail("intersect", hit);
                    // Moving y along the cores' closest-point line closes the gap at half the step.
                    if (truth > tol && cores > 0) {
                        const Real sign = order == 0 ? 1 : -1;
                        const Vec3 step = to_vec((-2 * sign * Real(truth) / cores) * (cb - ca));
                        const CastResult r = shape_cast(x, px, {}, y, py, step, 1e-10, 256);
                        // Within the cast's contact distance, its tolerance of the size: a gap of
                        // 1e-12 of 1e-150 squares to zero, and a hit at 0 is then within it.
                        const double off = std::fabs(r.toi - 0.5) * length(step);
                        if (!r.hit || !(off <= tol + 1e-10 * (ra + rb + ha + hb)))
                            fail("shape cast toi", r.hit ? r.toi : -1);
                    }
                }
            }
        }
    }
    std::printf(
        "placed line cores: %d cases, %d overlapping, %d parallel, worst signed distance error %.3g of the "
        "reach\n",
        cases, overlapping, parallel, worst);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(overlapping, cases / 5) << "seed " << seed;
    EXPECT_LT(overlapping, cases * 3 / 5) << "seed " << seed;
}

// Placed boxes face to face: B's placed frame is A's, turned by 0, 1e-9 or 1e-6 about a random
// axis (parallel and nearly parallel faces), its face at a gap from -1e-2 to 1e-2 of the size,
// touching, or 1e-12 to 1e-6 apart, shifted sideways within the faces; 1 or 1e4 of the size from the
// origin; both argument orders. Truth: the polytope oracle on the vertices mapped in long double.
TEST(RigidPlacement, PlacedBoxesFaceToFace) {
    const uint64_t seed = 2812;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const double gaps[] = {-1e-2, -1e-6, -1e-12, 0, 1e-12, 1e-9, 1e-6, 1e-2};
    int cases = 0, failures = 0, overlapping = 0;
    double worst_distance = 0, worst_depth = 0;
    for (double far : {1.0, 1e4}) {
        for (int i = 0; i < 240; ++i) {
            const Vec3 ha{0.2 + std::fabs(u(rng)), 0.2 + std::fabs(u(rng)), 0.2 + std::fabs(u(rng))};
            const Vec3 hb{0.2 + std::fabs(u(rng)), 0.2 + std::fabs(u(rng)), 0.2 + std::fabs(u(rng))};
            BoxShape box_a(ha), box_b(hb);
            const Mat3 la = placement_rotation(rng, i % 3), lb = placement_rotation(rng, i / 3 % 3);
            const Vec3 oa{u(rng), u(rng), u(rng)}, ob{u(rng), u(rng), u(rng)};
            TransformedShape a(box_a, la, oa), b(box_b, lb, ob);
            const Transform pa = make_transform(far * Vec3{u(rng), u(rng), u(rng)}, random_quat(rng));
            const Mat3 frame_a = pa.rotation * la;  // A's box axes in the world (columns)
            const double tilt = i % 8 < 4 ? 0 : i % 8 < 6 ? 1e-9 : 1e-6;
            const Mat3 turn = to_matrix(axis_angle(random_unit(rng), tilt));
            const Mat3 rbm = turn * frame_a * transpose(lb);
            const int k = i % 3;
            const double side = i % 2 == 0 ? 1 : -1;
            const Vec3 e_k = k == 0 ? Vec3{1, 0, 0} : k == 1 ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
            const Vec3 normal = side * (frame_a * e_k);
            const double gap = gaps[i / 3 % 8];
            const double half_a[3] = {ha.x, ha.y, ha.z}, half_b[3] = {hb.x, hb.y, hb.z};
            // Shifted sideways by up to 0.4 of the smaller box's extent along the face's other axes.
            Vec3 lateral{};
            for (int j = 0; j < 3; ++j)
                if (j != k) {
                    const Vec3 e_j = j == 0 ? Vec3{1, 0, 0} : j == 1 ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
                    lateral = lateral + 0.4 * u(rng) * std::min(half_a[j], half_b[j]) * (frame_a * e_j);
                }
            const Vec3 centre_b = pa.apply(oa) + (half_a[k] + half_b[k] + gap) * normal + lateral;
            const Transform pb{rbm, centre_b - rbm * ob};
            std::vector<P3> va, vb;
            for (const auto& v : gjk_test::box_vertices(ha))
                va.push_back(map(pa.rotation, map(la, {v[0], v[1], v[2]}, oa), pa.translation));
            for (const auto& v : gjk_test::box_vertices(hb))
                vb.push_back(map(pb.rotation, map(lb, {v[0], v[1], v[2]}, ob), pb.translation));
            const oracle::Result o = oracle::distance(oracle::make_polytope(va), oracle::make_polytope(vb));
            const double truth = o.intersecting ? -double(o.depth) : double(o.distance);
            // Rounding of the placed vertices' coordinates: a few units in the last place of them.
            const double tol = 1e-15 * (4 + max_abs(pa.translation) + max_abs(pb.translation)) * 16;
            ++cases;
            if (o.intersecting) ++overlapping;
            auto fail = [&](const char* rule, double got) {
                if (++failures <= 8)
                    ADD_FAILURE() << rule << ": got " << got << ", truth " << truth << " (gap " << gap << ", tilt "
                                  << tilt << ", tol " << tol << "); far " << far << " case " << i << " seed " << seed;
            };
            for (int order = 0; order < 2; ++order) {
                const Shape& x = order == 0 ? a : b;
                const Shape& y = order == 0 ? b : a;
                const Transform& px = order == 0 ? pa : pb;
                const Transform& py = order == 0 ? pb : pa;
                const DistanceResult d = gjk_distance(x, px, y, py, 1e-12, 256);
                const double err = std::fabs(d.distance - std::fmax(truth, 0.0));
                if (!o.intersecting) worst_distance = std::max(worst_distance, err);
                if (!(err <= tol)) fail("distance", d.distance);
                const DistanceResult s = signed_distance(x, px, y, py, 1e-12, 256);
                const double serr = std::fabs(s.distance - truth);
                if (o.intersecting) worst_depth = std::max(worst_depth, serr);
                if (!(serr <= tol)) fail("signed distance", s.distance);
                // The axis: the face normal (from x toward y), to the tilt.
                const double along = dot(s.axis, order == 0 ? normal : -1.0 * normal);
                if (!(along > 1 - 1e-9)) fail("signed distance axis . face normal", along);
                Vec3 sep{};
                const bool hit = gjk_intersect(x, px, y, py, sep, nullptr);
                if (std::fabs(truth) > tol && hit != (truth < 0)) fail("intersect", hit);
            }
        }
    }
    std::printf("placed boxes face to face: %d cases, %d overlapping, worst distance error %.3g, depth %.3g\n", cases,
                overlapping, worst_distance, worst_depth);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(overlapping, cases / 4) << "seed " << seed;
    EXPECT_LT(overlapping, cases * 3 / 4) << "seed " << seed;
}

// Placed balls carried by motions that translate and turn (0, 0.3, 2 radians and nearly pi per
// step about random axes): the placement's offset moves the ball's centre on an arc, which only a
// correct composition of placement and motion follows. B is a placed ball that only translates.
// Truth: conservative advancement on the exact centre distance along LMotion in long double, with
// half steps, so the reference's first contact is proven and a miss's clearance is at least half
// the smallest distance sampled. Sizes 1e-3 to 1e3.
TEST(RigidPlacement, PlacedBallsOnTurningMotions) {
    const uint64_t seed = 2813;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const double tolerance = 1e-6;
    int cases = 0, failures = 0, hits = 0, checked_misses = 0;
    double worst_late = 0;
    for (double size : {1e-3, 1.0, 1e3}) {
        for (int i = 0; i < 160; ++i) {
            const double ra = size * (0.2 + std::fabs(u(rng))), rb = size * (0.2 + std::fabs(u(rng)));
            SphereShape ball_a(ra), ball_b(rb);
            const Mat3 la = placement_rotation(rng, i % 3), lb = placement_rotation(rng, 2);
            const Vec3 oa = 2 * size * Vec3{u(rng), u(rng), u(rng)}, ob = size * Vec3{u(rng), u(rng), u(rng)};
            TransformedShape a(ball_a, la, oa), b(ball_b, lb, ob);
            const double angles[] = {0, 0.3, 2.0, 3.14};
            const double angle = angles[i % 4];
            const Quat q0 = random_quat(rng);
            const Quat q1 = normalized(axis_angle(random_unit(rng), angle) * q0);
            const Vec3 p0 = size * Vec3{u(rng), u(rng), u(rng)};
            // A's ball centre starts 0.5 to 3 sizes away from B's and heads roughly toward it.
            const Vec3 ca0 = p0 + to_matrix(q0) * oa;
            const Vec3 cb0 = ca0 + (ra + rb) * (1.1 + 2 * std::fabs(u(rng))) * random_unit(rng);
            const Vec3 p1 = p0 + 2.5 * (cb0 - ca0) + size * Vec3{u(rng), u(rng), u(rng)};
            const Quat qb = random_quat(rng);
            const Vec3 pb0 = cb0 - to_matrix(qb) * ob;
            const Vec3 pb1 = pb0 + 0.3 * size * Vec3{u(rng), u(rng), u(rng)};
            const Motion ma(Pose{p0, q0}, Pose{p1, q1}), mb(Pose{pb0, qb}, Pose{pb1, qb});
            const CastResult r = motion_cast(a, ma, b, mb, tolerance, 256);
            // The reference, in long double.
            const motion_ref::LMotion la_m(Pose{p0, q0}, Pose{p1, q1}), lb_m(Pose{pb0, qb}, Pose{pb1, qb});
            auto centre = [](const motion_ref::LMotion& m, Vec3 o, Real t) {
                cast_oracle::Body body;
                m.place(body, t);
                return P3{body.R[0] * o.x + body.R[1] * o.y + body.R[2] * o.z + body.t.x,
                          body.R[3] * o.x + body.R[4] * o.y + body.R[5] * o.z + body.t.y,
                          body.R[6] * o.x + body.R[7] * o.y + body.R[8] * o.z + body.t.z};
            };
            const Vec3 ob_frame = ob;  // lb * 0 + ob: the ball's centre in B's frame
            auto dist = [&](Real t) {
                return oracle::norm(centre(lb_m, ob_frame, t) - centre(la_m, oa, t)) - Real(ra) - Real(rb);
            };
            const Real speed =
                oracle::norm(la_m.p1 - la_m.p0) + la_m.angle * Real(length(oa)) + oracle::norm(lb_m.p1 - lb_m.p0);
            Real t = 0, smallest = dist(0);
            bool contact = false;
            for (int step = 0; step < 1000000 && t <= 1; ++step) {
                const Real d = dist(t);
                smallest = std::min(smallest, d);
                if (d <= Real(1e-12) * Real(size)) {
                    contact = true;
                    break;
                }
                t += d / (2 * speed);
            }
            ++cases;
            const double delta = tolerance * std::min(ra + length(oa), rb + length(ob));
            auto fail = [&](const char* rule, double got) {
                if (++failures <= 8)
                    ADD_FAILURE() << rule << ": got " << got << ", reference " << double(t) << " (contact " << contact
                                  << ", smallest " << double(smallest) << "); size " << size << " angle " << angle
                                  << " case " << i << " seed " << seed;
            };
            if (contact) {
                ++hits;
                if (!r.hit) {
                    fail("missed", -1);
                    continue;
                }
                worst_late = std::max(worst_late, (r.toi - double(t)) * double(speed) / size);
                // Never later than the contact (to the reference's own 1e-12 of the size), and at
                // the answer the true distance is within the contact distance.
                if (!(r.toi <= double(t) + 1e-9)) fail("late", r.toi);
                if (!(double(dist(Real(r.toi))) <= 2 * delta + 1e-9 * size)) fail("apart at toi", r.toi);
            } else if (smallest / 2 > Real(4 * delta)) {
                ++checked_misses;
                if (r.hit) fail("false hit", r.toi);
            }
        }
    }
    std::printf(
        "placed balls on turning motions: %d cases, %d hits, %d clear misses, worst lateness %.3g of the "
        "size\n",
        cases, hits, checked_misses, worst_late);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(hits, cases / 4) << "seed " << seed;
    EXPECT_GT(checked_misses, cases / 8) << "seed " << seed;
}
