// SPDX-License-Identifier: MIT
// GJK benchmark: Kairos against FCL (GST_INDEP), Bullet f64 (btGjkPairDetector) and libccd on the
// same pre-generated random queries; and the signed distance of overlapping pairs (Kairos's EPA)
// against libccd's MPR penetration, FCL's signed distance and Bullet f64's GJK-EPA, each with its
// depth error against a truth (the polytope oracle, or Kairos at 1e-13 on curved shapes). Reports time per query (use --benchmark_repetitions and the
// median aggregate) and mean GJK iterations where the library exposes them. Kairos is timed twice:
// the core's gjk_distance, and kairos_distance as users call it (the C boundary's cost is the
// difference).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <vector>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConeShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <ccd/ccd.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include "gjk/gjk.hpp"
#include "gjk/penetration.hpp"
#include "gjk_peer_bullet.hpp"
#include "gjk_peer_fcl.hpp"
#include "gjk_peer_shapes.hpp"
#include "capi_poses.hpp"
#include "kairos/kairos.h"

using namespace kairos;
using peer::bullet_shape;
using peer::bullet_transform;
using peer::fcl_geometry;
using peer::fcl_transform;
using peer::Kind;
using peer::Spec;

namespace {

// Per scenario, generated once with a fixed seed. Few enough that every library's queries stay
// in cache: the comparison is of the algorithms, not of memory latency (with 4096 scattered
// queries a third of Kairos's time was the first load of each shape).
constexpr int kQueries = 512;
constexpr double kTolerance = 1e-10;  // Kairos's public default

// 32 points on an ellipsoid: every one is a hull vertex.
Spec hull32(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> ext(0.3, 1.5);
    Spec s;
    s.kind = Kind::Hull;
    const Vec3 radii{ext(rng), ext(rng), ext(rng)};
    for (int i = 0; i < 32; ++i) {
        const Vec3 d = gjk_test::random_unit(rng);
        s.verts.push_back({d.x * radii.x, d.y * radii.y, d.z * radii.z});
    }
    const double id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, zero[3] = {0, 0, 0};
    s.local_poly = oracle::make_polytope(oracle::transform(s.verts, id, zero));
    return s;
}

enum Scenario { BoxBox, Hull32, CylinderCone, SphereCapsule, BoxBoxMixed, ParallelCylinders, CapsuleBox };

// ---- The same queries through the public C API ---------------------------------------------------

struct ShapeRelease {
    void operator()(kairos_shape* s) const { kairos_shape_release(s); }
};
using CShape = std::unique_ptr<kairos_shape, ShapeRelease>;

CShape c_shape(const Spec& s) {
    kairos_shape* out = nullptr;
    int32_t status = KAIROS_ERROR_INVALID_ARGUMENT;
    switch (s.kind) {
        case Kind::Box:
            status = kairos_shape_box({s.a, s.b, s.c}, &out);
            break;
        case Kind::Sphere:
            status = kairos_shape_sphere(s.a, &out);
            break;
        case Kind::Capsule:
            status = kairos_shape_capsule(s.a, s.b, &out);
            break;
        case Kind::Cylinder:
            status = kairos_shape_cylinder(s.a, s.b, &out);
            break;
        case Kind::Cone:
            status = kairos_shape_cone(s.a, s.b, &out);
            break;
        case Kind::Hull: {
            std::vector<kairos_vec3> points;
            for (const auto& v : s.verts) points.push_back({v[0], v[1], v[2]});
            status = kairos_shape_convex_hull(points.data(), points.size(), &out);
            break;
        }
    }
    if (status != KAIROS_OK) {
        std::fprintf(stderr, "bench_gjk: the C API rejected a shape: %s\n", kairos_last_error());
        std::abort();
    }
    return CShape(out);
}


struct Query {
    Spec a, b;
    gjk_test::ShapePtr ka, kb;
    std::shared_ptr<fcl::CollisionObjectd> fa, fb;
    std::unique_ptr<btConvexShape> ba, bb;
    btTransform ta, tb;
    Vec3 axis_cache;
    CShape ca, cb;  // the shapes and poses through the C API
    kairos_pose pa, pb;
    double truth = NAN;  // distance scenarios: the true distance (true_distance)
};

// Cylinders with parallel axes: A at random, B's axis across A's by up to rho_max of the radii's
// sum and along it by up to dz_max of the half heights' sum, turned about its axis.
void place_parallel(std::mt19937_64& rng, Spec& a, Spec& b, double rho_max, double dz_max) {
    std::uniform_real_distribution<double> u(0, 1);
    const double rho = rho_max * (a.a + b.a) * u(rng), phi = 2 * M_PI * u(rng);
    const double dz = dz_max * (a.b + b.b) * (2 * u(rng) - 1), turn = 2 * M_PI * u(rng);
    const Quat qa = gjk_test::random_quat(rng);
    a.pose = make_transform(0.2 * gjk_test::random_unit(rng), qa);
    b.pose =
        make_transform(a.pose.apply({rho * std::cos(phi), rho * std::sin(phi), dz}), qa * axis_angle({0, 0, 1}, turn));
}

// Cylinders with parallel axes: A - B is the cylinder of radius ra + rb and half height ha + hb
// about B's offset, so their gap (> 0 apart) or depth (< 0) is that of the origin from it, in long
// double.
long double parallel_cylinders_gap(const Spec& a, const Spec& b) {
    const Vec3 t = a.pose.to_local_direction(b.pose.translation - a.pose.translation);
    const long double radial = std::hypot((long double)t.x, (long double)t.y) - ((long double)a.a + b.a);
    const long double axial = std::fabs((long double)t.z) - ((long double)a.b + b.b);
    if (radial <= 0 && axial <= 0) return std::max(radial, axial);
    return std::hypot(std::max(radial, 0.0L), std::max(axial, 0.0L));
}

// The true distance of a separated pair: the long double polytope oracle for boxes and hulls; for
// curved pairs Kairos at tolerance 1e-14, taken only when the test-side supports
// (gjk_peer_shapes.hpp, independent of src/) certify it: the gap between the two shapes along
// its own axis, a lower bound of the distance, is within 1e-11 of the size of it.
double true_distance(const Query& x) {
    if ((x.a.kind == Kind::Box || x.a.kind == Kind::Hull) && (x.b.kind == Kind::Box || x.b.kind == Kind::Hull))
        return double(oracle::distance(gjk_test::world_polytope(x.a.verts, x.a.pose),
                                       gjk_test::world_polytope(x.b.verts, x.b.pose))
                          .distance);
    const DistanceResult r = gjk_distance(*x.ka, x.a.pose, *x.kb, x.b.pose, 1e-14, 100000);
    const Vec3 n = r.axis;
    const double lower = dot(n, peer::world_support(x.b, -n)) - dot(n, peer::world_support(x.a, n));
    const double size = std::max(peer::extent(x.a), peer::extent(x.b));
    // Not certified (1 of the 512 cylinder/cone pairs, where GJK at 1e-14 stops on JohnsonFailed
    // with a gap of 2e-11): no truth, the pair is left out of every library's errors.
    if (!(r.distance - lower <= 1e-11 * size) || !(lower <= r.distance + 1e-11 * size)) return NAN;
    return r.distance;
}

std::vector<Query>& queries(Scenario sc) {
    static std::vector<Query> all[7];
    std::vector<Query>& q = all[sc];
    if (!q.empty()) return q;
    std::mt19937_64 rng(1234 + sc);
    q.resize(kQueries);
    for (Query& x : q) {
        switch (sc) {
            case BoxBox:
            case BoxBoxMixed:
                x.a = peer::random_spec(rng, Kind::Box), x.b = peer::random_spec(rng, Kind::Box);
                break;
            case Hull32:
                x.a = hull32(rng), x.b = hull32(rng);
                break;
            case CylinderCone:
                x.a = peer::random_spec(rng, Kind::Cylinder), x.b = peer::random_spec(rng, Kind::Cone);
                break;
            case ParallelCylinders:
                x.a = peer::random_spec(rng, Kind::Cylinder), x.b = peer::random_spec(rng, Kind::Cylinder);
                break;
            case SphereCapsule:
                x.a = peer::random_spec(rng, Kind::Sphere), x.b = peer::random_spec(rng, Kind::Capsule);
                break;
            case CapsuleBox:
                x.a = peer::random_spec(rng, Kind::Capsule), x.b = peer::random_spec(rng, Kind::Box);
                break;
        }
        // Distance scenarios hold separated pairs only (penetration is another query: Bullet would
        // run EPA on overlapping pairs and FCL returns early); box/box keeps both for intersection.
        for (;;) {
            if (sc == ParallelCylinders)
                place_parallel(rng, x.a, x.b, 1.6, 1.3);
            else
                peer::place_pair(rng, x.a, x.b);
            x.ka = peer::make_kairos(x.a), x.kb = peer::make_kairos(x.b);
            if (sc == BoxBoxMixed || !gjk_distance(*x.ka, x.a.pose, *x.kb, x.b.pose, kTolerance, 256).intersecting)
                break;
        }
        x.fa = std::make_shared<fcl::CollisionObjectd>(fcl_geometry(x.a), fcl_transform(x.a.pose));
        x.fb = std::make_shared<fcl::CollisionObjectd>(fcl_geometry(x.b), fcl_transform(x.b.pose));
        x.ba = bullet_shape(x.a), x.bb = bullet_shape(x.b);
        x.ta = bullet_transform(x.a.pose), x.tb = bullet_transform(x.b.pose);
        x.axis_cache = {};
        x.ca = c_shape(x.a), x.cb = c_shape(x.b);
        x.pa = c_pose(x.a.pose), x.pb = c_pose(x.b.pose);
        if (sc == ParallelCylinders) {
            x.truth = double(parallel_cylinders_gap(x.a, x.b));
        } else if (sc != BoxBoxMixed) {
            x.truth = true_distance(x);
        }
        // The C API must answer the core's query: same shapes, same poses up to rounding.
        kairos_distance_result r;
        const DistanceResult core = gjk_distance(*x.ka, x.a.pose, *x.kb, x.b.pose, kTolerance, 256);
        if (kairos_distance(x.ca.get(), &x.pa, x.cb.get(), &x.pb, nullptr, &r) != KAIROS_OK ||
            !(std::fabs(r.distance - core.distance) <= 1e-9 * (1 + core.distance))) {
            std::fprintf(stderr, "bench_gjk: the C API and the core disagree (%.17g against %.17g)\n", r.distance,
                         core.distance);
            std::abort();
        }
    }
    return q;
}

// ---- Distance ----------------------------------------------------------------------------------

// Median and largest error over pairs 0 .. n-1 as counters (the accuracy each library's time
// buys). error_of(i): the pair's absolute error, NAN when the library gave no answer (counted in
// "failed"), nullopt when the pair has no truth.
template <class ErrorOf>
void error_counters(benchmark::State& state, size_t n, ErrorOf&& error_of) {
    std::vector<double> err;
    int failed = 0;
    for (size_t i = 0; i < n; ++i) {
        const std::optional<double> e = error_of(i);
        if (!e) continue;
        if (std::isnan(*e))
            ++failed;
        else
            err.push_back(*e);
    }
    std::sort(err.begin(), err.end());
    state.counters["err_median"] = err.empty() ? NAN : err[err.size() / 2];
    state.counters["err_max"] = err.empty() ? NAN : err.back();
    state.counters["failed"] = failed;
}

// |distance - truth| over a distance scenario's pairs with a truth (error_counters).
template <class Distance>
void distance_errors(benchmark::State& state, const std::vector<Query>& q, Distance&& distance_of) {
    error_counters(state, q.size(), [&](size_t i) -> std::optional<double> {
        if (std::isnan(q[i].truth)) return std::nullopt;
        return std::fabs(distance_of(q[i]) - q[i].truth);
    });
}

// tolerance: 10^-range(1) (the default 1e-10, and coarser ones to compare at a peer's accuracy).
void BM_KairosDistance(benchmark::State& state) {
    auto& q = queries(static_cast<Scenario>(state.range(0)));
    const double tolerance = std::pow(10.0, -double(state.range(1)));
    size_t i = 0;
    uint64_t iters = 0, n = 0;
    for (auto _ : state) {
        const Query& x = q[i];
        const DistanceResult r = gjk_distance(*x.ka, x.a.pose, *x.kb, x.b.pose, tolerance, 256);
        benchmark::DoNotOptimize(r);
        iters += r.iterations, ++n;
        i = (i + 1) % q.size();
    }
    state.counters["gjk_iterations"] = double(iters) / double(n);
    distance_errors(state, q, [&](const Query& x) {
        return gjk_distance(*x.ka, x.a.pose, *x.kb, x.b.pose, tolerance, 256).distance;
    });
}

// The same queries as users make them: kairos_distance on C shapes and poses (checks, quaternion
// to matrix, result conversion included).
void BM_KairosCapiDistance(benchmark::State& state) {
    auto& q = queries(static_cast<Scenario>(state.range(0)));
    kairos_query_settings settings;
    kairos_query_settings_init(&settings);
    settings.tolerance = kTolerance;
    settings.max_iterations = 256;
    size_t i = 0;
    for (auto _ : state) {
        const Query& x = q[i];
        kairos_distance_result r;
        const int32_t status = kairos_distance(x.ca.get(), &x.pa, x.cb.get(), &x.pb, &settings, &r);
        benchmark::DoNotOptimize(status);
        benchmark::DoNotOptimize(r);
        i = (i + 1) % q.size();
    }
    distance_errors(state, q, [&](const Query& x) {
        kairos_distance_result r;
        return kairos_distance(x.ca.get(), &x.pa, x.cb.get(), &x.pb, &settings, &r) == KAIROS_OK ? r.distance
                                                                                                 : double(NAN);
    });
}

void BM_FclDistanceGstIndep(benchmark::State& state) {
    auto& q = queries(static_cast<Scenario>(state.range(0)));
    size_t i = 0;
    for (auto _ : state) {
        const Query& x = q[i];
        fcl::DistanceRequestd req;
        req.enable_nearest_points = true;
        req.gjk_solver_type = fcl::GST_INDEP;
        fcl::DistanceResultd res;
        fcl::distance(x.fa.get(), x.fb.get(), req, res);
        benchmark::DoNotOptimize(res.min_distance);
        i = (i + 1) % q.size();
    }
    distance_errors(state, q, [](const Query& x) {
        fcl::DistanceRequestd req;
        req.enable_nearest_points = true;
        req.gjk_solver_type = fcl::GST_INDEP;
        fcl::DistanceResultd res;
        fcl::distance(x.fa.get(), x.fb.get(), req, res);
        return res.min_distance;
    });
}

void BM_BulletF64Distance(benchmark::State& state) {
    auto& q = queries(static_cast<Scenario>(state.range(0)));
    size_t i = 0;
    uint64_t iters = 0, n = 0;
    auto run = [](const Query& x, btGjkPairDetector& detector) {
        btGjkPairDetector::ClosestPointInput in;
        in.m_transformA = x.ta;
        in.m_transformB = x.tb;
        btPointCollector out;
        detector.getClosestPoints(in, out, nullptr);
        return out.m_hasResult ? double(out.m_distance) : double(NAN);
    };
    for (auto _ : state) {
        const Query& x = q[i];
        btVoronoiSimplexSolver simplex;
        btGjkEpaPenetrationDepthSolver epa;
        btGjkPairDetector detector(x.ba.get(), x.bb.get(), &simplex, &epa);
        benchmark::DoNotOptimize(run(x, detector));
        iters += detector.m_curIter, ++n;
        i = (i + 1) % q.size();
    }
    state.counters["gjk_iterations"] = double(iters) / double(n);
    distance_errors(state, q, [&](const Query& x) {
        btVoronoiSimplexSolver simplex;
        btGjkEpaPenetrationDepthSolver epa;
        btGjkPairDetector detector(x.ba.get(), x.bb.get(), &simplex, &epa);
        return run(x, detector);
    });
}

// ---- Box/box intersection (random pairs, about a third overlapping) ----------------------------------------------------------------------

void BM_KairosIntersect(benchmark::State& state) {
    auto& q = queries(BoxBoxMixed);
    const bool cached = state.range(0) != 0;
    size_t i = 0;
    uint64_t iters = 0, n = 0;
    for (auto _ : state) {
        Query& x = q[i];
        Vec3 fresh{};
        uint32_t it = 0;
        const bool hit = gjk_intersect(*x.ka, x.a.pose, *x.kb, x.b.pose, cached ? x.axis_cache : fresh, &it);
        benchmark::DoNotOptimize(hit);
        iters += it, ++n;
        i = (i + 1) % q.size();
    }
    state.counters["gjk_iterations"] = double(iters) / double(n);
}

void ccd_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
    const Spec& s = *static_cast<const Spec*>(obj);
    const Vec3 p = peer::world_support(s, {dir->v[0], dir->v[1], dir->v[2]});
    out->v[0] = p.x, out->v[1] = p.y, out->v[2] = p.z;
}
void ccd_center(const void* obj, ccd_vec3_t* out) {
    const Spec& s = *static_cast<const Spec*>(obj);
    out->v[0] = s.pose.translation.x, out->v[1] = s.pose.translation.y, out->v[2] = s.pose.translation.z;
}

