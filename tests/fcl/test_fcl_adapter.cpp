// SPDX-License-Identifier: MIT
// kairos_fcl: the adapter's conversions against closed forms and FCL's own support functions,
// the motion mapping, the verdicts on made-up FCL answers, and the checker on FCL's known wrong
// answers (fcl#508 with GST_LIBCCD, the GST_INDEP hull pair 0.119 for 0.0802) and on campaigns
// where FCL is right (sphere/sphere, axis-aligned boxes with GST_INDEP). Every real FCL call runs
// in a forked child (campaign::run_guarded): the Debian build can abort.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/narrowphase/detail/convexity_based_algorithm/minkowski_diff.h>

#include "campaign.hpp"

using namespace kairos::fcl_check;
using namespace kairos::fcl_check::campaign;

namespace {

fcl::Vector3d unit(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    for (;;) {
        const fcl::Vector3d v(g(rng), g(rng), g(rng));
        if (v.norm() > 1e-3) return v.normalized();
    }
}

fcl::Quaterniond random_rotation(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    return fcl::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
}

double support_value(const kairos_shape* s, const kairos_pose& pose, const fcl::Vector3d& d) {
    const kairos_vec3 p = world_support(s, pose, {d[0], d[1], d[2]});
    return d[0] * p.x + d[1] * p.y + d[2] * p.z;
}

std::vector<std::shared_ptr<fcl::ShapeBased>> every_kind() {
    auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
    std::vector<Point> points;
    std::mt19937_64 rng(11);
    for (int i = 0; i < 20; ++i) {
        const fcl::Vector3d v = unit(rng).cwiseProduct(fcl::Vector3d(0.7, 1.1, 0.4));
        points.push_back({v[0] + 0.3, v[1] - 0.2, v[2] + 0.1});  // off-centre: hulls are never recentred
    }
    std::vector<Point> hull;
    std::vector<std::array<int, 3>> triangles;
    EXPECT_TRUE(build_hull(points, hull, triangles));
    auto faces = std::make_shared<std::vector<int>>();
    for (const Point& p : hull) vertices->emplace_back(p[0], p[1], p[2]);
    for (const auto& t : triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
    return {std::make_shared<fcl::Sphered>(0.7),
            std::make_shared<fcl::Boxd>(0.6, 1.4, 2.2),
            std::make_shared<fcl::Capsuled>(0.35, 1.8),
            std::make_shared<fcl::Cylinderd>(0.45, 1.3),
            std::make_shared<fcl::Coned>(0.55, 1.7),
            std::make_shared<fcl::Ellipsoidd>(0.5, 1.2, 0.8),
            std::make_shared<fcl::Convexd>(vertices, int(triangles.size()), faces)};
}

Case box_pair(double side, Point pa, Point pb) {
    Case c;
    c.a.kind = c.b.kind = Kind::Box;
    c.a.size = c.b.size = {side, side, side};
    c.a0.p = pa;
    c.b0.p = pb;
    return c;
}

const Verdict* find(const std::vector<Verdict>& v, const std::string& quantity) {
    for (const Verdict& x : v)
        if (x.quantity == quantity) return &x;
    return nullptr;
}

}  // namespace

// Every converted shape has FCL's own support function (fcl::detail::getSupport, the one GST_INDEP
// uses), in the shape's local frame and after a random pose: sizes (full against half), the
// capsule's length without its caps, the cone's apex at +lz/2, the ellipsoid's radii, the hull.
TEST(FclAdapter, ShapesHaveFclsSupportFunctions) {
    std::mt19937_64 rng(2024);
    for (const auto& g : every_kind()) {
        SCOPED_TRACE(testing::Message() << "node type " << int(g->getNodeType()));
        const Shape k = to_kairos(*g);
        ASSERT_TRUE(k);
        const fcl::Transform3d tf = [&] {
            fcl::Transform3d t = fcl::Transform3d::Identity();
            t.linear() = random_rotation(rng).toRotationMatrix();
            t.translation() = fcl::Vector3d(0.4, -1.3, 2.0);
            return t;
        }();
        const kairos_pose identity{{0, 0, 0}, {0, 0, 0, 1}};
        const kairos_pose posed = to_kairos(tf);
        for (int i = 0; i < 300; ++i) {
            const fcl::Vector3d d = unit(rng);
            const fcl::Vector3d local = fcl::detail::getSupport(g.get(), d);
            EXPECT_NEAR(support_value(k.get(), identity, d), d.dot(local), 1e-12);
            const fcl::Vector3d world = tf * fcl::Vector3d(fcl::detail::getSupport(g.get(), tf.linear().transpose() * d));
            EXPECT_NEAR(support_value(k.get(), posed, d), d.dot(world), 1e-12);
        }
    }
}

// Closed forms: bounds of each primitive from FCL's parameters, the cone's apex and base, a
// triangle, and the distance between two balls.
TEST(FclAdapter, ConversionsMatchClosedForms) {
    const auto bounds = [](const fcl::CollisionGeometryd& g) {
        const Shape k = to_kairos(g);
        kairos_vec3 lo{}, hi{};
        EXPECT_EQ(kairos_shape_bounds(k.get(), nullptr, &lo, &hi), KAIROS_OK);
        return std::array<double, 6>{lo.x, lo.y, lo.z, hi.x, hi.y, hi.z};
    };
    EXPECT_EQ(bounds(fcl::Boxd(2, 4, 6)), (std::array<double, 6>{-1, -2, -3, 1, 2, 3}));
    EXPECT_EQ(bounds(fcl::Capsuled(0.5, 2)), (std::array<double, 6>{-0.5, -0.5, -1.5, 0.5, 0.5, 1.5}));
    EXPECT_EQ(bounds(fcl::Cylinderd(0.5, 2)), (std::array<double, 6>{-0.5, -0.5, -1, 0.5, 0.5, 1}));
    EXPECT_EQ(bounds(fcl::Coned(0.5, 2)), (std::array<double, 6>{-0.5, -0.5, -1, 0.5, 0.5, 1}));
    const auto e = bounds(fcl::Ellipsoidd(1, 2, 3));
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(e[size_t(i)], -(i + 1.0), 1e-12);
        EXPECT_NEAR(e[size_t(i + 3)], i + 1.0, 1e-12);
    }
    const Shape cone = to_kairos(fcl::Coned(0.5, 2));
    kairos_vec3 p{};
    kairos_shape_support(cone.get(), {0, 0, 1}, &p);
    EXPECT_EQ(p.z, 1);  // the apex at +lz/2
    kairos_shape_support(cone.get(), {1, 0, -1}, &p);
    EXPECT_EQ(p.x, 0.5);
    EXPECT_EQ(p.z, -1);  // the base rim at -lz/2
    const Shape tri = to_kairos(fcl::TrianglePd(fcl::Vector3d(0, 0, 0), fcl::Vector3d(1, 0, 0), fcl::Vector3d(0, 2, 0)));
    kairos_shape_support(tri.get(), {0, 1, 0}, &p);
    EXPECT_EQ(p.y, 2);

