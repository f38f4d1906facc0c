// Reproducer for FCL 0.7.0: continuous (GST_INDEP, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a box and a convex: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.7315008435638506.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 36089 (family flat), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-indep-box-convex-flat.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
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

TEST(KairosFound, TimeOfContactCaGstIndepBoxConvexFlat) {
  const auto a = std::make_shared<fcl::Boxd>(1, 1, 3e-06);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.05, -0.3, 0.03),
      fcl::Vector3d(0.1, 0.2, 0.1),
      fcl::Vector3d(0.1, -0.1, -0.2),
      fcl::Vector3d(-0.1, 0.3, 0.07),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 3, 2, 0,
      3, 3, 0, 1,
      3, 3, 1, 2,
      3, 0, 2, 1,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 4, b_faces);
  const fcl::Transform3d tf_a0 = pose(0.39036002917941326, -0.19518001458970663, -0.19518001458970663, 0.8783100656536798, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(0.39036002917941326, -0.19518001458970663, -0.19518001458970663, 0.8783100656536798, -0.01, -0.2, -0.09);
  const fcl::Transform3d tf_b0 = pose(-0.6255432421712243, 0.20851441405707477, -0.41702882811414954, -0.6255432421712243, -1, -0.3, -0.4);
  const fcl::Transform3d tf_b1 = pose(-0.6255432421712243, 0.20851441405707477, -0.41702882811414954, -0.6255432421712243, -0.6, 0.03, -0.2);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.7314845158957173.
  // The shapes overlap by more than the tolerance at time 0.7315008435638506: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.7315008435638506);
}
