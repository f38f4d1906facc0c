// Reproducer for FCL 0.7.0: distance (GST_INDEP) between a cone and a cylinder: distance.
// FCL 0.7.0 returns min_distance 0.0009926822369346277; expected: distance 0.00027337327292033156.
// Found by kairos-fcl-check (Kairos 0.1.0) with --seed 1, case 7028 (family scale), shrunk.
// Build: g++ $(pkg-config --cflags fcl) -std=c++17 distance-indep-cone-cylinder-scale.cpp -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/cylinder.h>
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

TEST(KairosFound, DistanceGstIndepConeCylinderScale) {
  const auto a = std::make_shared<fcl::Coned>(0.000266, 0.000963);
  const auto b = std::make_shared<fcl::Cylinderd>(0.000257, 0.00157);
  const fcl::Transform3d tf_a = pose(-0.6373066692764355, -0.057227537649312585, 0.31415116821475786, 0.7013374806323097, 0, 0, 0);
  const fcl::Transform3d tf_b = pose(-0.6992101442272558, -0.5291590361891536, -0.446134083441139, -0.17905381375776652, 0.00117, -0.000165, -0.000844);
  fcl::DistanceRequestd request;
  request.gjk_solver_type = fcl::GST_INDEP;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);
  // The distance is 0.00027337327292033156 (Kairos 0.1.0; certified between 0.0002733732729202714 and 0.0002733732729203918: the gap along its separating axis and the distance between two points of the shapes).
  EXPECT_NEAR(result.min_distance, 0.00027337327292033156, 1.0008650567289154e-06);
}
