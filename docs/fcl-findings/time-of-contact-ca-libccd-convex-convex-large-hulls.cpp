// Reproducer for FCL 0.7.0: continuous (GST_LIBCCD, CCDC_CONSERVATIVE_ADVANCEMENT, CCDM_TRANS) between a convex and a convex: time of contact.
// FCL 0.7.0 reports no contact; expected: contact by time 0.2844742728006795.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 98874 (family large_hulls), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 time-of-contact-ca-libccd-convex-convex-large-hulls.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/continuous_collision.h>

namespace {

// A rigid transform from the unit quaternion (w, x, y, z) and the translation (x, y, z).
fcl::Transform3d pose(double qw, double qx, double qy, double qz, double x, double y, double z) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = fcl::Quaterniond(qw, qx, qy, qz).toRotationMatrix();
  tf.translation() = fcl::Vector3d(x, y, z);
  return tf;
}

}  // namespace

TEST(KairosFound, TimeOfContactCaGstLibccdConvexConvexLargeHulls) {
  const auto a_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.76639, 0.26094, 0.47009),
      fcl::Vector3d(-1.0833, 0.726, 0.14429),
      fcl::Vector3d(1.047, 0.77625, -0.093389),
      fcl::Vector3d(0.25553, 1.062, 0.089039),
  });
  const auto a_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 1, 2, 0,
      3, 1, 3, 2,
      3, 1, 0, 3,
      3, 2, 3, 0,
  });
  const auto a = std::make_shared<fcl::Convexd>(a_vertices, 4, a_faces);
  const auto b_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{
      fcl::Vector3d(-0.48738, 0.17526, -0.84984),
      fcl::Vector3d(-0.35856, 1.0058, -0.10712),
      fcl::Vector3d(-0.49906, 0.74073, -0.094153),
      fcl::Vector3d(-0.58422, 0.11035, 0.33726),
  });
  const auto b_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 3, 0, 1,
      3, 3, 2, 0,
      3, 3, 1, 2,
      3, 0, 2, 1,
  });
  const auto b = std::make_shared<fcl::Convexd>(b_vertices, 4, b_faces);
  const fcl::Transform3d tf_a0 = pose(0.21754051268920743, 0.29064068496824147, 0.7611717938937391, 0.5374212665690625, 0, 0, 0);
  const fcl::Transform3d tf_a1 = pose(0.21754051268920743, 0.29064068496824147, 0.7611717938937391, 0.5374212665690625, -0.16509, -0.81897, 1.0459);
  const fcl::Transform3d tf_b0 = pose(-0.8370265071793758, 0.47841800361367803, 0.1720292821405063, -0.2022591559945289, 1.2101, 0.10002, 2.0959);
  const fcl::Transform3d tf_b1 = pose(-0.8370265071793758, 0.47841800361367803, 0.1720292821405063, -0.2022591559945289, 0.025544, -1.3599, 2.0591);
  fcl::ContinuousCollisionRequestd request;
  request.ccd_motion_type = fcl::CCDM_TRANS;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
  fcl::ContinuousCollisionResultd result;
  fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result);
  // Kairos 0.1.0: first contact at time 0.2844726684052053.
  // The shapes overlap by more than the tolerance at time 0.2844742728006795: contact comes no later.
  ASSERT_TRUE(result.is_collide);
  EXPECT_LE(result.time_of_contact, 0.2844742728006795);
}
