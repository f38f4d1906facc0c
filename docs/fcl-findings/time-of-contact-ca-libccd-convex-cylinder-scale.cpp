// Reproducer for FCL 0.7.0: continuous (GST_LIBCCD, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a convex and a cylinder: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.3039272097129825.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 9436 (family scale), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-libccd-convex-cylinder-scale.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
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

TEST(KairosFound, TimeOfContactCaGstLibccdConvexCylinderScale) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.0003, -3e-05, 0.0005),
      fcl::Vector3d(-0.0005, 0.0006, 0.0001),
      fcl::Vector3d(0.0007, -5e-05, 0.0002),
      fcl::Vector3d(0.0003, -0.0009, 0.0002),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 1, 2, 3,
      3, 1, 3, 0,
      3, 1, 0, 2,
      3, 3, 2, 0,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 4, a_faces);
  const auto b = std::make_shared<fcl::Cylinderd>(0.0006, 0.002);
  const fcl::Transform3d tf_a0 = pose(1, 0, 0, 0, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(1, 0, 0, 0, -0.0008, 0.0003, -0.0007);
  const fcl::Transform3d tf_b0 = pose(-0.20203050891044216, 0.30304576336566325, -0.7071067811865476, -0.6060915267313265, -0.0008, 0.002, 0.0006);
  const fcl::Transform3d tf_b1 = pose(-0.20203050891044216, 0.30304576336566325, -0.7071067811865476, -0.6060915267313265, -0.001, 0.001, -0.0003);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.3025291365943123.
  // The shapes overlap by more than the tolerance at time 0.3039272097129825: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.3039272097129825);
}
