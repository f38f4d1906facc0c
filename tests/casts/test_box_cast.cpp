// SPDX-License-Identifier: MIT
// The box/box shape cast's closed form (casts/box_cast.hpp, the separating axis test over the
// step) against truths it does not share: the GJK cast on the same boxes given as hulls of their
// corners (another algorithm), constructed contacts whose time is known (a face onto a face, flat
// or tilted by 1e-12 to 1e-3 rad, an edge onto an edge, crossing or nearly parallel), and the long double oracle. Gaps at the start
// from 1e-13 to 1e-1 of the size, twists from 0 to 0.5 rad, edges from parallel to crossing (the
// band the closed form leaves to GJK, 1e-14 to 1e-3 rad, and both sides of it), sizes 1e-3 to
// 1e3, up to 1e5 sizes from the origin, both argument orders.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <random>
#include <utility>
#include <vector>

#include "cast_four_ways.hpp"
#include "cast_test_support.hpp"
#include "casts/box_cast.hpp"
#include "casts/cast.hpp"
#include "gjk/closed_forms.hpp"
#include "gjk/support_kernels.hpp"
#include "shapes/shape.hpp"

using namespace kairos;
using namespace cast_test;

namespace {

constexpr uint32_t kMaxIt = 256;
constexpr double kTol = 1e-10;

// The same box as the hull of its eight corners: shape_cast takes the GJK path for it.
ShapePtr box_as_hull(Vec3 h) {
    std::vector<Vec3> p;
    for (int k = 0; k < 8; ++k) p.push_back({(k & 1) ? h.x : -h.x, (k & 2) ? h.y : -h.y, (k & 4) ? h.z : -h.z});
    return hull_shape(p);
}

// Whether the closed form answers this cast itself (shape_cast's own call).
bool closed_form_answers(Vec3 ha, const Transform& pa, Vec3 ta, Vec3 hb, const Transform& pb, Vec3 tb) {
    const kernels::RelativeFrame f = kernels::relative_frame(pa, pb);
    return cast_detail::box_box_cast(ha, hb, f.r, f.t, pa.to_local_direction(tb - ta), kTol).verdict !=
           cast_detail::BoxCast::Verdict::Declined;
}

Vec3 rotate(Quat q, Vec3 v) { return to_matrix(q) * v; }

// A box's body for the oracle, placed.
Solid placed_box(Vec3 h, const Transform& pose) {
    Solid s = make_solid(Kind::Box, 0, 0, h);
    place(s.body, pose);
    return s;
}

// The checks every cast of two boxes gets, in both argument orders: the verdict, the time within
// `toi_slack` of `truth` and never later, the normal's plane a support plane of M at the true hit
// (the judge's normal gap), the point on both boxes at toi, the swapped order's mirror answer,
// and the same verdict and time as the GJK cast on the boxes as hulls. Returns the cast.
// A random cast of a onto b (B aimed at A, about half of them hitting), both bodies placed, and
// the oracle's truth; `usable` is false for a graze or an overlap at the start (not judged here).
struct Placed {
    Cast cast;
    cast_oracle::Truth truth;
    bool usable = false;
};
Placed place_random(std::mt19937_64& rng, Solid& a, Solid& b, Vec3 base) {
    Placed p{random_cast(rng, a, b, base), {}, false};
    place(a.body, p.cast.pa);
    place(b.body, p.cast.pb);
    p.truth = cast_oracle::toi(a.body, b.body, p3(p.cast.ta), p3(p.cast.tb));
    p.usable = !p.truth.grazing && !p.truth.start_overlap;
    return p;
}

// unique_normal: the contact has one normal (not two parallel edges, whose normals fill a cone:
// each order may then give another). The point is held to point_slack of the size when the closed
// form answers; the GJK cast's (what it declines) is returned for the caller to judge.
struct Checked {
    CastResult r;
    bool closed_form = false;
    double point_error = 0;  // of the first order's point, relative to the size
};
Checked check_pair(const char* what, Vec3 ha, const Transform& pa, Vec3 ta, Vec3 hb, const Transform& pb, Vec3 tb,
                   bool truth_hit, double truth_toi, double toi_slack, double point_slack, bool unique_normal = true) {
    const BoxShape a(ha), b(hb);
    Checked out;
    out.closed_form = closed_form_answers(ha, pa, ta, hb, pb, tb);
    const CastResult r = shape_cast(a, pa, ta, b, pb, tb, kTol, kMaxIt);
    const CastResult s = shape_cast(b, pb, tb, a, pa, ta, kTol, kMaxIt);
    out.r = r;
    const ShapePtr ha_hull = box_as_hull(ha), hb_hull = box_as_hull(hb);
    const CastResult g = shape_cast(*ha_hull, pa, ta, *hb_hull, pb, tb, kTol, kMaxIt);
    EXPECT_EQ(r.hit, truth_hit) << what << " (the hulls: " << g.hit << " " << g.toi << ", swapped: " << s.hit << ")";
    EXPECT_EQ(s.hit, r.hit) << what << ": the swapped order";
    EXPECT_EQ(g.hit, r.hit) << what << ": the GJK cast of the hulls";
    if (!r.hit || !truth_hit) return out;
    EXPECT_LE(r.toi, truth_toi + toi_slack) << what;
    EXPECT_GE(r.toi, truth_toi - toi_slack) << what;
    EXPECT_NEAR(s.toi, r.toi, toi_slack) << what << ": the swapped order";
    EXPECT_NEAR(g.toi, r.toi, 2 * toi_slack) << what << ": the GJK cast of the hulls";
    EXPECT_NEAR(length(r.normal), 1, 1e-12) << what;
    if (r.toi > 0) {
        if (unique_normal) {
            EXPECT_LE(length(r.normal + s.normal), 1e-9) << what << ": the swapped order's normal";
        }
        // The normal's plane separates the boxes at the true time: h_M(n) - n . (toi r) ~ 0.
        const Solid sa = placed_box(ha, pa), sb = placed_box(hb, pb);
        const double gap = static_cast<double>(cast_oracle::support_m(sa.body, sb.body, p3(r.normal)) -
                                               Real(truth_toi) * cast_oracle::dot(p3(r.normal), p3(tb - ta)));
        const double size = static_cast<double>(cast_oracle::size_of(sa.body, sb.body));
        EXPECT_LE(std::fabs(gap), point_slack * size) << what << ": the normal's plane at the true time";
        const double pg = static_cast<double>(point_gap(sa.body, sb.body, p3(ta), p3(tb), r.toi, p3(r.point)));
        const double ps = static_cast<double>(point_gap(sa.body, sb.body, p3(ta), p3(tb), s.toi, p3(s.point)));
        out.point_error = pg / size;
        if (out.closed_form) {
            EXPECT_LE(pg, point_slack * size) << what << ": the point off the boxes at toi";
            EXPECT_LE(ps, point_slack * size) << what << ": the swapped order's point";
        }
    }
    return out;
}

// The casts of a constructed family: how many, how many the closed form answered, and the worst
// point of the GJK cast on the rest (relative to the size), held to `gjk_bound` at the end.
struct Tally {
    int cases = 0, closed = 0;
    double gjk_point = 0;
    void add(const Checked& c) {
        ++cases;
        closed += c.closed_form;
        if (!c.closed_form) gjk_point = std::fmax(gjk_point, c.point_error);
    }
    void report(const char* family, double gjk_bound) const {
        std::printf("[%s] %d casts, %d by the closed form; the GJK cast's points off by up to %.2g of the size\n",
                    family, cases, closed, gjk_point);
        EXPECT_LE(gjk_point, gjk_bound) << family;
    }
};

// B falls onto A, closing `gap` of the size at lambda: the time's slack is the tolerance's share
// of the size plus the positions' rounding (eps of the distance from the origin), over the
// closing speed; the point's is 1e-9 of the size plus that rounding.
struct Slack {
    double toi, point;
};
Slack falling_slack(double gap, double size, double lambda, Vec3 base) {
    const double speed = gap * size / lambda, rounding = 1e-15 * (length(base) + size);
    return {(kTol * size + 8 * rounding) / speed, 1e-9 + 100 * rounding / size};
}

}  // namespace

