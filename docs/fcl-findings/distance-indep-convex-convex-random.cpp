// Reproducer for FCL 0.7.0: distance (GST_INDEP) between a convex and a convex: distance.
// FCL 0.7.0 returns min_distance 0.02379015306208181; expected: the shapes intersect.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 68826 (family random), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-indep-convex-convex-random.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/convex.h>
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

TEST(KairosFound, DistanceGstIndepConvexConvexRandom) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.02, -0.48, 0.18),
      fcl::Vector3d(0.061, 0.19, 0.44),
      fcl::Vector3d(-0.026, -0.52, -0.093),
      fcl::Vector3d(0.12, 0.42, 0.026),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 2, 1, 3,
      3, 2, 3, 0,
      3, 2, 0, 1,
      3, 3, 1, 0,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 4, a_faces);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.25, 0.33, -0.031),
      fcl::Vector3d(-0.069, 0.23, -0.25),
      fcl::Vector3d(-0.21, -0.024, -0.21),
      fcl::Vector3d(0.25, 0.32, -0.089),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 0, 2, 3,
      3, 0, 3, 1,
      3, 0, 1, 2,
      3, 3, 2, 1,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 4, b_faces);
  const fcl::Transform3d tf_a = pose(-0.17034435849980264, 0.031062794785258124, -0.7014179467638931, -0.6913976903815517, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(0.06804342556268535, -0.6504150972903746, -0.6003831667295765, -0.460293761159342, -0.0067, 0.12, -0.78);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The shapes intersect (Kairos 0.1.0: depth 0.010833694024388038): FCL must report a distance of at most 0.
  EXPECT_LE(result.min_distance, 1.691664673440322e-06);
}
