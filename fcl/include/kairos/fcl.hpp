// SPDX-License-Identifier: MIT
// kairos_fcl: FCL's shapes, poses and motions read as Kairos's, and checks of FCL's answers
// against Kairos (Kairos as a regression reference for FCL). Optional C++ library, never part of
// libkairos or kairos.h; see docs/fcl-regression.md.
//
// Conventions (FCL 0.7; each conversion below states its own):
//   - sizes: FCL Box takes full side lengths, Kairos half extents; FCL Capsule, Cylinder and Cone
//     take the full length lz along local z, Kairos the half height; a Capsule's lz excludes the caps;
//   - frames: both are centred at the local origin, axis z; FCL's Cone has its apex at +lz/2 and its
//     base at -lz/2 (its origin is the axis midpoint, as in Kairos, not its centre of mass);
//   - rotations: Eigen's Quaterniond(w, x, y, z) constructor is w first, its coeffs() are
//     (x, y, z, w); kairos_quat is {x, y, z, w};
//   - Ellipsoid has no Kairos primitive: a unit sphere mapped by diag(radii);
//   - Convex: the hull of its vertices (faces are not read).
//
// Thread safety: every function is reentrant and shapes are immutable (share them freely); a
// Reference computes on first use, so one Reference is used by one thread at a time.
#pragma once

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <fcl/common/types.h>
#include <fcl/geometry/collision_geometry.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>
#include <fcl/narrowphase/continuous_collision_request.h>
#include <fcl/narrowphase/continuous_collision_result.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

#include "kairos/kairos.h"