// A face falling onto a face: B above A's top face (both turned by one random rotation, B also
// twisted about the face normal), the footprints overlapping, the gap g of the size closed at a
// chosen lambda* with a sideways drift. The contact time is lambda*, the normal A's face normal.
TEST(BoxCast, FaceOntoFaceAtEveryGapAndTwist) {
    const uint64_t seed = 24001;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Tally tally;
    for (double scale : {1e-3, 1.0, 1e3}) {
        for (double far : {0.0, 1e5}) {
            for (double gap : {1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3, 1e-1}) {
                for (double twist : {0.0, 1e-15, 1e-9, 1e-4, 0.5}) {
                    const Vec3 ha = scale * Vec3{0.5 + u(rng), 0.5 + u(rng), 0.2 + u(rng)};
                    const Vec3 hb = scale * Vec3{0.5 + u(rng), 0.5 + u(rng), 0.2 + u(rng)};
                    const Quat q = random_quat(rng);
                    const Vec3 up = rotate(q, {0, 0, 1});
                    const Vec3 base = far * scale * random_unit(rng);
                    const double size = scale * 2;
                    const Vec3 offset{0.1 * scale * (2 * u(rng) - 1), 0.1 * scale * (2 * u(rng) - 1),
                                      ha.z + hb.z + gap * size};
                    const Transform pa = make_transform(base, q);
                    const Transform pb = make_transform(base + rotate(q, offset), q * axis_angle({0, 0, 1}, twist));
                    const double lambda = 0.2 + 0.6 * u(rng);
                    const Vec3 drift = rotate(q, {0.05 * scale * (2 * u(rng) - 1), 0.05 * scale * (2 * u(rng) - 1), 0});
                    const Vec3 ta = 0.3 * scale * random_unit(rng);
                    const Vec3 tb = ta + drift - (gap * size / lambda) * up;
                    const Slack slack = falling_slack(gap, size, lambda, base);
                    char what[160];
                    std::snprintf(what, sizeof what, "seed %llu scale %g far %g gap %g twist %g",
                                  static_cast<unsigned long long>(seed), scale, far, gap, twist);
                    const Checked c = check_pair(what, ha, pa, ta, hb, pb, tb, true, lambda, slack.toi, slack.point);
                    // The closed form takes every clear gap, and every twist but 1e-9: the edges'
                    // axes then lie in the band it leaves to GJK (1e-12 to about 3e-5 rad here).
                    EXPECT_EQ(c.closed_form, gap >= 1e-7 && twist != 1e-9) << what;
                    if (c.r.hit && c.r.toi > 0) {
                        EXPECT_LE(angle_between(c.r.normal, up), 1e-9) << what << ": not the face's normal";
                        EXPECT_GT(dot(c.r.normal, up), 0) << what << ": the normal points from A toward B";
                    }
                    tally.add(c);
                }
            }
        }
    }
    tally.report("face onto face", 1e-7);
}

