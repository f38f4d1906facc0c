// Reproducer for FCL 0.7.0: continuous (GST_INDEP, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a box and a capsule: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.07781024143384807.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 66046 (family offset), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-indep-box-capsule-offset.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
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

TEST(KairosFound, TimeOfContactCaGstIndepBoxCapsuleOffset) {
  const auto a = std::make_shared<fcl::Boxd>(0.411335, 1.38034, 0.571967);
  const auto b = std::make_shared<fcl::Capsuled>(0.226843, 0.92659);
  const fcl::Transform3d tf_a0 = pose(-0.37235084744333885, -0.8865596367657573, 0.27401288773359445, 0.016846193097910238, 4193.39, 2973.31, 4304.23);
  const fcl::Transform3d tf_a1 = pose(-0.37235084744333885, -0.8865596367657573, 0.27401288773359445, 0.016846193097910238, 4193.45, 2973.33, 4304.31);
  const fcl::Transform3d tf_b0 = pose(-0.7907150786614311, -0.18996501889798317, 0.5768680573876334, 0.07685180764532426, 4192.9, 2973.93, 4303.97);
  const fcl::Transform3d tf_b1 = pose(-0.7907150786614311, -0.18996501889798317, 0.5768680573876334, 0.07685180764532426, 4193.47, 2973.91, 4304.22);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.07780656399869414.
  // The shapes overlap by more than the tolerance at time 0.07781024143384807: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.07781024143384807);
}