    const Reference balls(fcl::Sphered(1), fcl::Transform3d::Identity(), fcl::Sphered(0.5),
                          to_fcl({{3, 0, 0}, {0, 0, 0, 1}}));
    EXPECT_NEAR(balls.distance().distance, 1.5, 1e-15);
    EXPECT_NEAR(balls.lower_bound(), 1.5, 1e-15);
    EXPECT_NEAR(balls.upper_bound(), 1.5, 1e-15);
    EXPECT_EQ(balls.size(), std::sqrt(3.0));  // the corner of the larger ball's bounding box

    EXPECT_THROW(to_kairos(fcl::Planed(0, 0, 1, 0)), ConversionError);
    EXPECT_THROW(to_kairos(fcl::Sphered(0)), ConversionError);
}

// Quaternion order: Eigen's constructor is (w, x, y, z), kairos_quat {x, y, z, w}.
TEST(FclAdapter, TransformsKeepTheRotation) {
    const double s = std::sqrt(0.5);
    fcl::Transform3d quarter = fcl::Transform3d::Identity();
    quarter.linear() = fcl::Quaterniond(s, 0, 0, s).toRotationMatrix();  // a quarter turn about z
    quarter.translation() = fcl::Vector3d(1, 2, 3);
    const kairos_pose k = to_kairos(quarter);
    EXPECT_NEAR(k.orientation.x, 0, 1e-15);
    EXPECT_NEAR(k.orientation.y, 0, 1e-15);
    EXPECT_NEAR(k.orientation.z, s, 1e-15);
    EXPECT_NEAR(k.orientation.w, s, 1e-15);
    EXPECT_EQ(k.position.x, 1);
    EXPECT_EQ(k.position.z, 3);
    // A rod along x turned a quarter about z lies along y.
    const Shape rod = to_kairos(fcl::Boxd(4, 0.2, 0.2));
    EXPECT_NEAR(world_support(rod.get(), k, {0, 1, 0}).y, 2 + 2, 1e-12);
    EXPECT_NEAR(world_support(rod.get(), k, {1, 0, 0}).x, 1 + 0.1, 1e-12);
    EXPECT_TRUE(to_fcl(k).isApprox(quarter, 1e-15));

    fcl::Transform3d scaled = quarter;
    scaled.linear() *= 1.01;
    EXPECT_THROW(to_kairos(scaled), ConversionError);
    fcl::Transform3d mirror = fcl::Transform3d::Identity();
    mirror.linear()(0, 0) = -1;
    EXPECT_THROW(to_kairos(mirror), ConversionError);
}