// A face falling onto a face tilted against it by 1e-12 to 1e-3 rad about a random axis across the
// normal (the faces nearly parallel: A - B a slab of nearly coplanar facets, where GJK's rounding
// stops live), B's lowest corner `gap` of the size above A's top face and closing it at lambda*.
// The truth: that corner's height over the face, in long double from the placed doubles, over the
// closing speed. The same boxes rounded by balls (cores shrunk by the radii) take the GJK cast
// with margins: the lowest core corner less B's radius.
TEST(BoxCast, FaceOntoTiltedFace) {
    const uint64_t seed = 24005;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Tally tally;
    int misses = 0, rounded_casts = 0;
    for (double scale : {1e-3, 1.0, 1e3}) {
        for (double far : {0.0, 1e5}) {
            for (double gap : {1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3, 1e-1}) {
                for (int k = 0; k < 12; ++k) {
                    const double tilt = std::array<double, 4>{1e-12, 1e-9, 1e-6, 1e-3}[k % 4];
                    const Vec3 ha = scale * Vec3{1 + u(rng), 1 + u(rng), 0.2 + u(rng)};
                    // B's footprint, twisted any way, and its offset and drift stay within A's face.
                    const Vec3 hb = scale * Vec3{0.3 + 0.3 * u(rng), 0.3 + 0.3 * u(rng), 0.2 + u(rng)};
                    const Quat q = random_quat(rng);
                    const Vec3 up = rotate(q, {0, 0, 1});
                    const Vec3 base = far * scale * random_unit(rng);
                    const double size = scale * 2;
                    const double turn = 6.283185307179586 * u(rng);
                    const Quat qb = q * axis_angle({std::cos(turn), std::sin(turn), 0}, tilt) *
                                    axis_angle({0, 0, 1}, u(rng) < 0.5 ? 0.0 : 3 * u(rng));
                    // B's lowest corner along -up, in B's frame, and where it sits under B's origin.
                    const Vec3 down = transpose(to_matrix(qb)) * (-1.0 * up);
                    const Vec3 corner{down.x < 0 ? -hb.x : hb.x, down.y < 0 ? -hb.y : hb.y, down.z < 0 ? -hb.z : hb.z};
                    const double below = -dot(up, rotate(qb, corner));
                    const Vec3 offset{0.1 * scale * (2 * u(rng) - 1), 0.1 * scale * (2 * u(rng) - 1),
                                      ha.z + below + gap * size};
                    const Transform pa = make_transform(base, q);
                    const Transform pb = make_transform(base + rotate(q, offset), qb);
                    const double lambda = 0.2 + 0.6 * u(rng);
                    const Vec3 drift = rotate(q, {0.05 * scale * (2 * u(rng) - 1), 0.05 * scale * (2 * u(rng) - 1), 0});
                    const Vec3 ta = 0.3 * scale * random_unit(rng);
                    const Vec3 tb = ta + drift - (gap * size / lambda) * up;
                    // The truth from the placed doubles: the corner's height over A's top face over
                    // the closing speed along A's normal.
                    const auto placed = [](const Transform& t, Real x, Real y, Real z) {
                        const Vec3* r = t.rotation.r;
                        return std::array<Real, 3>{r[0].x * x + r[0].y * y + r[0].z * z + Real(t.translation.x),
                                                   r[1].x * x + r[1].y * y + r[1].z * z + Real(t.translation.y),
                                                   r[2].x * x + r[2].y * y + r[2].z * z + Real(t.translation.z)};
                    };
                    const Vec3 nd = pa.rotation.col(2);
                    const auto along = [&](const std::array<Real, 3>& x) {
                        return Real(nd.x) * x[0] + Real(nd.y) * x[1] + Real(nd.z) * x[2];
                    };
                    Real height = INFINITY;
                    for (int j = 0; j < 8; ++j)
                        height = std::min(height, along(placed(pb, (j & 1) ? hb.x : -hb.x, (j & 2) ? hb.y : -hb.y,
                                                               (j & 4) ? hb.z : -hb.z)));
                    height -= along(placed(pa, 0, 0, ha.z));
                    const Vec3 rel = tb - ta;
                    const Real closing = -(Real(nd.x) * rel.x + Real(nd.y) * rel.y + Real(nd.z) * rel.z);
                    const double truth = std::fmax(0.0, double(height / closing));
                    // The cast stops within twice the tolerance of A - B's size seen from the ray
                    // point (cast_loop.hpp), which its diameter bounds: the casts that GJK ends
                    // (near-parallel faces are in the closed form's band) hit up to 1.5e-10 of
                    // `size` early, within that.
                    const double diameter = 2 * (length(ha) + length(hb));
                    const Slack slack{falling_slack(gap, size, lambda, base).toi * 2 * diameter / size,
                                      falling_slack(gap, size, lambda, base).point};
                    char what[160];
                    std::snprintf(what, sizeof what, "seed %llu scale %g far %g gap %g tilt %g",
                                  static_cast<unsigned long long>(seed), scale, far, gap, tilt);
                    // Far from the origin the placed gap is the construction's only to rounding (1e-8
                    // at 1e8): the truth decides the verdict. A gap left at the step's end within
                    // the contact distance (twice the tolerance of the diameter) may go either way.
                    const Real left = height - closing;
                    if (left > 0 && left <= 2 * kTol * diameter + 1e-15 * length(base)) continue;
                    const bool hit = !(left > 0);
                    misses += !hit;
                    const Checked c = check_pair(what, ha, pa, ta, hb, pb, tb, hit, truth, slack.toi, slack.point);
                    if (c.r.hit && c.r.toi > 0) {
                        EXPECT_LE(angle_between(c.r.normal, up), tilt + 1e-9) << what << ": not the face's normal";
                        EXPECT_GT(dot(c.r.normal, up), 0) << what << ": the normal points from A toward B";
                    }
                    tally.add(c);

                    // The same boxes rounded (cores shrunk by the radii, so A's top face stays and
                    // B's lowest point moves by less than the radius): the GJK cast with margins.
                    const double ra = 0.1 * scale * u(rng), rb = 0.1 * scale * u(rng);
                    const Vec3 ca = ha - Vec3{ra, ra, ra}, cb = hb - Vec3{rb, rb, rb};
                    const BoxShape core_a(ca), core_b(cb);
                    const SphereShape ball_a(ra), ball_b(rb);
                    const MinkowskiSumShape round_a(core_a, ball_a), round_b(core_b, ball_b);
                    Real low = INFINITY;
                    for (int j = 0; j < 8; ++j)
                        low = std::min(low, along(placed(pb, (j & 1) ? cb.x : -cb.x, (j & 2) ? cb.y : -cb.y,
                                                         (j & 4) ? cb.z : -cb.z)));
                    const Real rounded_height = low - Real(rb) - along(placed(pa, 0, 0, ha.z));
                    const Real rounded_left = rounded_height - closing;
                    if (rounded_left > 0 && rounded_left <= 2 * kTol * diameter + 1e-15 * length(base)) continue;
                    const double rounded_truth = std::fmax(0.0, double(rounded_height / closing));
                    for (int order = 0; order < 2; ++order) {
                        const CastResult q = order == 0 ? shape_cast(round_a, pa, ta, round_b, pb, tb, kTol, kMaxIt)
                                                        : shape_cast(round_b, pb, tb, round_a, pa, ta, kTol, kMaxIt);
                        ++rounded_casts;
                        EXPECT_EQ(q.hit, !(rounded_left > 0)) << what << " rounded, order " << order;
                        if (!q.hit || rounded_left > 0) continue;
                        EXPECT_LE(q.toi, rounded_truth + slack.toi) << what << " rounded, order " << order;
                        EXPECT_GE(q.toi, rounded_truth - slack.toi) << what << " rounded, order " << order;
                        if (q.toi > 0) {
                            const Vec3 facing = order == 0 ? up : -1.0 * up;
                            EXPECT_LE(angle_between(q.normal, facing), tilt + 1e-9)
                                << what << " rounded, order " << order << ": not the face's normal";
                        }
                    }
                }
            }
        }
    }
    tally.report("face onto tilted face", 1e-7);
    std::printf("[face onto tilted face] %d casts of the rounded boxes\n", rounded_casts);
    EXPECT_GT(rounded_casts, tally.cases) << "seed " << seed;
    // Only a few far, nearly touching starts are misses.
    EXPECT_LT(misses, tally.cases / 20) << "seed " << seed;
}

