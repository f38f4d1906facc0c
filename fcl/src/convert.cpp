// SPDX-License-Identifier: MIT
// FCL geometries, transforms and continuous motions read as Kairos shapes, poses and motions
// (the conventions table of docs/fcl-regression.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>

#include "kairos/fcl.hpp"

namespace kairos::fcl_check {

Shape::Shape(const Shape& other) noexcept : shape_(other.shape_) { kairos_shape_retain(shape_); }
Shape& Shape::operator=(const Shape& other) noexcept {
    if (this != &other) {
        kairos_shape_retain(other.shape_);
        kairos_shape_release(shape_);
        shape_ = other.shape_;
    }
    return *this;
}
Shape::Shape(Shape&& other) noexcept : shape_(other.shape_) { other.shape_ = nullptr; }
Shape& Shape::operator=(Shape&& other) noexcept {
    if (this != &other) {
        kairos_shape_release(shape_);
        shape_ = other.shape_;
        other.shape_ = nullptr;
    }
    return *this;
}
Shape::~Shape() { kairos_shape_release(shape_); }

namespace {

// A Kairos constructor's status turned into a Shape or a ConversionError naming the FCL geometry.
// out is read only after the constructor has run (argument order is unspecified).
Shape made(int32_t status, kairos_shape* const* out, const char* what) {
    if (status != KAIROS_OK)
        throw ConversionError(std::string(what) + ": Kairos refused it (" + kairos_status_name(status) + ": " +
                              kairos_last_error() + ")");
    return Shape(*out);
}

kairos_vec3 kv(const fcl::Vector3d& v) { return {v[0], v[1], v[2]}; }

Eigen::Matrix3d rotation_of(const kairos_quat& q) {
    return Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

}  // namespace

Shape to_kairos(const fcl::CollisionGeometryd& geometry) {
    kairos_shape* s = nullptr;
    switch (geometry.getNodeType()) {
        case fcl::GEOM_SPHERE: {
            const auto& g = static_cast<const fcl::Sphered&>(geometry);
            return made(kairos_shape_sphere(g.radius, &s), &s, "fcl::Sphere");
        }
        case fcl::GEOM_BOX: {
            // FCL: full side lengths; Kairos: half extents.
            const auto& g = static_cast<const fcl::Boxd&>(geometry);
            return made(kairos_shape_box({g.side[0] / 2, g.side[1] / 2, g.side[2] / 2}, &s), &s, "fcl::Box");
        }
        case fcl::GEOM_CAPSULE: {
            // FCL: lz is the length of the core segment (caps excluded), centred on the origin.
            const auto& g = static_cast<const fcl::Capsuled&>(geometry);
            return made(kairos_shape_capsule(g.radius, g.lz / 2, &s), &s, "fcl::Capsule");
        }
        case fcl::GEOM_CYLINDER: {
            const auto& g = static_cast<const fcl::Cylinderd&>(geometry);
            return made(kairos_shape_cylinder(g.radius, g.lz / 2, &s), &s, "fcl::Cylinder");
        }
        case fcl::GEOM_CONE: {
            // Both: apex at +lz/2 on z, base disk at -lz/2, origin at the axis midpoint.
            const auto& g = static_cast<const fcl::Coned&>(geometry);
            return made(kairos_shape_cone(g.radius, g.lz / 2, &s), &s, "fcl::Cone");
        }
        case fcl::GEOM_ELLIPSOID: {
            const auto& g = static_cast<const fcl::Ellipsoidd&>(geometry);
            kairos_shape* unit = nullptr;
            const Shape ball = made(kairos_shape_sphere(1, &unit), &unit, "fcl::Ellipsoid");
            const double diag[9] = {g.radii[0], 0, 0, 0, g.radii[1], 0, 0, 0, g.radii[2]};
            return made(kairos_shape_transformed(ball.get(), diag, {0, 0, 0}, &s), &s, "fcl::Ellipsoid");
        }
        case fcl::GEOM_CONVEX: {
            // The hull of the vertices; FCL's faces only steer its own support search.
            const auto& g = static_cast<const fcl::Convexd&>(geometry);
            std::vector<kairos_vec3> points;
            points.reserve(g.getVertices().size());
            for (const auto& v : g.getVertices()) points.push_back(kv(v));
            return made(kairos_shape_convex_hull(points.data(), points.size(), &s), &s, "fcl::Convex");
        }
        case fcl::GEOM_TRIANGLE: {
            const auto& g = static_cast<const fcl::TrianglePd&>(geometry);
            return made(kairos_shape_triangle(kv(g.a), kv(g.b), kv(g.c), &s), &s, "fcl::TriangleP");
        }
        case fcl::GEOM_PLANE:
        case fcl::GEOM_HALFSPACE:
            throw ConversionError("fcl::Plane and fcl::Halfspace are unbounded: Kairos has no such shape");
        default:
            throw ConversionError("FCL geometry of node type " + std::to_string(int(geometry.getNodeType())) +
                                  " (a BVH model or an octree) has no Kairos shape: only convex primitives convert");
    }
}

kairos_pose to_kairos(const fcl::Transform3d& transform) {
    const Eigen::Matrix3d r = transform.linear();
    const Eigen::Vector3d t = transform.translation();
    if (!r.allFinite() || !t.allFinite()) throw ConversionError("fcl::Transform3d with a NaN or infinite entry");
    const double off = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (!(off <= 1e-9) || r.determinant() <= 0)
        throw ConversionError("fcl::Transform3d whose linear part is not a rotation (|R^T R - I| = " + number(off) +
                              ", det " + number(r.determinant()) + ")");
    Eigen::Quaterniond q(r);
    q.normalize();
    return {{t[0], t[1], t[2]}, {q.x(), q.y(), q.z(), q.w()}};
}

fcl::Transform3d to_fcl(const kairos_pose& pose) {
    fcl::Transform3d t = fcl::Transform3d::Identity();
    t.linear() = rotation_of(pose.orientation);
    t.translation() = fcl::Vector3d(pose.position.x, pose.position.y, pose.position.z);
    return t;
}

double bounding_radius(const kairos_shape* shape) {
    kairos_vec3 lo{}, hi{};
    if (kairos_shape_bounds(shape, nullptr, &lo, &hi) != KAIROS_OK) return 0;
    const double x = std::max(std::fabs(lo.x), std::fabs(hi.x));
    const double y = std::max(std::fabs(lo.y), std::fabs(hi.y));
    const double z = std::max(std::fabs(lo.z), std::fabs(hi.z));
    return std::sqrt(x * x + y * y + z * z);
}

kairos_vec3 world_support(const kairos_shape* shape, const kairos_pose& pose, kairos_vec3 direction) {
    const Eigen::Matrix3d r = rotation_of(pose.orientation);
    const Eigen::Vector3d local = r.transpose() * Eigen::Vector3d(direction.x, direction.y, direction.z);
    kairos_vec3 s{};
    kairos_shape_support(shape, {local[0], local[1], local[2]}, &s);
    const Eigen::Vector3d w = r * Eigen::Vector3d(s.x, s.y, s.z);
    return {w[0] + pose.position.x, w[1] + pose.position.y, w[2] + pose.position.z};
}

Motion map_motion(const fcl::Transform3d& begin, const fcl::Transform3d& end, fcl::CCDMotionType type) {
    Motion m;
    m.motion.start = to_kairos(begin);
    m.motion.end = to_kairos(end);
    // FCL's own reading of the turn (its InterpMotion and ScrewMotion use this angle and axis).
    const Eigen::AngleAxisd turn(Eigen::Matrix3d(end.linear() * begin.linear().transpose()));
    const double angle = std::fabs(turn.angle());
    const Eigen::Vector3d d = end.translation() - begin.translation();
    const kairos_quat qa = m.motion.start.orientation, qb = m.motion.end.orientation;
    const bool equal_q = (qa.x == qb.x && qa.y == qb.y && qa.z == qb.z && qa.w == qb.w) ||
                         (qa.x == -qb.x && qa.y == -qb.y && qa.z == -qb.z && qa.w == -qb.w);
    m.translation_only = equal_q;
    switch (type) {
        case fcl::CCDM_TRANS:
            // TranslationMotion keeps the begin rotation for the whole step.
            m.same = true;
            m.translation_only = true;
            if (!equal_q) {
                m.motion.end.orientation = m.motion.start.orientation;
                m.note = "CCDM_TRANS keeps the begin rotation and ignores the end transform's turn of " +
                         number(angle) + " rad";
            }
            return m;
        case fcl::CCDM_LINEAR:
            m.same = false;
            m.note =
                "CCDM_LINEAR: FCL 0.7's InterpMotion built from two transforms leaves its reference point "
                "uninitialised, so its path is undefined (with the reference point at the origin it would be "
                "Kairos's motion)";
            return m;
        case fcl::CCDM_SCREW: {
            if (angle < 1e-10) {
                // ScrewMotion without a turn advances along d by t * |d|: the translation scaled by its length.
                const double len = d.norm();
                m.same = len == 0 || std::fabs(len - 1) <= 1e-12;
                if (!m.same)
                    m.note = "CCDM_SCREW without rotation moves the origin by |d| d, not d (|d| = " + number(len) +
                             "): the end transform is not reached";
                return m;
            }
            if (angle > M_PI - 1e-9) {
                m.same = false;
                m.note = "CCDM_SCREW by a half turn: the turning direction is ambiguous";
                return m;
            }
            // The origin moves on a line exactly when it lies on the screw axis, i.e. when the
            // translation is along the rotation axis.
            const Eigen::Vector3d axis = turn.axis().normalized();
            const double across = (d - d.dot(axis) * axis).norm();
            m.same = across <= 1e-12 * std::max(1.0, d.norm());
            if (!m.same)
                m.note = "CCDM_SCREW turns about an axis that misses the origin (translation " + number(across) +
                         " across the rotation axis): the origin follows a helix, Kairos's moves on a line";
            return m;
        }
        case fcl::CCDM_SPLINE:
            m.same = false;
            m.note = "CCDM_SPLINE from two transforms is not implemented in FCL 0.7";
            return m;
    }
    m.same = false;
    m.note = "unknown CCDMotionType " + std::to_string(int(type));
    return m;
}

}  // namespace kairos::fcl_check
