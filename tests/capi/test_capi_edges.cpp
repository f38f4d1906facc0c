// SPDX-License-Identifier: MIT
// GJK at the rounding limit (issue 12), through the shared library: the reported cases as
// regressions in both argument orders, and a sweep over every pair of shape kinds at gaps built to
// be exact. Truth comes from the construction, not from the library: B is placed so that its
// support point toward -n lands at g n from A's support point toward n, so the two support planes
// are g apart and so are those two points, and the distance is g exactly (to the rounding of the
// placement, about 1e-16 of the size). Supports are computed here from the shapes' definitions.
// Every answer is also checked for what it claims: a separated answer by its own axis (the gap
// between the support planes along it, from the test-side supports), its witness points on their
// shapes and the distance apart; an intersecting answer by its contact point lying in both shapes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "kairos/kairos.h"

namespace {

struct V {
    double x, y, z;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator-(V a) { return {-a.x, -a.y, -a.z}; }
V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double norm(V a) { return std::sqrt(dot(a, a)); }
V unit(V a) { return (1 / norm(a)) * a; }
kairos_vec3 kv(V a) { return {a.x, a.y, a.z}; }
V fromk(kairos_vec3 a) { return {a.x, a.y, a.z}; }
double sgn(double x) { return x < 0 ? -1.0 : 1.0; }

// Rotation as a quaternion (x, y, z, w) and its matrix (rows), as the library defines them.
struct Rot {
    double q[4];
    double m[9];
};
Rot make_rot(V axis, double angle) {
    Rot r{};
    const V u = unit(axis);
    const double s = std::sin(angle / 2), w = std::cos(angle / 2);
    const double x = u.x * s, y = u.y * s, z = u.z * s;
    r.q[0] = x, r.q[1] = y, r.q[2] = z, r.q[3] = w;
    r.m[0] = 1 - 2 * (y * y + z * z), r.m[1] = 2 * (x * y - z * w), r.m[2] = 2 * (x * z + y * w);
    r.m[3] = 2 * (x * y + z * w), r.m[4] = 1 - 2 * (x * x + z * z), r.m[5] = 2 * (y * z - x * w);
    r.m[6] = 2 * (x * z - y * w), r.m[7] = 2 * (y * z + x * w), r.m[8] = 1 - 2 * (x * x + y * y);
    return r;
}
Rot compose(const Rot& a, const Rot& b) {  // a then... the rotation a * b (b applied first)
    const double* p = a.q;
    const double* q = b.q;
    const double x = p[3] * q[0] + p[0] * q[3] + p[1] * q[2] - p[2] * q[1];
    const double y = p[3] * q[1] - p[0] * q[2] + p[1] * q[3] + p[2] * q[0];
    const double z = p[3] * q[2] + p[0] * q[1] - p[1] * q[0] + p[2] * q[3];
    const double w = p[3] * q[3] - p[0] * q[0] - p[1] * q[1] - p[2] * q[2];
    const double n = std::sqrt(x * x + y * y + z * z + w * w);
    const double s = std::sqrt(std::max(0.0, 1 - (w / n) * (w / n)));
    if (s < 1e-300) return make_rot({0, 0, 1}, 0);
    const double angle = 2 * std::atan2(s, w / n);
    return make_rot({x / n / s, y / n / s, z / n / s}, angle);
}
V apply(const Rot& r, V p) {
    return {r.m[0] * p.x + r.m[1] * p.y + r.m[2] * p.z, r.m[3] * p.x + r.m[4] * p.y + r.m[5] * p.z,
            r.m[6] * p.x + r.m[7] * p.y + r.m[8] * p.z};
}
V apply_t(const Rot& r, V p) {
    return {r.m[0] * p.x + r.m[3] * p.y + r.m[6] * p.z, r.m[1] * p.x + r.m[4] * p.y + r.m[7] * p.z,
            r.m[2] * p.x + r.m[5] * p.y + r.m[8] * p.z};
}

// A shape made through the C API with its support written here from the definition (local frame).
struct TShape {
    std::string name;
    std::shared_ptr<kairos_shape> k;
    std::function<V(V)> support;
    double size;    // bounding radius about the local origin (nominal)
    bool polytope;  // exact supports: the sweep holds it to 1e-12 of the size
};
std::shared_ptr<kairos_shape> own(kairos_shape* s) { return {s, kairos_shape_release}; }
kairos_shape* must(int32_t status, kairos_shape*& s) {  // by reference: read after the call
    EXPECT_EQ(status, KAIROS_OK) << kairos_last_error();
    return s;
}

V box_support(V h, V d) { return {sgn(d.x) * h.x, sgn(d.y) * h.y, sgn(d.z) * h.z}; }
V ball_support(double r, V d) { return norm(d) > 0 ? (r / norm(d)) * d : V{0, 0, r}; }
V points_support(const std::vector<V>& p, V d) {
    V best = p[0];
    for (const V& q : p)
        if (dot(q, d) > dot(best, d)) best = q;
    return best;
}

// The basic kinds, local frame: axes along z, as the library defines them.
TShape box_kind(const std::string& name, V h) {
    kairos_shape* k = nullptr;
    return {name, own(must(kairos_shape_box(kv(h), &k), k)), [h](V d) { return box_support(h, d); }, norm(h), true};
}
TShape sphere_kind(const std::string& name, double r) {
    kairos_shape* k = nullptr;
    return {name, own(must(kairos_shape_sphere(r, &k), k)), [r](V d) { return ball_support(r, d); }, r, false};
}
TShape capsule_kind(const std::string& name, double r, double h) {
    kairos_shape* k = nullptr;
    return {name, own(must(kairos_shape_capsule(r, h, &k), k)),
            [r, h](V d) {
                return ball_support(r, d) + V{0, 0, sgn(d.z) * h};
            },
            r + h, false};
}
TShape cylinder_kind(const std::string& name, double r, double h) {
    kairos_shape* k = nullptr;
    return {name, own(must(kairos_shape_cylinder(r, h, &k), k)),
            [r, h](V d) {
                const double rl = std::hypot(d.x, d.y);
                return rl > 0 ? V{r * d.x / rl, r * d.y / rl, sgn(d.z) * h} : V{0, 0, sgn(d.z) * h};
            },
            std::hypot(r, h), false};
}
TShape cone_kind(const std::string& name, double r, double h) {
    kairos_shape* k = nullptr;
    return {name, own(must(kairos_shape_cone(r, h, &k), k)),
            [r, h](V d) {
                const double rl = std::hypot(d.x, d.y);
                const V rim = rl > 0 ? V{r * d.x / rl, r * d.y / rl, -h} : V{0, 0, -h};
                return d.z * h >= dot(rim, d) ? V{0, 0, h} : rim;
            },
            std::hypot(r, h), false};
}
TShape hull_kind(const std::string& name, const std::vector<V>& p, double size) {
    kairos_shape* k = nullptr;
    std::vector<kairos_vec3> kp;
    for (const V& q : p) kp.push_back(kv(q));
    return {name, own(must(kairos_shape_convex_hull(kp.data(), kp.size(), &k), k)),
            [p](V d) { return points_support(p, d); }, size, true};
}

std::vector<TShape> shape_kinds(double s) {
    std::vector<TShape> out;
    kairos_shape* k = nullptr;
    out.push_back(box_kind("box", {1.0 * s, 0.7 * s, 0.4 * s}));
    out.push_back(sphere_kind("sphere", 0.8 * s));
    out.push_back(capsule_kind("capsule", 0.4 * s, 0.6 * s));
    out.push_back(cylinder_kind("cylinder", 0.6 * s, 0.5 * s));
    out.push_back(cone_kind("cone", 0.6 * s, 0.7 * s));
    {
        const double h = 0.9 * s;
        out.push_back({"segment", own(must(kairos_shape_segment(h, &k), k)),
                       [h](V d) {
                           return V{0, 0, sgn(d.z) * h};
                       },
                       h, true});
    }
    out.push_back({"point", own(must(kairos_shape_point(&k), k)), [](V) { return V{0, 0, 0}; }, 0.5 * s, true});
    {
        // An irregular polytope (its hull keeps all 10 points: they lie on an ellipsoid).
        std::vector<V> p;
        for (int i = 0; i < 10; ++i) {
            const double t = 2.399963 * i, zz = 1 - (2 * i + 1) / 10.0, rr = std::sqrt(1 - zz * zz);
            p.push_back({s * 0.9 * rr * std::cos(t), s * 0.6 * rr * std::sin(t), s * 0.5 * zz});
        }
        out.push_back(hull_kind("hull", p, 0.9 * s));
    }
    {
        const std::vector<V> p{{-0.8 * s, -0.5 * s, 0}, {0.9 * s, -0.3 * s, 0}, {0.1 * s, 0.7 * s, 0}};
        out.push_back({"triangle", own(must(kairos_shape_triangle(kv(p[0]), kv(p[1]), kv(p[2]), &k), k)),
                       [p](V d) { return points_support(p, d); }, 0.95 * s, true});
    }
    out.push_back(hull_kind("flat hull",
                            {{-0.7 * s, -0.6 * s, 0.1 * s},
                             {0.8 * s, -0.5 * s, 0.1 * s},
                             {0.6 * s, 0.7 * s, 0.1 * s},
                             {-0.5 * s, 0.6 * s, 0.1 * s}},
                            1.0 * s));
    {
        // A sheared, scaled box with an offset: support L s(L^T d) + o.
        const double L[9] = {1.0, 0.3, 0.0, 0.0, 0.8, 0.2, 0.1, 0.0, 1.2};
        const V o{0.1 * s, -0.05 * s, 0.02 * s};
        const V h{0.5 * s, 0.4 * s, 0.3 * s};
        kairos_shape* inner = must(kairos_shape_box(kv(h), &k), k);
        kairos_shape* t = nullptr;
        must(kairos_shape_transformed(inner, L, kv(o), &t), t);
        kairos_shape_release(inner);
        auto lin = [L](V p) {
            return V{L[0] * p.x + L[1] * p.y + L[2] * p.z, L[3] * p.x + L[4] * p.y + L[5] * p.z,
                     L[6] * p.x + L[7] * p.y + L[8] * p.z};
        };
        auto lin_t = [L](V p) {
            return V{L[0] * p.x + L[3] * p.y + L[6] * p.z, L[1] * p.x + L[4] * p.y + L[7] * p.z,
                     L[2] * p.x + L[5] * p.y + L[8] * p.z};
        };
        out.push_back(
            {"transformed box", own(t), [=](V d) { return lin(box_support(h, lin_t(d))) + o; }, 1.2 * s, true});
    }
    {
        // A rounded box (box + sphere) and a rounded triangle.
        const V h{0.6 * s, 0.4 * s, 0.3 * s};
        const double r = 0.2 * s;
        kairos_shape *b = must(kairos_shape_box(kv(h), &k), k), *ball = nullptr, *sum = nullptr;
        must(kairos_shape_sphere(r, &ball), ball);
        must(kairos_shape_minkowski_sum(b, ball, &sum), sum);
        kairos_shape_release(b);
        kairos_shape_release(ball);
        out.push_back({"box+sphere", own(sum), [h, r](V d) { return box_support(h, d) + ball_support(r, d); },
                       norm(h) + r, false});
    }
    {
        // The hull of a segment and a displaced... in one frame: a segment along z and a box.
        const double hl = 0.9 * s;
        const V h{0.5 * s, 0.3 * s, 0.2 * s};
        kairos_shape *seg = must(kairos_shape_segment(hl, &k), k), *b = nullptr, *hull = nullptr;
        must(kairos_shape_box(kv(h), &b), b);
        must(kairos_shape_hull(seg, b, &hull), hull);
        kairos_shape_release(seg);
        kairos_shape_release(b);
        out.push_back({"hull of two", own(hull),
                       [hl, h](V d) {
                           const V p = {0, 0, sgn(d.z) * hl}, q = box_support(h, d);
                           return dot(p, d) >= dot(q, d) ? p : q;
                       },
                       std::hypot(norm(h), hl), true});
    }
    return out;
}

// Needles, plates, discs, flat cones and a sliver: one dimension 1e-6 of the others, beside a
// ball and a cube of the same size. Long axes along z, so that the face-to-face variants meet a
// needle's tip and a plate's face.
std::vector<TShape> needle_kinds(double s, double thin) {
    const double e = thin * s;
    std::vector<TShape> out;
    out.push_back(box_kind("rod", {e, e, s}));
    out.push_back(box_kind("plate", {s, 0.8 * s, e}));
    out.push_back(capsule_kind("needle capsule", e, s));
    out.push_back(cylinder_kind("needle cylinder", e, s));
    out.push_back(cylinder_kind("disc", s, e));
    out.push_back(cone_kind("needle cone", e, s));
    out.push_back(cone_kind("flat cone", s, e));
    out.push_back(hull_kind("sliver", {{s, 0, 0}, {-s, 0.2 * s, 0}, {0.1 * s, s, 0}, {0, -0.9 * s, e}}, s));
    out.push_back(sphere_kind("ball", 0.5 * s));
    out.push_back(box_kind("cube", {0.5 * s, 0.5 * s, 0.5 * s}));
    return out;
}

struct Posed {
    const TShape* s;
    Rot r;
    V c;
    V support(V d) const { return apply(r, s->support(apply_t(r, d))) + c; }
    double h(V d) const { return dot(support(d), d); }
    kairos_pose pose() const { return {kv(c), {r.q[0], r.q[1], r.q[2], r.q[3]}}; }
};

// Is p within eps of the posed shape? Checked on the support planes of 26 fixed directions and
// of `extra` (necessary, not sufficient: it catches points far off, as in the issue).
// How far p lies outside the shape along the 26 test directions and `extra` (<= 0: inside them all).
double off_shape(const Posed& s, V p, V extra) {
    std::vector<V> dirs{extra};
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z)
                if (x || y || z) dirs.push_back({double(x), double(y), double(z)});
    double worst = -INFINITY;
    for (V d : dirs) {
        if (!(norm(d) > 0)) continue;
        d = unit(d);
        worst = std::max(worst, dot(p, d) - s.h(d));
    }
    return worst;
}
bool near_shape(const Posed& s, V p, V extra, double eps) { return !(off_shape(s, p, extra) > eps); }

struct Tally {
    int separated = 0, intersecting = 0, cases = 0;
    double worst_rel = 0;                      // worst |distance - g| / size on constructed gaps
    std::map<std::string, int> failures;       // per check and pair of kinds
    std::map<std::string, std::string> first;  // the first failing case of each
    void fail(const std::string& key, const std::string& detail) {
        if (failures[key]++ == 0) first[key] = detail;
    }
};

std::string fmt(const char* f, double x, double y) {
    char buf[160];
    std::snprintf(buf, sizeof buf, f, x, y);
    return buf;
}

// One query in one argument order, checked against the constructed gap g along n (from a to b).
// deep: the contact is not a graze (see the casts below); ray_origin: B's contact point, for a ray
// cast onto A (null: no ray, as when A's contact point is B's support point, which may be a corner).
// What check_pair allows beyond its defaults (fat shapes at the origin). slack: the rounding of
// the placement itself, absolute (a few eps of the distance from the origin, for shapes placed
// far from it), added to every allowance. graze_possible: a negative gap need not make the
// shapes overlap with volume (a sliver's apex pushed into a plate's plane at the plate's corner
// touches it only there), so an intersecting distance is not held against a separated
// intersection test. points, distance (fractions of the size, 0: the defaults): the witness and
// contact points' allowance, and the distance's on curved pairs. tilt: the axis's rounding
// allowance, tilt size^2 / distance (see "axis" below).
struct Allow {
    double slack = 0;
    bool graze_possible = false;
    double points = 0, distance = 0;
    double tilt = 1e-12;
};

void check_pair(const Posed& a, const Posed& b, V n, double g, double size, bool deep, const V* ray_origin,
                const std::string& kinds, const std::string& what, Tally& t, const Allow& allow = {}) {
    const bool exact = a.s->polytope && b.s->polytope;
    const double slack = allow.slack, base = exact ? 1e-12 : 1e-9;
    const double tol = base * size + slack, band = 1e-9 * size + slack;
    const double point_tol = std::max(base, allow.points) * size + slack;
    const double distance_tol = (exact ? base : std::max(base, allow.distance)) * size + slack;
    kairos_pose pa = a.pose(), pb = b.pose();
    kairos_distance_result r{};
    ASSERT_EQ(kairos_distance(a.s->k.get(), &pa, b.s->k.get(), &pb, nullptr, &r), KAIROS_OK) << kairos_last_error();
    ++t.cases;
    auto pose_text = [](const kairos_pose& p) {
        char buf[256];
        std::snprintf(buf, sizeof buf, "p (%.17g, %.17g, %.17g) q (%.17g, %.17g, %.17g, %.17g)", p.position.x,
                      p.position.y, p.position.z, p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w);
        return std::string(buf);
    };
    auto check = [&](bool ok, const std::string& name, const std::string& detail) {
        if (!ok)
            t.fail(name + " " + kinds, what + ": " + detail + " (termination " + std::to_string(r.termination) +
                                           "); A at " + pose_text(pa) + ", B at " + pose_text(pb));
    };
    check(std::isfinite(r.distance), "finite", "");
    const V qa = fromk(r.point_a), qb = fromk(r.point_b), axis = fromk(r.axis);
    if (r.intersecting) {
        ++t.intersecting;
        check(g < band, "intersecting-at-gap", fmt("gap %.3g %.0g", g, 0));
        check(r.distance == 0, "intersecting-distance", fmt("distance %.3g %.0g", r.distance, 0));
        check(near_shape(a, qa, n, point_tol) && near_shape(b, qa, -n, point_tol), "contact-point",
              fmt("off a shape by %.3g of the size (allowed %.0g)",
                  std::max(off_shape(a, qa, n), off_shape(b, qa, -n)) / size, point_tol / size));
    } else {
        ++t.separated;
        // The answer's own certificate: the support planes along its axis are at least distance -
        // tol apart, the witness points lie on their shapes, and they are the distance apart.
        // The axis is the direction of v, whose absolute rounding (some eps of the size) tilts it
        // by that over the distance: along faces the separation falls short by up to about
        // eps size^2 / distance (seen: 5.5e-11 at a distance of 0.013, box on a box tilted by
        // 1e-12; 1.4e-9 of the size at 1e-2 of it, a point beside a flat hull tilted by 1e-9;
        // 4.3e-4 at 1.3e-9, boxes tilted by 1e-3 after Johnson failed, v about 1000 eps of the
        // size off). The check is for gross errors: 1e-8 of the size, plus 1e-12 size^2 /
        // distance (4500 eps of the size on v).
        // Within the band (shapes touching within 1e-9 of the size) the axis is a rounding artefact.
        const double sep = -b.h(-axis) - a.h(axis);
        const double tilt_allowance = 1e-8 * size + allow.tilt * size * size / std::max(r.distance, 1e-300);
        if (r.distance > band)
            check(sep >= r.distance - tol - tilt_allowance, "axis",
                  fmt("distance %.17g separation %.17g", r.distance, sep));
        check(std::fabs(norm(qb - qa) - r.distance) <= point_tol, "witness-apart",
              fmt("distance %.17g apart %.17g", r.distance, norm(qb - qa)));
        check(near_shape(a, qa, axis, point_tol) && near_shape(b, qb, -axis, point_tol), "witness-on-shape", "");
        // Negative gaps need not overlap (flat shapes: a point 1e-12 below a triangle's corner is
        // 1e-12 away), so the value is checked from 0 up.
        if (g >= 0) {
            check(std::fabs(r.distance - std::max(g, 0.0)) <= distance_tol, "distance",
                  fmt("distance %.17g gap %.17g", r.distance, g) + " iterations " + std::to_string(r.iterations));
        }
        if (g > band) t.worst_rel = std::max(t.worst_rel, std::fabs(r.distance - g) / size);
    }
    // Casts from the constructed gap: B translated along -n by g + size / 2 first touches A after
    // g exactly (the support planes are perpendicular to the motion and the two support points
    // face each other), so toi = g / (g + size / 2); a ray from A's support point pushed out by g n
    // (as B's support point is) hits A at the same toi. Never late (1e-9 of the step), never a
    // miss; early by design within the tolerance's stop (1e-7 here flags only gross errors).
    // Judged only where the contact is not a graze (`deep`: A's contact point has A's solid
    // below it, so the motion goes on into overlap): a corner meeting a corner or an edge
    // sliding along a face touches over an instant or an interval that rounding decides.
    if (g >= 0 && deep) {
        const double len = g + size / 2, truth = g / len, late = 1e-9 + slack / len, early = 1e-7 + slack / len;
        const V ta{0, 0, 0}, tb = -len * n;
        kairos_cast_result c{};
        ASSERT_EQ(kairos_shape_cast(a.s->k.get(), &pa, kv(ta), b.s->k.get(), &pb, kv(tb), nullptr, &c), KAIROS_OK);
        check(c.hit == 1, "shape-cast-miss", fmt("truth %.17g %.0g", truth, 0));
        if (c.hit == 1)
            check(c.toi <= truth + late && c.toi >= truth - early, "shape-cast-toi",
                  fmt("toi %.17g truth %.17g", c.toi, truth));
        if (ray_origin != nullptr) {
            kairos_cast_result ray{};
            ASSERT_EQ(kairos_ray_cast(a.s->k.get(), &pa, kv(*ray_origin), kv(tb), nullptr, &ray), KAIROS_OK);
            check(ray.hit == 1, "ray-cast-miss", fmt("truth %.17g %.0g", truth, 0));
            if (ray.hit == 1)
                check(ray.toi <= truth + late && ray.toi >= truth - early, "ray-cast-toi",
                      fmt("toi %.17g truth %.17g", ray.toi, truth));
        }
    }
    // kairos_intersect agrees with the sign beyond the band.
    int32_t hit = -1;
    kairos_vec3 cache{0, 0, 0};
    ASSERT_EQ(kairos_intersect(a.s->k.get(), &pa, b.s->k.get(), &pb, &cache, &hit), KAIROS_OK);
    if (g > band) check(hit == 0, "intersect-verdict", fmt("touching at gap %.3g %.0g", g, 0));
    // The two verdicts agree beyond the band (at gaps within it either may say touching).
    if (r.intersecting && g < -band && !allow.graze_possible)
        check(hit == 1, "intersect-vs-distance", "distance says intersecting");
    if (!r.intersecting && r.distance > band)
        check(hit == 0, "intersect-vs-distance", fmt("distance %.17g %.0g", r.distance, 0));
    // Its separating axis, where the verdict is judged (within the band the axis is as uncertain
    // as the sign: its tilt grows as eps size / distance).
    if (hit == 0 && g > band) {
        const V ax = unit(fromk(cache));
        check(-b.h(-ax) - a.h(ax) > -tol - 1e-10 * size - 1e-13 * size * size / g, "intersect-axis", "");
    }
}

// B placed so that its support point toward -n is g n beyond pa, a point of A on its support
// plane toward n.
Posed place_b(const V pa, const TShape& b, const Rot& rb, V n, double g) {
    const V qb = apply(rb, b.support(apply_t(rb, -n)));
    return {&b, rb, pa + g * n - qb};
}

// Solid shapes whose top point (0, 0, h(+z)) is a point of theirs with the solid below it: a
// motion through a contact there goes on into overlap (a cast's first contact is not a graze).
bool solid_top(const TShape& s) {
    for (const char* name :
         {"box", "sphere", "capsule", "cylinder", "cone", "box+sphere", "hull of two", "rod", "plate", "needle capsule",
          "needle cylinder", "disc", "needle cone", "flat cone", "ball", "cube"})
        if (s.name == name) return true;
    return false;
}

// Needle kinds with a tip or a wedge about 1e-6 wide (a cone's apex or rim, a sliver's edges).
bool sharp(const TShape& s) { return s.name == "needle cone" || s.name == "flat cone" || s.name == "sliver"; }

// ---- The reported cases, both orders -----------------------------------------------------------

struct Query {
    kairos_distance_result ab, ba;
};
Query both_orders(const kairos_shape* a, const kairos_pose& pa, const kairos_shape* b, const kairos_pose& pb) {
    Query q{};
    EXPECT_EQ(kairos_distance(a, &pa, b, &pb, nullptr, &q.ab), KAIROS_OK);
    EXPECT_EQ(kairos_distance(b, &pb, a, &pa, nullptr, &q.ba), KAIROS_OK);
    return q;
}
double apart(const kairos_distance_result& r) { return norm(fromk(r.point_b) - fromk(r.point_a)); }

TEST(GjkEdges, BoxRestingOnABoxTurnedAPicoradian) {
    kairos_shape *a = nullptr, *b = nullptr;
    ASSERT_EQ(kairos_shape_box({2, 2, 0.5}, &a), KAIROS_OK);
    ASSERT_EQ(kairos_shape_box({1, 1, 0.25}, &b), KAIROS_OK);
    const kairos_pose pa{{0, 0, 0}, {0, 0, 0, 1}};
    // Turned about x by 2 asin(5e-13 / |q|): the lowest bottom corner drops by sin(angle) * 1 and
    // cos(angle) * 0.25 of the half height (the rest is below rounding).
    const double qx = 5e-13, n = std::sqrt(1 + qx * qx), angle = 2 * std::asin(qx / n);
    const double cz = 0.75000055868305626;
    const kairos_pose pb{{-0.18530079113186138, 0.070589394614759438, cz}, {qx, 0, 0, 1}};
    const double truth = (cz - 0.25 * std::cos(angle) - std::sin(angle)) - 0.5;
    const Query q = both_orders(a, pa, b, pb);
    for (const auto* r : {&q.ab, &q.ba}) {
        EXPECT_NEAR(r->distance, truth, 1e-12 * 2.9) << "termination " << r->termination;  // 2.9: A's bounding radius
        EXPECT_NEAR(apart(*r), r->distance, 1e-12);
        EXPECT_EQ(r->intersecting, 0);
    }
    // Exactly parallel faces 3.16e-7 apart.
    const kairos_pose flat{{-0.18530079113186138, 0.070589394614759438, 0.75 + 3.16e-7}, {0, 0, 0, 1}};
    const Query p = both_orders(a, pa, b, flat);
    for (const auto* r : {&p.ab, &p.ba}) {
        EXPECT_NEAR(r->distance, (0.75 + 3.16e-7) - 0.75, 1e-12 * 2.9);
    }
    kairos_shape_release(a);
    kairos_shape_release(b);
}

// A rotation from a unit quaternion (x, y, z, w), its matrix as the library forms it.
Rot from_quat(const double* q) {
    Rot r{};
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double x = q[0] / n, y = q[1] / n, z = q[2] / n, w = q[3] / n;
    r.q[0] = x, r.q[1] = y, r.q[2] = z, r.q[3] = w;
    r.m[0] = 1 - 2 * (y * y + z * z), r.m[1] = 2 * (x * y - z * w), r.m[2] = 2 * (x * z + y * w);
    r.m[3] = 2 * (x * y + z * w), r.m[4] = 1 - 2 * (x * x + z * z), r.m[5] = 2 * (y * z - x * w);
    r.m[6] = 2 * (x * z - y * w), r.m[7] = 2 * (y * z + x * w), r.m[8] = 1 - 2 * (x * x + y * y);
    return r;
}

// FCL issue 319's cylinder rotation (rows of the report) as a quaternion.
Rot fcl319_cylinder_rotation() {
    const double m[9] = {
        -0.99999999997999022838,    6.2572835802045040178e-10, 6.3260669852976095481e-06, 6.3260669851683709551e-06,
        -6.3943303429958554955e-10, 0.99999999997999056145,    6.2573180158128459924e-10, 1,
        6.3942912945996747041e-10};
    double q[4];
    const double t0 = 1 + m[0] - m[4] - m[8], t1 = 1 - m[0] + m[4] - m[8], t2 = 1 - m[0] - m[4] + m[8],
                 t3 = 1 + m[0] + m[4] + m[8];
    if (t1 >= t0 && t1 >= t2 && t1 >= t3) {
        const double s = 2 * std::sqrt(t1);
        q[1] = s / 4, q[0] = (m[1] + m[3]) / s, q[2] = (m[5] + m[7]) / s, q[3] = (m[2] - m[6]) / s;
    } else if (t2 >= t0 && t2 >= t3) {
        const double s = 2 * std::sqrt(t2);
        q[2] = s / 4, q[0] = (m[2] + m[6]) / s, q[1] = (m[5] + m[7]) / s, q[3] = (m[3] - m[1]) / s;
    } else if (t0 >= t3) {
        const double s = 2 * std::sqrt(t0);
        q[0] = s / 4, q[1] = (m[1] + m[3]) / s, q[2] = (m[2] + m[6]) / s, q[3] = (m[7] - m[5]) / s;
    } else {
        const double s = 2 * std::sqrt(t3);
        q[3] = s / 4, q[0] = (m[7] - m[5]) / s, q[1] = (m[2] - m[6]) / s, q[2] = (m[3] - m[1]) / s;
    }
    return from_quat(q);
}

// FCL issue 319's cylinder/box (FCL's test_fcl_signed_distance.cpp): one order read 0.0121.
TEST(GjkEdges, FclIssue319CylinderBoxBothOrders) {
    kairos_shape *cyl = nullptr, *box = nullptr;
    ASSERT_EQ(kairos_shape_cylinder(0.05, 0.03, &cyl), KAIROS_OK);
    ASSERT_EQ(kairos_shape_box({0.0125, 0.175, 0.9225}, &box), KAIROS_OK);
    const Rot rc = fcl319_cylinder_rotation();
    const double* q = rc.q;
    const kairos_pose pc{{0.57500009756757608503, -0.42711963046787942977, 1.1867093358746836351},
                         {q[0], q[1], q[2], q[3]}};
    const double h = std::sqrt(0.5);
    const kairos_pose pbx{{0.8, -0.4575, 1.0225}, {0, 0, h, h}};  // rows (0,-1,0),(1,0,0),(0,0,1): +90 deg about z
    const Query r = both_orders(cyl, pc, box, pbx);
    // FCL's expected distance is 1.554e-8 (its test's own truth); the two orders agree with it and
    // with each other within 1e-9 of the size (about 0.93).
    for (const auto* x : {&r.ab, &r.ba}) {
        EXPECT_NEAR(x->distance, 1.554e-8, 1e-10) << "termination " << x->termination;
        EXPECT_NEAR(apart(*x), x->distance, 1e-12);
    }
    EXPECT_NEAR(r.ab.distance, r.ba.distance, 1e-12);
    kairos_shape_release(cyl);
    kairos_shape_release(box);
}

// Around FCL issue 319's pose, +-2 mm on every axis (one order was wrong in about a quarter of
// these poses): both orders agree within 1e-10 (the bound for curved pairs is 1e-9 of the size;
// rims converge to about 1e-11), and each answer passes its own certificate (its
// axis separates the test-side supports by the distance, up to the axis's rounding tilt).
TEST(GjkEdges, FclIssue319NeighbourhoodBothOrdersAgree) {
    kairos_shape *cyl = nullptr, *box = nullptr;
    ASSERT_EQ(kairos_shape_cylinder(0.05, 0.03, &cyl), KAIROS_OK);
    ASSERT_EQ(kairos_shape_box({0.0125, 0.175, 0.9225}, &box), KAIROS_OK);
    const Rot rc = fcl319_cylinder_rotation();
    const double h = std::sqrt(0.5);
    const kairos_pose pbx{{0.8, -0.4575, 1.0225}, {0, 0, h, h}};
    const double qb[4] = {0, 0, h, h};
    const Rot rb = from_quat(qb);
    auto h_cyl = [&](V c, V d) {  // world support of the cylinder posed at c, rc
        const V l = apply_t(rc, d);
        const double rl = std::hypot(l.x, l.y);
        const V s = rl > 0 ? V{0.05 * l.x / rl, 0.05 * l.y / rl, sgn(l.z) * 0.03} : V{0, 0, sgn(l.z) * 0.03};
        return dot(apply(rc, s) + c, d);
    };
    auto h_box = [&](V d) {
        return dot(apply(rb, box_support({0.0125, 0.175, 0.9225}, apply_t(rb, d))) + V{0.8, -0.4575, 1.0225}, d);
    };
    int separated = 0, intersecting = 0;
    double worst = 0;
    for (int i = -4; i <= 4; ++i)
        for (int j = -4; j <= 4; ++j)
            for (int k = -4; k <= 4; ++k) {
                const V c{0.57500009756757608503 + 5e-4 * i, -0.42711963046787942977 + 5e-4 * j,
                          1.1867093358746836351 + 5e-4 * k};
                const kairos_pose pc{kv(c), {rc.q[0], rc.q[1], rc.q[2], rc.q[3]}};
                const Query q = both_orders(cyl, pc, box, pbx);
                SCOPED_TRACE(testing::Message() << "offset " << i << " " << j << " " << k << ": " << q.ab.distance
                                                << " / " << q.ba.distance);
                ASSERT_NEAR(q.ab.distance, q.ba.distance, 1e-10);  // curved: 1e-9 of the size (0.93) is the bound
                ASSERT_EQ(q.ab.intersecting, q.ba.intersecting);
                worst = std::max(worst, std::fabs(q.ab.distance - q.ba.distance));
                if (q.ab.intersecting) {
                    ++intersecting;
                    continue;
                }
                ++separated;
                const V n = fromk(q.ab.axis);
                const double sep = -h_box(-n) - h_cyl(c, n);
                ASSERT_GE(sep, q.ab.distance - 1e-12 - 1e-13 / std::max(q.ab.distance, 1e-300)) << "axis";
            }
    std::printf("[fcl 319 neighbourhood] %d separated, %d intersecting, worst order disagreement %.3g\n", separated,
                intersecting, worst);
    EXPECT_GT(separated, 100);
    EXPECT_GT(intersecting, 100);
    kairos_shape_release(cyl);
    kairos_shape_release(box);
}

// The fuzzer's finding of 2026-11-26 (CI): a plate 1e-10 thick and 7300 long against a point grown by a
// unit sphere: the distance was right and the witness points 1058 apart.
TEST(GjkEdges, ThinPlateAgainstARoundedPointWitnessPoints) {
    kairos_shape *plate = nullptr, *pt = nullptr, *ball = nullptr, *sum = nullptr;
    const V h{0.099649805447470818, 3649.5307850766767, 9.964980544747082e-11};
    const V p{0.76662161642728521, -0.13694400590298006, -0.94713245681480451};
    ASSERT_EQ(kairos_shape_box(kv(h), &plate), KAIROS_OK);
    const kairos_vec3 kp = kv(p);
    ASSERT_EQ(kairos_shape_convex_hull(&kp, 1, &pt), KAIROS_OK);
    ASSERT_EQ(kairos_shape_sphere(1, &ball), KAIROS_OK);
    ASSERT_EQ(kairos_shape_minkowski_sum(pt, ball, &sum), KAIROS_OK);
    const kairos_pose pose{{-4, -4, -4}, {0, 0, 0, 1}};
    const double truth = std::hypot(p.x - h.x, -p.z - h.z) - 1;  // the plate's edge x = +h.x, z = -h.z
    const Query q = both_orders(plate, pose, sum, pose);
    for (const auto* r : {&q.ab, &q.ba}) {
        EXPECT_NEAR(r->distance, truth, 1e-12);
        EXPECT_NEAR(apart(*r), r->distance, 1e-9);
    }
    for (kairos_shape* s : {plate, pt, ball, sum}) kairos_shape_release(s);
}

// Shapes 1e-160 and 1e99 in size: the same answer as at unit scale (GJK runs at unit scale).
TEST(GjkEdges, TinyAndHugeScalesGiveTheUnitScaleAnswer) {
    for (double s : {1.0, 1e-100, 1e-160, 1e-200, 1e-300, 1e50, 1e99}) {
        SCOPED_TRACE(testing::Message() << "scale " << s);
        kairos_shape *a = nullptr, *b = nullptr;
        ASSERT_EQ(kairos_shape_box({s, 2 * s, 0.5 * s}, &a), KAIROS_OK);
        ASSERT_EQ(kairos_shape_capsule(0.5 * s, s, &b), KAIROS_OK);
        const kairos_pose pa{{0, 0, 0}, {0, 0, 0, 1}};
        const kairos_pose pb{{3 * s, 0.5 * s, 0}, {0, 0, 0, 1}};  // capsule axis z: its side 1.5 s from the box's face
        const Query q = both_orders(a, pa, b, pb);
        EXPECT_NEAR(q.ab.distance / s, 1.5, 1e-12);
        EXPECT_NEAR(q.ba.distance / s, 1.5, 1e-12);
        EXPECT_NEAR(norm((1 / s) * fromk(q.ab.point_b) - (1 / s) * fromk(q.ab.point_a)), 1.5, 1e-12);
        kairos_shape_release(a);
        kairos_shape_release(b);
    }
}

// Never late on thin and needle capsules: a ray crossing the axis of a capsule (radius r, half
// height H along local z) reports a normal whose support plane the ray point at toi has not
// crossed: n . x(toi) >= |n . axis| H + r (closed form) minus 1e-6 of the size. The final v, used
// as the normal of rounded shapes, had a direction error of eps H / |v| there, tilting the plane
// by 0.95 on H = 1e4, r = 7e-300, and by 5e-4 on H = 1.35, r = 6e-13 (found by fuzzing; those
// two rays first, then a seeded sweep of rays through points of the axis).
TEST(GjkEdges, RayCastNormalOnNeedleCapsulesIsNeverLate) {
    struct Ray {
        double radius, half;
        kairos_pose pose;
        V origin, translation;
    };
    std::vector<Ray> rays = {
        {7.0087891966124971e-300,
         9967.3151750972756,
         {{0, 0, 0}, {0, 0, 0, 1}},
         {-0.67450980392156845, -0.67450980392156845, -0.67450980392156845},
         {6.2431372549019599, 6.2431372549019599, 6.2431372549019599}},
        {5.7656672007324327e-13,
         1.3492332341496911,
         {{-2.3686274509803922, -2.3686274509803922, -2.3686274509803922},
          {0.46286995766905958, 0.46286995766905958, 0.46286995766905958, 0.59770745926609359}},
         {-2.3686274509803922, -3.9936522468909743, -4},
         {0, 1.6250247959105821, 1.6313725490196078}},
    };
    const uint64_t seed = 20261126;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (double half : {1.0, 1e4}) {
        for (double rel : {1e-2, 1e-6, 1e-9, 1e-13, 1e-300}) {
            for (int k = 0; k < 100; ++k) {
                const Rot rot = make_rot({u(rng), u(rng), u(rng) + 2}, 3 * u(rng));
                const V at{10 * u(rng), 10 * u(rng), 10 * u(rng)};
                const V on_axis = apply(rot, V{0, 0, 0.9 * half * u(rng)}) + at;
                // Mostly across the axis, starting outside: the start is at least r + 2 from the
                // axis line, hence from the capsule.
                const double phi = 3.14159 * u(rng);
                const V local = unit({std::cos(phi), std::sin(phi), 0.3 * u(rng)});
                const V dir = apply(rot, local);
                const double reach =
                    (rel * half + 2) / std::sqrt(local.x * local.x + local.y * local.y) * (1.5 + 0.5 * u(rng));
                rays.push_back({rel * half,
                                half,
                                {{at.x, at.y, at.z}, {rot.q[0], rot.q[1], rot.q[2], rot.q[3]}},
                                on_axis - reach * dir,
                                2 * reach * dir});
            }
        }
    }
    int hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const Ray& ray = rays[i];
        SCOPED_TRACE(testing::Message() << "ray " << i << " seed " << seed << " radius " << ray.radius << " half "
                                        << ray.half);
        kairos_shape* cap = nullptr;
        ASSERT_EQ(kairos_shape_capsule(ray.radius, ray.half, &cap), KAIROS_OK);
        kairos_cast_result c{};
        ASSERT_EQ(kairos_ray_cast(cap, &ray.pose, kv(ray.origin), kv(ray.translation), nullptr, &c), KAIROS_OK);
        kairos_shape_release(cap);
        if (i >= 2) {
            ASSERT_EQ(c.hit, 1);  // every sweep ray crosses the axis inside the capsule
            ASSERT_GT(c.toi, 0);  // from outside
        }
        if (c.hit == 0) continue;
        ++hits;
        const V n = fromk(c.normal);
        const V x = ray.origin + c.toi * ray.translation;
        // The capsule's axis in the world frame: the pose's rotation of local z.
        const double qx = ray.pose.orientation.x, qy = ray.pose.orientation.y, qz = ray.pose.orientation.z,
                     qw = ray.pose.orientation.w;
        const double qn = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
        const double x2 = qx / qn, y2 = qy / qn, z2 = qz / qn, w2 = qw / qn;
        const V axis{2 * (x2 * z2 + y2 * w2), 2 * (y2 * z2 - x2 * w2), 1 - 2 * (x2 * x2 + y2 * y2)};
        const V centre = fromk(ray.pose.position);
        const double h = dot(n, centre) + std::fabs(dot(n, axis)) * ray.half + ray.radius;
        const double size = ray.half + norm(ray.translation);
        EXPECT_GE(dot(n, x), h - 1e-6 * size) << "normal " << n.x << " " << n.y << " " << n.z << " toi " << c.toi;
        EXPECT_NEAR(norm(n), 1, 1e-12);
    }
    EXPECT_EQ(hits, static_cast<int>(rays.size()));
}

