// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between an ellipsoid and an ellipsoid: crash.
// FCL 0.7.0 dies: signal 6 (Aborted); expected: the shapes touch.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 88022 (family aligned), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-crash-libccd-ellipsoid-ellipsoid-aligned.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/ellipsoid.h>
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

TEST(KairosFound, DistanceCrashGstLibccdEllipsoidEllipsoidAligned) {
  const auto a = std::make_shared<fcl::Ellipsoidd>(0.5, 0.8, 1);
  const auto b = std::make_shared<fcl::Ellipsoidd>(0.5, 0.8, 1);
  const fcl::Transform3d tf_a = pose(1, 0, 0, 0, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(1, 0, 0, 0, 1, 0, 0);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  EXPECT_NO_THROW(fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result));
  // The shapes touch (Kairos 0.1.0: depth 0): FCL must report a distance of at most 0.
  EXPECT_LE(result.min_distance, 2.374772732234479e-06);
}
