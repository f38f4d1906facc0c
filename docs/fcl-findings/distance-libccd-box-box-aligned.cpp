// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between a box and a box: distance.
// FCL 0.7.0 returns min_distance 3.475359693614461; expected: distance 1.5.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 38344 (family aligned), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-libccd-box-box-aligned.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
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

TEST(KairosFound, DistanceGstLibccdBoxBoxAligned) {
  const auto a = std::make_shared<fcl::Boxd>(1.5, 1.5, 1.5);
  const auto b = std::make_shared<fcl::Boxd>(1.5, 1.5, 1.5);
  const fcl::Transform3d tf_a = pose(1, 0, 0, 0, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(0, 0, 1, 0, -0.25, -3, 1.375);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 1.5 (Kairos 0.1.0; certified between 1.5 and 1.5: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 1.5, 2.2990381517625447e-06);
}
