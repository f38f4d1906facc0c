// Reproducer for FCL 0.7.0: collide (GST_INDEP) between a cone and a convex: collision.
// FCL 0.7.0 reports no collision; expected: a collision.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 34073 (family near_contact), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 collision-indep-cone-convex-near-contact.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
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

TEST(KairosFound, CollisionGstIndepConeConvexNearContact) {
  const auto a = std::make_shared<fcl::Coned>(0.283, 0.743);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(0.269, -0.344, -0.17),
      fcl::Vector3d(0.427, -0.12, -0.32),
      fcl::Vector3d(0.211, -0.418, 0.205),
      fcl::Vector3d(0.254, -0.153, 0.406),
      fcl::Vector3d(0.00987, -0.417, -0.342),
      fcl::Vector3d(-0.0631, 0.12, -0.476),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 5, 4, 3,
      3, 5, 3, 1,
      3, 5, 1, 4,
      3, 4, 1, 0,
      3, 0, 1, 2,
      3, 1, 3, 2,
      3, 3, 4, 2,
      3, 4, 0, 2,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 8, b_faces);
  const fcl::Transform3d tf_a = pose(0.7978492207445727, 0.16496882383816353, 0.10697978273141513, -0.5698923005318376, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.34900997484762375, 0.01780050874581004, -0.8360238939043365, 0.4230120898582947, 0.341, 0.816, -0.357);
  fcl::CollisionRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::CollisionResultd result;
  fcl::collide(a.get(), tf_a, b.get(), tf_b, request, result);
  // The shapes overlap (Kairos 0.1.0: depth 0.0006998247011875198).
  EXPECT_TRUE(result.isCollision());
}