// The casts at the same scales: the capsule moves 3 s toward the box, whose face is 1.5 s from its
// side (toi 1/2); a ray from 5 s out along -x meets the box's face x = s at 4 s of its 10 s
// (toi 0.4). Below 1e-160 the cast loop's squares underflowed and both reported a hit at toi 0.
TEST(GjkEdges, TinyAndHugeScaleCastsGiveTheUnitScaleAnswer) {
    for (double s : {1.0, 1e-100, 1e-160, 1e-200, 1e-300, 1e50, 1e99}) {
        SCOPED_TRACE(testing::Message() << "scale " << s);
        kairos_shape *a = nullptr, *b = nullptr;
        ASSERT_EQ(kairos_shape_box({s, 2 * s, 0.5 * s}, &a), KAIROS_OK);
        ASSERT_EQ(kairos_shape_capsule(0.5 * s, s, &b), KAIROS_OK);
        const kairos_pose pa{{0, 0, 0}, {0, 0, 0, 1}};
        const kairos_pose pb{{3 * s, 0.5 * s, 0}, {0, 0, 0, 1}};
        for (int order = 0; order < 2; ++order) {
            SCOPED_TRACE(order == 0 ? "capsule moves" : "box moves");
            kairos_cast_result c{};
            const int32_t st = order == 0 ? kairos_shape_cast(a, &pa, {0, 0, 0}, b, &pb, {-3 * s, 0, 0}, nullptr, &c)
                                          : kairos_shape_cast(b, &pb, {0, 0, 0}, a, &pa, {3 * s, 0, 0}, nullptr, &c);
            ASSERT_EQ(st, KAIROS_OK) << kairos_last_error();
            ASSERT_EQ(c.hit, 1);
            EXPECT_NEAR(c.toi, 0.5, 1e-6);
            EXPECT_NEAR(std::fabs(c.normal.x), 1, 1e-9);
            EXPECT_NEAR(c.point.x / s, order == 0 ? 1.0 : 2.5, 1e-6);  // the box's face, where it is at toi
        }
        kairos_cast_result r{};
        ASSERT_EQ(kairos_ray_cast(a, &pa, {5 * s, 0.5 * s, 0.1 * s}, {-10 * s, 0, 0}, nullptr, &r), KAIROS_OK);
        ASSERT_EQ(r.hit, 1);
        EXPECT_NEAR(r.toi, 0.4, 1e-6);
        EXPECT_NEAR(r.normal.x, 1, 1e-9);
        EXPECT_NEAR(r.point.x / s, 1, 1e-6);
        EXPECT_NEAR(r.point.y / s, 0.5, 1e-6);
        // Shapes s apart that do not move: no hit.
        kairos_cast_result m{};
        const kairos_pose far{{2.5 * s + s, 0, 0}, {0, 0, 0, 1}};
        ASSERT_EQ(kairos_shape_cast(a, &pa, {0, 0, 0}, b, &far, {0, 0, 0}, nullptr, &m), KAIROS_OK);
        EXPECT_EQ(m.hit, 0);
        kairos_shape_release(a);
        kairos_shape_release(b);
    }
}

