// Reproducer for FCL 0.7.0: continuous (GST_LIBCCD, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a box and a box: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.49372925863915695.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 13318 (family parallel_faces), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-libccd-box-box-parallel-faces.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
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

TEST(KairosFound, TimeOfContactCaGstLibccdBoxBoxParallelFaces) {
  const auto a = std::make_shared<fcl::Boxd>(4, 4, 1);
  const auto b = std::make_shared<fcl::Boxd>(2, 2, 0.5);
  const fcl::Transform3d tf_a0 = pose(1, 0, 0, 0, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(1, 0, 0, 0, 1.4646459121198316, 1.241159617242036, 0.5551778202951112);
  const fcl::Transform3d tf_b0 = pose(1, 0, 0, 0, -1.467053076347725, -0.18194493063743084, 1.9964935660519194);
  const fcl::Transform3d tf_b1 = pose(1, 0, 0, 0, 2.3732666623149936, 0.965636946502622, 0.027013557137163247);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.49372772485451216.
  // The shapes overlap by more than the tolerance at time 0.49372925863915695: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.49372925863915695);
}
