// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between a cylinder and a cone: distance.
// FCL 0.7.0 returns min_distance 0.00117846365808016; expected: distance 0.0007013777008452563.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 48564 (family scale), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-libccd-cylinder-cone-scale.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/cone.h>
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

TEST(KairosFound, DistanceGstLibccdCylinderConeScale) {
  const auto a = std::make_shared<fcl::Cylinderd>(0.0007396, 0.0006407);
  const auto b = std::make_shared<fcl::Coned>(0.0002079, 0.001058);
  const fcl::Transform3d tf_a = pose(-0.5414993414289014, -0.190199768679182, -0.8185990044204963, -0.022319972854465523, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.623192590284152, 0.6471923049292413, -0.10509875038328687, -0.4262949313833986, 0.0008094, 0.0003443, 0.001407);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 0.0007013777008452563 (Kairos 0.1.0; certified between 0.0007013777008452518 and 0.0007013777008452607: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 0.0007013777008452563, 1.001093910651041e-06);
}