// Which FCL motions are Kairos's motion, and what the others do instead.
TEST(FclAdapter, MotionMapping) {
    const auto tf = [](fcl::Quaterniond q, fcl::Vector3d t) {
        fcl::Transform3d x = fcl::Transform3d::Identity();
        x.linear() = q.toRotationMatrix();
        x.translation() = t;
        return x;
    };
    const fcl::Quaterniond id = fcl::Quaterniond::Identity();
    const fcl::Quaterniond turn_z(Eigen::AngleAxisd(0.8, fcl::Vector3d::UnitZ()));
    const fcl::Vector3d o(0.5, 0, 0);

    const Motion trans = map_motion(tf(id, o), tf(turn_z, o + fcl::Vector3d(2, 0, 0)), fcl::CCDM_TRANS);
    EXPECT_TRUE(trans.same);
    EXPECT_TRUE(trans.translation_only);
    EXPECT_NE(trans.note.find("ignores the end"), std::string::npos) << trans.note;
    EXPECT_EQ(trans.motion.end.orientation.w, 1);  // the end turn dropped, as FCL does
    EXPECT_EQ(trans.motion.end.position.x, 2.5);

    EXPECT_FALSE(map_motion(tf(id, o), tf(turn_z, o), fcl::CCDM_LINEAR).same);
    EXPECT_FALSE(map_motion(tf(id, o), tf(turn_z, o), fcl::CCDM_SPLINE).same);
    // Screw without a turn: the translation scaled by its length, unless that length is 1.
    const Motion screw2 = map_motion(tf(id, o), tf(id, o + fcl::Vector3d(2, 0, 0)), fcl::CCDM_SCREW);
    EXPECT_FALSE(screw2.same);
    EXPECT_NE(screw2.note.find("|d| d"), std::string::npos) << screw2.note;
    EXPECT_TRUE(map_motion(tf(id, o), tf(id, o + fcl::Vector3d(0, 1, 0)), fcl::CCDM_SCREW).same);
    // Screw with a turn: Kairos's motion exactly when the translation lies along the axis.
    const Motion spin = map_motion(tf(id, o), tf(turn_z, o), fcl::CCDM_SCREW);
    EXPECT_TRUE(spin.same);
    EXPECT_FALSE(spin.translation_only);
    EXPECT_TRUE(map_motion(tf(id, o), tf(turn_z, o + fcl::Vector3d(0, 0, 1.5)), fcl::CCDM_SCREW).same);
    const Motion helix = map_motion(tf(id, o), tf(turn_z, o + fcl::Vector3d(1, 0, 0)), fcl::CCDM_SCREW);
    EXPECT_FALSE(helix.same);
    EXPECT_NE(helix.note.find("helix"), std::string::npos) << helix.note;
}