// An edge onto an edge: A turned 45 degrees about its x axis (its top an edge along x), B the
// same and then twisted about the vertical by psi, falling straight onto it: from crossing at right angles
// to parallel, through the band of nearly parallel edges the closed form leaves to GJK. The
// edges touch at lambda* whatever psi (both stay horizontal), the normal vertical when they cross.
TEST(BoxCast, EdgeOntoEdgeFromCrossingToParallel) {
    const uint64_t seed = 24002;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const double tilt = std::acos(-1.0) / 4;
    Tally tally;
    for (double scale : {1e-3, 1.0, 1e3}) {
        for (double far : {0.0, 1e5}) {
            for (double psi : {1.5707963267948966, 0.3, 1e-2, 2e-3, 5e-4, 1e-5, 1e-9, 1e-13, 1e-16, 0.0}) {
                for (double gap : {1e-6, 1e-2, 0.5}) {
                    // Square sections: the edges lie over the centres, so B's crosses the line of
                    // A's at B's centre's offset along it, whatever psi.
                    const double sa = scale * (0.3 + u(rng)), sb = scale * (0.3 + u(rng));
                    const Vec3 ha{scale * (0.8 + u(rng)), sa, sa}, hb{scale * (0.8 + u(rng)), sb, sb};
                    const Quat q = random_quat(rng);
                    const Vec3 up = rotate(q, {0, 0, 1});
                    const Vec3 base = far * scale * random_unit(rng);
                    const double size = 2 * scale;
                    // Heights of A's top edge over its centre and of B's centre over its bottom edge.
                    const double top = ha.y * std::sin(tilt) + ha.z * std::cos(tilt);
                    const double bottom = hb.y * std::sin(tilt) + hb.z * std::cos(tilt);
                    const Vec3 offset{0.5 * scale * (2 * u(rng) - 1), 0, top + bottom + gap * size};
                    const Transform pa = make_transform(base, q * axis_angle({1, 0, 0}, tilt));
                    const Transform pb = make_transform(base + rotate(q, offset),
                                                        q * axis_angle({0, 0, 1}, psi) * axis_angle({1, 0, 0}, tilt));
                    const double lambda = 0.2 + 0.6 * u(rng);
                    const Vec3 ta = 0.3 * scale * random_unit(rng);
                    const Vec3 tb = ta - (gap * size / lambda) * up;
                    const Slack slack = falling_slack(gap, size, lambda, base);
                    char what[160];
                    std::snprintf(what, sizeof what, "seed %llu scale %g far %g psi %g gap %g",
                                  static_cast<unsigned long long>(seed), scale, far, psi, gap);
                    const Checked c =
                        check_pair(what, ha, pa, ta, hb, pb, tb, true, lambda, slack.toi, slack.point, psi > 1e-3);
                    EXPECT_EQ(c.closed_form, psi != 1e-5 && psi != 1e-9) << what;
                    if (c.r.hit && c.r.toi > 0 && psi > 1e-3) {
                        EXPECT_LE(angle_between(c.r.normal, up), 1e-9)
                            << what << ": crossing edges touch along the vertical";
                    }
                    tally.add(c);
                }
            }
        }
    }
    // GJK's points on nearly parallel edges are the weaker (docs/algorithms.md §3, "Box pairs").
    tally.report("edge onto edge", 1e-5);
}

// Random boxes, turns and motions (half of them hit) against the long double oracle, in both
// orders and against the GJK cast of the hulls, at three scales and far from the origin.
TEST(BoxCast, RandomCastsMatchTheOracle) {
    const uint64_t seed = 24003;
    std::mt19937_64 rng(seed);
    int cases = 0, closed = 0, hits = 0;
    for (double scale : {1e-3, 1.0, 1e3}) {
        for (double far : {0.0, 1e4}) {
            for (int i = 0; i < 300; ++i) {
                Solid a = random_solid(rng, Kind::Box, scale), b = random_solid(rng, Kind::Box, scale);
                const Vec3 base = far * scale * random_unit(rng);
                const Placed placed = place_random(rng, a, b, base);
                if (!placed.usable) continue;
                const Cast& c = placed.cast;
                const cast_oracle::Truth& t = placed.truth;
                const double size = static_cast<double>(cast_oracle::size_of(a.body, b.body));
                const double rounding = 1e-15 * (length(base) + size);
                const double toi_slack = (kTol * size + 8 * rounding) / length(c.tb - c.ta);
                const Vec3 ha = static_cast<const BoxShape&>(*a.shape).half_extents;
                const Vec3 hb = static_cast<const BoxShape&>(*b.shape).half_extents;
                char what[120];
                std::snprintf(what, sizeof what, "seed %llu scale %g far %g case %d",
                              static_cast<unsigned long long>(seed), scale, far, i);
                const Checked k = check_pair(what, ha, c.pa, c.ta, hb, c.pb, c.tb, t.hit, static_cast<double>(t.toi),
                                             toi_slack, 1e-9 + 100 * rounding / size);
                if (k.r.hit && k.r.toi > 0 && t.hit) {
                    const Vec3 tn{static_cast<double>(t.normal.x), static_cast<double>(t.normal.y),
                                  static_cast<double>(t.normal.z)};
                    EXPECT_LE(angle_between(k.r.normal, tn), 1e-9) << what << ": the normal against the oracle's";
                }
                ++cases;
                closed += k.closed_form;
                hits += t.hit;
            }
        }
    }
    std::printf("[random] %d casts, %d hits, %d by the closed form\n", cases, hits, closed);
    EXPECT_GT(hits, cases / 4);
    EXPECT_LT(hits, 3 * cases / 4);
    EXPECT_GT(closed, 95 * cases / 100);
}

