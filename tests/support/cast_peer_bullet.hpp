// SPDX-License-Identifier: MIT
// Bullet's btSubsimplexConvexCast on the cast test shapes, for the peer cross-check and the cast
// benchmark. Compiled in the float or the double build of Bullet (btScalar), never both in one
// program. Box, cylinder, cone and hull margins are set to 0 so the shapes are exact; spheres
// and capsules keep their radius as Bullet's margin (that is their shape).
#pragma once

#include <memory>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConeShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btSubSimplexConvexCast.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include "cast_test_support.hpp"

namespace cast_peer {

inline btVector3 bt(kairos::Vec3 v) {
    return {static_cast<btScalar>(v.x), static_cast<btScalar>(v.y), static_cast<btScalar>(v.z)};
}
inline kairos::Vec3 from_bt(const btVector3& v) { return {double(v.x()), double(v.y()), double(v.z())}; }

// Bullet's shape for a cast_test body (local frame; the pose goes into the transforms).
inline std::unique_ptr<btConvexShape> bullet_shape(const cast_test::Body& b) {
    using cast_test::Kind;
    const auto s = [](long double v) { return static_cast<btScalar>(v); };
    std::unique_ptr<btConvexShape> out;
    switch (b.kind) {
        case Kind::Sphere:
            out = std::make_unique<btSphereShape>(s(b.radius));
            break;
        case Kind::Capsule:
            out = std::make_unique<btCapsuleShapeZ>(s(b.radius), s(2 * b.half));
            break;
        case Kind::Box:
            out =
                std::make_unique<btBoxShape>(btVector3(s(b.half_extents.x), s(b.half_extents.y), s(b.half_extents.z)));
            break;
        case Kind::Cylinder:
            out = std::make_unique<btCylinderShapeZ>(btVector3(s(b.radius), s(b.radius), s(b.half)));
            break;
        case Kind::Cone:
            out = std::make_unique<btConeShapeZ>(s(b.radius), s(2 * b.half));
            break;
        case Kind::Hull: {
            auto h = std::make_unique<btConvexHullShape>();
            for (const auto& p : b.verts) h->addPoint(btVector3(s(p.x), s(p.y), s(p.z)), false);
            h->recalcLocalAabb();
            out = std::move(h);
            break;
        }
        case Kind::Point:
        case Kind::Segment:
            return nullptr;  // no exact counterpart
    }
    if (b.kind != Kind::Sphere && b.kind != Kind::Capsule) out->setMargin(0);
    return out;
}

inline btScalar s_(double v) { return static_cast<btScalar>(v); }

inline btTransform bt_pose(const kairos::Transform& p, kairos::Vec3 shift = {}) {
    const kairos::Mat3& r = p.rotation;
    btMatrix3x3 m(s_(r.r[0].x), s_(r.r[0].y), s_(r.r[0].z), s_(r.r[1].x), s_(r.r[1].y), s_(r.r[1].z), s_(r.r[2].x),
                  s_(r.r[2].y), s_(r.r[2].z));
    return btTransform(m, bt(p.translation + shift));
}

// One cast with a new solver and cast object (as a caller would per query).
inline kairos::CastResult bullet_cast(const btConvexShape& a, const btConvexShape& b, const cast_test::Cast& c) {
    btVoronoiSimplexSolver simplex;
    btSubsimplexConvexCast cast(&a, &b, &simplex);
    btConvexCast::CastResult res;
    kairos::CastResult out;
    const bool hit = cast.calcTimeOfImpact(bt_pose(c.pa), bt_pose(c.pa, c.ta), bt_pose(c.pb), bt_pose(c.pb, c.tb), res);
    out.hit = hit && res.m_fraction <= btScalar(1);
    out.toi = out.hit ? double(res.m_fraction) : 1;
    // Bullet's normal points from B toward A; its hit point is on B at the hit.
    out.normal = -from_bt(res.m_normal);
    const double n = kairos::length(out.normal);
    if (n > 0) out.normal = out.normal / n;
    out.point = from_bt(res.m_hitPoint);
    return out;
}

}  // namespace cast_peer
