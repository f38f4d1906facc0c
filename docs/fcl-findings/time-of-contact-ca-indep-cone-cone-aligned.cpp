// Reproducer for FCL 0.7.0: continuous (GST_INDEP, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a cone and a cone: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.30866410021305746.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 39408 (family aligned), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-indep-cone-cone-aligned.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/cone.h>
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

TEST(KairosFound, TimeOfContactCaGstIndepConeConeAligned) {
  const auto a = std::make_shared<fcl::Coned>(0.75, 1.5);
  const auto b = std::make_shared<fcl::Coned>(0.5, 1);
  const fcl::Transform3d tf_a0 = pose(1, 0, 0, 0, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(1, 0, 0, 0, -0.00704, -0.00324, -0.000961);
  const fcl::Transform3d tf_b0 = pose(0, 1, 0, 0, -1.35, -0.552, -1.45);
  const fcl::Transform3d tf_b1 = pose(0, 1, 0, 0, -0.904, 0.549, -0.803);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.3086605521011295.
  // The shapes overlap by more than the tolerance at time 0.30866410021305746: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.30866410021305746);
}
