// SPDX-License-Identifier: MIT
// FCL's continuousCollide (translation motion, conservative advancement, GST_INDEP) on the cast
// test shapes, every call guarded in a forked child: the Debian build can abort, and some of its
// paths throw. For the peer cross-check and the cast benchmark.
#pragma once

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <memory>
#include <vector>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/continuous_collision.h>

#include "cast_test_support.hpp"

namespace cast_peer {

inline std::shared_ptr<fcl::CollisionGeometryd> fcl_shape(const cast_test::Body& b) {
    using cast_test::Kind;
    const auto d = [](long double v) { return static_cast<double>(v); };
    switch (b.kind) {
        case Kind::Sphere:
            return std::make_shared<fcl::Sphered>(d(b.radius));
        case Kind::Capsule:
            return std::make_shared<fcl::Capsuled>(d(b.radius), d(2 * b.half));
        case Kind::Box:
            return std::make_shared<fcl::Boxd>(d(2 * b.half_extents.x), d(2 * b.half_extents.y),
                                               d(2 * b.half_extents.z));
        case Kind::Cylinder:
            return std::make_shared<fcl::Cylinderd>(d(b.radius), d(2 * b.half));
        case Kind::Cone:
            return std::make_shared<fcl::Coned>(d(b.radius), d(2 * b.half));
        case Kind::Hull: {
            auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
            for (const auto& p : b.verts) verts->emplace_back(d(p.x), d(p.y), d(p.z));
            auto faces = std::make_shared<std::vector<int>>();
            for (const auto& f : b.local_poly.faces) {
                faces->push_back(3);
                for (int i : f) faces->push_back(i);
            }
            return std::make_shared<fcl::Convexd>(verts, static_cast<int>(b.local_poly.faces.size()), faces);
        }
        default:
            return nullptr;
    }
}

inline fcl::Transform3d fcl_pose(const kairos::Transform& p, kairos::Vec3 shift = {}) {
    fcl::Transform3d t = fcl::Transform3d::Identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) t.linear()(i, j) = p.rotation.r[i][j];
    const kairos::Vec3 x = p.translation + shift;
    t.translation() = fcl::Vector3d(x.x, x.y, x.z);
    return t;
}

struct FclOut {
    int status = 0;  // 0 answered, 1 threw, 2 the process died (abort, signal)
    int hit = 0;
    double toi = 1;
    double seconds = 0;  // time of the call in the child
};

// One cast (translation, conservative advancement, GST_INDEP, FCL's other defaults).
inline FclOut fcl_cast(const fcl::CollisionGeometryd* a, const fcl::CollisionGeometryd* b, const cast_test::Cast& c) {
    fcl::ContinuousCollisionRequestd req;
    req.ccd_motion_type = fcl::CCDM_TRANS;
    req.gjk_solver_type = fcl::GST_INDEP;
    req.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
    fcl::ContinuousCollisionResultd res;
    FclOut out;
    const auto t0 = std::chrono::steady_clock::now();
    try {
        fcl::continuousCollide(a, fcl_pose(c.pa), fcl_pose(c.pa, c.ta), b, fcl_pose(c.pb), fcl_pose(c.pb, c.tb), req,
                               res);
        out.hit = res.is_collide ? 1 : 0;
        out.toi = res.is_collide ? res.time_of_contact : 1;
    } catch (...) {
        out.status = 1;
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
}

// Runs fn(i) for i in [0, n) in forked children, streaming results through a pipe. A child that
// dies marks its current index as status 2 and a new child goes on from the next one.
inline std::vector<FclOut> run_guarded(int n, const std::function<FclOut(int)>& fn) {
    std::vector<FclOut> out(static_cast<size_t>(n));
    int next = 0;
    while (next < n) {
        int fd[2];
        if (pipe(fd) != 0) break;
        const pid_t pid = fork();
        if (pid < 0) break;
        if (pid == 0) {
            close(fd[0]);
            for (int i = next; i < n; ++i) {
                const FclOut r = fn(i);
                if (write(fd[1], &r, sizeof r) != static_cast<ssize_t>(sizeof r)) _exit(3);
            }
            _exit(0);
        }
        close(fd[1]);
        FclOut r;
        while (next < n && read(fd[0], &r, sizeof r) == static_cast<ssize_t>(sizeof r))
            out[static_cast<size_t>(next++)] = r;
        close(fd[0]);
        int st = 0;
        waitpid(pid, &st, 0);
        if (next < n) out[static_cast<size_t>(next++)].status = 2;  // the child died on this one
    }
    return out;
}

}  // namespace cast_peer