// The fuzz finding it comes from: a ball of radius 1e-315 about 1.6e-240 from a point, neither
// moving, was a hit at toi 0.
TEST(GjkEdges, StillCastBetweenShapes1e240Apart) {
    kairos_shape *ball = nullptr, *pt = nullptr;
    ASSERT_EQ(kairos_shape_sphere(1e-315, &ball), KAIROS_OK);
    ASSERT_EQ(kairos_shape_point(&pt), KAIROS_OK);
    const kairos_pose at{{1e-240, -1.2e-240, 0}, {0, 0, 0, 1}};
    const kairos_pose id{{0, 0, 0}, {0, 0, 0, 1}};
    for (int order = 0; order < 2; ++order) {
        kairos_cast_result c{};
        const int32_t st = order == 0 ? kairos_shape_cast(ball, &at, {0, 0, 0}, pt, &id, {0, 0, 0}, nullptr, &c)
                                      : kairos_shape_cast(pt, &id, {0, 0, 0}, ball, &at, {0, 0, 0}, nullptr, &c);
        ASSERT_EQ(st, KAIROS_OK);
        EXPECT_EQ(c.hit, 0) << "order " << order << " toi " << c.toi;
        EXPECT_EQ(c.toi, 1);
    }
    kairos_shape_release(ball);
    kairos_shape_release(pt);
}

