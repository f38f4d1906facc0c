// Reproducer for FCL 0.7.0: continuous (GST_INDEP, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a convex and a box: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.5165404596745142.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 44039 (family needles), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-indep-convex-box-needles.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
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

TEST(KairosFound, TimeOfContactCaGstIndepConvexBoxNeedles) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.0003, 6.1e-05, 0.44),
      fcl::Vector3d(0.00086, 0.00027, -0.06),
      fcl::Vector3d(-0.00074, -0.00057, -0.0036),
      fcl::Vector3d(0.00034, -0.00054, 0.29),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 2, 0, 1,
      3, 2, 3, 0,
      3, 2, 1, 3,
      3, 0, 3, 1,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 4, a_faces);
  const auto b = std::make_shared<fcl::Boxd>(0.94, 0.33, 1.1);
  const fcl::Transform3d tf_a0 = pose(-0.6513693148546404, -0.721516779531294, 0.15031599573568624, 0.1803791948828235, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(-0.6513693148546404, -0.721516779531294, 0.15031599573568624, 0.1803791948828235, 0.46, -0.52, -0.081);
  const fcl::Transform3d tf_b0 = pose(-0.12016835362522194, -0.2002805893753699, 0.5207295323759618, -0.8211504164390165, -0.3, -0.65, 1.2);
  const fcl::Transform3d tf_b1 = pose(-0.12016835362522194, -0.2002805893753699, 0.5207295323759618, -0.8211504164390165, -0.1, -1.5, -0.21);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.5165389264538309.
  // The shapes overlap by more than the tolerance at time 0.5165404596745142: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.5165404596745142);
}