// Touching or overlapping at the start, a graze within 1e-9 of the size, and the step ending at
// contact are the GJK cast's: the closed form declines them, and the answers are the GJK cast's
// on the same boxes as hulls (overlapping: toi 0).
TEST(BoxCast, TouchingAtTheStartIsLeftToGjk) {
    const Vec3 h{1, 1, 1};
    const BoxShape a(h), b(h);
    const ShapePtr hull = box_as_hull(h);
    const Transform pa = make_transform({0, 0, 0}, Quat{});
    auto same_as_hulls = [&](const Transform& pb, Vec3 tb, const char* what) {
        EXPECT_FALSE(closed_form_answers(h, pa, {}, h, pb, tb)) << what;
        const CastResult r = shape_cast(a, pa, {}, b, pb, tb, kTol, kMaxIt);
        const CastResult g = shape_cast(*hull, pa, {}, *hull, pb, tb, kTol, kMaxIt);
        EXPECT_EQ(r.hit, g.hit) << what;
        EXPECT_NEAR(r.toi, g.toi, 1e-12) << what;
        return r;
    };
    for (double gap : {0.0, 1e-12, -1e-3}) {
        const Transform pb = make_transform({0.3, -0.2, 2 + gap}, axis_angle({0, 0, 1}, 0.4));
        for (Vec3 tb : {Vec3{0, 0, -1}, Vec3{1, 0, 0}, Vec3{0, 0, 1}}) {
            char what[80];
            std::snprintf(what, sizeof what, "gap %g motion %g %g %g", gap, tb.x, tb.y, tb.z);
            const CastResult r = same_as_hulls(pb, tb, what);
            if (gap <= 0) {
                EXPECT_TRUE(r.hit) << what;
                EXPECT_EQ(r.toi, 0) << what;
            }
        }
    }
    // The step ends 1e-12 short of contact, and a side grazed 1e-12 apart.
    same_as_hulls(make_transform({0, 0, 3}, Quat{}), {0, 0, -(1 - 1e-12)}, "ends short");
    same_as_hulls(make_transform({0, 2 + 1e-12, 3}, Quat{}), {0, 0, -6}, "grazes");
}

// ---- A ball or a ray against a box, rounded or not (ray_rounded_box) ----------------------------

namespace {

// The box with its eight corners as a hull: the GJK path for the same rounded box.
struct RoundedPair {
    BoxShape box;
    SphereShape ball;
    MinkowskiSumShape rounded;
    ShapePtr hull;
    SphereShape hull_ball;
    MinkowskiSumShape rounded_hull;
    RoundedPair(Vec3 h, double rho)
        : box(h), ball(rho), rounded(box, ball), hull(box_as_hull(h)), hull_ball(rho), rounded_hull(*hull, hull_ball) {}
    const Shape& shape() const { return ball.radius > 0 ? static_cast<const Shape&>(rounded) : box; }
    const Shape& gjk_shape() const { return ball.radius > 0 ? static_cast<const Shape&>(rounded_hull) : *hull; }
};

}  // namespace

// Random balls (and points) cast onto boxes rounded by 0 to 3 times their size, and rays onto the
// same boxes grown by both radii: the time against the oracle (a ball of both radii against the
// plain box, its closed form of slabs, edge cylinders and corner balls), against the GJK cast on
// the hull of the box's corners grown the same, and the swapped order; the normal against the
// oracle's and the point on both shapes. Sizes 1e-3 to 1e3, 1e4 sizes from the origin.
TEST(BoxCast, BallsAndRaysOntoRoundedBoxesMatchTheOracle) {
    const uint64_t seed = 24004;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    int cases = 0, closed = 0, hits = 0, corners = 0;
    double worst_toi = 0, worst_angle = 0;
    for (double scale : {1e-3, 1.0, 1e3}) {
        for (double far : {0.0, 1e4}) {
            for (double rounding : {0.0, 1e-9, 1e-3, 0.3, 3.0}) {
                for (int i = 0; i < 60; ++i) {
                    Solid box = random_solid(rng, Kind::Box, scale);
                    const Vec3 h = static_cast<const BoxShape&>(*box.shape).half_extents;
                    const double rho_box = rounding * scale * u(rng), rho_ball = (i % 3 == 0 ? 0.0 : u(rng)) * scale;
                    // The oracle's pair: a ball of both radii against the plain box.
                    Solid ball = make_solid(Kind::Sphere, rho_box + rho_ball, 0, {});
                    const Vec3 base = far * scale * random_unit(rng);
                    const Placed placed = place_random(rng, box, ball, base);
                    if (!placed.usable) continue;
                    const Cast& c = placed.cast;
                    const cast_oracle::Truth& t = placed.truth;
                    const RoundedPair pair(h, rho_box);
                    const SphereShape moving(rho_ball);
                    const PointShape point;
                    const Shape& b = rho_ball > 0 ? static_cast<const Shape&>(moving) : point;
                    // The ball's centre as a ray against the box grown by both radii.
                    const RoundedPair grown(h, rho_box + rho_ball);
                    const FourWays f{shape_cast(pair.shape(), c.pa, c.ta, b, c.pb, c.tb, kTol, kMaxIt),
                                     shape_cast(b, c.pb, c.tb, pair.shape(), c.pa, c.ta, kTol, kMaxIt),
                                     shape_cast(pair.gjk_shape(), c.pa, c.ta, b, c.pb, c.tb, kTol, kMaxIt),
                                     ray_cast(grown.shape(), c.pa, c.pb.translation, c.tb - c.ta, kTol, kMaxIt)};
                    const CastResult& r = f.r;
                    const auto [size, rlen, round_off, toi_slack] = slack_of(box.body, ball.body, c, base, kTol);
                    char what[160];
                    std::snprintf(what, sizeof what, "seed %llu scale %g far %g rounding %g case %d",
                                  static_cast<unsigned long long>(seed), scale, far, rounding, i);
                    worst_angle =
                        std::fmax(worst_angle, expect_four_ways_agree(f, t, toi_slack, 2 * toi_slack, true, what));
                    ++cases;
                    // shape_cast's own call: the ball's centre as a ray against the box grown by both radii.
                    closed += cast_detail::ray_rounded_box(h, rho_box + rho_ball, c.pa.apply_inverse(c.pb.translation),
                                                           c.pa.to_local_direction(c.tb - c.ta))
                                  .verdict != cast_detail::BoxCast::Verdict::Declined;
                    if (!t.hit || !r.hit) continue;
                    ++hits;
                    worst_toi = std::fmax(worst_toi, std::fabs(r.toi - static_cast<double>(t.toi)) * rlen / size);
                    // The contact point: on the rounded box and on the ball at toi.
                    const Vec3 at_box = c.pa.apply_inverse(r.point - r.toi * c.ta);
                    const Vec3 core = closed_form::box_nearest(h, at_box);
                    EXPECT_NEAR(length(at_box - core), rho_box, 1e-9 * size + 100 * round_off) << what;
                    const Vec3 centre = c.pb.translation + r.toi * c.tb;
                    EXPECT_NEAR(length(r.point - centre), rho_ball, 1e-9 * size + 100 * round_off) << what;
                    int out_axes = 0;
                    for (int k = 0; k < 3; ++k) out_axes += std::fabs(at_box[k]) > h[k] * (1 + 1e-9);
                    corners += out_axes >= 2;
                }
            }
        }
    }
    std::printf(
        "[balls onto rounded boxes] %d casts, %d hits (%d at an edge or corner), %d by the closed form; "
        "worst time %.2g of the size, normal %.2g rad\n",
        cases, hits, corners, closed, worst_toi, worst_angle);
    EXPECT_GT(hits, cases / 4);
    EXPECT_LT(hits, 3 * cases / 4);
    EXPECT_GT(corners, hits / 10);  // the rounded edges and corners are met, not only faces
    EXPECT_GT(closed, 9 * cases / 10);
}

