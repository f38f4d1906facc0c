// Reproducer for FCL 0.7.0: distance (GST_INDEP) between a convex and a convex: distance.
// FCL 0.7.0 returns min_distance 0.07529287245833693; expected: distance 0.0023342270301964733.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 77338 (family large_hulls), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-indep-convex-convex-large-hulls.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
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

TEST(KairosFound, DistanceGstIndepConvexConvexLargeHulls) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.14, 0.33, -0.43),
      fcl::Vector3d(0.48, -0.28, -0.24),
      fcl::Vector3d(0.28, 0.39, -0.32),
      fcl::Vector3d(0.59, -0.23, -0.048),
      fcl::Vector3d(-0.43, 0.1, -0.39),
      fcl::Vector3d(0.24, 0.1, -0.46),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 4, 3, 2,
      3, 2, 5, 0,
      3, 4, 2, 0,
      3, 5, 4, 0,
      3, 2, 3, 1,
      3, 3, 4, 1,
      3, 4, 5, 1,
      3, 5, 2, 1,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 8, a_faces);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.26, 0.33, 0.051),
      fcl::Vector3d(-0.29, -0.12, 0.38),
      fcl::Vector3d(0.31, 0.29, -0.064),
      fcl::Vector3d(-0.00026, 0.42, 0.34),
      fcl::Vector3d(-0.046, -0.046, 0.62),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 1, 0, 2,
      3, 1, 3, 0,
      3, 2, 0, 3,
      3, 1, 2, 4,
      3, 2, 3, 4,
      3, 3, 1, 4,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 6, b_faces);
  const fcl::Transform3d tf_a = pose(-0.2408444358835647, 0.3211259145114196, -0.7727092317931035, 0.49172405659561125, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(0.26132448238692346, 0.5628527312949121, 0.7839734471607703, 0.017086600771452687, -0.99, 0.2, 0.022);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 0.0023342270301964733 (Kairos 0.1.0; certified between 0.0023342270301963675 and 0.002334227030196579: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 0.0023342270301964733, 1.8436824233448158e-06);
}
