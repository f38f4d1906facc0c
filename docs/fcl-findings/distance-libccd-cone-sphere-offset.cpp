// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between a cone and a sphere: distance.
// FCL 0.7.0 returns min_distance 0.032860584678758256; expected: distance 0.02962232059970268.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 63253 (family offset), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-libccd-cone-sphere-offset.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/sphere.h>
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

TEST(KairosFound, DistanceGstLibccdConeSphereOffset) {
  const auto a = std::make_shared<fcl::Coned>(0.1170345, 0.4804108);
  const auto b = std::make_shared<fcl::Sphered>(0.5100384);
  const fcl::Transform3d tf_a = pose(-0.8591080249383426, 0.05253552152501059, 0.30640310889432465, 0.4065594118016799, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(1, 0, 0, 0, -0.02462849, -0.5082855, -0.6204291);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 0.02962232059970268 (Kairos 0.1.0; certified between 0.02962232059970268 and 0.02962232059970268: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 0.02962232059970268, 1.8834124394695565e-06);
}