// Constructed entries into the rounded parts with known times, from starts inside the box grown
// by the radius on every axis (outside the rounded box): a corner's ball along its diagonal, an
// edge's cylinder across it, a cap met moving along an edge, and a face. Both orders, turned and
// far from the origin.
TEST(BoxCast, RoundedCornersEdgesAndCapsAgainstTheClosedForm) {
    const uint64_t seed = 24005;
    std::mt19937_64 rng(seed);
    const Vec3 h{1, 0.6, 0.8};
    const double rho = 0.5;
    struct Case {
        const char* name;
        Vec3 start, dir;  // box frame, dir unit
        double distance;  // how far the ball's centre travels to contact
    };
    const double d = 0.69, a = 0.3;
    const Vec3 diag = (1 / std::sqrt(3.0)) * Vec3{1, 1, 1};
    const Case cases[] = {
        {"corner ball along the diagonal", Vec3{1, 0.6, 0.8} + d * diag, -1 * diag, d - rho},
        {"edge cylinder across the edge", {1.4, 0.6 + 0.4, 0}, {-1, 0, 0}, 1.4 - (1 + std::sqrt(rho * rho - 0.16))},
        {"cap moving along an edge", {1 + a, 0.6, 3}, {0, 0, -1}, 3 - (0.8 + std::sqrt(rho * rho - a * a))},
        {"face", {0.2, -0.1, 3}, {0, 0, -1}, 3 - 0.8 - rho},
    };
    for (const Case& k : cases) {
        for (double far : {0.0, 1e4}) {
            const Quat q = random_quat(rng);
            const Transform pa = make_transform(far * random_unit(rng), q);
            const Transform pb = make_transform(pa.apply(k.start), Quat{});
            const double motion = k.distance / 0.5;  // contact at lambda 0.5
            const Vec3 tb = motion * rotate(q, k.dir);
            const BoxShape box(h);
            const SphereShape ball(rho);
            const PointShape point;
            const MinkowskiSumShape rounded(box, ball);
            for (int order = 0; order < 2; ++order) {
                // The ball of radius rho against the plain box, or the point against the rounded box.
                const Shape& a_shape = order == 0 ? static_cast<const Shape&>(box) : rounded;
                const Shape& b_shape = order == 0 ? static_cast<const Shape&>(ball) : point;
                const CastResult r = shape_cast(a_shape, pa, {}, b_shape, pb, tb, kTol, kMaxIt);
                const CastResult s = shape_cast(b_shape, pb, tb, a_shape, pa, {}, kTol, kMaxIt);
                const double slack = 1e-13 * (1 + far) / motion;
                EXPECT_TRUE(r.hit && s.hit) << k.name << " far " << far << " order " << order;
                EXPECT_NEAR(r.toi, 0.5, slack) << k.name << " far " << far << " order " << order;
                EXPECT_NEAR(s.toi, 0.5, slack) << k.name << " far " << far << " order " << order << ": swapped";
                EXPECT_EQ(r.iterations, 1u) << k.name << ": the closed form";
            }
            const CastResult ray = ray_cast(rounded, pa, pb.translation, tb, kTol, kMaxIt);
            EXPECT_TRUE(ray.hit) << k.name;
            EXPECT_NEAR(ray.toi, 0.5, 1e-13 * (1 + far) / motion) << k.name << " far " << far;
        }
    }
}

