// SPDX-License-Identifier: MIT
// The campaign behind kairos-fcl-check: cases described by FCL's own parameters, their
// generation by family, FCL run in time-limited child processes, verdicts, shrinking, and
// reproducers in FCL's test style. Internal to the tool and its test; not installed.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <fcl/geometry/collision_geometry.h>

#include "kairos/fcl.hpp"

namespace kairos::fcl_check::campaign {

enum class Kind { Sphere, Box, Capsule, Cylinder, Cone, Ellipsoid, Convex };
const char* kind_name(Kind kind);       // "sphere", "box", ...
const char* fcl_class_name(Kind kind);  // "Sphered", "Boxd", ...

using Point = std::array<double, 3>;

// A shape in FCL's constructor parameters: sphere {r}; box {x, y, z} full sides; capsule,
// cylinder, cone {r, lz}; ellipsoid {a, b, c} radii; convex: vertices and outward triangles.
struct ShapeSpec {
    Kind kind = Kind::Sphere;
    std::array<double, 3> size{};
    std::vector<Point> vertices;
    std::vector<std::array<int, 3>> triangles;
};

// A pose: translation p and the rotation of the quaternion q = (w, x, y, z), Eigen's constructor order.
struct PoseSpec {
    Point p{};
    std::array<double, 4> q{1, 0, 0, 0};
};

enum class Query { Distance, Collide, Continuous };
enum class Solver { Libccd, Indep };
enum class Ccd { Advancement, Naive };
const char* query_name(Query q);
const char* solver_name(Solver s);  // "GST_LIBCCD", "GST_INDEP"
const char* ccd_name(Ccd c);        // "CCDC_CONSERVATIVE_ADVANCEMENT", "CCDC_NAIVE"

struct Case {
    uint64_t id = 0;     // with the campaign's seed, regenerates the case
    std::string family;  // the generator family
    ShapeSpec a, b;
    PoseSpec a0, b0;     // poses; for continuous queries, at the start of the motion
    PoseSpec a1, b1;     // continuous queries: at the end
    bool screw = false;  // continuous: CCDM_SCREW (a pure turn of B) instead of CCDM_TRANS
};

// What FCL is asked, and how its answers are judged.
struct Settings {
    Query query = Query::Distance;
    Solver solver = Solver::Libccd;
    Ccd ccd = Ccd::Advancement;
    double distance_tolerance = 1e-6;  // DistanceRequest::distance_tolerance (FCL's default)
    Tolerance tolerance{};
    unsigned timeout_seconds = 5;  // per FCL call
    bool quiet_children = true;    // children's stderr to /dev/null (FCL prints warnings there)
};

std::shared_ptr<fcl::CollisionGeometryd> make_geometry(const ShapeSpec& s);
fcl::Transform3d make_transform(const PoseSpec& p);
fcl::DistanceRequestd distance_request(const Settings& s);
fcl::CollisionRequestd collision_request(const Settings& s);
fcl::ContinuousCollisionRequestd continuous_request(const Settings& s, const Case& c);

// The hull of points as FCL's Convex wants it: the vertices on the hull and outward triangles.
// false when the points are (nearly) coplanar, collinear or too few.
bool build_hull(const std::vector<Point>& points, std::vector<Point>& vertices,
                std::vector<std::array<int, 3>>& triangles);

// Whole-case transforms: sizes and positions scaled by factor; positions shifted by d.
void scale_case(Case& c, double factor);
void shift_case(Case& c, Point d);
// Bounding radius of the shape about its local origin (through the adapter).
double shape_radius(const ShapeSpec& s);

// ---- Families -------------------------------------------------------------------------------------

// Every family's name, in order; "random" first.
const std::vector<std::string>& family_names();
// Case `id` of a campaign: its family drawn from `families` (random 40 %, the others sharing the
// rest), then its shapes and poses; a function of (seed, id, query, families) alone.
Case generate(uint64_t seed, uint64_t id, Query query, const std::vector<std::string>& families);

// ---- Running FCL ----------------------------------------------------------------------------------

// Unsupported: FCL has no algorithm for the pair (it warns on stderr and returns its error value,
// e.g. conservative advancement with an Ellipsoid); not a wrong answer.
enum Status : int32_t { Answered = 0, Threw = 1, Crashed = 2, TimedOut = 3, Unsupported = 4 };

// FCL's answer to one case, written by the child through a pipe (a plain struct).
struct Answer {
    int32_t status = Answered;
    int32_t hit = 0;   // collide: isCollision(); continuous: is_collide
    double value = 0;  // distance: min_distance; continuous: time_of_contact
    double points[6] = {};  // distance: nearest_points[0], nearest_points[1]
    char message[120] = {};  // what was thrown, or the signal
};

// One FCL call in this process (may abort or hang: use run_guarded).
Answer run_fcl(const Case& c, const Settings& s);
// Runs cases[i] for every i in forked children, a batch per child, each call under alarm(): a
// child that dies marks its current case Crashed (TimedOut on SIGALRM) and a new child goes on
// from the next case. progress(done) is called after each batch.
std::vector<Answer> run_guarded(const std::vector<Case>& cases, const Settings& s, size_t batch = 512,
                                const std::function<void(size_t)>& progress = {});

// Verdicts on FCL's answer: distance gives "distance" and "nearest points", collide
// "collision", continuous "time of contact". Empty for a crash or timeout. reference: the
// case's Reference when the caller already has one (distance and collide), else built here.
std::vector<Verdict> judge(const Case& c, const Settings& s, const Answer& a, const Reference* reference = nullptr);

// ---- Shrinking and reproducers ------------------------------------------------------------------

// FCL's error in a verdict relative to the case: over the larger shape's bounding radius for
// lengths, as is for a time of contact (already a fraction of the step).
double relative_error(const Verdict& v, const Case& c);

// What a disagreement is: the quantity FCL got wrong, or "crash"/"timeout"/"exception".
std::string disagreement_of(const Case& c, const Settings& s, const Answer& a, const std::vector<Verdict>& v);
// A smaller case that still shows `what` with at least half of FCL's relative error (move to
// the origin, scale to unit size, drop turns, round numbers to fewer digits, drop hull
// vertices); each try runs FCL guarded. The case itself when FCL does not show `what` on it.
Case shrink(const Case& c, const Settings& s, const std::string& what);

struct Reproducer {
    std::string test_name;  // GoogleTest name, e.g. DistanceGstLibccdBoxBox
    std::string file_name;  // e.g. distance-libccd-box-box.cpp
    std::string source;     // the whole file
    std::string summary;    // one line: FCL's answer, the expected one
    bool fails = true;      // the assertions written fail on this FCL (checked by evaluating them)
    // FCL's error over the written case's size (NaN for a crash, exception or timeout).
    double relative_error = std::numeric_limits<double>::quiet_NaN();
};
Reproducer write_reproducer(const Case& c, const Settings& s, const std::string& what, uint64_t seed,
                            bool shrunk);

}  // namespace kairos::fcl_check::campaign