// A distance whose square underflows at unit scale: a point 1e-170 beside a unit segment (the
// axis came out 1.0000054 long on such a pair; found by fuzzing).
TEST(GjkEdges, DistanceWhoseSquareUnderflows) {
    kairos_shape *seg = nullptr, *pt = nullptr;
    ASSERT_EQ(kairos_shape_segment(1, &seg), KAIROS_OK);
    for (double d : {1e-150, 1e-160, 1e-170, 1e-300}) {
        SCOPED_TRACE(testing::Message() << "gap " << d);
        const kairos_vec3 p{d, 0, 0.5};
        ASSERT_EQ(kairos_shape_convex_hull(&p, 1, &pt), KAIROS_OK);
        const kairos_pose id{{0, 0, 0}, {0, 0, 0, 1}};
        const Query q = both_orders(seg, id, pt, id);
        // Far below rounding of the size: touching (distance 0) or the distance itself, either way
        // with a unit axis.
        for (const auto* r : {&q.ab, &q.ba}) {
            if (r->intersecting == 0)
                EXPECT_NEAR(r->distance / d, 1, 1e-12);
            else
                EXPECT_EQ(r->distance, 0);
            EXPECT_NEAR(norm(fromk(r->axis)), 1, 1e-15);
        }
        kairos_shape_release(pt);
    }
    kairos_shape_release(seg);
}

// The stability catalogue's rotation-near-pi case: a rod (box 1 x 0.05 x 0.05) turning by
// pi - 1e-6 about a fixed axis passes 4e-8 from a ball. The motion cast ran out of its 4096
// advancement steps near the closest approach and reported a hit; it must report the miss. The
// closest approach is computed here: the ball's centre in the rod's frame at time t (the turn
// q(t) = axis_angle(t angle) q_start, shortest arc), its distance to the box in closed form, minimised by
// dense sampling and golden-section refinement.
TEST(GjkEdges, MotionCastRodTurningByNearlyPiPastABall) {
    const V half{1, 0.050000000000000003, 0.050000000000000003};
    const double radius = 0.14870715125989725;
    const V rod_at{0.44511733908081785, 1.5544975286573379, -0.17482169220176491};
    const V ball_at{0.52068329082351861, 0.48163008675941299, -0.5818306903376157};
    const double q0[4] = {0.4946859016427001, -0.36803314471923559, -0.54469162858198661, 0.56846151396266265};
    const double q1[4] = {0.36803339206214059, 0.49468571762606595, -0.56846178630840605, -0.5446913443511614};
    // q_rel = q1 * conj(q0), w >= 0.
    auto mul = [](const double* p, const double* q, double* o) {
        o[0] = p[3] * q[0] + p[0] * q[3] + p[1] * q[2] - p[2] * q[1];
        o[1] = p[3] * q[1] - p[0] * q[2] + p[1] * q[3] + p[2] * q[0];
        o[2] = p[3] * q[2] + p[0] * q[1] - p[1] * q[0] + p[2] * q[3];
        o[3] = p[3] * q[3] - p[0] * q[0] - p[1] * q[1] - p[2] * q[2];
    };
    const double c0[4] = {-q0[0], -q0[1], -q0[2], q0[3]};
    double rel[4];
    mul(q1, c0, rel);
    if (rel[3] < 0)
        for (double& x : rel) x = -x;
    const double sv = std::sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]);
    const double angle = 2 * std::atan2(sv, rel[3]);
    const V axis{rel[0] / sv, rel[1] / sv, rel[2] / sv};
    auto gap = [&](double t) {
        const Rot turn = make_rot(axis, t * angle);
        double q[4];
        mul(turn.q, q0, q);
        const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        Rot r = make_rot({0, 0, 1}, 0);
        {  // the matrix of q / |q|
            const double x = q[0] / n, y = q[1] / n, z = q[2] / n, w = q[3] / n;
            r.m[0] = 1 - 2 * (y * y + z * z), r.m[1] = 2 * (x * y - z * w), r.m[2] = 2 * (x * z + y * w);
            r.m[3] = 2 * (x * y + z * w), r.m[4] = 1 - 2 * (x * x + z * z), r.m[5] = 2 * (y * z - x * w);
            r.m[6] = 2 * (x * z - y * w), r.m[7] = 2 * (y * z + x * w), r.m[8] = 1 - 2 * (x * x + y * y);
        }
        const V p = apply_t(r, ball_at - rod_at);
        const V out{std::max(std::fabs(p.x) - half.x, 0.0), std::max(std::fabs(p.y) - half.y, 0.0),
                    std::max(std::fabs(p.z) - half.z, 0.0)};
        return norm(out) - radius;
    };
    double best = INFINITY, t_best = 0;
    for (int i = 0; i <= 100000; ++i) {
        const double t = i / 100000.0, g = gap(t);
        if (g < best) best = g, t_best = t;
    }
    double lo = std::max(0.0, t_best - 1e-5), hi = std::min(1.0, t_best + 1e-5);
    for (int i = 0; i < 200; ++i) {
        const double m1 = lo + (hi - lo) * 0.381966, m2 = hi - (hi - lo) * 0.381966;
        (gap(m1) < gap(m2) ? hi : lo) = gap(m1) < gap(m2) ? m2 : m1;
    }
    best = std::min(best, gap(0.5 * (lo + hi)));
    ASSERT_GT(best, 1e-8) << "the configuration is a near miss";
    ASSERT_LT(best, 1e-7);

    kairos_shape *rod = nullptr, *ball = nullptr;
    ASSERT_EQ(kairos_shape_box(kv(half), &rod), KAIROS_OK);
    ASSERT_EQ(kairos_shape_sphere(radius, &ball), KAIROS_OK);
    const kairos_motion ma{{kv(rod_at), {q0[0], q0[1], q0[2], q0[3]}}, {kv(rod_at), {q1[0], q1[1], q1[2], q1[3]}}};
    const kairos_motion mb{{kv(ball_at), {0, 0, 0, 1}}, {kv(ball_at), {0, 0, 0, 1}}};
    for (double tol : {1e-12, 1e-10, 1e-6}) {
        kairos_query_settings st;
        kairos_query_settings_init(&st);
        st.tolerance = tol;
        kairos_cast_result ab{}, ba{};
        ASSERT_EQ(kairos_motion_cast(rod, &ma, ball, &mb, &st, &ab), KAIROS_OK);
        ASSERT_EQ(kairos_motion_cast(ball, &mb, rod, &ma, &st, &ba), KAIROS_OK);
        // A hit within the tolerance's contact distance (tol * the ball's bounding radius) is allowed by the
        // contract; the closest approach is 4e-8, beyond that for every tolerance here but 1e-6.
        const bool may_hit = best <= tol * radius * std::sqrt(3.0);
        if (!may_hit) {
            EXPECT_EQ(ab.hit, 0) << "tolerance " << tol << " toi " << ab.toi << " termination " << ab.termination;
            EXPECT_EQ(ba.hit, 0) << "tolerance " << tol << " toi " << ba.toi << " termination " << ba.termination;
        }
        EXPECT_NE(ab.termination, KAIROS_TERMINATION_MAX_ITERATIONS);
        EXPECT_NE(ba.termination, KAIROS_TERMINATION_MAX_ITERATIONS);
    }
    kairos_shape_release(rod);
    kairos_shape_release(ball);
}

// The sweeps' gaps (fractions of the size) and their random draws: uniform numbers in [-1, 1] and
// unit vectors (rejection from the unit ball), from one seeded generator.
constexpr double kSweepGaps[] = {1e-2, 1e-4, 1e-6, 1e-9, 1e-12, 0, -1e-12, -1e-9, -1e-6, -1e-4, -1e-2};
struct Draws {
    std::mt19937_64 rng;
    std::uniform_real_distribution<double> u{-1, 1};
    explicit Draws(uint64_t seed) : rng(seed) {}
    double uniform() { return u(rng); }
    V unit() {
        for (;;) {
            const V d{u(rng), u(rng), u(rng)};
            if (norm(d) > 0.1 && norm(d) <= 1) return ::unit(d);
        }
    }
};

// A sweep case's orientations: face to face (n = +z of A, B flipped so that its +z faces A, then
// tilted by `tilt` rad about a random axis) for tilt >= 0, else random poses and direction.
void orient(Draws& draw, double tilt, Rot& ra, Rot& rb, V& n) {
    ra = make_rot({0, 0, 1}, 0);
    if (tilt >= 0) {
        n = {0, 0, 1};
        rb = compose(make_rot(draw.unit(), tilt), make_rot({1, 0, 0}, M_PI));
    } else {
        ra = make_rot(draw.unit(), draw.uniform() * M_PI);
        rb = make_rot(draw.unit(), draw.uniform() * M_PI);
        n = draw.unit();
    }
}

// ---- The sweep -----------------------------------------------------------------------------

// Every pair of kinds, both orders, at gaps from -1e-2 to 1e-2 of the size down to +-1e-12 and 0
// (distance, intersect, and from gaps >= 0 a shape cast and a ray cast),
// with A's face normal as the direction and B tilted by 0, 1e-15 ... 1e-3 rad from the flipped
// pose (nearly parallel faces where both have faces), and along random directions at random
// poses. Scales 1 and 1e-4, 1e4.
TEST(GjkEdges, SweepEveryPairOfKindsAtConstructedGaps) {
    const uint64_t seed = 12;
    Draws draw(seed);
    const double tilts[] = {0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3};
    Tally t;
    for (double scale : {1.0, 1e-4, 1e4}) {
        const std::vector<TShape> kinds = shape_kinds(scale);
        for (size_t i = 0; i < kinds.size(); ++i) {
            for (size_t j = 0; j < kinds.size(); ++j) {
                const double size = std::max(kinds[i].size, kinds[j].size);
                for (int variant = 0; variant < 8; ++variant) {
                    Rot ra, rb;
                    V n;
                    orient(draw, variant < 6 ? tilts[variant] : -1, ra, rb, n);
                    const Posed a{&kinds[i], ra, {0, 0, 0}};
                    // Face to face on a solid top: the contact point is A's top point, not its
                    // support point (a box's support ties go to a corner, and a corner on an edge
                    // grazes).
                    const bool deep = variant < 6 && solid_top(kinds[i]);
                    const V pa = deep ? V{0, 0, kinds[i].support({0, 0, 1}).z} : a.support(n);
                    for (double gr : kSweepGaps) {
                        const double g = gr * size;
                        const Posed b = place_b(pa, kinds[j], rb, n, g);
                        const std::string what = kinds[i].name + "/" + kinds[j].name + " scale " +
                                                 std::to_string(scale) + " variant " + std::to_string(variant) +
                                                 " gap " + std::to_string(gr) + " seed " + std::to_string(seed);
                        const std::string kinds_ab = kinds[i].name + "/" + kinds[j].name;
                        const V contact_b = pa + g * n;
                        check_pair(a, b, n, g, size, deep, &contact_b, kinds_ab, what + " (a, b)", t);
                        check_pair(b, a, -n, g, size, deep, nullptr, kinds_ab + " swapped", what + " (b, a)", t);
                    }
                }
            }
        }
    }
    std::printf("[sweep] %d queries: %d separated, %d intersecting; worst |distance - gap| / size %.3g\n", t.cases,
                t.separated, t.intersecting, t.worst_rel);
    int total = 0;
    for (const auto& [key, count] : t.failures) {
        std::printf("  FAIL %-40s %4d  first: %s\n", key.c_str(), count, t.first[key].c_str());
        total += count;
    }
    EXPECT_EQ(total, 0) << "failed checks (listed above)";
    // Both verdicts occur in quantity (the negative gaps overlap).
    EXPECT_GT(t.intersecting, t.cases / 5);
    EXPECT_GT(t.separated, t.cases / 3);
}

