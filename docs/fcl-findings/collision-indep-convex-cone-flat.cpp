// Reproducer for FCL 0.7.0: collide (GST_INDEP) between a convex and a cone: collision.
// FCL 0.7.0 reports no collision; expected: a collision.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 64512 (family flat), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 collision-indep-convex-cone-flat.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
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

TEST(KairosFound, CollisionGstIndepConvexConeFlat) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.543, -0.383, 1.82e-05),
      fcl::Vector3d(-0.511, 0.304, 1.84e-05),
      fcl::Vector3d(0.0624, 0.848, 9.44e-06),
      fcl::Vector3d(-0.237, 0.633, -1.46e-05),
      fcl::Vector3d(0.663, -0.515, -1.47e-05),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 0, 4, 2,
      3, 0, 3, 4,
      3, 2, 4, 3,
      3, 0, 2, 1,
      3, 2, 3, 1,
      3, 3, 0, 1,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 6, a_faces);
  const auto b = std::make_shared<fcl::Coned>(0.478, 1.09);
  const fcl::Transform3d tf_a = pose(-0.9026429489615423, -0.07477042367920639, -0.05817698740815256, -0.4198339297495545, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.19403813223984587, 0.6911358215347086, 0.24104737046290128, -0.6531283523330894, -1.12, -0.318, 0.436);
  fcl::CollisionRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::CollisionResultd result;
  fcl::collide(a.get(), tf_a, b.get(), tf_b, request, result);
  // The shapes overlap (Kairos 0.1.0: depth 0.02495320700132207).
  EXPECT_TRUE(result.isCollision());
}