void BM_LibccdIntersect(benchmark::State& state) {
    auto& q = queries(BoxBoxMixed);
    const bool mpr = state.range(0) != 0;
    ccd_t c;
    CCD_INIT(&c);
    c.support1 = c.support2 = ccd_support;
    c.center1 = c.center2 = ccd_center;
    c.max_iterations = 1000;
    size_t i = 0;
    for (auto _ : state) {
        const Query& x = q[i];
        const int hit = mpr ? ccdMPRIntersect(&x.a, &x.b, &c) : ccdGJKIntersect(&x.a, &x.b, &c);
        benchmark::DoNotOptimize(hit);
        i = (i + 1) % q.size();
    }
}

// ---- Signed distance of overlapping pairs ----------------------------------------------------------

// Overlapping pairs and their true depth: the long double oracle for polytopes (the smallest
// overlap over face normals and edge cross products), Kairos at tolerance 1e-13 on curved shapes;
// cylinders with parallel axes (B's axis across A's by up to 0.9 of the radii's sum, along it by up
// to 0.6 of the half heights' sum, turned about it): A - B is the cylinder of radius ra + rb and half
// height ha + hb, so the depth is the least of its radial and axial rooms; a capsule and a box:
// capsule_box_depth.
struct Overlap {
    std::vector<Query> q;
    std::vector<double> depth;
    int cores_overlap = 0;  // capsule/box: pairs whose segment itself enters the box
};