// The sweep's construction on needles, plates, discs, flat cones and a sliver (needle_kinds), at
// scales 1e-8, 1 and 1e8, with A at the origin and 1e3 and 1e6 sizes from it in a random
// direction. Far from the origin the placement itself rounds by a few eps of the distance to it
// (the points of contact are computed there), which every allowance gains (slack).
TEST(GjkEdges, SweepNeedlesAndPlatesFarFromTheOrigin) {
    const uint64_t seed = 13;
    Draws draw(seed);
    const double tilts[] = {0, 1e-9, 1e-3};
    Tally tallies[2];  // A within 1e3 sizes of the origin; 1e6 sizes away
    for (double scale : {1.0, 1e-8, 1e8})
        for (double thin : {1e-5, 1e-6}) {
            const std::vector<TShape> kinds = needle_kinds(scale, thin);
            for (size_t i = 0; i < kinds.size(); ++i) {
                for (size_t j = 0; j < kinds.size(); ++j) {
                    const double size = std::max(kinds[i].size, kinds[j].size);
                    for (double away : {0.0, 1e3, 1e6}) {
                        for (int variant = 0; variant < 5; ++variant) {
                            Rot ra, rb;
                            V n;
                            orient(draw, variant < 3 ? tilts[variant] : -1, ra, rb, n);
                            const V c = away * size * draw.unit();
                            const Posed a{&kinds[i], ra, c};
                            const bool deep = variant < 3 && solid_top(kinds[i]);
                            // A first contact at a tip or a wedge 1e-6 wide moves by the placement's
                            // rounding over that width (the ray passes beside the tip and meets its
                            // side later): far from the origin such casts have no sharp truth.
                            const bool cast = deep && (away == 0 || !(sharp(kinds[i]) || sharp(kinds[j])));
                            const V pa = deep ? c + V{0, 0, kinds[i].support({0, 0, 1}).z} : a.support(n);
                            // Points within 1e-7 of the size (the stated bound at an aspect of 1e5 is
                            // 1e-6; seen: 3.9e-8, the common point of two needle cones crossing);
                            // distances on curved pairs within the header's 5e-8 for a cylinder
                            // touching (seen: 1.2e-8, a needle cylinder touching a cube, NO_PROGRESS);
                            // v's rounding, which tilts the axis, is larger on needles' slivers (seen:
                            // 1.7e-12 size^2 / distance, a plate 1e-9 of its size from a needle).
                            const Allow allow{8 * 0x1p-52 * norm(c), !deep, 1e-7, 5e-8, 1e-11};
                            for (double gr : kSweepGaps) {
                                const double g = gr * size;
                                const Posed b = place_b(pa, kinds[j], rb, n, g);
                                const std::string kinds_ab = kinds[i].name + "/" + kinds[j].name;
                                const std::string what = kinds_ab + " scale " + std::to_string(scale) + " thin " +
                                                         std::to_string(thin) + " away " + std::to_string(away) +
                                                         " variant " + std::to_string(variant) + " gap " +
                                                         std::to_string(gr) + " seed " + std::to_string(seed);
                                const V contact_b = pa + g * n;
                                Tally& t = tallies[away == 1e6];
                                check_pair(a, b, n, g, size, cast, &contact_b, kinds_ab, what + " (a, b)", t, allow);
                                check_pair(b, a, -n, g, size, cast, nullptr, kinds_ab + " swapped", what + " (b, a)", t,
                                           allow);
                            }
                        }
                    }
                }
            }
        }
    int total = 0;
    for (int far = 0; far < 2; ++far) {
        Tally& t = tallies[far];
        std::printf("[needles, %s] %d queries: %d separated, %d intersecting; worst |distance - gap| / size %.3g\n",
                    far ? "1e6 sizes from the origin" : "near the origin", t.cases, t.separated, t.intersecting,
                    t.worst_rel);
        for (const auto& [key, count] : t.failures) {
            std::printf("  FAIL %-40s %4d  first: %s\n", key.c_str(), count, t.first[key].c_str());
            total += count;
        }
        EXPECT_GT(t.intersecting, t.cases / 5);
        EXPECT_GT(t.separated, t.cases / 3);
    }
    EXPECT_EQ(total, 0) << "failed checks (listed above)";
}

// A tip (a segment's end, a point, a rod's end, a needle cone's apex) over a box face, or over a
// hull of the box's corners, whose foot falls on the face's diagonal (on the centre, or 1e-3 of the
// size off it): Johnson's determinants cannot decide between the face's two triangles and the loop
// stops on a rounding rule with v tilted by rounding. The reported axis must still show the gap:
// the support planes along it at least the distance apart, within 1e-11 of the size (the faces'
// planes among the last points give the face's normal). Gaps 1e-9 .. 1e-2 of the size, random
// turns of the whole pair, near the origin and 1e3 sizes from it, both argument orders. Before the
// faces were also tried after a repeated support point, 3 of the 6000 answers fell short by up to
// 5.9e-8 of the size (tip first, gaps 2e-9 .. 2e-7); with v's direction alone, 250 of them.
TEST(GjkEdges, TipOverAFaceDiagonalGetsAnAxisThatShowsTheGap) {
    const uint64_t seed = 29;
    Draws draw(seed);
    std::vector<TShape> faces, tips;
    faces.push_back(box_kind("box", {1, 1, 1}));
    {
        std::vector<V> corners;
        for (int i = 0; i < 8; ++i) corners.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
        faces.push_back(hull_kind("box hull", corners, std::sqrt(3.0)));
    }
    kairos_shape* k = nullptr;
    tips.push_back({"segment", own(must(kairos_shape_segment(1, &k), k)),
                    [](V d) {
                        return V{0, 0, d.z < 0 ? -1.0 : 1.0};
                    },
                    1, true});
    tips.push_back({"point", own(must(kairos_shape_point(&k), k)), [](V) { return V{0, 0, 0}; }, 1, true});
    tips.push_back(box_kind("rod", {1e-6, 1e-6, 1}));
    tips.push_back(cone_kind("needle cone", 1e-6, 1));
    int queries = 0, failures = 0, stops = 0;
    double worst = 0;
    std::string first;
    for (int trial = 0; trial < 3000; ++trial) {
        const TShape& f = faces[trial % faces.size()];
        const TShape& t = tips[(trial / faces.size()) % tips.size()];
        const Rot r = make_rot(draw.unit(), draw.uniform() * M_PI);
        const V c = (trial % 3 == 2 ? 1e3 : 0.0) * draw.unit();
        const Posed a{&f, r, c};
        const V n = apply(r, {0, 0, 1});  // the face's normal (world)
        // The tip's axis along -n: B turned half a turn about x, then with the face.
        const Rot rb = compose(r, make_rot({1, 0, 0}, M_PI));
        const double off = trial % 2 ? 1e-3 : 0.0;
        const V foot = c + apply(r, {off * draw.uniform(), off * draw.uniform(), 1});
        const double g = std::pow(10.0, -9 + 7 * (0.5 + 0.5 * draw.uniform()));
        const Posed b = place_b(foot, t, rb, n, g);
        const kairos_pose pa = a.pose(), pb = b.pose();
        const Query q = both_orders(f.k.get(), pa, t.k.get(), pb);
        for (int order = 0; order < 2; ++order) {
            const kairos_distance_result& res = order ? q.ba : q.ab;
            const Posed& from = order ? b : a;
            const Posed& to = order ? a : b;
            ++queries;
            stops += res.termination != KAIROS_TERMINATION_RELATIVE_ERROR;
            const V axis = fromk(res.axis);
            const double sep = -to.h(-axis) - from.h(axis);
            const double allowed = 1e-11 + 64 * 0x1p-52 * norm(c);
            const double shortfall = res.distance - sep;
            worst = std::max(worst, shortfall);
            const bool ok = !res.intersecting && std::fabs(res.distance - g) <= 1e-12 + 16 * 0x1p-52 * norm(c) &&
                            shortfall <= allowed;
            if (!ok && failures++ == 0)
                first = f.name + " / " + t.name + (order ? " (b, a)" : " (a, b)") +
                        fmt(" gap %.17g distance %.17g", g, res.distance) +
                        fmt(" separation along the axis %.17g trial %.0f", sep, trial) + " seed " +
                        std::to_string(seed);
        }
    }
    std::printf(
        "tips over a face's diagonal: %d queries, %d ended by a rounding rule, worst shortfall of the "
        "axis's separation %.3g of the size\n",
        queries, stops, worst);
    EXPECT_EQ(failures, 0) << "first: " << first;
    // The foot on the diagonal must make rounding stops common, or the test shows nothing.
    EXPECT_GT(stops, queries / 20);
}

// A fuzz_world finding: a unit ball travelling 1.5e11 ends inside a box of half extents 6.7e19, 3.28
// and 6.7e10. The ball's overlap at the end (about 4) is far below the rounding of a support plane
// 6.7e19 out, so the last clip crossed lambda = 1 by that rounding and the cast reported a miss.
// Truth in long double, in the box's frame: the centre's entry into the box itself (the ball enters
// no later: a hit must come by then) and the ball's distance to the box at the reported toi (within
// 1e-9 of the pair's size, the accuracy the library states: here 6.7e10; the box-moving order stops
// about 4e10 short, since the loop's tolerances are relative to the simplex's size). A miss is wrong
// only when the centre enters the box. The motion is scaled
// around the finding's so that the entry falls within 1e-12 .. 1e-5 of the step's end, on both
// sides of it, in both argument orders.
TEST(GjkEdges, CastIntoAHugeSlabNeverMissesAnEntryAtTheStepsEnd) {
    const V half{6.7030899519340806e+19, 3.279560540169375, 67030899519.340813};
    const V start{99999999999, -100000000001, 49999999999};
    const V end{-3.7108110170138096, -3.99487296864271, -4};
    const V box_at{-4, -4, -3.4321202410925462};
    const double q[4] = {0.49327263250092857, 0.060854646124513738, -0.49041242649878691, 0.71587322481444715};
    kairos_shape *ball = nullptr, *slab = nullptr;
    ASSERT_EQ(kairos_shape_sphere(1, &ball), KAIROS_OK);
    ASSERT_EQ(kairos_shape_box(kv(half), &slab), KAIROS_OK);
    const kairos_pose box_pose{kv(box_at), {q[0], q[1], q[2], q[3]}};
    // The box's rotation (the library normalises the quaternion; so does this).
    const long double n = std::sqrt((long double)q[0] * q[0] + (long double)q[1] * q[1] +
                                    (long double)q[2] * q[2] + (long double)q[3] * q[3]);
    const long double x = q[0] / n, y = q[1] / n, z = q[2] / n, w = q[3] / n;
    const long double m[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
                              2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                              2 * (x * z - y * w),     2 * (y * z + x * w), 1 - 2 * (x * x + y * y)};
    auto local = [&](V p) {  // R^T (p - box_at)
        const long double d[3] = {(long double)p.x - box_at.x, (long double)p.y - box_at.y,
                                  (long double)p.z - box_at.z};
        std::array<long double, 3> l{};
        for (int i = 0; i < 3; ++i) l[i] = m[i] * d[0] + m[3 + i] * d[1] + m[6 + i] * d[2];
        return l;
    };
    const long double h[3] = {half.x, half.y, half.z};
    // Entry time of the centre's path p0 + t d (t in [0, 1]) into the box; 2 when there is none.
    auto entry = [&](V p0, V d) {
        const auto pl = local(p0);
        const auto e = local(p0 + d);
        long double t0 = 0, t1 = 1;
        for (int i = 0; i < 3; ++i) {
            const long double dl = e[i] - pl[i];
            if (dl == 0) {
                if (std::fabs(pl[i]) > h[i]) return 2.0L;
                continue;
            }
            long double a = (-h[i] - pl[i]) / dl, b = (h[i] - pl[i]) / dl;
            if (a > b) std::swap(a, b);
            t0 = std::max(t0, a), t1 = std::min(t1, b);
        }
        return t0 <= t1 ? t0 : 2.0L;
    };
    auto gap = [&](V centre) {  // the ball's distance to the box (0 when they overlap)
        const auto l = local(centre);
        long double sq = 0;
        for (int i = 0; i < 3; ++i) {
            const long double out = std::fabs(l[i]) - h[i];
            if (out > 0) sq += out * out;
        }
        return std::max(0.0L, std::sqrt(sq) - 1);
    };
    const long double band = 1e-9L * half.x;
    int hits = 0, misses = 0;
    for (double k : {1.0, 1 - 1e-5, 1 - 1e-8, 1 - 1e-10, 1 - 1e-12, 1 + 1e-12, 1 + 1e-10, 1 + 1e-9, 1 + 1e-8,
                     1 + 3e-8, 1 + 1e-7, 1 + 1e-6, 1.5, 0.5}) {
        const V motion = k * (end - start);
        const long double late = entry(start, motion);
        for (int order = 0; order < 2; ++order) {
            SCOPED_TRACE(testing::Message() << "motion scaled by 1 + " << (k - 1) << (order ? ", box moves" : ""));
            const kairos_pose bp{kv(start), {0, 0, 0, 1}};
            kairos_cast_result c{};
            const int32_t st =
                order == 0 ? kairos_shape_cast(ball, &bp, kv(motion), slab, &box_pose, {0, 0, 0}, nullptr, &c)
                           : kairos_shape_cast(slab, &box_pose, kv(-motion), ball, &bp, {0, 0, 0}, nullptr, &c);
            ASSERT_EQ(st, KAIROS_OK) << kairos_last_error();
            if (late <= 1) {
                ASSERT_EQ(c.hit, 1) << "the centre enters the box at " << (double)late;
                // Never late beyond the support planes' rounding (about 1e-7 of this motion).
                EXPECT_LE(c.toi, (double)late + 1e-6);
            }
            if (c.hit) {
                ++hits;
                EXPECT_LE(gap(start + c.toi * motion), band);
            } else {
                ++misses;
            }
        }
    }
    EXPECT_GE(hits, 8);
    EXPECT_GE(misses, 2);
    kairos_shape_release(ball);
    kairos_shape_release(slab);
}


