// Reproducer for FCL 0.7.0: distance (GST_INDEP) between a cylinder and a cylinder: distance.
// FCL 0.7.0 returns min_distance 5.65685834634843; expected: distance 5.65685424949238.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 13210 (family aligned), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-indep-cylinder-cylinder-aligned.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

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

TEST(KairosFound, DistanceGstIndepCylinderCylinderAligned) {
  const auto a = std::make_shared<fcl::Cylinderd>(0.5, 1);
  const auto b = std::make_shared<fcl::Cylinderd>(0.5, 1);
  const fcl::Transform3d tf_a = pose(1, 0, 0, 0, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(1, 0, 0, 0, 0, 5, -5);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 5.65685424949238 (Kairos 0.1.0; certified between 5.65685424949238 and 5.656854249492381: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 5.65685424949238, 1.8660254835994598e-06);
}
