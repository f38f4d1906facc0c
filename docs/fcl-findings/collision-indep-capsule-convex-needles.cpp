// Reproducer for FCL 0.7.0: collide (GST_INDEP) between a capsule and a convex: collision.
// FCL 0.7.0 reports no collision; expected: a collision.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 23877 (family needles), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 collision-indep-capsule-convex-needles.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/capsule.h>
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

TEST(KairosFound, CollisionGstIndepCapsuleConvexNeedles) {
  const auto a = std::make_shared<fcl::Capsuled>(0.00056, 2);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.00276, -0.000588, 0.647),
      fcl::Vector3d(-0.000312, -0.000828, -0.796),
      fcl::Vector3d(0.00144, 0.0036, 0.204),
      fcl::Vector3d(-0.00221, -0.00224, 0.482),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 0, 2, 1,
      3, 0, 1, 3,
      3, 0, 3, 2,
      3, 1, 2, 3,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 4, b_faces);
  const fcl::Transform3d tf_a = pose(-0.8127728617232876, -0.17395138737989183, -0.5048589116485366, -0.23293490379031492, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.5110853583828702, -0.7281216064632671, -0.36006013506425294, -0.28104693875848635, 0.401, 0.305, 0.637);
  fcl::CollisionRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::CollisionResultd result;
  fcl::collide(a.get(), tf_a, b.get(), tf_b, request, result);
  // The shapes overlap (Kairos 0.1.0: depth 0.00040571736301948664).
  EXPECT_TRUE(result.isCollision());
}
