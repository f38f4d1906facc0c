// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between a box and a box: distance.
// FCL 0.7.0 returns min_distance 0.0010798279781289713; expected: distance 2.799930361703037e-06.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 85502 (family flat), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-libccd-box-box-flat.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
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

TEST(KairosFound, DistanceGstLibccdBoxBoxFlat) {
  const auto a = std::make_shared<fcl::Boxd>(1, 1, 0.00114701);
  const auto b = std::make_shared<fcl::Boxd>(1, 1, 0.00644101);
  const fcl::Transform3d tf_a = pose(-0.40826612582723115, 0.3093490953410965, 0.6438581984364835, 0.5683911751776188, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.8043901284836166, -0.588532094005047, -0.04103590655458277, 0.07001821118386797, -1.08175, 0.0631528, 0.744774);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 2.799930361703037e-06 (Kairos 0.1.0; certified between 2.799930361674363e-06 and 2.7999303617317107e-06: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 2.799930361703037e-06, 1.7071141352627245e-06);
}
