// SPDX-License-Identifier: MIT
// Reproducers in FCL's own test style: one self-contained GoogleTest case per disagreement,
// written with FCL's API only, the expected value from Kairos and a tolerance, and the numbers in
// the shortest decimal form that reads back to the same double.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <set>
#include <sstream>

#include <fcl/config.h>

#include "campaign.hpp"

namespace kairos::fcl_check::campaign {

namespace {

std::string num(double v) {
    if (v == 0) return "0";
    char buf[40];
    for (int p = 1; p <= 17; ++p) {
        std::snprintf(buf, sizeof buf, "%.*g", p, v);
        if (std::strtod(buf, nullptr) == v) break;
    }
    return buf;
}

std::string with_article(const char* noun) {
    return std::string(std::strchr("aeiou", noun[0]) ? "an " : "a ") + noun;
}

std::string camel(const std::string& s) {
    std::string out;
    bool up = true;
    for (char ch : s) {
        if (ch == ' ' || ch == '_' || ch == '-') {
            up = true;
            continue;
        }
        out += up ? char(std::toupper(static_cast<unsigned char>(ch))) : char(std::tolower(static_cast<unsigned char>(ch)));
        up = false;
    }
    return out;
}

std::string kairos_version_string() {
    const uint32_t v = kairos_version();
    return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
}

// C++ for the geometry `name` of spec s.
std::string geometry_source(const ShapeSpec& s, const std::string& name) {
    std::ostringstream o;
    if (s.kind != Kind::Convex) {
        const int n = s.kind == Kind::Sphere ? 1 : (s.kind == Kind::Box || s.kind == Kind::Ellipsoid) ? 3 : 2;
        o << "  const auto " << name << " = std::make_shared<fcl::" << fcl_class_name(s.kind) << ">(";
        for (int i = 0; i < n; ++i) o << (i ? ", " : "") << num(s.size[size_t(i)]);
        o << ");\n";
        return o.str();
    }
    o << "  const auto " << name << "_vertices = std::make_shared<const std::vector<fcl::Vector3d>>(std::vector<fcl::Vector3d>{\n";
    for (const Point& v : s.vertices)
        o << "      fcl::Vector3d(" << num(v[0]) << ", " << num(v[1]) << ", " << num(v[2]) << "),\n";
    o << "  });\n";
    o << "  const auto " << name << "_faces = std::make_shared<const std::vector<int>>(std::vector<int>{\n";
    for (const auto& t : s.triangles) o << "      3, " << t[0] << ", " << t[1] << ", " << t[2] << ",\n";
    o << "  });\n";
    o << "  const auto " << name << " = std::make_shared<fcl::Convexd>(" << name << "_vertices, "
      << s.triangles.size() << ", " << name << "_faces);\n";
    return o.str();
}

std::string pose_source(const PoseSpec& p) {
    return "pose(" + num(p.q[0]) + ", " + num(p.q[1]) + ", " + num(p.q[2]) + ", " + num(p.q[3]) + ", " + num(p.p[0]) +
           ", " + num(p.p[1]) + ", " + num(p.p[2]) + ")";
}

// How far the local point q lies outside s: <= 0 inside; outside, a lower bound of the distance
// (the largest violated half-space, or a scaled sphere distance for the ellipsoid). The same
// formula as outside_source writes.
double outside(const ShapeSpec& s, const fcl::Vector3d& q) {
    switch (s.kind) {
        case Kind::Sphere:
            return q.norm() - s.size[0];
        case Kind::Box:
            return (q.cwiseAbs() - fcl::Vector3d(s.size[0] / 2, s.size[1] / 2, s.size[2] / 2)).maxCoeff();
        case Kind::Capsule: {
            const double h = s.size[1] / 2;
            return fcl::Vector3d(q[0], q[1], q[2] - std::clamp(q[2], -h, h)).norm() - s.size[0];
        }
        case Kind::Cylinder:
            return std::max(std::hypot(q[0], q[1]) - s.size[0], std::abs(q[2]) - s.size[1] / 2);
        case Kind::Cone: {
            const double r = s.size[0], h = s.size[1] / 2;
            return std::max(-h - q[2], (2 * h * std::hypot(q[0], q[1]) + r * q[2] - r * h) / std::sqrt(4 * h * h + r * r));
        }
        case Kind::Ellipsoid: {
            const fcl::Vector3d radii(s.size[0], s.size[1], s.size[2]);
            return radii.minCoeff() * (q.cwiseQuotient(radii).norm() - 1);
        }
        case Kind::Convex: {
            double most = -1e300;
            for (const auto& t : s.triangles) {
                const fcl::Vector3d v0(s.vertices[size_t(t[0])][0], s.vertices[size_t(t[0])][1], s.vertices[size_t(t[0])][2]);
                const fcl::Vector3d v1(s.vertices[size_t(t[1])][0], s.vertices[size_t(t[1])][1], s.vertices[size_t(t[1])][2]);
                const fcl::Vector3d v2(s.vertices[size_t(t[2])][0], s.vertices[size_t(t[2])][1], s.vertices[size_t(t[2])][2]);
                const fcl::Vector3d n = (v1 - v0).cross(v2 - v0).normalized();
                most = std::max(most, n.dot(q - v0));
            }
            return most;
        }
    }
    return 0;
}

std::string outside_source(const ShapeSpec& s, const std::string& name) {
    std::ostringstream o;
    o << "  // > 0: how far a point (in " << name << "'s frame) lies outside " << name << ", a lower bound.\n";
    o << "  const auto outside_" << name << " = [&](const fcl::Vector3d& q) {\n";
    const std::string r = num(s.size[0]);
    switch (s.kind) {
        case Kind::Sphere:
            o << "    return q.norm() - " << r << ";\n";
            break;
        case Kind::Box:
            o << "    return (q.cwiseAbs() - fcl::Vector3d(" << num(s.size[0]) << ", " << num(s.size[1]) << ", "
              << num(s.size[2]) << ") / 2).maxCoeff();\n";
            break;
        case Kind::Capsule:
            o << "    const double h = " << num(s.size[1]) << " / 2.0;\n"
              << "    return fcl::Vector3d(q[0], q[1], q[2] - std::clamp(q[2], -h, h)).norm() - " << r << ";\n";
            break;
        case Kind::Cylinder:
            o << "    return std::max(std::hypot(q[0], q[1]) - " << r << ", std::abs(q[2]) - " << num(s.size[1])
              << " / 2.0);\n";
            break;
        case Kind::Cone:
            o << "    const double r = " << r << ", h = " << num(s.size[1]) << " / 2.0;\n"
              << "    return std::max(-h - q[2], (2 * h * std::hypot(q[0], q[1]) + r * q[2] - r * h) / "
                 "std::sqrt(4 * h * h + r * r));\n";
            break;
        case Kind::Ellipsoid:
            o << "    const fcl::Vector3d radii(" << num(s.size[0]) << ", " << num(s.size[1]) << ", " << num(s.size[2])
              << ");\n"
              << "    return radii.minCoeff() * (q.cwiseQuotient(radii).norm() - 1);\n";
            break;
        case Kind::Convex:
            o << "    double most = -1e300;\n"
              << "    const auto& v = *" << name << "_vertices;\n"
              << "    const auto& f = *" << name << "_faces;\n"
              << "    for (size_t i = 0; i < f.size(); i += 4) {\n"
              << "      const fcl::Vector3d n = (v[f[i + 2]] - v[f[i + 1]]).cross(v[f[i + 3]] - v[f[i + 1]]).normalized();\n"
              << "      most = std::max(most, n.dot(q - v[f[i + 1]]));\n"
              << "    }\n"
              << "    return most;\n";
            break;
    }
    o << "  };\n";
    return o.str();
}

const Verdict* find(const std::vector<Verdict>& v, const std::string& quantity) {
    for (const Verdict& x : v)
        if (x.quantity == quantity) return &x;
    return nullptr;
}

}  // namespace

Reproducer write_reproducer(const Case& c, const Settings& s, const std::string& what, uint64_t seed, bool shrunk) {
    Reproducer r;
    const Answer answer = run_guarded({c}, s, 1)[0];
    const bool died = answer.status != Answered;
    // Kairos's side of a crashed call: the verdicts on a made-up FCL answer carry it.
    Answer probe = answer;
    if (died) {
        probe = Answer{};
        probe.value = std::numeric_limits<double>::quiet_NaN();
    }
    const std::vector<Verdict> verdicts = judge(c, s, probe);
    const std::string kinds = std::string(kind_name(c.a.kind)) + "-" + kind_name(c.b.kind);
    const std::string solver = s.solver == Solver::Libccd ? "libccd" : "indep";
    std::string query_tag = what;
    if (s.query == Query::Continuous) query_tag += s.ccd == Ccd::Advancement ? " ca" : " naive";
    if (died) query_tag = std::string(query_name(s.query)) + " " + what;
    r.test_name = camel(query_tag) + camel(std::string("gst ") + solver) + camel(kind_name(c.a.kind)) +
                  camel(kind_name(c.b.kind)) + camel(c.family);
    r.file_name = query_tag + "-" + solver + "-" + kinds + "-" + c.family + ".cpp";
    for (char& ch : r.file_name)
        if (ch == ' ' || ch == '_') ch = '-';

    std::ostringstream body, claim;
    // FCL's shape headers are named as kind_name names the kinds.
    std::set<std::string> headers = {"fcl/geometry/shape/" + std::string(kind_name(c.a.kind)) + ".h",
                                     "fcl/geometry/shape/" + std::string(kind_name(c.b.kind)) + ".h"};
    body << geometry_source(c.a, "a") << geometry_source(c.b, "b");
    const std::string sv = std::string("fcl::") + solver_name(s.solver);
    std::string call;
    bool fails = true;
    switch (s.query) {
        case Query::Distance: {
            headers.insert("fcl/narrowphase/distance.h");
            body << "  const fcl::Transform3d tf_a = " << pose_source(c.a0) << ";\n"
                 << "  const fcl::Transform3d tf_b = " << pose_source(c.b0) << ";\n"
                 << "  fcl::DistanceRequestd request;\n"
                 << "  request.gjk_solver_type = " << sv << ";\n"
                 << "  request.enable_nearest_points = true;\n";
            if (s.distance_tolerance != 1e-6) body << "  request.distance_tolerance = " << num(s.distance_tolerance) << ";\n";
            body << "  fcl::DistanceResultd result;\n";
            call = "fcl::distance(a.get(), tf_a, b.get(), tf_b, request, result)";
            const Verdict* d = find(verdicts, "distance");
            const bool nearest = what == "nearest points";
            const Verdict* v = nearest ? find(verdicts, "nearest points") : d;
            if (!d || !v) break;
            const double band = d->tolerance;
            if (!died) claim << "FCL " << FCL_VERSION << " returns min_distance " << num(answer.value);
            if (nearest) {
                const fcl::Vector3d p0(answer.points[0], answer.points[1], answer.points[2]);
                const fcl::Vector3d p1(answer.points[3], answer.points[4], answer.points[5]);
                claim << " with nearest points (" << num(p0[0]) << ", " << num(p0[1]) << ", " << num(p0[2]) << ") and ("
                      << num(p1[0]) << ", " << num(p1[1]) << ", " << num(p1[2]) << ")";
            }
            const double expected = (d->lower + d->upper) / 2;
            const double tol = band + (d->upper - d->lower) / 2;
            const bool intersecting = d->upper == 0;
            std::ostringstream check;
            if (intersecting) {
                const double depth = -Reference(*make_geometry(c.a), make_transform(c.a0), *make_geometry(c.b),
                                                make_transform(c.b0))
                                          .signed_distance();
                r.summary = depth > 0 ? "the shapes intersect" : "the shapes touch";
                check << "  // The shapes " << (depth > 0 ? "intersect" : "touch") << " (Kairos "
                      << kairos_version_string() << ": depth " << num(depth)
                      << "): FCL must report a distance of at most 0.\n"
                      << "  EXPECT_LE(result.min_distance, " << num(band) << ");\n";
                if (!died) fails = answer.value > band;
            } else {
                r.summary = "distance " + num(expected);
                check << "  // The distance is " << num(expected) << " (Kairos " << kairos_version_string()
                      << "; certified between " << num(d->lower) << " and " << num(d->upper)
                      << ": the gap along its separating axis and the distance between two points of the shapes).\n";
                if (!nearest) {
                    check << "  EXPECT_NEAR(result.min_distance, " << num(expected) << ", " << num(tol) << ");\n";
                    if (!died) fails = !(std::fabs(answer.value - expected) <= tol);
                } else {
                    const fcl::Vector3d p0(answer.points[0], answer.points[1], answer.points[2]);
                    const fcl::Vector3d p1(answer.points[3], answer.points[4], answer.points[5]);
                    const double oa = outside(c.a, make_transform(c.a0).inverse() * p0);
                    const double ob = outside(c.b, make_transform(c.b0).inverse() * p1);
                    const double sep = (p1 - p0).norm();
                    fails = oa > band || ob > band || !(std::fabs(sep - expected) <= tol);
                    check << outside_source(c.a, "a") << outside_source(c.b, "b")
                          << "  const fcl::Vector3d& p0 = result.nearest_points[0];\n"
                          << "  const fcl::Vector3d& p1 = result.nearest_points[1];\n"
                          << "  EXPECT_LE(outside_a(tf_a.inverse() * p0), " << num(band) << ") << \"nearest_points[0] is not on a\";\n"
                          << "  EXPECT_LE(outside_b(tf_b.inverse() * p1), " << num(band) << ") << \"nearest_points[1] is not on b\";\n"
                          << "  EXPECT_NEAR((p1 - p0).norm(), " << num(expected) << ", " << num(tol) << ");\n";
                    r.summary = "nearest points on the shapes, " + num(expected) + " apart";
                }
            }
            body << (died ? "  EXPECT_NO_THROW(" + call + ");\n" : "  " + call + ";\n") << check.str();
            break;
        }
        case Query::Collide: {
            headers.insert("fcl/narrowphase/collision.h");
            body << "  const fcl::Transform3d tf_a = " << pose_source(c.a0) << ";\n"
                 << "  const fcl::Transform3d tf_b = " << pose_source(c.b0) << ";\n"
                 << "  fcl::CollisionRequestd request;\n"
                 << "  request.gjk_solver_type = " << sv << ";\n"
                 << "  fcl::CollisionResultd result;\n";
            call = "fcl::collide(a.get(), tf_a, b.get(), tf_b, request, result)";
            const Verdict* v = find(verdicts, "collision");
            if (!v) break;
            const bool expect = v->kairos == 1;
            if (!died) claim << "FCL " << FCL_VERSION << " reports " << (answer.hit ? "a collision" : "no collision");
            body << (died ? "  EXPECT_NO_THROW(" + call + ");\n" : "  " + call + ";\n");
            if (expect)
                body << "  // The shapes overlap (Kairos " << kairos_version_string() << ": depth "
                     << num(-Reference(*make_geometry(c.a), make_transform(c.a0), *make_geometry(c.b), make_transform(c.b0))
                                 .signed_distance())
                     << ").\n  EXPECT_TRUE(result.isCollision());\n";
            else
                body << "  // The shapes are at least " << num(v->lower) << " apart (Kairos " << kairos_version_string()
                     << ", certified by a separating plane).\n  EXPECT_FALSE(result.isCollision());\n";
            r.summary = expect ? "a collision" : "no collision";
            if (!died) fails = (answer.hit != 0) != expect;
            break;
        }
        case Query::Continuous: {
            headers.insert("fcl/narrowphase/continuous_collision.h");
            body << "  const fcl::Transform3d tf_a0 = " << pose_source(c.a0) << ";\n"
                 << "  const fcl::Transform3d tf_a1 = " << pose_source(c.a1) << ";\n"
                 << "  const fcl::Transform3d tf_b0 = " << pose_source(c.b0) << ";\n"
                 << "  const fcl::Transform3d tf_b1 = " << pose_source(c.b1) << ";\n"
                 << "  fcl::ContinuousCollisionRequestd request;\n"
                 << "  request.ccd_motion_type = " << (c.screw ? "fcl::CCDM_SCREW" : "fcl::CCDM_TRANS") << ";\n"
                 << "  request.gjk_solver_type = " << sv << ";\n"
                 << "  request.ccd_solver_type = fcl::" << ccd_name(s.ccd) << ";\n"
                 << "  fcl::ContinuousCollisionResultd result;\n";
            call = "fcl::continuousCollide(a.get(), tf_a0, tf_a1, b.get(), tf_b0, tf_b1, request, result)";
            const Verdict* v = find(verdicts, "time of contact");
            if (!v) break;
            if (!died)
                claim << "FCL " << FCL_VERSION << " reports "
                      << (answer.hit ? "contact at time " + num(answer.value) : std::string("no contact"));
            body << (died ? "  EXPECT_NO_THROW(" + call + ");\n" : "  " + call + ";\n");
            body << "  // Kairos " << kairos_version_string() << ": "
                 << (v->kairos < 1 ? "first contact at time " + num(v->kairos) : std::string("no contact")) << ".\n";
            const double toc = answer.hit ? answer.value : 1;
            if (s.ccd == Ccd::Naive) {
                if (v->lower < 1) {
                    body << "  // FCL's naive solver samples the motion; the first sample where the shapes overlap is "
                         << num(v->lower) << ".\n"
                         << "  ASSERT_TRUE(result.is_collide);\n"
                         << "  EXPECT_EQ(result.time_of_contact, " << num(v->lower) << ");\n";
                    r.summary = "contact at sample " + num(v->lower);
                    if (!died) fails = !answer.hit || toc != v->lower;
                } else {
                    body << "  // No sample of the motion has the shapes overlapping.\n  EXPECT_FALSE(result.is_collide);\n";
                    r.summary = "no contact at any sample";
                    if (!died) fails = answer.hit != 0;
                }
            } else if (!std::isnan(v->upper)) {
                body << "  // The shapes overlap by more than the tolerance at time " << num(v->upper)
                     << ": contact comes no later.\n"
                     << "  ASSERT_TRUE(result.is_collide);\n"
                     << "  EXPECT_LE(result.time_of_contact, " << num(v->upper) << ");\n";
                r.summary = "contact by time " + num(v->upper);
                if (!died) fails = !answer.hit || toc > v->upper;
            } else if (!std::isnan(v->lower)) {
                body << "  // Before time " << num(v->lower)
                     << " the shapes are apart by more than conservative advancement's stopping gap.\n"
                     << "  if (result.is_collide) EXPECT_GE(result.time_of_contact, " << num(v->lower) << ");\n";
                r.summary = "contact not before time " + num(v->lower);
                if (!died) fails = answer.hit && toc < v->lower;
            } else {
                body << "  // The shapes never come within the tolerance of each other.\n  EXPECT_FALSE(result.is_collide);\n";
                r.summary = "no contact";
                if (!died) fails = answer.hit != 0;
            }
            break;
        }
    }
    if (died) claim << "FCL " << FCL_VERSION << " " << (answer.status == TimedOut ? "does not return: " : "dies: ") << answer.message;
    r.fails = fails;
    for (const Verdict& v : verdicts)
        if (v.quantity == what && v.outcome == Outcome::FclOff && std::isnan(r.relative_error))
            r.relative_error = relative_error(v, c);

    std::ostringstream o;
    o << "// Reproducer for FCL " << FCL_VERSION << ": " << query_name(s.query) << " (" << solver_name(s.solver);
    if (s.query == Query::Continuous) o << ", " << ccd_name(s.ccd) << ", " << (c.screw ? "CCDM_SCREW" : "CCDM_TRANS");
    o << ") between " << with_article(kind_name(c.a.kind)) << " and " << with_article(kind_name(c.b.kind)) << ": "
      << what << ".\n"
      << "// " << claim.str() << "; expected: " << r.summary << ".\n"
      << "// Found by kairos-fcl-check (Kairos " << kairos_version_string() << ") with --seed " << seed << ", case "
      << c.id << " (family " << c.family << ")" << (shrunk ? ", shrunk" : "") << ".\n"
      << "// Build: g++ $(pkg-config --cflags fcl) -std=c++17 " << r.file_name
      << " -lgtest -lgtest_main $(pkg-config --libs fcl) -pthread\n"
      << "#include <algorithm>\n#include <cmath>\n#include <memory>\n#include <vector>\n\n#include <gtest/gtest.h>\n\n";
    for (const std::string& h : headers) o << "#include <" << h << ">\n";
    o << "\nnamespace {\n\n"
      << "// A rigid transform from the unit quaternion (w, x, y, z) and the translation (x, y, z).\n"
      << "fcl::Transform3d pose(double qw, double qx, double qy, double qz, double x, double y, double z) {\n"
      << "  fcl::Transform3d tf = fcl::Transform3d::Identity();\n"
      << "  tf.linear() = fcl::Quaterniond(qw, qx, qy, qz).toRotationMatrix();\n"
      << "  tf.translation() = fcl::Vector3d(x, y, z);\n"
      << "  return tf;\n"
      << "}\n\n"
      << "}  // namespace\n\n"
      << "TEST(KairosFound, " << r.test_name << ") {\n"
      << body.str() << "}\n";
    r.source = o.str();
    r.summary = claim.str() + "; expected " + r.summary;
    return r;
}

}  // namespace kairos::fcl_check::campaign