// A fuzz finding: a segment 1.25e-219 long turning and moving into a ball. Its bounding radius
// squared underflowed to 0, so the motion cast took it for a point and measured "within tolerance
// of contact" by the ball's radius: a hit 0.0011 short of the ball at tolerance 1e-3. The radius
// is the segment's own now (kairos.h: tolerance * min(rA, rB)), so the hit is at contact. Truth:
// the distance at the reported toi, from kairos_distance at the linearly moved positions (the
// segment's and the ball's turns do not move their points).
TEST(GjkEdges, MotionCastOfAShapeWhoseRadiusSquaredUnderflows) {
    kairos_shape *a = nullptr, *b = nullptr;
    ASSERT_EQ(kairos_shape_segment(6.2551155870908672e-220, &a), KAIROS_OK);
    ASSERT_EQ(kairos_shape_sphere(0.6775051499198903, &b), KAIROS_OK);
    const kairos_motion ma{{{-2.996078431372549, -2.996078431372549, -2.996078431372549}, {1, 0, 0, 0}},
                           {{-1.2078431372549021, -1.2078431372549021, -1.2078431372549021},
                            {-3.0196078431372555e-05, 0, 0, 1}}};
    const kairos_motion mb{{{-0.0074901960784313727, 0.0036037232013427945, -0.00088426031891355788},
                            {0.53989437693969433, 0.53989437693969433, -0.35431932948499745, -0.53989437693969433}},
                           {{-3.0959136339360649, -2.996078431372549, -2.996078431372549}, {-5.2370489051651797e-05, 0, 0, 1}}};
    for (int order = 0; order < 2; ++order) {
        SCOPED_TRACE(order == 0 ? "segment first" : "ball first");
        kairos_query_settings s;
        kairos_query_settings_init(&s);
        s.tolerance = 1e-3;
        kairos_cast_result r{};
        ASSERT_EQ(order == 0 ? kairos_motion_cast(a, &ma, b, &mb, &s, &r) : kairos_motion_cast(b, &mb, a, &ma, &s, &r),
                  KAIROS_OK)
            << kairos_last_error();
        ASSERT_EQ(r.hit, 1);
        // HIT, or the step guard NO_PROGRESS at rounding-level distances (a lower bound of the time).
        ASSERT_TRUE(r.termination == KAIROS_TERMINATION_HIT || r.termination == KAIROS_TERMINATION_NO_PROGRESS)
            << r.termination;
        auto at = [&](const kairos_motion& m) {
            kairos_pose p = m.start;
            p.position = kv(fromk(m.start.position) + r.toi * (fromk(m.end.position) - fromk(m.start.position)));
            return p;
        };
        const kairos_pose pa = at(ma), pb = at(mb);
        kairos_distance_result d{};
        ASSERT_EQ(kairos_distance(a, &pa, b, &pb, nullptr, &d), KAIROS_OK);
        // Within 1e-3 of the segment's radius (6.3e-220) of contact, up to the rounding of the
        // positions at toi (about 1e-15 here).
        EXPECT_LE(d.distance, 1e-14) << "toi " << r.toi;
    }
    kairos_shape_release(a);
    kairos_shape_release(b);
}

// The fuzzer's finding of 2026-11-27 (tests/fuzz/findings/distance_long_box_cylinder.c): a box of
// half extents (6.79, 1, L) beside an upright cylinder of radius 1 (parallel axes), overlapping by
// 1.5. From L = 1e6 on, distance, intersect and signed distance said 0.031 apart in both orders:
// the tetrahedron that held the origin was a sliver (edges 2e6 long, nearly parallel) and the
// flatness test, relative to its edges' product, called it flat. Truth by construction: the
// cylinder's disk lies inside the box's x span, so the pair's gap is g across the box's bottom face
// and, overlapping, its depth is -g (pushing B down; up takes 4 + g). Whole scene turned about the
// world origin by seeded rotations too. Accuracy bound: 1e-9 of the size (L) for the curved pair.
TEST(GjkEdges, LongBoxBesideACylinderAtGapsBothOrders) {
    const uint64_t seed = 27112026;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    kairos_shape* cylinder = nullptr;
    ASSERT_EQ(kairos_shape_cylinder(1, 7.8455481803616385, &cylinder), KAIROS_OK);
    const V box_centre{-4, -3.4999923704890517, -3.9765621423666744};
    int intersecting = 0, separated = 0;
    for (double half_length = 1e2; half_length <= 1e6; half_length *= 10) {
        kairos_shape* box = nullptr;
        ASSERT_EQ(kairos_shape_box({6.785763332570383, 1, half_length}, &box), KAIROS_OK);
        for (int turn = 0; turn < 4; ++turn) {
            const Rot r = turn == 0 ? make_rot({0, 0, 1}, 0)
                                    : make_rot({gauss(rng), gauss(rng), gauss(rng)}, std::uniform_real_distribution<double>(0, M_PI)(rng));
            const kairos_quat q{r.q[0], r.q[1], r.q[2], r.q[3]};
            for (double gap : {-1.5, -0.5, -1e-2, 1e-2, 0.5}) {
                // The finding's own pose (gap -1.49999...) first: the cylinder at (-4, -4, -4).
                const double cy = gap == -1.5 ? -4.0 : box_centre.y - 1 - 1 - gap;
                const double truth = gap == -1.5 ? (box_centre.y - 1) - (cy + 1) : gap;
                const kairos_pose pa{kv(apply(r, box_centre)), q}, pb{kv(apply(r, {-4, cy, -4})), q};
                const double bound = 1e-9 * half_length;
                SCOPED_TRACE(testing::Message() << "seed " << seed << " half length " << half_length << " turn " << turn
                                                << " gap " << gap);
                const Query d = both_orders(box, pa, cylinder, pb);
                kairos_distance_result sab{}, sba{};
                ASSERT_EQ(kairos_signed_distance(box, &pa, cylinder, &pb, nullptr, &sab), KAIROS_OK);
                ASSERT_EQ(kairos_signed_distance(cylinder, &pb, box, &pa, nullptr, &sba), KAIROS_OK);
                int32_t iab = -1, iba = -1;
                ASSERT_EQ(kairos_intersect(box, &pa, cylinder, &pb, nullptr, &iab), KAIROS_OK);
                ASSERT_EQ(kairos_intersect(cylinder, &pb, box, &pa, nullptr, &iba), KAIROS_OK);
                const int want = truth < 0 ? 1 : 0;
                EXPECT_EQ(iab, want);
                EXPECT_EQ(iba, want);
                for (const auto* x : {&d.ab, &d.ba}) {
                    EXPECT_EQ(x->intersecting, want) << "termination " << x->termination;
                    EXPECT_NEAR(x->distance, std::max(truth, 0.0), bound) << "termination " << x->termination;
                }
                for (const auto* x : {&sab, &sba}) {
                    EXPECT_NEAR(x->distance, truth, bound) << "termination " << x->termination;
                    EXPECT_NEAR(apart(*x), std::fabs(x->distance), bound);
                }
                (want ? intersecting : separated) += 1;
            }
        }
        kairos_shape_release(box);
    }
    EXPECT_EQ(intersecting, 5 * 4 * 3);
    EXPECT_EQ(separated, 5 * 4 * 2);
    kairos_shape_release(cylinder);
}

// A ball far smaller than the rounding of the positions (radius 1e-15 .. 1e-12 at about unit
// distance) cast onto a unit ball given as a hull of two balls (a generic shape, so the GJK cast
// runs, not the closed form): the normal is the radial direction at the contact, to 1e-6 rad. The
// cast's final v is then x minus a support point within the tiny radius, pure rounding noise in
// direction; it was taken as the normal (1.6 degrees off; found by fuzz_queries).
TEST(GjkEdges, TinyBallOntoAGenericRoundShapeGetsTheRadialNormal) {
    kairos_shape *ball = nullptr, *hull = nullptr;
    ASSERT_EQ(kairos_shape_sphere(1, &ball), KAIROS_OK);
    ASSERT_EQ(kairos_shape_hull(ball, ball, &hull), KAIROS_OK);
    const uint64_t seed = 20261127;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0, 1);
    std::uniform_real_distribution<double> u(0, 1);
    int hits = 0, off = 0;
    double worst = 0;
    for (int i = 0; i < 600; ++i) {
        kairos_shape* tiny = nullptr;
        const double radius = std::pow(10.0, -15 + 3 * u(rng));
        ASSERT_EQ(kairos_shape_sphere(radius, &tiny), KAIROS_OK);
        // From 2 .. 6 units away, head-on (every third case) or aimed within 0.8 of the centre.
        double d[3] = {g(rng), g(rng), g(rng)};
        const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double dist = 2 + 4 * u(rng);
        const kairos_pose pa{{0, 0, 0}, {0, 0, 0, 1}};
        const kairos_pose pb{{dist * d[0] / n, dist * d[1] / n, dist * d[2] / n}, {0, 1, 0, 0}};
        double aim[3] = {0, 0, 0};
        if (i % 3 != 0)
            for (double& c : aim) c = 0.45 * (2 * u(rng) - 1);
        const kairos_vec3 tb{aim[0] - pb.position.x, aim[1] - pb.position.y, aim[2] - pb.position.z};
        kairos_cast_result r;
        ASSERT_EQ(kairos_shape_cast(hull, &pa, {0, 0, 0}, tiny, &pb, tb, nullptr, &r), KAIROS_OK);
        kairos_shape_release(tiny);
        if (!r.hit) continue;
        ++hits;
        // B's centre at toi, and its direction from A's centre: the contact normal.
        const double c[3] = {pb.position.x + r.toi * tb.x, pb.position.y + r.toi * tb.y, pb.position.z + r.toi * tb.z};
        const double cn = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        // The angle from the cross product (acos near 1 resolves only 2e-8).
        const double x[3] = {r.normal.y * c[2] - r.normal.z * c[1], r.normal.z * c[0] - r.normal.x * c[2],
                             r.normal.x * c[1] - r.normal.y * c[0]};
        const double cosine = (r.normal.x * c[0] + r.normal.y * c[1] + r.normal.z * c[2]) / cn;
        const double angle = cosine > 0 ? std::asin(std::fmin(1.0, std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) / cn))
                                        : 3.14159;
        worst = std::fmax(worst, angle);
        if (!(angle <= 1e-6)) {
            if (++off <= 5)
                ADD_FAILURE() << "seed " << seed << " case " << i << ": radius " << radius << ", normal " << angle
                              << " rad off the radial direction (toi " << r.toi << ")";
        }
    }
    std::printf("tiny balls onto a hull of balls: %d hits, worst normal %.3g rad\n", hits, worst);
    EXPECT_EQ(off, 0);
    EXPECT_GT(hits, 450);  // every head-on case and most aimed ones hit
    kairos_shape_release(hull);
    kairos_shape_release(ball);
}

}  // namespace

// Beyond the accuracy ranges (a needle hull of nine nearly collinear points, aspect 1e8 .. 1e11,
// across a slab 1e-11 as thick as it is wide; docs/c-api.md "Where the accuracy holds"), a
// distance of 0 still comes with a common point near both shapes. The tetrahedron of A - B that
// holds the origin is a sliver there, and its barycentric coordinates in double put the point
// outside the slab by up to 1e-7 of the needle's length (0.13 on a needle 1.6e6 long, found by
// fuzz_queries); they are recomputed in long double when they do not reproduce the origin. Truth:
// the slab's own box (its local frame, exact), and the needle's hull by its points' projections.
TEST(GjkEdges, NeedleAcrossAThinSlabGivesACommonPointNearBoth) {
    const uint64_t seed = 20261127;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit01(0, 1);
    const V half{0.13175097276264591, 10, 1.3175097276264592e-10};
    kairos_shape* slab = nullptr;
    ASSERT_EQ(kairos_shape_box(kv(half), &slab), KAIROS_OK);
    const kairos_pose slab_pose{{-3.9980468451972229, -4, -3.9765621423666744}, {0, 0, 0, 1}};
    double worst = 0;
    int intersecting = 0, cases = 0;
    for (int i = 0; i < 400; ++i) {
        // The needle's line through a point of the slab, at a steep angle to it.
        const double length = std::pow(10.0, 4 + 2.5 * unit01(rng));
        const double thickness = length * std::pow(10.0, -8 - 3 * unit01(rng));
        V dir = unit({0.3 * gauss(rng), 0.3 * gauss(rng), 1});
        const V through = fromk(slab_pose.position) + V{half.x * (2 * unit01(rng) - 1), half.y * (2 * unit01(rng) - 1), 0};
        std::vector<kairos_vec3> points;
        for (int k = 0; k < 9; ++k) {
            const double t = length * (unit01(rng) - 0.5);
            points.push_back(kv(t * dir + thickness * V{gauss(rng), gauss(rng), gauss(rng)}));
        }
        points[0] = kv(-0.5 * length * dir), points[1] = kv(0.5 * length * dir);  // it spans the slab
        kairos_shape* needle = nullptr;
        ASSERT_EQ(kairos_shape_convex_hull(points.data(), 9, &needle), KAIROS_OK);
        const kairos_pose needle_pose{kv(through), {0, 0, 0, 1}};
        SCOPED_TRACE(testing::Message() << "seed " << seed << " case " << i << " length " << length << " thickness "
                                        << thickness);
        for (int order = 0; order < 2; ++order) {
            kairos_distance_result r{};
            ASSERT_EQ(order == 0 ? kairos_distance(needle, &needle_pose, slab, &slab_pose, nullptr, &r)
                                 : kairos_distance(slab, &slab_pose, needle, &needle_pose, nullptr, &r),
                      KAIROS_OK);
            ++cases;
            if (!r.intersecting) continue;
            ++intersecting;
            // Outside the slab: the excess over its half extents, in its (unturned) frame.
            const V p = fromk(r.point_a) - fromk(slab_pose.position);
            const double out = std::max({std::fabs(p.x) - half.x, std::fabs(p.y) - half.y, std::fabs(p.z) - half.z, 0.0});
            worst = std::max(worst, out / length);
            EXPECT_LE(out, 1e-9 * length) << "order " << order << " termination " << r.termination;
        }
        kairos_shape_release(needle);
    }
    std::printf("needle across a slab: %d of %d intersecting, worst point outside the slab %.3g of the length\n",
                intersecting, cases, worst);
    EXPECT_GE(intersecting, cases * 9 / 10);
    kairos_shape_release(slab);
}

