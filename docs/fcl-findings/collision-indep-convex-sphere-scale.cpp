// Reproducer for FCL 0.7.0: collide (GST_INDEP) between a convex and a sphere: collision.
// FCL 0.7.0 reports no collision; expected: a collision.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 34095 (family scale), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 collision-indep-convex-sphere-scale.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>

namespace {

// A rigid transform from the unit quaternion (w, x, y, z) and the translation (x, y, z).
fcl::Transform3d pose(double qw, double qx, double qy, double qz, double x, double y, double z) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = fcl::Quaterniond(qw, qx, qy, qz).toRotationMatrix();
  tf.translation() = fcl::Vector3d(x, y, z);
  return tf;
}

}  // namespace

TEST(KairosFound, CollisionGstIndepConvexSphereScale) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.0002, -0.0004, 0.0004),
      fcl::Vector3d(-0.0006, -0.0004, -0.0003),
      fcl::Vector3d(-0.0007, 8e-05, 0.0003),
      fcl::Vector3d(0.0004, -0.0006, -0.0002),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 2, 3, 1,
      3, 2, 0, 3,
      3, 2, 1, 0,
      3, 3, 0, 1,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 4, a_faces);
  const auto b = std::make_shared<fcl::Sphered>(0.0007);
  const fcl::Transform3d tf_a = pose(-0.6060915267313265, -0.7071067811865476, -0.20203050891044216, 0.30304576336566325, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(1, 0, 0, 0, -0.0004, -0.0005, 0.0006);
  fcl::CollisionRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::CollisionResultd result;
  fcl::collide(a.get(), tf_a, b.get(), tf_b, request, result);
  // The shapes overlap (Kairos 0.1.0: depth 0.0004094832190733211).
  EXPECT_TRUE(result.isCollision());
}
