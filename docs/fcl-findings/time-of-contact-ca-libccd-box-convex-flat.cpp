// Reproducer for FCL 0.7.0: continuous (GST_LIBCCD, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a box and a convex: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.4273271000900023.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 52209 (family flat), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-libccd-box-convex-flat.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
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

TEST(KairosFound, TimeOfContactCaGstLibccdBoxConvexFlat) {
  const auto a = std::make_shared<fcl::Boxd>(2, 2, 2.09e-06);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.0802, 0.344, -0.448),
      fcl::Vector3d(0.818, -0.212, -0.703),
      fcl::Vector3d(0.0338, -0.156, -1.21),
      fcl::Vector3d(1.1, -0.009, 0.426),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 2, 3, 0,
      3, 2, 1, 3,
      3, 2, 0, 1,
      3, 3, 1, 0,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 4, b_faces);
  const fcl::Transform3d tf_a0 = pose(-0.20004901801485622, 0.6151507303956829, 0.7541847979160079, 0.11302769517839377, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(-0.20004901801485622, 0.6151507303956829, 0.7541847979160079, 0.11302769517839377, 0.236, -0.89, 0.743);
  const fcl::Transform3d tf_b0 = pose(0.459861602483345, -0.13196028593000336, 0.49285167396584584, -0.7267812717508517, 2.48, 1.44, 0.9);
  const fcl::Transform3d tf_b1 = pose(0.459861602483345, -0.13196028593000336, 0.49285167396584584, -0.7267812717508517, 1.15, 0.237, 1.27);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.42732272369342766.
  // The shapes overlap by more than the tolerance at time 0.4273271000900023: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.4273271000900023);
}