// A flat hull 1e5 .. 3e9 long (points on a line and one off it: a triangle with no thickness)
// crossed by a cone or a box 2000 long, centred on the triangle: they intersect by construction.
// The tetrahedron of A - B that holds the origin spans the hull's length and is as wide as the
// small shape, so its coordinates carry errors of 1e-7 even in long double; summed over the
// hull's vertices they put the common point 1.4e3 along the hull, out of a cone of radius 10
// (found by fuzz_queries). Truth: the small shape by its closed form in its own frame, the
// triangle by its plane and edges.
TEST(GjkEdges, HugeFlatHullCrossedByASmallShapeGivesACommonPointInBoth) {
    const uint64_t seed = 20261128;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit01(0, 1);
    const double radius = 10, half = 1000;
    kairos_shape *cone = nullptr, *box = nullptr;
    ASSERT_EQ(kairos_shape_cone(radius, half, &cone), KAIROS_OK);
    ASSERT_EQ(kairos_shape_box({radius, radius, half}, &box), KAIROS_OK);
    double worst_small = 0, worst_hull = 0;
    int cases = 0, intersecting = 0;
    for (int i = 0; i < 300; ++i) {
        const double length = std::pow(10.0, 5 + 4.5 * unit01(rng));
        const V dir = unit({gauss(rng), gauss(rng), gauss(rng)});
        V side = {gauss(rng), gauss(rng), gauss(rng)};
        side = unit(side - dot(side, dir) * dir);
        const V normal{dir.y * side.z - dir.z * side.y, dir.z * side.x - dir.x * side.z, dir.x * side.y - dir.y * side.x};
        // Ten points on the line, its two ends first, and one beside it: the triangle's corners.
        std::vector<kairos_vec3> points = {kv(-0.5 * length * dir), kv(0.5 * length * dir), kv(0.2 * length * side)};
        for (int k = 0; k < 8; ++k) points.push_back(kv(length * (unit01(rng) - 0.5) * dir));
        kairos_shape* hull = nullptr;
        ASSERT_EQ(kairos_shape_convex_hull(points.data(), points.size(), &hull), KAIROS_OK);
        const kairos_pose hull_pose{{4 * gauss(rng), 4 * gauss(rng), 4 * gauss(rng)}, {0, 0, 0, 1}};
        // The small shape's centre on the triangle, within 1e3 of the long edge, turned anyhow.
        const V centre = fromk(hull_pose.position) + (0.4 * length * (2 * unit01(rng) - 1)) * dir +
                         (1e3 * unit01(rng)) * side;
        const Rot turn = make_rot({gauss(rng), gauss(rng), gauss(rng)}, 6.283185307179586 * unit01(rng));
        const kairos_pose small_pose{kv(centre), {turn.q[0], turn.q[1], turn.q[2], turn.q[3]}};
        const bool is_cone = i % 2 == 0;
        kairos_shape* small = is_cone ? cone : box;
        // How far p lies outside the small shape (its frame: the cone's apex at +half on z).
        auto outside_small = [&](V p) {
            const V l = apply_t(turn, p - centre);
            const double rho = std::sqrt(l.x * l.x + l.y * l.y);
            if (!is_cone) return std::max({std::fabs(l.x) - radius, std::fabs(l.y) - radius, std::fabs(l.z) - half});
            const double slant = (rho * 2 * half + (l.z - half) * radius) / std::sqrt(4 * half * half + radius * radius);
            return std::max({slant, -half - l.z, l.z - half});
        };
        // How far p lies off the triangle: off its plane, or beyond its long edge or the two others.
        auto outside_hull = [&](V p) {
            const V q = p - fromk(hull_pose.position);
            const double s = dot(q, side), t = dot(q, dir);
            const double beyond = std::max({-s, s - 0.2 * length * (1 - 2 * std::fabs(t) / length), std::fabs(t) - 0.5 * length});
            return std::max(std::fabs(dot(q, normal)), beyond);
        };
        SCOPED_TRACE(testing::Message() << "seed " << seed << " case " << i << " length " << length);
        for (int order = 0; order < 2; ++order) {
            kairos_distance_result r{};
            ASSERT_EQ(order == 0 ? kairos_distance(hull, &hull_pose, small, &small_pose, nullptr, &r)
                                 : kairos_distance(small, &small_pose, hull, &hull_pose, nullptr, &r),
                      KAIROS_OK);
            ++cases;
            if (!r.intersecting) {
                ADD_FAILURE() << "order " << order << ": apart by " << r.distance;
                continue;
            }
            ++intersecting;
            const V p = fromk(r.point_a);
            const double out_small = outside_small(p), out_hull = outside_hull(p);
            worst_small = std::max(worst_small, out_small / half);
            worst_hull = std::max(worst_hull, out_hull / length);
            EXPECT_LE(out_small, 1e-9 * half) << "order " << order << " termination " << r.termination;
            EXPECT_LE(out_hull, 1e-9 * length) << "order " << order << " termination " << r.termination;
        }
        kairos_shape_release(hull);
    }
    std::printf("flat hull across a small shape: %d of %d intersecting, worst point outside the small shape %.3g "
                "of its half length, outside the hull %.3g of its length\n",
                intersecting, cases, worst_small, worst_hull);
    EXPECT_EQ(intersecting, cases);
    kairos_shape_release(box);
    kairos_shape_release(cone);
}

// A box 2e5 .. 2e9 long and about 2 thick through a cylinder thousands wide and about 2 thick,
// both about the same point and turned alike: they overlap deeply, by
// min(hz + h, min(hx, hy) + r) (the origin's depth in the box grown by the cylinder). A sliver
// tetrahedron of A - B held the origin by only 0.2, GJK stopped 0.22 away with no lower bound,
// and kairos_intersect, kairos_distance and kairos_signed_distance all said "apart" for an overlap
// of 4622 (found by fuzz_queries; the code before the fix said 0.22 and 0.29 apart on this test's
// first two cases). Truth: the closed form above.
TEST(GjkEdges, NeedleBoxThroughAFlatWideCylinderOverlaps) {
    const uint64_t seed = 20261128;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit01(0, 1);
    std::normal_distribution<double> gauss;
    int cases = 0, wrong = 0;
    double worst_depth = 0;
    for (int i = 0; i < 200; ++i) {
        V h{std::pow(10.0, 5 + 4 * unit01(rng)), 0.5 + 1.5 * unit01(rng), 1e3 + 4e3 * unit01(rng)};
        double radius = 1e3 + 4e3 * unit01(rng), half = 0.5 + 1.5 * unit01(rng);
        kairos_pose pose{{0, 0, 0}, {0, 0, 0, 1}};
        if (i == 0) {  // the finding
            h = {632529182.87937737, 1, 4621.1490043488211};
            radius = 4635.2941176470586, half = 1.0201876859693293;
        } else if (i % 2 == 0) {  // turned alike, somewhere else
            const Rot turn = make_rot({gauss(rng), gauss(rng), gauss(rng)}, 6.283185307179586 * unit01(rng));
            pose = {{1e3 * gauss(rng), 1e3 * gauss(rng), 1e3 * gauss(rng)}, {turn.q[0], turn.q[1], turn.q[2], turn.q[3]}};
        }
        kairos_shape *box = nullptr, *cylinder = nullptr;
        ASSERT_EQ(kairos_shape_box(kv(h), &box), KAIROS_OK);
        ASSERT_EQ(kairos_shape_cylinder(radius, half, &cylinder), KAIROS_OK);
        const double depth = std::min(h.z + half, std::min(h.x, h.y) + radius);
        SCOPED_TRACE(testing::Message() << "seed " << seed << " case " << i << " box " << h.x << " " << h.y << " "
                                        << h.z << " cylinder " << radius << " " << half);
        for (int order = 0; order < 2; ++order) {
            const kairos_shape* a = order ? cylinder : box;
            const kairos_shape* b = order ? box : cylinder;
            int32_t hit = 0;
            kairos_distance_result d{}, sd{};
            ASSERT_EQ(kairos_intersect(a, &pose, b, &pose, nullptr, &hit), KAIROS_OK);
            ASSERT_EQ(kairos_distance(a, &pose, b, &pose, nullptr, &d), KAIROS_OK);
            ASSERT_EQ(kairos_signed_distance(a, &pose, b, &pose, nullptr, &sd), KAIROS_OK);
            ++cases;
            const double depth_error = std::fabs(-sd.distance - depth) / depth;
            worst_depth = std::max(worst_depth, depth_error);
            const bool ok = hit == 1 && d.intersecting == 1 && d.distance == 0 && depth_error <= 1e-6;
            if (!ok && ++wrong <= 5)
                ADD_FAILURE() << "order " << order << ": intersect " << hit << ", distance " << d.distance
                              << " (termination " << d.termination << "), signed distance " << sd.distance
                              << " (depth " << depth << ", termination " << sd.termination << ")";
        }
        kairos_shape_release(box);
        kairos_shape_release(cylinder);
    }
    std::printf("needle boxes through flat cylinders: %d queries, %d wrong, worst depth error %.3g of the depth\n",
                cases, wrong, worst_depth);
    EXPECT_EQ(wrong, 0);
}

// Ray casts onto capsules and rounded boxes (a box plus a sphere) at every tolerance: the normal is
// the exact one at the ray point (from the core's nearest point, in closed form here), so its
// support plane never has the ray point past it. At tolerance 1e-3 GJK's v tilted 0.009 rad along
// a capsule's straight side, and that plane cut the ray point by 0.018 (found by fuzz_queries).
// Truth: the segment's or box's nearest point to the ray point, and the shape's support along the
// normal, both in closed form.
TEST(GjkEdges, RayOntoRoundedCoresGetsTheExactNormalAtEveryTolerance) {
    const uint64_t seed = 202611282;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit01(0, 1);
    std::normal_distribution<double> gauss;
    const double tolerances[] = {0.5, 1e-1, 1e-2, 1e-3, 1e-6, 1e-10};
    int hits = 0, wrong = 0;
    double worst_angle = 0, worst_plane = 0;
    for (int i = 0; i < 600; ++i) {
        const bool capsule = i % 2 == 0;
        const double radius = 0.2 + 1.3 * unit01(rng);
        const V h = capsule ? V{0, 0, 0.2 + 1.3 * unit01(rng)}
                            : V{0.2 + unit01(rng), 0.2 + unit01(rng), 0.2 + unit01(rng)};
        kairos_shape* shape = nullptr;
        if (capsule) {
            ASSERT_EQ(kairos_shape_capsule(radius, h.z, &shape), KAIROS_OK);
        } else {
            kairos_shape *box = nullptr, *sphere = nullptr;
            ASSERT_EQ(kairos_shape_box(kv(h), &box), KAIROS_OK);
            ASSERT_EQ(kairos_shape_sphere(radius, &sphere), KAIROS_OK);
            ASSERT_EQ(kairos_shape_minkowski_sum(box, sphere, &shape), KAIROS_OK);
            kairos_shape_release(box);
            kairos_shape_release(sphere);
        }
        const Rot turn = make_rot({gauss(rng), gauss(rng), gauss(rng)}, 6.283185307179586 * unit01(rng));
        const kairos_pose pose{{gauss(rng), gauss(rng), gauss(rng)}, {turn.q[0], turn.q[1], turn.q[2], turn.q[3]}};
        const V centre = fromk(pose.position);
        // From 3 .. 6 away, aimed at a point within the shape's reach (most hit, some graze or miss).
        const V origin = centre + (3 + 3 * unit01(rng)) * unit({gauss(rng), gauss(rng), gauss(rng)});
        const V aim = centre + (0.5 * (radius + norm(h))) * V{gauss(rng), gauss(rng), gauss(rng)};
        const V translation = 1.5 * (aim - origin);
        kairos_query_settings settings;
        kairos_query_settings_init(&settings);
        settings.tolerance = tolerances[i % 6];
        kairos_cast_result r;
        ASSERT_EQ(kairos_ray_cast(shape, &pose, kv(origin), kv(translation), &settings, &r), KAIROS_OK);
        kairos_shape_release(shape);
        if (!r.hit || !(r.toi > 0)) continue;
        ++hits;
        // The ray point at toi in the shape's frame, the core's nearest point, the exact normal.
        const V x = apply_t(turn, origin + r.toi * translation - centre);
        const V q{std::clamp(x.x, -h.x, h.x), std::clamp(x.y, -h.y, h.y), std::clamp(x.z, -h.z, h.z)};
        const V exact = unit(x - q);
        const V n = apply_t(turn, fromk(r.normal));
        const V c{n.y * exact.z - n.z * exact.y, n.z * exact.x - n.x * exact.z, n.x * exact.y - n.y * exact.x};
        const double angle = std::asin(std::min(1.0, norm(c)));
        // The support plane of the reported normal: h . |n| + radius, against the ray point.
        const double support = h.x * std::fabs(n.x) + h.y * std::fabs(n.y) + h.z * std::fabs(n.z) + radius * norm(n);
        const double past = support - dot(n, x);
        worst_angle = std::max(worst_angle, angle), worst_plane = std::max(worst_plane, past);
        if (!(dot(n, exact) > 0 && angle <= 1e-9 && past <= 1e-12) && ++wrong <= 5)
            ADD_FAILURE() << "seed " << seed << " case " << i << " (" << (capsule ? "capsule" : "rounded box")
                          << ", tolerance " << settings.tolerance << "): normal " << angle
                          << " rad off the exact one, the ray point " << past << " past its plane (toi " << r.toi
                          << ", termination " << r.termination << ")";
    }
    std::printf("rays onto capsules and rounded boxes: %d hits, %d wrong, worst normal %.3g rad, worst plane %.3g\n",
                hits, wrong, worst_angle, worst_plane);
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(hits, 300);
}

