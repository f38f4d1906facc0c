// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between a convex and a cylinder: distance.
// FCL 0.7.0 returns min_distance 0.005331028555615209; expected: distance 0.0022595259833600003.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 82195 (family large_hulls), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-libccd-convex-cylinder-large-hulls.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
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

TEST(KairosFound, DistanceGstLibccdConvexCylinderLargeHulls) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.507703, 0.157421, 0.612787),
      fcl::Vector3d(0.204452, 0.0818903, 0.725181),
      fcl::Vector3d(0.874755, -0.0809059, 0.201155),
      fcl::Vector3d(-0.360372, -0.0440897, -0.704993),
      fcl::Vector3d(-0.794126, 0.0813701, 0.366968),
      fcl::Vector3d(0.650329, 0.127887, 0.510302),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 4, 3, 2,
      3, 4, 0, 3,
      3, 0, 4, 1,
      3, 4, 2, 1,
      3, 0, 1, 5,
      3, 1, 2, 5,
      3, 2, 3, 5,
      3, 3, 0, 5,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 8, a_faces);
  const auto b = std::make_shared<fcl::Cylinderd>(0.610638, 1.12517);
  const fcl::Transform3d tf_a = pose(0.2326359962110576, 0.5556049909508617, -0.638101989607233, -0.479592992188869, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.5503320100942394, -0.8332050152827215, -0.027971100513048446, 0.046061900844871544, -1.34938, -0.712198, -0.571847);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 0.0022595259833600003 (Kairos 0.1.0; certified between 0.002259525983359434 and 0.002259525983360567: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 0.0022595259833600003, 2.147111689865951e-06);
}