// The verdicts on answers made up to be right and wrong, without running FCL.
TEST(FclChecker, VerdictsOnMadeUpAnswers) {
    const fcl::Sphered a(1), b(0.5);
    const fcl::Transform3d ta = fcl::Transform3d::Identity();
    const fcl::Transform3d tb = to_fcl({{3, 0, 0}, {0, 0, 0, 1}});
    fcl::DistanceRequestd dreq;
    dreq.enable_nearest_points = true;
    fcl::DistanceResultd dres;
    dres.min_distance = 1.5;
    dres.nearest_points[0] = fcl::Vector3d(1, 0, 0);
    dres.nearest_points[1] = fcl::Vector3d(2.5, 0, 0);
    EXPECT_EQ(check_distance(a, ta, b, tb, dreq, dres).outcome, Outcome::Agree);
    EXPECT_EQ(check_nearest_points(a, ta, b, tb, dreq, dres).outcome, Outcome::Agree);
    dres.nearest_points[1] = fcl::Vector3d(2.5, 0.5, 0);  // off B, and too far from p0
    const Verdict np = check_nearest_points(a, ta, b, tb, dreq, dres);
    EXPECT_EQ(np.outcome, Outcome::FclOff) << to_string(np);
    dres.min_distance = 1.6;
    const Verdict d = check_distance(a, ta, b, tb, dreq, dres);
    EXPECT_EQ(d.outcome, Outcome::FclOff);
    EXPECT_NEAR(d.error, 0.1, 1e-12);
    dres.min_distance = -1;  // "intersecting" while 1.5 apart
    EXPECT_EQ(check_distance(a, ta, b, tb, dreq, dres).outcome, Outcome::FclOff);

    fcl::CollisionRequestd creq;
    fcl::CollisionResultd none, one;
    one.addContact(fcl::Contactd());
    EXPECT_EQ(check_collision(a, ta, b, tb, creq, none).outcome, Outcome::Agree);
    EXPECT_EQ(check_collision(a, ta, b, tb, creq, one).outcome, Outcome::FclOff);
    const fcl::Transform3d touching = to_fcl({{1.5, 0, 0}, {0, 0, 0, 1}});
    EXPECT_EQ(check_collision(a, ta, b, touching, creq, one).outcome, Outcome::NotJudged);

    // B moves from x = 4 to x = 0 towards A: first contact at t = 2.5 / 4.
    const fcl::Transform3d b0 = to_fcl({{4, 0, 0}, {0, 0, 0, 1}}), b1 = fcl::Transform3d::Identity();
    fcl::ContinuousCollisionRequestd ccd;
    ccd.ccd_motion_type = fcl::CCDM_TRANS;
    ccd.ccd_solver_type = fcl::CCDC_CONSERVATIVE_ADVANCEMENT;
    fcl::ContinuousCollisionResultd hit;
    hit.is_collide = true;
    hit.time_of_contact = 0.625 - 1e-5;
    EXPECT_EQ(check_continuous(a, ta, ta, b, b0, b1, ccd, hit).outcome, Outcome::Agree);
    hit.time_of_contact = 0.7;  // late: they overlap from 0.625 on
    const Verdict late = check_continuous(a, ta, ta, b, b0, b1, ccd, hit);
    EXPECT_EQ(late.outcome, Outcome::FclOff) << to_string(late);
    EXPECT_NEAR(late.upper, 0.625, 1e-6);
    hit.time_of_contact = 0.3;  // early by far more than FCL's stopping gap
    EXPECT_EQ(check_continuous(a, ta, ta, b, b0, b1, ccd, hit).outcome, Outcome::FclOff);
    fcl::ContinuousCollisionResultd miss;
    miss.is_collide = false;
    miss.time_of_contact = 1;
    EXPECT_EQ(check_continuous(a, ta, ta, b, b0, b1, ccd, miss).outcome, Outcome::FclOff);
    // Naive: 10 samples at i / 9; the first overlapping one is 6 / 9.
    ccd.ccd_solver_type = fcl::CCDC_NAIVE;
    hit.time_of_contact = 6.0 / 9;
    const Verdict naive = check_continuous(a, ta, ta, b, b0, b1, ccd, hit);
    EXPECT_EQ(naive.outcome, Outcome::Agree) << to_string(naive);
    EXPECT_EQ(naive.kairos, 6.0 / 9);
    hit.time_of_contact = 7.0 / 9;
    EXPECT_EQ(check_continuous(a, ta, ta, b, b0, b1, ccd, hit).outcome, Outcome::FclOff);
    // A motion FCL does not share is not judged.
    ccd.ccd_motion_type = fcl::CCDM_LINEAR;
    EXPECT_EQ(check_continuous(a, ta, ta, b, b0, b1, ccd, hit).outcome, Outcome::NotJudged);
}

