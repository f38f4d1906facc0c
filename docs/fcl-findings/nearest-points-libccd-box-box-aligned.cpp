// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between a box and a box: nearest points.
// FCL 0.7.0 returns min_distance 2 with nearest points (-0.4999999999999998, -0.5000000000000002, 0.5) and (-0.4999999999999989, -2.5000000000000004, 0.5); expected: nearest points on the shapes, 2.0000000000000013 apart.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 82747 (family aligned), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 nearest-points-libccd-box-box-aligned.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
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

TEST(KairosFound, NearestPointsGstLibccdBoxBoxAligned) {
  const auto a = std::make_shared<fcl::Boxd>(1, 1, 1);
  const auto b = std::make_shared<fcl::Boxd>(1, 1, 1);
  const fcl::Transform3d tf_a = pose(0.7071067811865476, 0, 0, 0.7071067811865476, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(1, 0, 0, 0, 0.5, -3.0000000000000004, 0);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 2.0000000000000013 (Kairos 0.1.0; certified between 2.0000000000000004 and 2.000000000000002: the gap along its separating axis and the distance between two points of the shapes).
  // > 0: how far a point (in a's frame) lies outside a, a lower bound.
  const auto outside_a = [&](const fcl::Vector3d& q) {
    return (q.cwiseAbs() - fcl::Vector3d(1, 1, 1) / 2).maxCoeff();
  };
  // > 0: how far a point (in b's frame) lies outside b, a lower bound.
  const auto outside_b = [&](const fcl::Vector3d& q) {
    return (q.cwiseAbs() - fcl::Vector3d(1, 1, 1) / 2).maxCoeff();
  };
  const fcl::Vector3d& p0 = result.nearest_points[0];
  const fcl::Vector3d& p1 = result.nearest_points[1];
  EXPECT_LE(outside_a(tf_a.inverse() * p0), 1.8660254428585053e-06) << "nearest_points[0] is not on a";
  EXPECT_LE(outside_b(tf_b.inverse() * p1), 1.8660254428585053e-06) << "nearest_points[1] is not on b";
  EXPECT_NEAR((p1 - p0).norm(), 2.0000000000000013, 1.8660254437466838e-06);
}
