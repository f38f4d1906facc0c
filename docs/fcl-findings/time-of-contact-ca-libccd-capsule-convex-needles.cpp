// Reproducer for FCL 0.7.0: continuous (GST_LIBCCD, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a capsule and a convex: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.4947588274219626.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 36288 (family needles), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-libccd-capsule-convex-needles.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/continuous_collision.h>

namespace {

// A rigid transform from the unit quaternion (w, x, y, z) and the translation (x, y, z).
fcl::Transform3d pose(double qw, double qx, double qy, double qz, double x, double y, double z) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = fcl::Quaterniond(qw, qx, qy, qz).toRotationMatrix();
  tf.translation() = fcl::Vector3d(x, y, z);
  return tf;
}

}  // namespace

TEST(KairosFound, TimeOfContactCaGstLibccdCapsuleConvexNeedles) {
  const auto a = std::make_shared<fcl::Capsuled>(0.005779, 2);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.004495, -0.002365, -0.009218),
      fcl::Vector3d(0.001831, 0.002693, -0.6765),
      fcl::Vector3d(-0.001958, 0.003539, 0.6259),
      fcl::Vector3d(-0.0003098, 0.001274, 0.8191),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 2, 1, 0,
      3, 2, 3, 1,
      3, 2, 0, 3,
      3, 1, 3, 0,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 4, b_faces);
  const fcl::Transform3d tf_a0 = pose(-0.1805060091450683, -0.8374278784381175, 0.4896162995979249, 0.16250540989514461, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(-0.1805060091450683, -0.8374278784381175, 0.4896162995979249, 0.16250540989514461, 0.5928, -0.14, -0.1229);
  const fcl::Transform3d tf_b0 = pose(0.34328465515842316, -0.015889289747938667, 0.47507876395504467, 0.8100637901073073, 0.3811, -0.7678, 0.4192);
  const fcl::Transform3d tf_b1 = pose(0.34328465515842316, -0.015889289747938667, 0.47507876395504467, 0.8100637901073073, 0.6226, -0.3662, 0.3218);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.49475567246662305.
  // The shapes overlap by more than the tolerance at time 0.4947588274219626: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.4947588274219626);
}
