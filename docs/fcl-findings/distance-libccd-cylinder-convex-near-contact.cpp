// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between a cylinder and a convex: distance.
// FCL 0.7.0 returns min_distance 0.003424915543703307; expected: distance 0.0021998786117361445.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 47950 (family near_contact), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-libccd-cylinder-convex-near-contact.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/convex.h>
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

TEST(KairosFound, DistanceGstLibccdCylinderConvexNearContact) {
  const auto a = std::make_shared<fcl::Cylinderd>(0.67615, 1.1056);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.43655, 0.61147, 0.019408),
      fcl::Vector3d(0.6696, -0.25957, 0.58394),
      fcl::Vector3d(-0.10562, 0.44939, -0.61767),
      fcl::Vector3d(-0.47933, 0.25434, 0.71717),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 3, 2, 1,
      3, 3, 0, 2,
      3, 3, 1, 0,
      3, 2, 0, 1,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 4, b_faces);
  const fcl::Transform3d tf_a = pose(0.1208099893566404, -0.8217999275994294, -0.3107999726185236, -0.46200995929692434, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.4739112938032937, 0.1780704861419943, 0.7994521825474102, 0.32338088284718436, -1.4902, -0.22619, -0.52162);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 0.0021998786117361445 (Kairos 0.1.0; certified between 0.0021998786117354285 and 0.0021998786117368605: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 0.0021998786117361445, 2.156110978698317e-06);
}
