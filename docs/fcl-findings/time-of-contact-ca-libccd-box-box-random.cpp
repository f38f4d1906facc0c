// Reproducer for FCL 0.7.0: continuous (GST_LIBCCD, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a box and a box: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.17057239493910142.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 69461 (family random), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-libccd-box-box-random.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
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

TEST(KairosFound, TimeOfContactCaGstLibccdBoxBoxRandom) {
  const auto a = std::make_shared<fcl::Boxd>(1.2542094520589704, 0.7075538365022198, 1.442208957886956);
  const auto b = std::make_shared<fcl::Boxd>(1.1647066169577884, 1.0697828871397626, 1.3744153584966647);
  const fcl::Transform3d tf_a0 = pose(0.34563942775209944, -0.4780189582895777, -0.149645949320503, 0.7934969132585922, 0.13141891737446454, -0.04382322259874403, 0.11369961652149638);
  const fcl::Transform3d tf_a1 = pose(0.34563942775209944, -0.4780189582895777, -0.149645949320503, 0.7934969132585922, -0.05066162091479115, 0.2378663213613276, 0.7696846258727784);
  const fcl::Transform3d tf_b0 = pose(0.8035346651583629, 0.3353216053499174, 0.07177939263175354, -0.4865585079595344, -1.765512998788562, 0.23613442827214437, 0.16029320249076476);
  const fcl::Transform3d tf_b1 = pose(0.8035346651583629, 0.3353216053499174, 0.07177939263175354, -0.4865585079595344, -1.311920203110251, 0.08889661778343527, 1.1697971725873233);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.17056876496453313.
  // The shapes overlap by more than the tolerance at time 0.17057239493910142: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.17057239493910142);
}
