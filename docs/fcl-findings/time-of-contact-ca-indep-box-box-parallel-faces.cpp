// Reproducer for FCL 0.7.0: continuous (GST_INDEP, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a box and a box: time of contact.
// FCL 0.7.0 reports contact at time 0.49935952082113555; expected: contact by time 0.49893421579338393.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 23518 (family parallel_faces), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-indep-box-box-parallel-faces.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
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

TEST(KairosFound, TimeOfContactCaGstIndepBoxBoxParallelFaces) {
  const auto a = std::make_shared<fcl::Boxd>(1, 1, 0.25);
  const auto b = std::make_shared<fcl::Boxd>(0.5, 0.5, 0.12);
  const fcl::Transform3d tf_a0 = pose(1, 0, 0, 0, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(1, 0, 0, 0, -0.67, -0.044, -0.069);
  const fcl::Transform3d tf_b0 = pose(-0.9778022924970226, 0.00046894599742204146, -0.00016961876502499373, 0.20952906267793342, 0.065, -0.37, 0.55);
  const fcl::Transform3d tf_b1 = pose(-0.9778022924970226, 0.00046894599742204146, -0.00016961876502499373, 0.20952906267793342, -0.62, 0.11, -0.25);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.4989318654919421.
  // The shapes overlap by more than the tolerance at time 0.49893421579338393: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.49893421579338393);
}
