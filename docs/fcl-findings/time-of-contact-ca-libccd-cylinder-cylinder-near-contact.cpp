// Reproducer for FCL 0.7.0: continuous (GST_LIBCCD, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a cylinder and a cylinder: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.4962668449969895.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 24407 (family near_contact), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-libccd-cylinder-cylinder-near-contact.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

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

TEST(KairosFound, TimeOfContactCaGstLibccdCylinderCylinderNearContact) {
  const auto a = std::make_shared<fcl::Cylinderd>(0.7029686180726833, 0.9450857872175977);
  const auto b = std::make_shared<fcl::Cylinderd>(0.6471491322154184, 0.6572408181153906);
  const fcl::Transform3d tf_a0 = pose(-0.7125794107857133, -0.6637240327963784, -0.22604095574351307, 0.024626772816527545, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(-0.7125794107857133, -0.6637240327963784, -0.22604095574351307, 0.024626772816527545, 0.5516323447178046, -0.30654366045668335, -0.23184667134844922);
  const fcl::Transform3d tf_b0 = pose(0.38282268514888146, -0.4075265287792582, -0.26628266202813045, 0.7851512363740768, 0.7624723765366895, -1.5985896362085685, -1.1494855335513912);
  const fcl::Transform3d tf_b1 = pose(0.38282268514888146, -0.4075265287792582, -0.26628266202813045, 0.7851512363740768, 0.959669707876699, -0.6194904644124619, -1.1790805330279768);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.4962650009598214.
  // The shapes overlap by more than the tolerance at time 0.4962668449969895: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.4962668449969895);
}