// fcl#508: unit cubes, one at (0, 4, 0) (or z), the other at the origin: GST_LIBCCD reports
// sqrt(10) = 3.162 for a distance of 3. Along x, and with GST_INDEP, FCL is right.
TEST(FclChecker, FlagsFcl508) {
    const std::vector<Case> cases = {box_pair(1, {0, 4, 0}, {0, 0, 0}), box_pair(1, {0, 0, 4}, {0, 0, 0}),
                                     box_pair(1, {4, 0, 0}, {0, 0, 0})};
    Settings s;
    s.solver = Solver::Libccd;
    const std::vector<Answer> ccd = run_guarded(cases, s);
    for (size_t i = 0; i < cases.size(); ++i) {
        ASSERT_EQ(ccd[i].status, Answered) << ccd[i].message;
        const std::vector<Verdict> verdicts = judge(cases[i], s, ccd[i]);
        const Verdict* v = find(verdicts, "distance");
        ASSERT_NE(v, nullptr);
        std::printf("[fcl#508] offset along %c: %s\n", "yzx"[i], to_string(*v).c_str());
        EXPECT_EQ(v->kairos, 3);
        EXPECT_EQ(v->lower, 3);
        EXPECT_EQ(v->upper, 3);
        if (i < 2) {
            EXPECT_EQ(v->outcome, Outcome::FclOff);
            EXPECT_NEAR(v->fcl, std::sqrt(10.0), 1e-9);
            EXPECT_NEAR(v->error, std::sqrt(10.0) - 3, 1e-9);
        } else {
            EXPECT_EQ(v->outcome, Outcome::Agree);
        }
    }
    s.solver = Solver::Indep;
    const std::vector<Answer> indep = run_guarded(cases, s);
    for (size_t i = 0; i < cases.size(); ++i)
        EXPECT_EQ(judge(cases[i], s, indep[i])[0].outcome, Outcome::Agree);

    // Shrunk, it stays wrong, and its reproducer asserts the right distance in FCL's own API.
    s.solver = Solver::Libccd;
    Case noisy = box_pair(1, {0.3, 4.0625, -0.2}, {0.3, 0, -0.2});
    const Case small = shrink(noisy, s, "distance");
    const Reproducer r = write_reproducer(small, s, "distance", 1, true);
    EXPECT_TRUE(r.fails);
    EXPECT_NE(r.source.find("TEST(KairosFound, DistanceGstLibccdBoxBox"), std::string::npos);
    EXPECT_NE(r.source.find("request.gjk_solver_type = fcl::GST_LIBCCD;"), std::string::npos);
    EXPECT_NE(r.source.find("fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result);"), std::string::npos);
    EXPECT_NE(r.source.find("EXPECT_NEAR(result.min_distance, "), std::string::npos) << r.source;
    EXPECT_EQ(small.a0.p, (Point{0, 0, 0}));  // moved to the origin
}

