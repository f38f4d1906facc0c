// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between a capsule and a cylinder: distance.
// FCL 0.7.0 returns min_distance 0.0033913600690066883; expected: distance 6.608404287249687e-05.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 82725 (family needles), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-libccd-capsule-cylinder-needles.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/distance.h>

namespace {

// A rigid transform from the unit quaternion (w, x, y, z) and the translation (x, y, z).
fcl::Transform3d pose(double qw, double qx, double qy, double qz, double x, double y, double z) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = fcl::Quaterniond(qw, qx, qy, qz).toRotationMatrix();
  tf.translation() = fcl::Vector3d(x, y, z);
  return tf;
}

}  // namespace

TEST(KairosFound, DistanceGstLibccdCapsuleCylinderNeedles) {
  const auto a = std::make_shared<fcl::Capsuled>(0.0061327, 2);
  const auto b = std::make_shared<fcl::Cylinderd>(0.00050421, 2);
  const fcl::Transform3d tf_a = pose(-0.8090401311454158, -0.4042500655289409, -0.24721004007275074, 0.34774005636866767, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.08644014920879234, 0.6330410927248253, -0.6848711821914114, -0.3503406047409568, 0.44716, -1.4118, 1.2952);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 6.608404287249687e-05 (Kairos 0.1.0; certified between 6.608404287249687e-05 and 6.608404287249687e-05: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 6.608404287249687e-05, 2.0061701098056307e-06);
}