// A ball whose centre lies a small gap from a flat ellipse (a sphere mapped by a singular-looking
// diagonal, 1e-19 thick), the centre over the ellipse: the signed distance is the gap less the
// ball's radius, in both orders. The cores' GJK axis came out 3e-7 off the ellipse's normal, and
// along it the ellipse (50 wide) showed a gap 13 % short, which was taken as the depth in one
// order (found by fuzz_queries). Truth: the gap is the centre's height over the ellipse's plane.
TEST(GjkEdges, BallOverAFlatEllipseGivesTheGapLessTheRadius) {
    const uint64_t seed = 1127;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit01(0, 1);
    kairos_shape *ball = nullptr, *sphere = nullptr;
    ASSERT_EQ(kairos_shape_sphere(1, &ball), KAIROS_OK);
    ASSERT_EQ(kairos_shape_sphere(2.7294117647058824, &sphere), KAIROS_OK);
    const double linear[9] = {1, 0, 0, 0, -1.2148470283054856e-19, 0, 0, 0, 18.423590447852295};
    kairos_shape* ellipse = nullptr;
    ASSERT_EQ(kairos_shape_transformed(sphere, linear, {0, 0, 0}, &ellipse), KAIROS_OK);
    kairos_shape* point = nullptr;
    ASSERT_EQ(kairos_shape_point(&point), KAIROS_OK);
    // The ellipse's support from its definition (linear map L of a sphere of radius R: the point
    // R L (L^T d) / |L^T d|), world frame (the ellipse is not rotated).
    auto ellipse_support = [&](const kairos_pose& ep, V d) {
        const V ltd{linear[0] * d.x, linear[4] * d.y, linear[8] * d.z};
        const V p = (2.7294117647058824 / norm(ltd)) * V{linear[0] * ltd.x, linear[4] * ltd.y, linear[8] * ltd.z};
        return fromk(ep.position) + p;
    };
    int cases = 0, tilted = 0;
    double worst = 0;
    for (int i = 0; i < 300; ++i) {
        // The finding first; then gaps 1e-7 .. 1e-1 and centres anywhere over the ellipse's middle,
        // every other one on its middle line (w = 0, as the finding's), where GJK's axis tilts
        // along the ellipse's length.
        const double gap = std::pow(10.0, -7 + 6 * unit01(rng));
        const double u = 2.7 * (2 * unit01(rng) - 1) * 0.7;
        const double w = i % 2 ? 0.0 : 50 * (2 * unit01(rng) - 1) * 0.7;
        const kairos_pose ep{{-3.7187457084000917, -3.9998779278248264, -4}, {0, 0, 0, 1}};
        kairos_pose bp{{ep.position.x - u, ep.position.y - gap, ep.position.z + w},
                       {0.40052095632268653, 0.52868507839187229, 0.52918571949370496, 0.52918571949370496}};
        if (i == 0) bp.position = {-4, -4, -4};  // the finding's own pose
        // The centre's height over the plane as placed (exact up to the placement's rounding).
        const double truth = (ep.position.y - bp.position.y) - 1;
        SCOPED_TRACE(testing::Message() << "seed " << seed << " case " << i << " gap " << gap);
        // The branch: GJK's v between the ball's centre and the ellipse (the direction between
        // its witness points) shows less than the whole gap (the separation along it falls short
        // by more than this test's bound). The distance's reported axis is the proven one, which
        // never does (it was v's direction before, short in the same cases).
        kairos_distance_result c{};
        ASSERT_EQ(kairos_distance(point, &bp, ellipse, &ep, nullptr, &c), KAIROS_OK);
        auto along = [&](V axis) { return dot(axis, ellipse_support(ep, -axis) - fromk(bp.position)); };
        tilted += along(unit(fromk(c.point_b) - fromk(c.point_a))) < (truth + 1) - 1e-9 * 60;
        EXPECT_GE(along(fromk(c.axis)), (truth + 1) - 1e-9 * 60) << "the reported axis";
        for (int order = 0; order < 2; ++order) {
            kairos_distance_result r{};
            ASSERT_EQ(order == 0 ? kairos_signed_distance(ball, &bp, ellipse, &ep, nullptr, &r)
                                 : kairos_signed_distance(ellipse, &ep, ball, &bp, nullptr, &r),
                      KAIROS_OK);
            worst = std::max(worst, std::fabs(r.distance - truth));
            EXPECT_NEAR(r.distance, truth, 1e-9 * 60) << "order " << order << " termination " << r.termination;
            EXPECT_NEAR(std::fabs(r.axis.y), 1, 1e-9) << "order " << order;
            ++cases;
        }
    }
    // The middle-line cases reach it (47 of 300 with this seed; the direction between the witness
    // points, rounded by eps of their distance from the origin over the gap, adds some at 1e-7).
    EXPECT_GE(tilted, 6) << "seed " << seed;
    EXPECT_LE(tilted, 100) << "seed " << seed;
    std::printf("ball over a flat ellipse: %d signed distances, worst error %.3g; GJK's axis short of the gap in %d "
                "of 300\n",
                cases, worst, tilted);
    kairos_shape_release(point);
    kairos_shape_release(ellipse);
    kairos_shape_release(sphere);
    kairos_shape_release(ball);
}

// A needle hull 1e9 .. 1e15 long whose other vertices lie within 1e-307 .. 1e-300 of its origin,
// and a unit ball centred there, offset by 1e-320 .. 1e-300. When the first support points are a
// near vertex and the ball's centre, GJK took its working scale from them (up to 2^1000) and the
// far vertex, met next, became infinite. The signed distance then failed ("no finite result") in
// one order, and a world reported a contact at (inf, nan, nan) (fuzz_world). The truth: the needle
// passes through the ball's centre, so the depth is the radius, 1 (to the needle's thickness), and
// the distance 0.
TEST(GjkEdges, ANearVertexMetFirstDoesNotScaleTheFarOneToInfinity) {
    const uint64_t seed = 1128;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit01(0, 1);
    std::normal_distribution<double> normal(0, 1);
    auto random_unit = [&] {
        V d{};
        do d = {normal(rng), normal(rng), normal(rng)};
        while (!(norm(d) > 1e-3));
        return unit(d);
    };
    kairos_shape* ball = nullptr;
    ASSERT_EQ(kairos_shape_sphere(1, &ball), KAIROS_OK);
    const kairos_pose origin{{0, 0, 0}, {0, 0, 0, 1}};
    auto finite = [](kairos_vec3 p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); };
    int cases = 0, away = 0;
    for (int i = 0; i < 200; ++i) {
        std::vector<kairos_vec3> points;
        V u{1, 0, 0}, off{0x1p-1022, 0, 0};
        if (i == 0) {  // the finding: 13 points, the ball at the smallest normal double along +x
            points = {{0x1.c6bf52634p+49, 0x1.14b00c28e01aep-997, 0x1.957e438a83b47p-1012},
                      {0x1.35ad3e0257aaep-998, -0x1.fe674547bc966p-998, -0x1.7600a676bbcdcp-1012},
                      {0x1.1fda542948b7ep-997, 0x1.c459465996efp-998, 0x1.4b73d41dd4e7ap-1012},
                      {0x1.8b1b80be22035p-998, -0x1.6ae51547e70edp-998, -0x1.09eb0e0fdb075p-1012},
                      {0x1.67b9c897101dep-998, 0x1.644f4fc6a18dp-999, 0x1.05142669ef156p-1013},
                      {0x1.b7d1379132ce3p-1000, -0x1.d6653d91247c9p-1001, -0x1.58b1228561d82p-1015},
                      {0x1.16674621853cdp-997, 0x1.0ce14eabec148p-997, 0x1.8a0f450219db2p-1012},
                      {0x1.8a8ca6e531c29p-1000, -0x1.d9b3b8d44454bp-998, -0x1.5b1e4b4887b31p-1012},
                      {0x1.34e24c73baa39p-998, 0x1.f7b568fef9b4cp-999, 0x1.7119646adac6bp-1013},
                      {0x1.8329f17b4b41cp-998, 0x1.52e0c517e7275p-997, 0x1.f0a4f9840d7a7p-1012},
                      {0x1.43393c438bcdp-998, -0x1.e346d0ec529bbp-998, -0x1.62218b184eb4cp-1012},
                      {0x1.7293ab482b3f8p-998, -0x1.45c94c573275dp-999, -0x1.dd7d5f090c277p-1014},
                      {-0x1.1805730fd9dbbp-1002, 0x1.02afa2b09a2ep-999, 0x1.7b266ad508b7dp-1014}};
        } else {
            u = random_unit();
            const double length = std::pow(10.0, 9 + 6 * unit01(rng));
            const double near = std::pow(10.0, -307 + 7 * unit01(rng));
            points.push_back(kv(length * u));
            const int n = 3 + static_cast<int>(unit01(rng) * 10);
            for (int k = 0; k < n; ++k) {  // behind the origin: the enclosing simplex needs the far vertex
                const V d = random_unit();
                points.push_back(kv((near * (0.1 + unit01(rng))) * (dot(d, u) < 0 ? d : -d)));
            }
            off = std::pow(10.0, -320 + 20 * unit01(rng)) * random_unit();
        }
        away += dot(off, u) < 0;
        SCOPED_TRACE(testing::Message() << "seed " << seed << " case " << i);
        kairos_shape* needle = nullptr;
        ASSERT_EQ(kairos_shape_convex_hull(points.data(), points.size(), &needle), KAIROS_OK);
        const kairos_pose bp{kv(off), {0, 0, 0, 1}};
        for (int order = 0; order < 2; ++order) {
            const kairos_shape* a = order == 0 ? needle : ball;
            const kairos_shape* b = order == 0 ? ball : needle;
            const kairos_pose& pa = order == 0 ? origin : bp;
            const kairos_pose& pb = order == 0 ? bp : origin;
            kairos_distance_result r{};
            ASSERT_EQ(kairos_signed_distance(a, &pa, b, &pb, nullptr, &r), KAIROS_OK)
                << "order " << order << ": " << kairos_last_error();
            EXPECT_NEAR(r.distance, -1, 1e-12) << "order " << order;
            EXPECT_NEAR(norm(fromk(r.axis)), 1, 1e-12) << "order " << order;
            ASSERT_TRUE(finite(r.point_a) && finite(r.point_b)) << "order " << order;
            EXPECT_LE(norm(fromk(r.point_b) - fromk(r.point_a) - r.distance * fromk(r.axis)), 1e-12) << "order " << order;
            kairos_distance_result d{};
            ASSERT_EQ(kairos_distance(a, &pa, b, &pb, nullptr, &d), KAIROS_OK) << "order " << order;
            EXPECT_EQ(d.distance, 0) << "order " << order;
            EXPECT_TRUE(finite(d.point_a) && finite(d.point_b) && finite(d.axis)) << "order " << order;
            kairos_cast_result c{};
            ASSERT_EQ(kairos_shape_cast(a, &pa, {0, 0, 0}, b, &pb, kv(-1 * u), nullptr, &c), KAIROS_OK)
                << "order " << order << ": " << kairos_last_error();
            EXPECT_EQ(c.hit, 1) << "order " << order;
            EXPECT_EQ(c.toi, 0) << "order " << order;
            EXPECT_TRUE(finite(c.point) && finite(c.normal)) << "order " << order;
            int32_t hit = -1;
            kairos_vec3 cache{0, 0, 0};
            ASSERT_EQ(kairos_intersect(a, &pa, b, &pb, &cache, &hit), KAIROS_OK) << "order " << order;
            EXPECT_EQ(hit, 1) << "order " << order;
            ++cases;
        }
        // The world's contact of the pair overlapping at the start of a step.
        kairos_world* w = nullptr;
        ASSERT_EQ(kairos_world_create(nullptr, &w), KAIROS_OK);
        kairos_object_id ids[2];
        ASSERT_EQ(kairos_world_add(w, needle, &origin, 1, &ids[0]), KAIROS_OK);
        ASSERT_EQ(kairos_world_add(w, ball, &bp, 2, &ids[1]), KAIROS_OK);
        ASSERT_EQ(kairos_world_step(w), KAIROS_OK);
        const kairos_contact* contacts = nullptr;
        size_t count = 0;
        ASSERT_EQ(kairos_world_contacts(w, &contacts, &count), KAIROS_OK);
        ASSERT_EQ(count, 1u);
        EXPECT_EQ(contacts[0].toi, 0);
        EXPECT_TRUE(finite(contacts[0].point) && finite(contacts[0].normal));
        EXPECT_NEAR(norm(fromk(contacts[0].normal)), 1, 1e-12);
        kairos_world_destroy(w);
        kairos_shape_release(needle);
    }
    // About half the offsets point away from the needle, where the near vertex comes first.
    EXPECT_GE(away, 60) << "seed " << seed;
    EXPECT_LE(away, 140) << "seed " << seed;
    std::printf("needle with a near vertex met first: %d query pairs, %d of 200 offsets away from the needle\n", cases,
                away);
    kairos_shape_release(ball);
}