// The depth of capsule A in box B, in long double: the capsule is its segment grown by its radius r.
// A segment entering the box has the depth the sum's facets give (gjk_test::box_segment_depth),
// plus r; a segment outside has r less its distance to the box, which an end (against the box, by
// clamping in B's frame) or one of the box's 12 edges attains.
double capsule_box_depth(const Spec& capsule, const Spec& box) {
    using oracle::P3;
    using oracle::Real;
    const Vec3 half{box.a, box.b, box.c};
    const double core = gjk_test::box_segment_depth(half, box.pose, capsule.b, capsule.pose);
    if (core > 0) return core + capsule.a;
    const auto end = [&](double z) { return gjk_test::to_p3(box.pose.apply_inverse(capsule.pose.apply({0, 0, z}))); };
    const P3 p = end(-capsule.b), q = end(capsule.b);
    const auto to_box_sq = [&](P3 x) {
        const Real c[3] = {x.x, x.y, x.z};
        Real sum = 0;
        for (int i = 0; i < 3; ++i) {
            const Real out = std::fabs(c[i]) - half[i];
            if (out > 0) sum += out * out;
        }
        return sum;
    };
    Real best = std::min(to_box_sq(p), to_box_sq(q));
    for (int i = 0; i < 3; ++i) {  // the 4 edges along axis i
        for (int s = 0; s < 4; ++s) {
            Real lo[3], hi[3];
            for (int j = 0, k = 0; j < 3; ++j) {
                if (j == i) {
                    lo[j] = -half[j], hi[j] = half[j];
                } else {
                    lo[j] = hi[j] = (s >> k++ & 1) ? half[j] : -half[j];
                }
            }
            best = std::min(best, oracle::segment_segment_sq(p, q, {lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}));
        }
    }
    return double(capsule.a - std::sqrt(best));
}

