// Reproducer for FCL 0.7.0: collide (GST_INDEP) between a convex and a box: collision.
// FCL 0.7.0 reports no collision; expected: a collision.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 73521 (family random), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 collision-indep-convex-box-random.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
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

TEST(KairosFound, CollisionGstIndepConvexBoxRandom) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.1, -0.247, 0.149),
      fcl::Vector3d(0.185, -0.24, 0.0871),
      fcl::Vector3d(0.125, 0.011, 0.28),
      fcl::Vector3d(-0.0794, 0.323, 0.0925),
      fcl::Vector3d(0.25, 0.0574, 0.0787),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 0, 2, 3,
      3, 3, 2, 4,
      3, 0, 3, 1,
      3, 2, 0, 1,
      3, 3, 4, 1,
      3, 4, 2, 1,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 6, a_faces);
  const auto b = std::make_shared<fcl::Boxd>(1.46, 0.502, 1.46);
  const fcl::Transform3d tf_a = pose(0.2079582046008908, 0.135972672239044, -0.4809033481395599, -0.840831009948794, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.020505001267100403, 0.1980483049212624, -0.7521834611150976, -0.6281532095482464, -0.984, 0.669, -0.0855);
  fcl::CollisionRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::CollisionResultd result;
  fcl::collide(a.get(), tf_a, b.get(), tf_b, request, result);
  // The shapes overlap (Kairos 0.1.0: depth 0.07769898595870604).
  EXPECT_TRUE(result.isCollision());
}
