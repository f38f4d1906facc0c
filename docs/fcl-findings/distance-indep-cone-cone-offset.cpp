// Reproducer for FCL 0.7.0: distance (GST_INDEP) between a cone and a cone: distance.
// FCL 0.7.0 returns min_distance 0.023953125911913016; expected: distance 0.02395049576446969.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 63214 (family offset), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-indep-cone-cone-offset.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/cone.h>
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

TEST(KairosFound, DistanceGstIndepConeConeOffset) {
  const auto a = std::make_shared<fcl::Coned>(0.43586, 0.6411);
  const auto b = std::make_shared<fcl::Coned>(0.24237, 1.2605);
  const fcl::Transform3d tf_a = pose(0.5986185367087065, 0.10835973512036923, 0.5854285689508837, 0.5358986900240483, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(0.4343729065508727, -0.3958826489982261, -0.6269641952509039, -0.5113834218569083, -0.32546, 0.58711, -0.82474);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 0.02395049576446969 (Kairos 0.1.0; certified between 0.023950495764464064 and 0.023950495764475315: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 0.02395049576446969, 1.7174270206260215e-06);
}