Overlap& overlapping(Scenario sc) {
    static Overlap all[7];
    Overlap& o = all[sc];
    if (!o.q.empty()) return o;
    std::mt19937_64 rng(4321 + sc);
    constexpr int kPairs = 256;
    o.q.resize(kPairs);
    for (Query& x : o.q) {
        for (;;) {
            if (sc == Hull32) {
                x.a = hull32(rng), x.b = hull32(rng);
            } else if (sc == ParallelCylinders) {
                x.a = peer::random_spec(rng, Kind::Cylinder), x.b = peer::random_spec(rng, Kind::Cylinder);
                place_parallel(rng, x.a, x.b, 0.9, 0.6);
            } else if (sc == CapsuleBox) {
                x.a = peer::random_spec(rng, Kind::Capsule), x.b = peer::random_spec(rng, Kind::Box);
            } else {
                x.a = peer::random_spec(rng, sc == CylinderCone ? Kind::Cylinder : Kind::Box);
                x.b = peer::random_spec(rng, sc == CylinderCone ? Kind::Cone : Kind::Box);
            }
            if (sc != ParallelCylinders) peer::place_pair(rng, x.a, x.b);
            x.ka = peer::make_kairos(x.a), x.kb = peer::make_kairos(x.b);
            if (gjk_distance(*x.ka, x.a.pose, *x.kb, x.b.pose, kTolerance, 256).intersecting) break;
        }
        x.fa = std::make_shared<fcl::CollisionObjectd>(fcl_geometry(x.a), fcl_transform(x.a.pose));
        x.fb = std::make_shared<fcl::CollisionObjectd>(fcl_geometry(x.b), fcl_transform(x.b.pose));
        x.ba = bullet_shape(x.a), x.bb = bullet_shape(x.b);
        x.ta = bullet_transform(x.a.pose), x.tb = bullet_transform(x.b.pose);
        x.ca = c_shape(x.a), x.cb = c_shape(x.b);
        x.pa = c_pose(x.a.pose), x.pb = c_pose(x.b.pose);
        if (sc == ParallelCylinders) {
            o.depth.push_back(-double(parallel_cylinders_gap(x.a, x.b)));
        } else if (sc == CapsuleBox) {
            o.depth.push_back(capsule_box_depth(x.a, x.b));
            o.cores_overlap += o.depth.back() > x.a.a;
        } else if (sc == CylinderCone) {
            o.depth.push_back(-signed_distance(*x.ka, x.a.pose, *x.kb, x.b.pose, 1e-13, 100000).distance);
        } else {
            const oracle::Result r = oracle::distance(gjk_test::world_polytope(x.a.verts, x.a.pose),
                                                      gjk_test::world_polytope(x.b.verts, x.b.pose));
            o.depth.push_back(r.intersecting ? double(r.depth) : -double(r.distance));
        }
    }
    return o;
}

