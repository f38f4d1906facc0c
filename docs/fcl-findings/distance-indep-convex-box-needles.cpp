// Reproducer for FCL 0.7.0: distance (GST_INDEP) between a convex and a box: distance.
// FCL 0.7.0 returns min_distance 0.0009799225230782734; expected: the shapes intersect.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 16270 (family needles), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-indep-convex-box-needles.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
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

TEST(KairosFound, DistanceGstIndepConvexBoxNeedles) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.00026, -6.86e-05, -0.915),
      fcl::Vector3d(-0.000858, -0.000333, -0.774),
      fcl::Vector3d(0.000137, 0.000315, 0.96),
      fcl::Vector3d(0.0017, -5.96e-05, -0.277),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 1, 3, 2,
      3, 1, 2, 0,
      3, 1, 0, 3,
      3, 2, 3, 0,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 4, a_faces);
  const auto b = std::make_shared<fcl::Boxd>(2, 0.000985, 0.000985);
  const fcl::Transform3d tf_a = pose(-0.2709146753137983, 0.22992758421466275, 0.16694741984282035, 0.919710336858651, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.1570431142531061, 0.15104146657464346, -0.5601537833231811, 0.7992194158486101, 0.601, 0.0248, -0.833);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The shapes intersect (Kairos 0.1.0: depth 3.1436533347705086e-06): FCL must report a distance of at most 0.
  EXPECT_LE(result.min_distance, 2.000000262830974e-06);
}
