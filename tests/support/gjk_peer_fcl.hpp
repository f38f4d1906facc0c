// SPDX-License-Identifier: MIT
// FCL versions of the peer shape descriptions (Spec), shared by the FCL cross-checks and the GJK
// benchmark: one construction, so tests and benchmark compare the same geometry.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>

#include "gjk_peer_shapes.hpp"

namespace peer {

inline std::shared_ptr<fcl::CollisionGeometryd> fcl_geometry(const Spec& s) {
    switch (s.kind) {
        case Kind::Box:
            return std::make_shared<fcl::Boxd>(2 * s.a, 2 * s.b, 2 * s.c);
        case Kind::Sphere:
            return std::make_shared<fcl::Sphered>(s.a);
        case Kind::Capsule:
            return std::make_shared<fcl::Capsuled>(s.a, 2 * s.b);
        case Kind::Cylinder:
            return std::make_shared<fcl::Cylinderd>(s.a, 2 * s.b);
        case Kind::Cone:
            return std::make_shared<fcl::Coned>(s.a, 2 * s.b);
        case Kind::Hull: {
            auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
            for (const auto& p : s.verts) verts->emplace_back(p[0], p[1], p[2]);
            auto faces = std::make_shared<std::vector<int>>();
            const auto& poly = s.local_poly;
            for (size_t f = 0; f < poly.faces.size(); ++f) {
                auto t = poly.faces[f];
                const oracle::P3 n = oracle::cross(poly.v[t[1]] - poly.v[t[0]], poly.v[t[2]] - poly.v[t[0]]);
                if (oracle::dot(n, poly.normals[f]) < 0) std::swap(t[1], t[2]);
                faces->insert(faces->end(), {3, t[0], t[1], t[2]});
            }
            return std::make_shared<fcl::Convexd>(verts, static_cast<int>(poly.faces.size()), faces);
        }
    }
    return nullptr;
}

inline fcl::Transform3d fcl_transform(const kairos::Transform& p) {
    fcl::Transform3d t = fcl::Transform3d::Identity();
    fcl::Matrix3d r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r(i, j) = p.rotation.r[i][j];
    t.linear() = r;
    t.translation() = fcl::Vector3d(p.translation.x, p.translation.y, p.translation.z);
    return t;
}

}  // namespace peer