// |depth - truth| over the scenario's pairs (error_counters); NAN depths (no answer, an
// exception) count in "failed".
template <class Depth>
void depth_errors(benchmark::State& state, const Overlap& o, Depth&& depth_of) {
    error_counters(state, o.q.size(),
                   [&](size_t i) -> std::optional<double> { return std::fabs(depth_of(o.q[i]) - o.depth[i]); });
}

// A peer's depth query timed over the scenario's pairs in turn, then its errors (depth_errors).
template <class Depth>
void time_depths(benchmark::State& state, const Overlap& o, Depth&& depth_of) {
    size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(depth_of(o.q[i]));
        i = (i + 1) % o.q.size();
    }
    depth_errors(state, o, depth_of);
}

// tolerance: 10^-range(1) (the default 1e-10, and coarser ones to compare at a peer's accuracy).
void BM_KairosSignedDistance(benchmark::State& state) {
    const Overlap& o = overlapping(static_cast<Scenario>(state.range(0)));
    const double tolerance = std::pow(10.0, -double(state.range(1)));
    size_t i = 0;
    uint64_t iters = 0, n = 0;
    for (auto _ : state) {
        const Query& x = o.q[i];
        const DistanceResult r = signed_distance(*x.ka, x.a.pose, *x.kb, x.b.pose, tolerance, 256);
        benchmark::DoNotOptimize(r);
        iters += r.iterations, ++n;
        i = (i + 1) % o.q.size();
    }
    state.counters["iterations"] = double(iters) / double(n);
    if (o.cores_overlap > 0) state.counters["cores_overlap"] = double(o.cores_overlap) / double(o.q.size());
    depth_errors(state, o, [&](const Query& x) {
        return -signed_distance(*x.ka, x.a.pose, *x.kb, x.b.pose, tolerance, 256).distance;
    });
}

