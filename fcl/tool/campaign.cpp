// SPDX-License-Identifier: MIT
// The campaign's cases: FCL objects built from FCL's own parameters, and the families that
// generate them (random pairs, and the stability catalogue's hard families of bench/stability.cpp
// recast for FCL's shapes).
#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>

#include "campaign.hpp"

namespace kairos::fcl_check::campaign {

const char* kind_name(Kind kind) {
    static const char* names[] = {"sphere", "box", "capsule", "cylinder", "cone", "ellipsoid", "convex"};
    return names[int(kind)];
}
const char* fcl_class_name(Kind kind) {
    static const char* names[] = {"Sphered", "Boxd", "Capsuled", "Cylinderd", "Coned", "Ellipsoidd", "Convexd"};
    return names[int(kind)];
}
const char* query_name(Query q) {
    static const char* names[] = {"distance", "collide", "continuous"};
    return names[int(q)];
}
const char* solver_name(Solver s) { return s == Solver::Libccd ? "GST_LIBCCD" : "GST_INDEP"; }
const char* ccd_name(Ccd c) { return c == Ccd::Advancement ? "CCDC_CONSERVATIVE_ADVANCEMENT" : "CCDC_NAIVE"; }

std::shared_ptr<fcl::CollisionGeometryd> make_geometry(const ShapeSpec& s) {
    switch (s.kind) {
        case Kind::Sphere:
            return std::make_shared<fcl::Sphered>(s.size[0]);
        case Kind::Box:
            return std::make_shared<fcl::Boxd>(s.size[0], s.size[1], s.size[2]);
        case Kind::Capsule:
            return std::make_shared<fcl::Capsuled>(s.size[0], s.size[1]);
        case Kind::Cylinder:
            return std::make_shared<fcl::Cylinderd>(s.size[0], s.size[1]);
        case Kind::Cone:
            return std::make_shared<fcl::Coned>(s.size[0], s.size[1]);
        case Kind::Ellipsoid:
            return std::make_shared<fcl::Ellipsoidd>(s.size[0], s.size[1], s.size[2]);
        case Kind::Convex: {
            auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
            for (const Point& v : s.vertices) vertices->emplace_back(v[0], v[1], v[2]);
            auto faces = std::make_shared<std::vector<int>>();
            for (const auto& t : s.triangles) faces->insert(faces->end(), {3, t[0], t[1], t[2]});
            return std::make_shared<fcl::Convexd>(vertices, int(s.triangles.size()), faces);
        }
    }
    return nullptr;
}

fcl::Transform3d make_transform(const PoseSpec& p) {
    fcl::Transform3d t = fcl::Transform3d::Identity();
    t.linear() = fcl::Quaterniond(p.q[0], p.q[1], p.q[2], p.q[3]).toRotationMatrix();
    t.translation() = fcl::Vector3d(p.p[0], p.p[1], p.p[2]);
    return t;
}

fcl::DistanceRequestd distance_request(const Settings& s) {
    fcl::DistanceRequestd r;
    r.enable_nearest_points = true;
    r.distance_tolerance = s.distance_tolerance;
    r.gjk_solver_type = s.solver == Solver::Libccd ? fcl::GST_LIBCCD : fcl::GST_INDEP;
    return r;
}
fcl::CollisionRequestd collision_request(const Settings& s) {
    fcl::CollisionRequestd r;
    r.gjk_solver_type = s.solver == Solver::Libccd ? fcl::GST_LIBCCD : fcl::GST_INDEP;
    return r;
}
fcl::ContinuousCollisionRequestd continuous_request(const Settings& s, const Case& c) {
    fcl::ContinuousCollisionRequestd r;
    r.ccd_motion_type = c.screw ? fcl::CCDM_SCREW : fcl::CCDM_TRANS;
    r.gjk_solver_type = s.solver == Solver::Libccd ? fcl::GST_LIBCCD : fcl::GST_INDEP;
    r.ccd_solver_type = s.ccd == Ccd::Advancement ? fcl::CCDC_CONSERVATIVE_ADVANCEMENT : fcl::CCDC_NAIVE;
    return r;
}

// ---- Generation ----------------------------------------------------------------------------------

namespace {

using Rng = std::mt19937_64;
using Q = std::array<double, 4>;  // w, x, y, z

uint64_t splitmix(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

Point add(Point a, Point b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Point sub(Point a, Point b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point scl(double s, Point a) { return {s * a[0], s * a[1], s * a[2]}; }
double dot(Point a, Point b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point cross(Point a, Point b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double len(Point a) { return std::sqrt(dot(a, a)); }

struct Gen {
    Rng r;
    double uni(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(r); }
    int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(r); }
    bool coin(double p = 0.5) { return uni(0, 1) < p; }
    Point unit() {
        std::normal_distribution<double> g;
        for (;;) {
            const Point v{g(r), g(r), g(r)};
            if (const double l = len(v); l > 1e-3) return scl(1 / l, v);
        }
    }
    Point perpendicular(Point u) {
        for (;;) {
            const Point w = cross(u, unit());
            if (const double l = len(w); l > 0.1) return scl(1 / l, w);
        }
    }
    Q quat() {
        std::normal_distribution<double> g;
        Q q{g(r), g(r), g(r), g(r)};
        const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (double& x : q) x /= n;
        return q;
    }
};

Q axis_angle(Point axis, double angle) {
    const Point u = scl(1 / len(axis), axis);
    const double s = std::sin(angle / 2);
    return {std::cos(angle / 2), u[0] * s, u[1] * s, u[2] * s};
}
Q qmul(const Q& a, const Q& b) {
    return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

ShapeSpec convex_of(Gen& g, int count, Point radii, double thickness = 1) {
    for (;;) {
        std::vector<Point> pts;
        for (int i = 0; i < count; ++i) {
            const Point d = g.unit();
            const double s = g.uni(0.8, 1.0);
            pts.push_back({s * d[0] * radii[0], s * d[1] * radii[1], s * d[2] * radii[2] * thickness});
        }
        ShapeSpec c;
        c.kind = Kind::Convex;
        if (build_hull(pts, c.vertices, c.triangles)) return c;
    }
}

ShapeSpec shape_of(Gen& g, Kind k, double s) {
    ShapeSpec c;
    c.kind = k;
    switch (k) {
        case Kind::Sphere:
            c.size = {s * g.uni(0.3, 1.2), 0, 0};
            break;
        case Kind::Box:
            c.size = {2 * s * g.uni(0.3, 1.5), 2 * s * g.uni(0.3, 1.5), 2 * s * g.uni(0.3, 1.5)};
            break;
        case Kind::Capsule:
            c.size = {s * g.uni(0.2, 0.6), 2 * s * g.uni(0.3, 1.2), 0};
            break;
        case Kind::Cylinder:
        case Kind::Cone:
            c.size = {s * g.uni(0.2, 0.9), 2 * s * g.uni(0.3, 1.2), 0};
            break;
        case Kind::Ellipsoid:
            c.size = {s * g.uni(0.3, 1.2), s * g.uni(0.3, 1.2), s * g.uni(0.3, 1.2)};
            break;
        case Kind::Convex:
            return convex_of(g, 8 + g.pick(17), {s * g.uni(0.4, 1.5), s * g.uni(0.4, 1.5), s * g.uni(0.4, 1.5)});
    }
    return c;
}

Kind any_kind(Gen& g) { return Kind(g.pick(7)); }

// World support of a spec at a pose, through the adapter (the conversion under test).
Point support(const ShapeSpec& s, const PoseSpec& p, Point d) {
    const Shape k = to_kairos(*make_geometry(s));
    const kairos_vec3 w = world_support(k.get(), to_kairos(make_transform(p)), {d[0], d[1], d[2]});
    return {w.x, w.y, w.z};
}

// B's position for a slab of width gap between the support planes normal to u: the distance is
// gap when gap >= 0 (before rounding).
Point place(const ShapeSpec& a, const PoseSpec& pa, const ShapeSpec& b, const Q& qb, Point u, double gap) {
    PoseSpec at_origin;
    at_origin.q = qb;
    const Point sa = support(a, pa, u);
    const Point sb = support(b, at_origin, scl(-1, u));
    return sub(add(sa, scl(gap, u)), sb);
}

double signed_gap(Gen& g) {
    const double m = std::pow(10.0, g.uni(-12, -2));
    return g.coin() ? m : -m;
}

// A pair with its contact configuration; u is the direction B was placed along.
struct Placed {
    Point u{1, 0, 0};
};

Placed random_pair(Gen& g, Case& c, double gap_lo, double gap_hi) {
    c.a = shape_of(g, any_kind(g), 1);
    c.b = shape_of(g, any_kind(g), 1);
    c.a0.q = g.quat();
    c.a0.p = scl(g.uni(0, 0.5), g.unit());
    c.b0.q = g.quat();
    Placed out{g.unit()};
    const double size = std::max(shape_radius(c.a), shape_radius(c.b));
    c.b0.p = place(c.a, c.a0, c.b, c.b0.q, out.u, size * g.uni(gap_lo, gap_hi));
    return out;
}

Placed near_contact(Gen& g, Case& c) {
    c.a = shape_of(g, any_kind(g), 1);
    c.b = shape_of(g, any_kind(g), 1);
    c.a0.q = g.quat();
    c.b0.q = g.quat();
    Placed out{g.unit()};
    const double size = std::max(shape_radius(c.a), shape_radius(c.b));
    c.b0.p = place(c.a, c.a0, c.b, c.b0.q, out.u, size * signed_gap(g));
    return out;
}

// Axis-aligned pairs offset along one, two or three axes (fcl#508's unit cubes among them):
// identity, half and quarter turns, cubes and equal pairs half of the time, sizes and gaps of few
// binary digits, the other axes aligned half of the time.
Placed aligned(Gen& g, Case& c) {
    const double halves[] = {0.25, 0.5, 1, 1.5, 2};
    const auto h = [&] { return halves[g.pick(5)]; };
    const auto aligned_shape = [&]() {
        ShapeSpec s;
        const Kind round[] = {Kind::Sphere, Kind::Capsule, Kind::Cylinder, Kind::Cone, Kind::Ellipsoid};
        s.kind = g.coin() ? Kind::Box : round[g.pick(5)];
        switch (s.kind) {
            case Kind::Box:
                if (g.coin()) {
                    const double side = 2 * h();
                    s.size = {side, side, side};
                } else {
                    s.size = {2 * h(), 2 * h(), 2 * h()};
                }
                break;
            case Kind::Sphere:
                s.size = {h(), 0, 0};
                break;
            case Kind::Ellipsoid:
                s.size = {h(), h(), h()};
                break;
            default:
                s.size = {h(), 2 * h(), 0};
                break;
        }
        return s;
    };
    c.a = aligned_shape();
    c.b = g.coin() ? c.a : aligned_shape();
    const double r = std::sqrt(0.5);
    const Q turns[] = {{0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}, {r, r, 0, 0}, {r, 0, r, 0}, {r, 0, 0, r}};
    c.a0.q = g.coin() ? Q{1, 0, 0, 0} : turns[g.pick(6)];
    c.b0.q = g.coin() ? Q{1, 0, 0, 0} : turns[g.pick(6)];
    if (g.coin()) c.a0.p = {double(g.pick(5) - 2), double(g.pick(5) - 2), double(g.pick(5) - 2)};
    const int mask = 1 + g.pick(7);  // which axes B is offset along
    const double gaps[] = {-0.25, 0, 0.5, 1, 2, 3};
    Point u{0, 0, 0};
    PoseSpec b_at_origin;
    b_at_origin.q = c.b0.q;
    Point pb = c.a0.p;
    const bool lateral = g.coin();
    for (int axis = 0; axis < 3; ++axis) {
        if (!(mask & (1 << axis))) {
            if (lateral) pb[size_t(axis)] += 0.25 * (g.pick(5) - 2);
            continue;
        }
        Point e{0, 0, 0};
        e[size_t(axis)] = g.coin() ? 1 : -1;
        const double reach_a = dot(e, sub(support(c.a, c.a0, e), c.a0.p));
        const double reach_b = dot(e, support(c.b, b_at_origin, scl(-1, e)));
        pb[size_t(axis)] += e[size_t(axis)] * (reach_a + gaps[g.pick(6)] - reach_b);
        u = add(u, e);
    }
    c.b0.p = pb;
    return {scl(1 / len(u), u)};
}

// A box (2, 2, 0.5) (half sides) under a box (1, 1, 0.25), the top tilted by 0 .. 1e-3 rad.
Placed parallel_faces(Gen& g, Case& c) {
    c.a.kind = c.b.kind = Kind::Box;
    c.a.size = {4, 4, 1};
    c.b.size = {2, 2, 0.5};
    const double tilts[] = {0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3};
    const double tilt = tilts[g.pick(6)];
    const double psi = g.uni(0, 2 * M_PI);
    const Q yaw = axis_angle({0, 0, 1}, g.coin() ? 0.0 : g.uni(0, 2 * M_PI));
    c.b0.q = tilt > 0 ? qmul(axis_angle({std::cos(psi), std::sin(psi), 0}, tilt), yaw) : yaw;
    PoseSpec probe;
    probe.q = c.b0.q;
    const double low = support(c.b, probe, {0, 0, -1})[2];
    const double gap = g.coin(0.8) ? signed_gap(g) : g.uni(0.01, 1);
    c.b0.p = {g.uni(-0.5, 0.5), g.uni(-0.5, 0.5), 0.5 + gap * 2.5 - low};
    return {{0, 0, 1}};
}

// Aspect ratios 1e2 .. 1e4: boxes, capsules, cylinders and convex needles.
Placed needles(Gen& g, Case& c) {
    const auto needle = [&]() {
        const double w = std::pow(10.0, -g.uni(2, 4));
        ShapeSpec s;
        switch (g.pick(4)) {
            case 0:
                s.kind = Kind::Box;
                s.size = {2, 2 * w, 2 * w};
                break;
            case 1:
                s.kind = Kind::Capsule;
                s.size = {w, 2, 0};
                break;
            case 2:
                s.kind = Kind::Cylinder;
                s.size = {w, 2, 0};
                break;
            default:
                s = convex_of(g, 10, {w, w, 1});
                break;
        }
        return s;
    };
    c.a = needle();
    c.b = g.coin() ? needle() : shape_of(g, any_kind(g), 1);
    c.a0.q = g.quat();
    c.b0.q = g.quat();
    Placed out{g.unit()};
    c.b0.p = place(c.a, c.a0, c.b, c.b0.q, out.u, g.coin() ? signed_gap(g) : g.uni(-0.01, 0.5));
    return out;
}

// Polytopes of 33 .. 100 vertices: FCL's GST_LIBCCD walks their edges instead of scanning.
Placed large_hulls(Gen& g, Case& c) {
    const auto big = [&] { return convex_of(g, 40 + g.pick(80), {g.uni(0.5, 1.5), g.uni(0.5, 1.5), g.uni(0.5, 1.5)}); };
    c.a = big();
    c.b = g.coin() ? big() : shape_of(g, any_kind(g), 1);
    c.a0.q = g.quat();
    c.b0.q = g.quat();
    Placed out{g.unit()};
    const double size = std::max(shape_radius(c.a), shape_radius(c.b));
    c.b0.p = place(c.a, c.a0, c.b, c.b0.q, out.u, size * (g.coin() ? signed_gap(g) : g.uni(-0.3, 1.0)));
    return out;
}

// Thin shapes: flat polytopes, plates and disks 1e-2 .. 1e-6 thick.
Placed flat(Gen& g, Case& c) {
    const auto thin = [&]() {
        const double t = std::pow(10.0, -g.uni(2, 6));
        ShapeSpec s;
        switch (g.pick(3)) {
            case 0:
                s = convex_of(g, 12, {1, 1, 1}, t);
                break;
            case 1:
                s.kind = Kind::Box;
                s.size = {2, 2, 2 * t};
                break;
            default:
                s.kind = Kind::Cylinder;
                s.size = {1, 2 * t, 0};
                break;
        }
        return s;
    };
    c.a = thin();
    c.b = g.coin(0.3) ? thin() : shape_of(g, any_kind(g), 1);
    c.a0.q = g.quat();
    c.b0.q = g.quat();
    Placed out{g.unit()};
    const double size = std::max(shape_radius(c.a), shape_radius(c.b));
    c.b0.p = place(c.a, c.a0, c.b, c.b0.q, out.u, size * (g.coin() ? signed_gap(g) : g.uni(-0.1, 1.0)));
    return out;
}

// The motion of a continuous case around its contact configuration: B reaches it at
// lambda = 1 (stops there) or 0.5 (goes on into A); a translation (CCDM_TRANS, A moving too) or,
// for a quarter of the cases, B turning in place (CCDM_SCREW with no translation).
void add_motion(Gen& g, Case& c, Point u) {
    const double size = std::max(shape_radius(c.a), shape_radius(c.b));
    const double lambda = g.coin() ? 1.0 : 0.5;
    c.a1 = c.a0;
    c.b1 = c.b0;
    if (g.coin(0.25)) {
        c.screw = true;
        const Point axis = g.unit();
        const double theta = g.uni(0.2, 1.5);
        const Q contact = c.b0.q;
        c.b0.q = qmul(axis_angle(axis, -theta * lambda), contact);
        c.b1.q = qmul(axis_angle(axis, theta * (1 - lambda)), contact);
        return;
    }
    const Point v = add(scl(-size * g.uni(0.5, 2.0), u), scl(size * g.uni(0, 1.0), g.perpendicular(u)));
    const Point ta = scl(size * g.uni(0, 1.0), g.unit());
    c.a1.p = add(c.a0.p, ta);
    c.b0.p = sub(c.b0.p, scl(lambda, v));
    c.b1.p = add(c.b0.p, add(ta, v));
}

}  // namespace

double shape_radius(const ShapeSpec& s) { return bounding_radius(to_kairos(*make_geometry(s)).get()); }

void scale_case(Case& c, double f) {
    for (ShapeSpec* s : {&c.a, &c.b}) {
        for (double& x : s->size) x *= f;
        for (Point& v : s->vertices) v = scl(f, v);
    }
    for (PoseSpec* p : {&c.a0, &c.b0, &c.a1, &c.b1}) p->p = scl(f, p->p);
}

const std::vector<std::string>& family_names() {
    static const std::vector<std::string> names = {"random",  "near_contact", "aligned",     "parallel_faces",
                                                   "needles", "scale",        "offset",      "large_hulls",
                                                   "flat"};
    return names;
}

Case generate(uint64_t seed, uint64_t id, Query query, const std::vector<std::string>& families) {
    Gen g{Rng(splitmix(splitmix(seed) ^ (id * 0xD1B54A32D192ED03ull)))};
    Case c;
    c.id = id;
    // random: 40 %; the other families share the rest evenly.
    const bool has_random = std::find(families.begin(), families.end(), "random") != families.end();
    std::vector<std::string> others;
    for (const std::string& f : families)
        if (f != "random") others.push_back(f);
    if (others.empty() || (has_random && g.coin(0.4)))
        c.family = "random";
    else
        c.family = others[size_t(g.pick(int(others.size())))];

    Placed placed;
    if (c.family == "random") {
        placed = random_pair(g, c, -0.3, 1.0);
    } else if (c.family == "near_contact") {
        placed = near_contact(g, c);
    } else if (c.family == "aligned") {
        placed = aligned(g, c);
    } else if (c.family == "parallel_faces") {
        placed = parallel_faces(g, c);
    } else if (c.family == "needles") {
        placed = needles(g, c);
    } else if (c.family == "scale") {
        placed = random_pair(g, c, -0.3, 1.0);
        scale_case(c, g.coin() ? 1e-3 : 1e3);
    } else if (c.family == "offset") {
        placed = random_pair(g, c, -0.3, 1.0);
        const Point shift = scl(std::pow(10.0, g.uni(3, 6)), g.unit());
        c.a0.p = add(c.a0.p, shift);
        c.b0.p = add(c.b0.p, shift);
    } else if (c.family == "large_hulls") {
        placed = large_hulls(g, c);
    } else {
        placed = flat(g, c);
    }
    if (query == Query::Continuous) add_motion(g, c, placed.u);
    return c;
}

}  // namespace kairos::fcl_check::campaign
