// SPDX-License-Identifier: MIT
// Cast benchmark: Kairos's shape cast over a range of tolerances against Bullet's double build
// (btSubsimplexConvexCast) and FCL (continuousCollide, translation, conservative advancement,
// GST_INDEP) on the same fixed random sets, in one program and one run. Writes CSV rows: median ns
// per cast, mean iterations, and the time-of-impact, normal-angle and contact-point errors
// (median, max) against the long double oracle; and the public kairos_shape_cast at its defaults
// (row kairos_capi) beside the core. Bullet's float build runs in bench_cast_bullet32.
//   bench_cast [out.csv]      (default: standard output)
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "cast_bench_common.hpp"
#include "cast_peer_bullet.hpp"
#include "cast_peer_fcl.hpp"
#include "capi_poses.hpp"
#include "casts/cast.hpp"
#include "kairos/kairos.h"

using namespace cast_bench;

namespace {

struct ShapeRelease {
    void operator()(kairos_shape* s) const { kairos_shape_release(s); }
};
using CShape = std::unique_ptr<kairos_shape, ShapeRelease>;

// The C API's shape for a scenario's body (the kinds the scenarios use).
CShape c_shape(const cast_oracle::Body& b) {
    using cast_oracle::Kind;
    kairos_shape* out = nullptr;
    int32_t status = KAIROS_ERROR_INVALID_ARGUMENT;
    const double r = double(b.radius), h = double(b.half);
    switch (b.kind) {
        case Kind::Sphere:
            status = kairos_shape_sphere(r, &out);
            break;
        case Kind::Box:
            status = kairos_shape_box({double(b.half_extents.x), double(b.half_extents.y), double(b.half_extents.z)}, &out);
            break;
        case Kind::Capsule:
            status = kairos_shape_capsule(r, h, &out);
            break;
        case Kind::Cylinder:
            status = kairos_shape_cylinder(r, h, &out);
            break;
        case Kind::Cone:
            status = kairos_shape_cone(r, h, &out);
            break;
        case Kind::Hull: {
            std::vector<kairos_vec3> p;
            for (const auto& v : b.verts) p.push_back({double(v.x), double(v.y), double(v.z)});
            status = kairos_shape_convex_hull(p.data(), p.size(), &out);
            break;
        }
        default:
            break;
    }
    if (status != KAIROS_OK) {
        std::fprintf(stderr, "bench_cast: the C API rejected a shape: %s\n", kairos_last_error());
        std::abort();
    }
    return CShape(out);
}

}  // namespace

int main(int argc, char** argv) {
    FILE* out = open_output(argc, argv);
    if (!out) return 2;
    csv_header(out);
    const double tolerances[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-10, 1e-12};
    for (const Scenario& sc : kScenarios) {
        const std::vector<Item> set = make_set(sc);
        const int n = static_cast<int>(set.size());
        std::vector<kairos::CastResult> res(set.size());

        // Kairos (the kairos_restart rows of results/cast.csv came from a clip policy since removed).
        for (const double tol : tolerances) {
            auto one = [&](size_t i) {
                const Item& x = set[i];
                res[i] = kairos::shape_cast(*x.a.shape, x.c.pa, x.c.ta, *x.b.shape, x.c.pb, x.c.tb, tol, 256);
                benchmark::DoNotOptimize(res[i]);
            };
            const Timing ns = time_casts(one, set.size());
            csv_row(out, sc.name, "kairos", tol, ns, summarize(set, res, true, true, true, tol));
        }

        // The same casts through the public C API at its default settings (tolerance 1e-10):
        // argument checks, quaternion to matrix, result conversion included.
        {
            std::vector<CShape> ca, cb;
            std::vector<kairos_pose> pa, pb;
            for (const Item& x : set) {
                ca.push_back(c_shape(x.a.body));
                cb.push_back(c_shape(x.b.body));
                pa.push_back(c_pose(x.c.pa));
                pb.push_back(c_pose(x.c.pb));
            }
            auto one = [&](size_t i) {
                const Item& x = set[i];
                kairos_cast_result r;
                const int32_t status =
                    kairos_shape_cast(ca[i].get(), &pa[i], {x.c.ta.x, x.c.ta.y, x.c.ta.z}, cb[i].get(), &pb[i],
                                      {x.c.tb.x, x.c.tb.y, x.c.tb.z}, nullptr, &r);
                benchmark::DoNotOptimize(status);
                res[i] = kairos::CastResult{};
                res[i].hit = status == KAIROS_OK && r.hit;
                res[i].toi = r.toi;
                res[i].point = {r.point.x, r.point.y, r.point.z};
                res[i].normal = {r.normal.x, r.normal.y, r.normal.z};
                res[i].iterations = r.iterations;
            };
            const Timing ns = time_casts(one, set.size());
            csv_row(out, sc.name, "kairos_capi", 1e-10, ns, summarize(set, res, true, true, true, 1e-10));
        }

        // Bullet f64: shapes made beforehand; a new solver and cast object per query.
        {
            std::vector<std::unique_ptr<btConvexShape>> sa, sb;
            for (const Item& x : set) {
                sa.push_back(cast_peer::bullet_shape(x.a.body));
                sb.push_back(cast_peer::bullet_shape(x.b.body));
            }
            auto one = [&](size_t i) {
                res[i] = cast_peer::bullet_cast(*sa[i], *sb[i], set[i].c);
                benchmark::DoNotOptimize(res[i]);
            };
            const Timing ns = time_casts(one, set.size());
            csv_row(out, sc.name, "bullet64", double(MAX_CONVEX_CAST_EPSILON), ns,
                    summarize(set, res, true, false, false));
        }

        // FCL conservative advancement, in forked children; time per call measured in the child.
        {
            std::vector<std::shared_ptr<fcl::CollisionGeometryd>> ga, gb;
            for (const Item& x : set) {
                ga.push_back(cast_peer::fcl_shape(x.a.body));
                gb.push_back(cast_peer::fcl_shape(x.b.body));
            }
            // Per cast: the fastest of 5 calls (each in the guarded child); median over the casts.
            std::vector<double> per(set.size(), 1e300);
            std::vector<cast_peer::FclOut> first;
            for (int rep = 0; rep < 5; ++rep) {
                const auto r = cast_peer::run_guarded(n, [&](int i) {
                    return cast_peer::fcl_cast(ga[size_t(i)].get(), gb[size_t(i)].get(), set[size_t(i)].c);
                });
                for (size_t i = 0; i < set.size(); ++i) per[i] = std::min(per[i], 1e9 * r[i].seconds);
                if (rep == 0) first = r;
            }
            Timing ns;
            for (double x : per) ns.mean += x;
            ns.mean /= n;
            ns.median = median(per);
            for (size_t i = 0; i < set.size(); ++i) {
                res[i] = kairos::CastResult{};
                res[i].hit = first[i].status == 0 && first[i].hit;
                res[i].toi = first[i].toi;
            }
            csv_row(out, sc.name, "fcl_ca", 1e-4, ns, summarize(set, res, false, false, false));
        }
    }
    if (out != stdout) std::fclose(out);
    return 0;
}