void BM_KairosCapiSignedDistance(benchmark::State& state) {
    const Overlap& o = overlapping(static_cast<Scenario>(state.range(0)));
    size_t i = 0;
    for (auto _ : state) {
        const Query& x = o.q[i];
        kairos_distance_result r;
        const int32_t status = kairos_signed_distance(x.ca.get(), &x.pa, x.cb.get(), &x.pb, nullptr, &r);
        benchmark::DoNotOptimize(status);
        benchmark::DoNotOptimize(r);
        i = (i + 1) % o.q.size();
    }
}

void BM_LibccdMprPenetration(benchmark::State& state) {
    const Overlap& o = overlapping(static_cast<Scenario>(state.range(0)));
    ccd_t c;
    CCD_INIT(&c);
    c.support1 = c.support2 = ccd_support;
    c.center1 = c.center2 = ccd_center;
    c.max_iterations = 1000;
    c.mpr_tolerance = 1e-10;
    auto depth_of = [&](const Query& x) {
        ccd_real_t depth = 0;
        ccd_vec3_t dir, pos;
        return ccdMPRPenetration(&x.a, &x.b, &c, &depth, &dir, &pos) == 0 ? double(depth) : NAN;
    };
    time_depths(state, o, depth_of);
}

void BM_FclSignedDistance(benchmark::State& state) {
    if (state.range(0) == CylinderCone || state.range(0) == ParallelCylinders || state.range(0) == CapsuleBox) {
        // libccd's EPA inside FCL fails an assertion on some of these pairs and aborts the process
        // (seen in this benchmark on cylinder/cone and capsule/box; the stability catalogue counts its
        // aborts in forked children, half of its parallel cylinders).
        state.SkipWithError("FCL aborts on overlapping curved pairs (assertion in gjk_libccd-inl.h)");
        return;
    }
    const Overlap& o = overlapping(static_cast<Scenario>(state.range(0)));
    // FCL's signed distance runs libccd's GJK and EPA (GST_LIBCCD); it may throw on degenerate
    // input (FCL issues 493, 495), counted as a failure.
    auto depth_of = [](const Query& x) {
        fcl::DistanceRequestd req;
        req.enable_nearest_points = true;
        req.enable_signed_distance = true;
        req.gjk_solver_type = fcl::GST_LIBCCD;
        req.distance_tolerance = kTolerance;
        fcl::DistanceResultd res;
        try {
            fcl::distance(x.fa.get(), x.fb.get(), req, res);
        } catch (...) {
            return double(NAN);
        }
        return -res.min_distance;
    };
    time_depths(state, o, depth_of);
}

