// SPDX-License-Identifier: MIT
// Bullet versions of the peer shape descriptions (Spec), exact shapes (zero margins except the
// sphere's and capsule's radius), shared by the Bullet cross-check and the GJK benchmark.
#pragma once

#include <memory>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConeShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include "gjk_peer_shapes.hpp"

namespace peer {

inline std::unique_ptr<btConvexShape> bullet_shape(const Spec& s) {
    std::unique_ptr<btConvexShape> out;
    switch (s.kind) {
        case Kind::Box:
            out = std::make_unique<btBoxShape>(btVector3(s.a, s.b, s.c));
            break;
        case Kind::Sphere:
            return std::make_unique<btSphereShape>(s.a);
        case Kind::Capsule:
            return std::make_unique<btCapsuleShapeZ>(s.a, 2 * s.b);
        case Kind::Cylinder:
            out = std::make_unique<btCylinderShapeZ>(btVector3(s.a, s.a, s.b));
            break;
        case Kind::Cone:
            out = std::make_unique<btConeShapeZ>(s.a, 2 * s.b);
            break;
        case Kind::Hull: {
            auto h = std::make_unique<btConvexHullShape>();
            for (const auto& p : s.verts) h->addPoint(btVector3(p[0], p[1], p[2]), false);
            h->recalcLocalAabb();
            out = std::move(h);
            break;
        }
    }
    out->setMargin(0);
    return out;
}

inline btTransform bullet_transform(const kairos::Transform& p) {
    const kairos::Mat3& r = p.rotation;
    return btTransform(
        btMatrix3x3(r.r[0].x, r.r[0].y, r.r[0].z, r.r[1].x, r.r[1].y, r.r[1].z, r.r[2].x, r.r[2].y, r.r[2].z),
        btVector3(p.translation.x, p.translation.y, p.translation.z));
}

}  // namespace peer