namespace kairos::fcl_check {

// One reference to an immutable kairos_shape; copies retain, destruction releases.
class Shape {
public:
    Shape() noexcept = default;
    explicit Shape(kairos_shape* adopted) noexcept : shape_(adopted) {}
    Shape(const Shape& other) noexcept;
    Shape& operator=(const Shape& other) noexcept;
    Shape(Shape&& other) noexcept;
    Shape& operator=(Shape&& other) noexcept;
    ~Shape();
    kairos_shape* get() const noexcept { return shape_; }
    explicit operator bool() const noexcept { return shape_ != nullptr; }

private:
    kairos_shape* shape_ = nullptr;
};

// Input Kairos cannot represent: an unbounded or unsupported FCL geometry (Plane, Halfspace,
// BVHModel, OcTree), a size Kairos refuses (zero radius, zero cylinder length), or a transform
// whose linear part is not a rotation.
class ConversionError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

// The Kairos shape of an FCL geometry, in the same local frame: Sphere, Box, Capsule, Cylinder,
// Cone, Ellipsoid, Convex and TriangleP. Throws ConversionError for any other geometry.
Shape to_kairos(const fcl::CollisionGeometryd& geometry);

// The Kairos pose of an FCL transform: position = translation, orientation = the unit quaternion
// of the linear part. Throws ConversionError when the linear part is not a rotation (orthonormal
// with determinant +1, within 1e-9 per entry).
kairos_pose to_kairos(const fcl::Transform3d& transform);

// The FCL transform of a Kairos pose (the quaternion normalised first).
fcl::Transform3d to_fcl(const kairos_pose& pose);

// Bounding radius of a shape about its local origin: the distance from the origin to the
// farthest corner of its local bounding box (the size the tolerances below scale with).
double bounding_radius(const kairos_shape* shape);

// A point of shape at pose farthest along direction (world frame; any non-zero length).
kairos_vec3 world_support(const kairos_shape* shape, const kairos_pose& pose, kairos_vec3 direction);

// How FCL moves a shape between two transforms under a CCDMotionType, read as a kairos_motion.
struct Motion {
    // true: FCL's motion is the motion below (to rounding), so the two casts answer the same
    // question; false: they differ and no FCL answer for it is judged (note says how).
    bool same = false;
    // Kairos's motion: the origin moves linearly from start.position to end.position and turns at
    // constant rate along the shortest arc between the orientations (kairos.h, kairos_motion).
    // When same is false this is the motion the caller presumably meant (begin to end).
    kairos_motion motion{};
    // true when start and end orientations are equal: kairos_shape_cast answers exactly.
    bool translation_only = false;
    // Empty, or what FCL does differently (or ignores, e.g. CCDM_TRANS drops the end rotation).
    std::string note;
};
Motion map_motion(const fcl::Transform3d& begin, const fcl::Transform3d& end, fcl::CCDMotionType type);

// ---- Verdicts ------------------------------------------------------------------------------------

enum class Outcome {
    Agree,      // FCL's answer lies within the tolerance of the truth's bounds
    FclOff,     // FCL's answer lies outside them by `error`
    NotJudged,  // the truth lies within the tolerance band (a touching pair), or the question differs
};
const char* to_string(Outcome outcome);

// The band a correct FCL answer must lie in: relative * size + absolute + FCL's own tolerance of
// the request (distance_tolerance, gjk_tolerance, abs_err and rel_err), plus 1e-14 of the
// positions' magnitude for rounding. size: the larger bounding radius of the two shapes.
struct Tolerance {
    double relative = 1e-6;
    double absolute = 0;
};

struct Verdict {
    Outcome outcome = Outcome::NotJudged;
    // "distance", "nearest points", "collision" or "time of contact".
    std::string quantity;
    // FCL's answer and Kairos's, in the quantity's unit: a length (distance; nearest points:
    // FCL's |p1 - p0|), 1 or 0 (collision), a fraction of the step in [0, 1] (time of contact;
    // 1 for no contact).
    double fcl = std::numeric_limits<double>::quiet_NaN();
    double kairos = std::numeric_limits<double>::quiet_NaN();
    // Certified bounds of the true value where Kairos can give them (NaN otherwise): the
    // distance lies between the gap along Kairos's separating axis (support functions evaluated
    // at that axis) and |point_b - point_a| of Kairos's closest points. For collision, the bounds
    // of the distance when the pair is apart. For time of contact, the window a right answer
    // lies in where a verdict found one: upper, a time at which the shapes overlap by more than
    // the band (contact must be reported by then); lower, for an early answer, the last time
    // before Kairos's contact at which they are still apart by the early band; naive: both the
    // expected sample time.
    double lower = std::numeric_limits<double>::quiet_NaN();
    double upper = std::numeric_limits<double>::quiet_NaN();
    // How far FCL's answer lies beyond what is allowed, in the quantity's unit (0 unless FclOff;
    // for collision, the distance or depth that makes the verdict clear).
    double error = 0;
    double tolerance = 0;  // the band used, a length (time of contact: see check_continuous)
    std::string detail;    // one line for a report
};
std::string to_string(const Verdict& verdict);

// Kairos's answers for one posed pair, computed on first use and shared by the checks below.
class Reference {
public:
    // Throws ConversionError as to_kairos does.
    Reference(const fcl::CollisionGeometryd& a, const fcl::Transform3d& transform_a, const fcl::CollisionGeometryd& b,
              const fcl::Transform3d& transform_b);
    Reference(Shape a, const kairos_pose& pose_a, Shape b, const kairos_pose& pose_b);

    // FCL's min_distance against the certified bounds. A negative FCL distance reads as "the
    // shapes intersect" (FCL returns -1 then unless enable_signed_distance); with
    // enable_signed_distance, a negative answer is compared with Kairos's signed distance (not
    // certified). Judged when the truth is clear of the band around 0 or FCL claims a distance.
    Verdict check_distance(const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                           const Tolerance& tolerance = {}) const;
    // FCL's nearest_points (world frame): each on its shape within the band, |p1 - p0| equal to
    // FCL's min_distance and to the true distance. Judged when the request enabled nearest points
    // and both FCL and Kairos have the shapes clearly apart.
    Verdict check_nearest_points(const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                                 const Tolerance& tolerance = {}) const;
    // FCL's isCollision() against the signed distance, judged when it is clear of the band.
    Verdict check_collision(const fcl::CollisionRequestd& request, const fcl::CollisionResultd& result,
                            const Tolerance& tolerance = {}) const;