void BM_BulletF64Epa(benchmark::State& state) {
    const Overlap& o = overlapping(static_cast<Scenario>(state.range(0)));
    // btGjkPairDetector runs btGjkEpaPenetrationDepthSolver when GJK finds the shapes overlapping.
    auto depth_of = [](const Query& x) {
        btVoronoiSimplexSolver simplex;
        btGjkEpaPenetrationDepthSolver epa;
        btGjkPairDetector detector(x.ba.get(), x.bb.get(), &simplex, &epa);
        btGjkPairDetector::ClosestPointInput in;
        in.m_transformA = x.ta;
        in.m_transformB = x.tb;
        btPointCollector out;
        detector.getClosestPoints(in, out, nullptr);
        return out.m_hasResult ? -double(out.m_distance) : double(NAN);
    };
    time_depths(state, o, depth_of);
}

void overlap_scenarios(benchmark::internal::Benchmark* b) {
    b->ArgName("scenario");
    for (int s : {BoxBox, Hull32, CylinderCone, ParallelCylinders, CapsuleBox}) b->Arg(s);
}

void scenarios(benchmark::internal::Benchmark* b) {
    b->ArgName("scenario");
    for (int s : {BoxBox, Hull32, CylinderCone, SphereCapsule, ParallelCylinders}) b->Arg(s);
}

}  // namespace