// Balls of radius 0 to 1e-14 of the box's size cast at the box's centre along lines through one of
// its edges or corners: the entry lies on two or three slabs at once, and the edges' capsules are
// thinner than the entry point's rounding. A fuzz_queries finding: a ball of radius 1e-150 (and
// one of 1e-100) moving from (6.22 6.24 6.24) box frame toward the centre of a box 0.09 wide was
// reported missing it, the edge's capsule tested against an entry rounded 1e-16 off the edge,
// while radii 0 and 1e-20 hit. Truth: the plain box's slab entry in long double (the rounded box is
// entered at most the radius earlier). Turned (the finding's exact axis permutation among them),
// 1e4 sizes from the origin, both argument orders, the ray cast onto the rounded box too.
TEST(BoxCast, TinyBallsThroughEdgesAndCornersHit) {
    const uint64_t seed = 53021;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const double radii[] = {0, 1e-300, 1e-150, 1e-100, 1e-30, 1e-20, 1e-14};
    int cases = 0, failures = 0, multi_slab = 0;
    for (int i = 0; i < 120; ++i) {
        const double scale = std::pow(10.0, 2 * static_cast<int>(rng() % 3) - 2);
        const Vec3 h = i == 0 ? Vec3{0.093471274891279474, 0.093471274891279474, 0.093471274891279474}
                              : scale * Vec3{0.3 + u(rng), 0.3 + u(rng), 0.3 + u(rng)};
        // The start: beyond the corner (+h) along (a, b, b), b >= a, so that y and z are entered
        // together (an edge along x), or along (1 1 1) scaled by h (the corner itself).
        const bool corner = i % 3 == 2;
        const double k = 10 + 60 * u(rng);
        const Vec3 s = i == 0   ? Vec3{6.2188448920424193, 6.2431372549019599, 6.2431372549019599}
                       : corner ? k * h
                                : k * Vec3{h.y * (0.8 + 0.19 * u(rng)), h.y, h.z};
        const Quat q = i == 0 ? Quat{0.5, 0.5, 0.5, 0.5} : i % 2 ? random_quat(rng) : Quat{0.5, 0.5, 0.5, 0.5};
        const double far = i % 4 == 3 ? 1e4 * scale : 0;
        const Transform pa = make_transform(far * Vec3{1, -1, 0.5}, q);
        const Transform pb = make_transform(pa.apply(s), Quat{0, 0, 0, -1});
        const Vec3 tb = pa.translation - pb.translation;  // to the box's centre
        // The plain box's entry in the box's frame from the placed start, in long double.
        const Vec3 sl = pa.to_local_direction(pb.translation - pa.translation), rl = pa.to_local_direction(tb);
        long double enter = 0;
        int on = 0;
        for (int m = 0; m < 3; ++m) {
            const long double t =
                (std::fabs(static_cast<long double>(sl[m])) - h[m]) / std::fabs(static_cast<long double>(rl[m]));
            enter = std::max(enter, t);
        }
        for (int m = 0; m < 3; ++m)
            on += std::fabs((std::fabs(static_cast<long double>(sl[m])) - h[m]) /
                                std::fabs(static_cast<long double>(rl[m])) -
                            enter) <= 1e-12L;
        multi_slab += on >= 2;
        const double speed = length(tb);
        const BoxShape box(h);
        for (const double rho : radii) {
            const SphereShape ball(std::max(rho * scale, 1e-300));
            const PointShape point;
            const Shape& b_shape = rho > 0 ? static_cast<const Shape&>(ball) : point;
            const double radius = rho > 0 ? std::max(rho * scale, 1e-300) : 0;
            const MinkowskiSumShape rounded(box, ball);
            // Slack: the tolerance, the radius's head start and the start's rounding, over the motion.
            const double slack = kTol + (radius + 1e-13 * (scale + far)) / speed;
            for (int order = 0; order < 3; ++order) {
                const CastResult r = order == 0   ? shape_cast(box, pa, {}, b_shape, pb, tb, kTol, kMaxIt)
                                     : order == 1 ? shape_cast(b_shape, pb, tb, box, pa, {}, kTol, kMaxIt)
                                                  : ray_cast(rounded, pa, pb.translation, tb, kTol, kMaxIt);
                ++cases;
                const double err = r.toi - static_cast<double>(enter);
                if ((!r.hit || !(std::fabs(err) <= slack)) && ++failures <= 10)
                    ADD_FAILURE() << "radius " << radius << " case " << i << (corner ? " corner" : " edge") << " order "
                                  << order << ": hit " << r.hit << " toi " << r.toi << ", entry "
                                  << static_cast<double>(enter) << "; seed " << seed;
            }
        }
    }
    std::printf(
        "tiny balls through edges and corners: %d casts, %d failures, %d of 120 entries on two or three slabs\n", cases,
        failures, multi_slab);
    EXPECT_EQ(failures, 0) << "seed " << seed;
    EXPECT_GT(multi_slab, 60) << "seed " << seed;
}

// Starts far beyond the box (1e2 to 1e18 of its size), aimed at it within about its size, so that
// the entry point s + lambda r carries rounding up to far above the box itself: every hit still
// enters through a face the ray moves toward or a capsule it approaches (the normal opposes r),
// is a unit normal, and lies on the rounded box within the start's rounding. Fuzzing found a
// normal along the motion (a cube 1e-240 wide grown by 1, from 1e18 away) when the face's side
// was read from the entry point's sign. Also a tiny box, a flat one, with and without rounding.
TEST(BoxCast, FarStartsEnterAgainstTheirMotion) {
    const uint64_t seed = 24006;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    int cases = 0, hits = 0, lost = 0;  // lost: hits whose entry point's rounding exceeds the box
    for (Vec3 h : {Vec3{1e-240, 1e-240, 1e-240}, Vec3{1, 0.6, 0.8}, Vec3{1, 1e-6, 0.5}}) {
        for (double rho : {0.0, 1e-3, 1.0}) {
            const double size = h.x + h.y + h.z + rho;
            for (double far : {1e2, 1e8, 1e12, 1e16, 1e18}) {
                for (int i = 0; i < 40; ++i) {
                    const Vec3 s = far * size * random_unit(rng);
                    const Vec3 aim = (1.5 * size * u(rng)) * random_unit(rng);
                    const double at = 0.1 + 0.8 * u(rng);
                    const Vec3 r = (1 / at) * (aim - s);
                    const cast_detail::BoxCast bc = cast_detail::ray_rounded_box(h, rho, s, r);
                    ++cases;
                    if (bc.verdict != cast_detail::BoxCast::Verdict::Hit) continue;
                    ++hits;
                    char what[160];
                    std::snprintf(what, sizeof what, "seed %llu h (%g %g %g) rho %g far %g case %d",
                                  static_cast<unsigned long long>(seed), h.x, h.y, h.z, rho, far, i);
                    EXPECT_LT(dot(bc.normal, r), 0) << what << ": the normal does not oppose the motion";
                    EXPECT_NEAR(length(bc.normal), 1, 1e-15) << what;
                    EXPECT_TRUE(bc.toi > 0 && bc.toi <= 1) << what << ": toi " << bc.toi;
                    // On the rounded box: its distance from the box is rho, to the entry's rounding.
                    const double off = closed_form::safe_length(bc.point - closed_form::box_nearest(h, bc.point));
                    EXPECT_NEAR(off, rho, 4e-16 * far * size + 1e-15 * size) << what;
                    lost += 1e-16 * far * size > size;
                }
            }
        }
    }
    std::printf("[far starts] %d rays, %d hits, %d beyond the entry's rounding\n", cases, hits, lost);
    // Most rays aimed within the box's size hit it; the far ones' hits are within rounding either way.
    EXPECT_GT(hits, cases / 4) << "seed " << seed;
    EXPECT_LT(hits, cases) << "seed " << seed;
    EXPECT_GT(lost, 50) << "seed " << seed << ": too few hits beyond the entry's rounding";
}