// The hull pair tests/gjk/test_gjk_peers.cpp found (random_pairs(5150), pair 475): GST_INDEP
// reports 0.119 where the distance is 0.0802.
TEST(FclChecker, FlagsGstIndepHullPair) {
    const std::vector<Point> a_points = {
        {-0.2280629121388312, 0.4576485753418999, 0.26611095269037954},
        {-0.13284527939635074, -0.76706416410308365, -0.26680864147649691},
        {-0.15216697253870204, -0.90138467641182562, -0.0069841194904558222},
        {-0.018212817961346103, 0.90625454803031391, 0.23299499302898607},
        {-0.35326743060880417, -0.13083833601628916, 0.10469390329863933},
        {0.065451685297343701, 0.90492855430383057, 0.15567081666284527},
        {0.2859925448506842, 0.59594057164247305, -0.073054322116465162},
        {0.05704766680139961, -1.1135554024008543, 0.13537358699117594},
        {0.31079505844757949, -0.75588139652950714, 0.13863931461807547},
        {0.10115407848193303, 0.12335161526552639, 0.41765465618801945},
        {-0.24600736859795475, 0.97013140514818086, 0.032718780093447655},
        {0.047176235573716918, 1.0645332941752317, -0.1507589021614251},
        {-0.11498505440093995, -0.37819989241743152, -0.40912485581675023},
        {-0.3505169973292166, -0.67413492527537, -0.071568309219268642},
        {0.30526868536885721, 0.40428101358578927, -0.26914291886789526},
        {-0.12028884587970647, -0.91798217918069436, 0.12290282687763114},
        {-0.35115793921561722, -0.22424061505829548, 0.069914869854145689},
        {0.29727048078066726, 0.025780582202471914, -0.36686341710089965},
        {0.05135822001195256, -1.16664424963333, -0.10871992338523261},
        {-0.30807043792775135, 0.59525370062823735, 0.0036361826715843597},
        {0.22114190747558088, 0.21702128870157911, -0.34921640972681339},
        {0.18452560795845452, -0.50018236042753295, 0.38808173902571097},
        {-0.27596066422089416, 0.0091441463362917745, -0.31305199951630575},
        {0.15053945854185674, 0.96881791734933698, 0.020228194597169444},
        {0.19938469825145147, -0.55837883152738232, -0.290550406414258},
        {-0.16572269052425245, -0.88594513326952251, 0.023885467989602296},
        {-0.078423587418654336, 0.35438163010377066, 0.45823071803962884},
        {0.29274629997534524, 0.50261743149755744, -0.15553325263030032},
        {0.14079790564062106, -0.83789916112861929, 0.19161198236441884},
        {0.40003125339093198, 0.0021026470682972082, 0.0709844948442067},
        {0.24833258042888623, 0.96087102833076909, -0.048561301434205222},
        {0.35107084848709819, -0.58367575860943355, 0.1806661225986288},
        {-0.16480688383726652, -0.92675366126941627, 0.093530216975983571},
        {0.21739279750929802, 0.70929988039158332, -0.13800346799330768},
        {0.0072130528961402074, 0.7774596394301676, 0.30942793243975542},
        {-0.068326811423744388, 0.32750479547903127, 0.44042753495251286},
        {0.26005607463439329, -0.79238581821020992, -0.17909423128597113},
        {0.17742565929722059, -0.86109490743997941, -0.28707010543118627},
        {-0.16696017598436283, -0.47191018745203772, -0.32197074528158481},
        {-0.29438475135833869, -0.2605462816396773, 0.26614775670896779},
        {-0.38427201373559811, -0.50684267471076283, -0.14077187917000378},
        {-0.3501030840599883, 0.62471963170928846, 0.075975390869775311},
        {-0.19881058053267184, -0.37157071286590698, 0.41453524801269359},
        {0.29322797103489656, 0.4811176416752258, -0.19385714792451833},
        {0.066451244775113646, -1.0039766258702878, -0.28871339536416113},
        {-0.40473189343254373, -0.26231414577896833, -0.15521176002956763},
        {-0.35213422337055472, 0.37311646098826812, 0.1841436383751304},
        {-0.33220862628617687, 0.41385086761182849, -0.15717952457302453},
        {-0.092800523187441183, -0.30151550530185794, -0.43945658951056166},
        {0.065097559661780241, 0.073946484840204232, -0.4831777938939103},
        {-0.2408308144024302, -0.49044628573639243, 0.25016321405466624},
        {-0.32941958863693072, -0.57092246553130255, 0.089666292223495328}};
    const std::vector<Point> b_points = {{0.73670365445970953, -0.25617916470830909, 0.36249203742921854},
                                         {0.24154662081275169, -1.0387271121724833, 0.41283045703812732},
                                         {-0.87192040118885117, 0.36457501410168586, 0.15923318649797347},
                                         {0.43102671675556714, -0.89488258994603365, 0.61532988716261261},
                                         {0.46545087190352008, 0.30187447229439079, -0.90485383704838884},
                                         {0.31808513443350411, 0.74468657014855555, 0.77144611865336987},
                                         {-0.72877042644168466, 0.40235934845949811, -0.51913371872007008},
                                         {0.32746604073165292, -0.073881947830524861, -1.1174899208732743},
                                         {0.74721469654807637, -0.43424102148161792, -0.27436660168860716},
                                         {0.14590783330606535, -0.31297520848123633, 0.94649138123735188},
                                         {0.56400440696293008, 0.89097624743422543, 0.35333054028949518}};
    Case c;
    c.a.kind = c.b.kind = Kind::Convex;
    ASSERT_TRUE(build_hull(a_points, c.a.vertices, c.a.triangles));
    ASSERT_TRUE(build_hull(b_points, c.b.vertices, c.b.triangles));
    // Poses: the quaternions as (w, x, y, z).
    c.a0.p = {-0.10707658935289562, 0.13799801724777577, -0.097422539734057151};
    c.a0.q = {0.32524457327403716, 0.22557140734350359, -0.50964824162488176, -0.76393205035102874};
    c.b0.p = {0.65732316214819797, -0.66789029644380471, -1.2059774108992913};
    c.b0.q = {-0.53355071468963289, 0.35454331513412873, -0.074255504906654723, 0.76427010443883103};
    Settings s;
    s.solver = Solver::Indep;
    const Answer a = run_guarded({c}, s)[0];
    ASSERT_EQ(a.status, Answered) << a.message;
    const std::vector<Verdict> verdicts = judge(c, s, a);
    const Verdict* v = find(verdicts, "distance");
    ASSERT_NE(v, nullptr);
    std::printf("[GST_INDEP hull pair] %s\n", to_string(*v).c_str());
    EXPECT_EQ(v->outcome, Outcome::FclOff);
    EXPECT_NEAR(v->kairos, 0.0802, 1e-4);
    EXPECT_NEAR(v->fcl, 0.119, 1e-3);
    EXPECT_LT(v->upper - v->lower, 1e-12);
}