// scenario: 0 box/box, 1 hull32/hull32, 2 cylinder/cone, 3 sphere/capsule, 5 parallel cylinders.
// tol_exp: the tolerance 10^-tol_exp (10 is the public default).
BENCHMARK(BM_KairosDistance)
    ->ArgNames({"scenario", "tol_exp"})
    ->ArgsProduct({{BoxBox, Hull32, CylinderCone, SphereCapsule}, {10, 8, 6}});
BENCHMARK(BM_KairosDistance)->ArgNames({"scenario", "tol_exp"})->Args({ParallelCylinders, 10});
BENCHMARK(BM_KairosCapiDistance)->Apply(scenarios);
BENCHMARK(BM_FclDistanceGstIndep)->Apply(scenarios);
BENCHMARK(BM_BulletF64Distance)->Apply(scenarios);
// cached: 0 fresh start, 1 the axis cached from this query's previous run.
BENCHMARK(BM_KairosIntersect)->ArgName("cached")->Arg(0)->Arg(1);
// mpr: 0 ccdGJKIntersect, 1 ccdMPRIntersect.
BENCHMARK(BM_LibccdIntersect)->ArgName("mpr")->Arg(0)->Arg(1);

// Overlapping pairs, scenario: 0 box/box, 1 hull32/hull32, 2 cylinder/cone, 5 parallel cylinders,
// 6 capsule/box.
BENCHMARK(BM_KairosSignedDistance)->ArgNames({"scenario", "tol_exp"})->ArgsProduct({{BoxBox, Hull32, CylinderCone}, {10, 11, 9, 8, 6}});
BENCHMARK(BM_KairosSignedDistance)->ArgNames({"scenario", "tol_exp"})->Args({ParallelCylinders, 10});
BENCHMARK(BM_KairosSignedDistance)->ArgNames({"scenario", "tol_exp"})->Args({CapsuleBox, 10});
BENCHMARK(BM_KairosCapiSignedDistance)->Apply(overlap_scenarios);
BENCHMARK(BM_LibccdMprPenetration)->Apply(overlap_scenarios);
BENCHMARK(BM_FclSignedDistance)->Apply(overlap_scenarios);
BENCHMARK(BM_BulletF64Epa)->Apply(overlap_scenarios);

BENCHMARK_MAIN();