// Rays whose entry into the box grown by rho on every axis lies in an edge's region (two
// coordinates past the box), where ray_rounded_box tests that edge's capsule alone, against the
// oracle's first contact over every piece of the rounded box (faces, the twelve cylinders, the
// eight balls): starts just outside a corner of the grown box aimed anywhere, and starts inside the
// grown box (outside the rounded one) in an edge's region. Boxes 1e-3 to 1 wide, radii 1e-3 to 5,
// all of it also scaled by 1e-80 and 1e80. Verdict and time, and for hits the normal (the
// oracle's, from its box point to its entry) and the point (on the ray, on the rounded box). The
// slab test below only sorts the cases into regions and counts them; nothing is checked against it.
TEST(BoxCast, RaysFromEdgeRegionsMatchEveryPieceOfTheRoundedBox) {
    const uint64_t seed = 24007;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> gauss(0, 1);
    auto pick = [&](std::initializer_list<double> v) { return *(v.begin() + static_cast<int>(rng() % v.size())); };
    int edge_entries = 0, hits = 0, grazes = 0, declined = 0, corner_hits = 0;
    double worst = 0, worst_angle = 0;
    // How many coordinates of x lie past the box: 3 on a corner's ball.
    auto out_axes = [](Vec3 hh, Vec3 x) {
        int n = 0;
        for (int k = 0; k < 3; ++k) n += std::fabs(x[k]) > hh[k];
        return n;
    };
    for (int i = 0; i < 40000; ++i) {
        Vec3 h, s;
        const double scale = pick({1.0, 1.0, 1e-80, 1e80});
        for (int k = 0; k < 3; ++k) h[k] = scale * pick({1e-3, 0.1, 1.0}) * (0.5 + 0.5 * u(rng));
        const double rho = scale * pick({1e-3, 0.3, 1.0, 5.0}) * (0.5 + 0.5 * u(rng));
        // Odd cases start inside the grown box in the region of the edge along axis m (the other
        // two coordinates past the box by up to rho), aimed anywhere; even ones just outside a
        // corner of the grown box, aimed at a point of it.
        const bool inside = i % 2 == 1;
        const int m = static_cast<int>(rng() % 3);
        Vec3 aim;
        for (int k = 0; k < 3; ++k) {
            const double sign = rng() % 2 ? 1.0 : -1.0;
            if (inside)
                s[k] = k == m ? (2 * u(rng) - 1) * h[k] : sign * (h[k] + rho * u(rng));
            else
                s[k] = sign * (h[k] + rho + 2 * rho * u(rng));
            aim[k] = (2 * u(rng) - 1) * (h[k] + rho);
        }
        const Vec3 r = inside ? 4 * rho * Vec3{gauss(rng), gauss(rng), gauss(rng)} : 1.5 * (aim - s);
        // The entry into the grown box (the start itself when inside it), and its region.
        double enter = 0, leave = 1;
        for (int k = 0; k < 3; ++k) {
            if (r[k] == 0) continue;
            double lo = (-(h[k] + rho) - s[k]) / r[k], hi = ((h[k] + rho) - s[k]) / r[k];
            if (lo > hi) std::swap(lo, hi);
            enter = std::fmax(enter, lo), leave = std::fmin(leave, hi);
        }
        if (!(enter <= leave)) continue;
        const Vec3 p = s + enter * r;
        int past = 0;
        for (int k = 0; k < 3; ++k) past += std::fabs(p[k]) > h[k];
        const double size = h.x + h.y + h.z + rho;
        if (past != 2 || closed_form::safe_length(s - closed_form::box_nearest(h, s)) < rho + 1e-6 * size) continue;
        ++edge_entries;
        const cast_detail::BoxCast bc = cast_detail::ray_rounded_box(h, rho, s, r);
        if (bc.verdict == cast_detail::BoxCast::Verdict::Declined) {
            ++declined;
            continue;
        }
        // The oracle at the radius and 1e-9 of the size either side of it: a verdict that changes
        // within that is a graze, where either answer is right.
        P3 box_point{};  // the oracle's box point nearest its entry at rho
        auto truth = [&](double radius, P3& at) {
            const Real l = cast_oracle::ray_rounded_box(p3(s), p3(r), p3(h), Real(radius), at);
            return l >= 0 && l <= 1 ? static_cast<double>(l) : -1.0;
        };
        P3 unused;
        const double t = truth(rho, box_point), t_lo = truth(rho - 1e-9 * size, unused),
                     t_hi = truth(rho + 1e-9 * size, unused);
        char what[200];
        std::snprintf(what, sizeof what, "seed %llu case %d h (%g %g %g) rho %g s (%g %g %g) r (%g %g %g)",
                      static_cast<unsigned long long>(seed), i, h.x, h.y, h.z, rho, s.x, s.y, s.z, r.x, r.y, r.z);
        const bool hit = bc.verdict == cast_detail::BoxCast::Verdict::Hit;
        if ((t_lo >= 0) != (t_hi >= 0)) {
            ++grazes;
            continue;
        }
        EXPECT_EQ(hit, t >= 0) << what << ": oracle toi " << t;
        if (!hit || t < 0) continue;
        ++hits;
        const double err = std::fabs(bc.toi - t) * length(r) / size;
        worst = std::fmax(worst, err);
        EXPECT_LE(err, 1e-12) << what << ": toi " << bc.toi << " oracle " << t;
        // The normal: the oracle's, from the box point nearest its entry to the entry (the
        // rounded box's outward normal there, whichever piece it is on); the point: on the
        // ray at toi, and on the rounded box.
        const P3 out = (p3(s) + Real(t) * p3(r)) - box_point;
        const Vec3 tn{static_cast<double>(out.x), static_cast<double>(out.y), static_cast<double>(out.z)};
        const double angle = angle_between(bc.normal, tn);
        worst_angle = std::fmax(worst_angle, angle);
        EXPECT_LE(angle, 1e-6) << what << ": normal (" << bc.normal.x << " " << bc.normal.y << " " << bc.normal.z
                               << ")";
        const double round_off = 1e-15 * (max_abs(s) + length(r) + size);
        EXPECT_LE(length(bc.point - (s + bc.toi * r)), 100 * round_off) << what << ": the point is off the ray";
        EXPECT_NEAR(length(bc.point - closed_form::box_nearest(h, bc.point)), rho, 1e-9 * size) << what;
        corner_hits += out_axes(h, bc.point) == 3;
    }
    std::printf(
        "[edge regions] %d entries in an edge's region, %d hits (%d on a corner's ball), %d grazes, %d declined; "
        "worst time %.2g of the size, normal %.2g rad\n",
        edge_entries, hits, corner_hits, grazes, declined, worst, worst_angle);
    EXPECT_GT(edge_entries, 8000) << "seed " << seed;
    EXPECT_GT(hits, edge_entries / 5) << "seed " << seed;
    EXPECT_LT(hits, edge_entries * 9 / 10) << "seed " << seed;
    EXPECT_LT(declined, edge_entries / 100) << "seed " << seed;
    EXPECT_GT(corner_hits, hits / 50) << "seed " << seed;
}
