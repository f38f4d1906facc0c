// Reproducer for FCL 0.7.0: distance (GST_LIBCCD) between a box and a cone: distance.
// FCL 0.7.0 returns min_distance 0.008087854861075229; expected: distance 0.004340514148426548.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 61166 (family random), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-libccd-box-cone-random.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cone.h>
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

TEST(KairosFound, DistanceGstLibccdBoxConeRandom) {
  const auto a = std::make_shared<fcl::Boxd>(0.80665, 0.99268, 1.8812);
  const auto b = std::make_shared<fcl::Coned>(0.47949, 1.033);
  const fcl::Transform3d tf_a = pose(0.4014799974473902, -0.5352299965970078, 0.743089995275434, 0.012645999919596734, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(0.03227404771276099, 0.32435047950777807, 0.6941610262220417, 0.6417909488000519, 1.4791, 0.92968, 0.13198);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 0.004340514148426548 (Kairos 0.1.0; certified between 0.004340514148425512 and 0.004340514148427585: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 0.004340514148426548, 2.137432582315674e-06);
}