// Cases where FCL is right: no disagreement may be reported. Ball pairs (both solvers) at gaps
// from overlapping to apart, and axis-aligned boxes with GST_INDEP offset in every direction.
TEST(FclChecker, AgreesWhereFclIsRight) {
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Case> balls, boxes;
    for (int i = 0; i < 1500; ++i) {
        Case c;
        c.a.kind = c.b.kind = Kind::Sphere;
        c.a.size[0] = 0.2 + u(rng), c.b.size[0] = 0.2 + u(rng);
        const fcl::Quaterniond qa = random_rotation(rng), qb = random_rotation(rng);
        c.a0.q = {qa.w(), qa.x(), qa.y(), qa.z()};
        c.b0.q = {qb.w(), qb.x(), qb.y(), qb.z()};
        const fcl::Vector3d d = unit(rng) * (c.a.size[0] + c.b.size[0]) * (0.5 + u(rng));
        c.a0.p = {u(rng), u(rng), u(rng)};
        c.b0.p = {c.a0.p[0] + d[0], c.a0.p[1] + d[1], c.a0.p[2] + d[2]};
        balls.push_back(c);
        Case b;
        b.a.kind = b.b.kind = Kind::Box;
        b.a.size = {0.2 + u(rng), 0.2 + u(rng), 0.2 + u(rng)};
        b.b.size = {0.2 + u(rng), 0.2 + u(rng), 0.2 + u(rng)};
        const fcl::Vector3d e = unit(rng) * (1.5 * u(rng) + 0.1);
        b.b0.p = {e[0], e[1], e[2]};
        boxes.push_back(b);
    }
    int judged = 0, intersecting = 0;
    const auto campaign = [&](const std::vector<Case>& cases, Solver solver) {
        Settings s;
        s.solver = solver;
        const std::vector<Answer> answers = run_guarded(cases, s);
        for (size_t i = 0; i < cases.size(); ++i) {
            ASSERT_EQ(answers[i].status, Answered) << answers[i].message;
            for (const Verdict& v : judge(cases[i], s, answers[i])) {
                EXPECT_NE(v.outcome, Outcome::FclOff)
                    << solver_name(solver) << " case " << i << ": " << to_string(v);
                judged += v.outcome == Outcome::Agree;
                intersecting += v.quantity == "distance" && v.upper == 0;
            }
        }
    };
    campaign(balls, Solver::Libccd);
    campaign(balls, Solver::Indep);
    campaign(boxes, Solver::Indep);
    std::printf("[FCL right] %d agreeing verdicts, %d intersecting pairs\n", judged, intersecting);
    EXPECT_GT(judged, 5000);
    EXPECT_GT(intersecting, 500);
}

// A crash (the Debian build's assertion in libccd, found by the campaign: a ball touching an
// ellipsoid) is counted and the runner goes on with the next case.
TEST(FclChecker, SurvivesCrashes) {
    Case touching;
    touching.a.kind = Kind::Sphere;
    touching.a.size = {0.5, 0, 0};
    touching.b.kind = Kind::Ellipsoid;
    touching.b.size = {0.5, 0.5, 0.5};
    touching.b0.p = {1, 0, 0};
    Settings s;
    s.solver = Solver::Libccd;
    const std::vector<Answer> a = run_guarded({touching, box_pair(1, {4, 0, 0}, {0, 0, 0})}, s);
    std::printf("[crash] ball touching an ellipsoid, GST_LIBCCD: status %d %s\n", a[0].status, a[0].message);
    EXPECT_TRUE(a[0].status == Crashed || a[0].status == Answered);
    EXPECT_EQ(a[1].status, Answered);
    EXPECT_EQ(a[1].value, 3);
}