    // Kairos's distance result (kairos_distance at tolerance 1e-12) and signed distance.
    const kairos_distance_result& distance() const;
    double signed_distance() const;
    // Certified bounds of the distance (both 0 when the shapes intersect).
    double lower_bound() const;
    double upper_bound() const;
    // The larger bounding radius of the two shapes.
    double size() const { return size_; }
    const kairos_shape* shape_a() const { return a_.get(); }
    const kairos_shape* shape_b() const { return b_.get(); }
    const kairos_pose& pose_a() const { return pose_a_; }
    const kairos_pose& pose_b() const { return pose_b_; }

private:
    void compute() const;
    double band(double fcl_tolerance) const;

    Shape a_, b_;
    kairos_pose pose_a_{}, pose_b_{};
    double size_ = 0;
    mutable bool computed_ = false;
    mutable kairos_distance_result distance_{};
    mutable double signed_ = 0, lower_ = 0, upper_ = 0;
};

// Convenience forms that build the Reference once for the call.
Verdict check_distance(const fcl::CollisionGeometryd& a, const fcl::Transform3d& transform_a,
                       const fcl::CollisionGeometryd& b, const fcl::Transform3d& transform_b,
                       const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                       const Tolerance& tolerance = {});
Verdict check_distance(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b,
                       const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                       const Tolerance& tolerance = {});
Verdict check_nearest_points(const fcl::CollisionGeometryd& a, const fcl::Transform3d& transform_a,
                             const fcl::CollisionGeometryd& b, const fcl::Transform3d& transform_b,
                             const fcl::DistanceRequestd& request, const fcl::DistanceResultd& result,
                             const Tolerance& tolerance = {});
Verdict check_collision(const fcl::CollisionGeometryd& a, const fcl::Transform3d& transform_a,
                        const fcl::CollisionGeometryd& b, const fcl::Transform3d& transform_b,
                        const fcl::CollisionRequestd& request, const fcl::CollisionResultd& result,
                        const Tolerance& tolerance = {});
Verdict check_collision(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b,
                        const fcl::CollisionRequestd& request, const fcl::CollisionResultd& result,
                        const Tolerance& tolerance = {});

// FCL's continuousCollide(a, begin_a, end_a, b, begin_b, end_b, request, result) against Kairos.
// Judged only when map_motion says both motions are the same as Kairos's (CCDM_TRANS always;
// CCDM_SCREW when each translation lies along its rotation axis) and the solver is
// CCDC_CONSERVATIVE_ADVANCEMENT or CCDC_NAIVE; otherwise NotJudged with the reason.
// The truth is the signed distance s(t) along the motion (kairos_signed_distance at time t):
//   - conservative advancement must report contact at a time where s <= band + 1e-3 times the
//     motion's reach (ten times FCL's fixed advancement threshold t_err = 1e-4: an early answer
//     is conservative, not wrong), with no time before it where s < -band, and report a miss only
//     when s >= -band throughout;
//   - naive samples n = min(num_max_iterations, ceil(1 / toc_err)) times t_i = i / (n - 1) and
//     must report the first sample where the shapes intersect: a contact between samples is
//     missed by design and is not an error.
// Each FclOff verdict carries a witness time in its detail (an earlier time of clear overlap, or
// the gap at FCL's time). kairos: Kairos's time of impact (naive: the expected sample time).
Verdict check_continuous(const fcl::CollisionGeometryd& a, const fcl::Transform3d& begin_a,
                         const fcl::Transform3d& end_a, const fcl::CollisionGeometryd& b,
                         const fcl::Transform3d& begin_b, const fcl::Transform3d& end_b,
                         const fcl::ContinuousCollisionRequestd& request,
                         const fcl::ContinuousCollisionResultd& result, const Tolerance& tolerance = {});

}  // namespace kairos::fcl_check
