// Reproducer for FCL 0.7.0: continuous (GST_LIBCCD, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a convex and a convex: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.5334773436472608.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 27244 (family offset), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-libccd-convex-convex-offset.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

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

TEST(KairosFound, TimeOfContactCaGstLibccdConvexConvexOffset) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.0261114, 0.267933, -0.349362),
      fcl::Vector3d(0.0671822, 0.149279, -0.374742),
      fcl::Vector3d(0.164568, -0.27738, -0.119148),
      fcl::Vector3d(0.087166, -0.282291, -0.232991),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 0, 3, 2,
      3, 0, 2, 1,
      3, 0, 1, 3,
      3, 2, 3, 1,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 4, a_faces);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.180096, -0.0754808, 0.462763),
      fcl::Vector3d(0.10883, -0.0582558, 0.511046),
      fcl::Vector3d(-0.0663227, 0.439919, 0.0129457),
      fcl::Vector3d(0.00291204, 0.432568, -0.118556),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 2, 0, 3,
      3, 2, 1, 0,
      3, 2, 3, 1,
      3, 0, 1, 3,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 4, b_faces);
  const fcl::Transform3d tf_a0 = pose(1, 0, 0, 0, -3136.59, -680.736, -4816.14);
  const fcl::Transform3d tf_a1 = pose(1, 0, 0, 0, -3136.61, -680.716, -4816.14);
  const fcl::Transform3d tf_b0 = pose(-0.8402309519599814, -0.4817879724538794, 0.0075844895663584894, -0.24866598578257734, -3136.54, -680.651, -4816.98);
  const fcl::Transform3d tf_b1 = pose(-0.8402309519599814, -0.4817879724538794, 0.0075844895663584894, -0.24866598578257734, -3136.54, -680.656, -4816.56);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.5334725644641681.
  // The shapes overlap by more than the tolerance at time 0.5334773436472608: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.5334773436472608);
}
