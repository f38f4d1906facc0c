// SPDX-License-Identifier: MIT
// The support-function model of the fuzz targets' shapes, and the checks of built shapes against it
// (see fuzz_support.hpp).
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "fuzz_support.hpp"

namespace kfuzz {

// ---- Vectors and the model ---------------------------------------------------------------------

Vr to_real(const kairos_vec3& v) { return {v.x, v.y, v.z}; }
real dot(const Vr& a, const Vr& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
real norm(const Vr& a) { return std::sqrt(dot(a, a)); }
Vr operator+(const Vr& a, const Vr& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vr operator-(const Vr& a, const Vr& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vr operator*(real s, const Vr& a) { return {s * a.x, s * a.y, s * a.z}; }
real ulp(real x) { return std::fabs(x) * 0x1p-52L; }
real biggest(const kairos_vec3& v) { return max3(std::fabs(real(v.x)), std::fabs(real(v.y)), std::fabs(real(v.z))); }

real support_value(const Model& m, const Vr& d) {
    switch (m.kind) {
        case Kind::Point:
            return 0;
        case Kind::Segment:
            return m.a * std::fabs(d.z);
        case Kind::Sphere:
            return m.a * norm(d);
        case Kind::Box:
            return m.a * std::fabs(d.x) + m.b * std::fabs(d.y) + m.c * std::fabs(d.z);
        case Kind::Capsule:
            return m.b * std::fabs(d.z) + m.a * norm(d);
        case Kind::Cylinder:
            return m.a * std::sqrt(d.x * d.x + d.y * d.y) + m.b * std::fabs(d.z);
        case Kind::Cone:
            return std::fmax(m.b * d.z, m.a * std::sqrt(d.x * d.x + d.y * d.y) - m.b * d.z);
        case Kind::Points: {
            real best = -std::numeric_limits<real>::infinity();
            for (const Vr& p : m.points) best = std::fmax(best, dot(d, p));
            return best;
        }
        case Kind::MinkowskiSum:
            return support_value(*m.left, d) + support_value(*m.right, d);
        case Kind::HullOfTwo:
            return std::fmax(support_value(*m.left, d), support_value(*m.right, d));
        case Kind::Transformed: {
            const real* l = m.linear;
            const Vr dt{l[0] * d.x + l[3] * d.y + l[6] * d.z, l[1] * d.x + l[4] * d.y + l[7] * d.z,
                        l[2] * d.x + l[5] * d.y + l[8] * d.z};
            return support_value(*m.left, dt) + dot(d, m.translation);
        }
    }
    return 0;
}

Placed place(const Model& m, const kairos_quat& q, const Vr& position) {
    Placed p;
    p.model = &m;
    p.position = position;
    real x = q.x, y = q.y, z = q.z, w = q.w;
    const real n = std::sqrt(x * x + y * y + z * z + w * w);
    if (n > 0 && std::isfinite(n)) {
        x /= n;
        y /= n;
        z /= n;
        w /= n;
    } else {
        x = y = z = 0;
        w = 1;
    }
    real* r = p.rotation;
    r[0] = 1 - 2 * (y * y + z * z);
    r[1] = 2 * (x * y - w * z);
    r[2] = 2 * (x * z + w * y);
    r[3] = 2 * (x * y + w * z);
    r[4] = 1 - 2 * (x * x + z * z);
    r[5] = 2 * (y * z - w * x);
    r[6] = 2 * (x * z - w * y);
    r[7] = 2 * (y * z + w * x);
    r[8] = 1 - 2 * (x * x + y * y);
    return p;
}

Placed place(const Model& m, const kairos_pose& pose) { return place(m, pose.orientation, to_real(pose.position)); }

real support_value(const Placed& p, const Vr& d) {
    const real* r = p.rotation;
    const Vr local{r[0] * d.x + r[3] * d.y + r[6] * d.z, r[1] * d.x + r[4] * d.y + r[7] * d.z,
                   r[2] * d.x + r[5] * d.y + r[8] * d.z};
    return support_value(*p.model, local) + dot(d, p.position);
}

real gap(const Placed& a, const Placed& b, const Vr& u) { return -support_value(b, -1 * u) - support_value(a, u); }

real own_aspect(const Model& m) {
    return aspect_of([&](const Vr& d) { return support_value(m, d) + support_value(m, -1 * d); });
}

const std::vector<Vr>& unit_directions() {
    static const std::vector<Vr> dirs = [] {
        std::vector<Vr> v;
        for (int x = -1; x <= 1; ++x)
            for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z) {
                    if (x == 0 && y == 0 && z == 0) continue;
                    const Vr d{real(x), real(y), real(z)};
                    v.push_back((1 / norm(d)) * d);
                }
        return v;
    }();
    return dirs;
}

// The pose of a motion at time t (docs/c-api.md: linear position; constant angular velocity about a
// fixed axis along the shortest arc), in long double.
void motion_at(const kairos_motion& m, real t, kairos_quat& q_out, Vr& p_out) {
    const Vr p0 = to_real(m.start.position), p1 = to_real(m.end.position);
    p_out = p0 + t * (p1 - p0);
    const kairos_quat &a = m.start.orientation, &b = m.end.orientation;
    auto unitq = [](const kairos_quat& q, real out[4]) {
        const real n = std::sqrt(real(q.x) * q.x + real(q.y) * q.y + real(q.z) * q.z + real(q.w) * q.w);
        out[0] = q.x / n;
        out[1] = q.y / n;
        out[2] = q.z / n;
        out[3] = q.w / n;
    };
    real qa[4], qb[4];
    unitq(a, qa);
    unitq(b, qb);
    q_out = a;
    const bool same = (a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w) ||
                      (a.x == -b.x && a.y == -b.y && a.z == -b.z && a.w == -b.w);
    if (same || t <= 0) return;
    // rel = qb * conj(qa)
    const real cx = -qa[0], cy = -qa[1], cz = -qa[2], cw = qa[3];
    real rx = qb[3] * cx + qb[0] * cw + qb[1] * cz - qb[2] * cy;
    real ry = qb[3] * cy - qb[0] * cz + qb[1] * cw + qb[2] * cx;
    real rz = qb[3] * cz + qb[0] * cy - qb[1] * cx + qb[2] * cw;
    real rw = qb[3] * cw - qb[0] * cx - qb[1] * cy - qb[2] * cz;
    if (rw < 0) {
        rx = -rx;
        ry = -ry;
        rz = -rz;
        rw = -rw;
    }
    const real s = std::sqrt(rx * rx + ry * ry + rz * rz);
    if (!(s > 0)) return;
    const real angle = 2 * std::atan2(s, rw) * t;
    const real k = std::sin(angle / 2) / s;
    const real tx = rx * k, ty = ry * k, tz = rz * k, tw = std::cos(angle / 2);
    // turn * qa
    q_out = {static_cast<double>(tw * qa[0] + tx * qa[3] + ty * qa[2] - tz * qa[1]),
             static_cast<double>(tw * qa[1] - tx * qa[2] + ty * qa[3] + tz * qa[0]),
             static_cast<double>(tw * qa[2] + tx * qa[1] - ty * qa[0] + tz * qa[3]),
             static_cast<double>(tw * qa[3] - tx * qa[0] - ty * qa[1] - tz * qa[2])};
}

real first_within(const Vr& p0, const Vr& dv, real reach) {
    if (!(reach > 0)) return -1;
    if (norm(p0) <= reach) return 0;
    const real vv = dot(dv, dv);
    if (!(vv > 0)) return -1;
    // The closest approach on the whole line (not clamped to the step: the chord below is measured
    // from the foot of the perpendicular).
    const real closest = -dot(p0, dv) / vv;
    if (!(closest > 0)) return -1;
    const real miss = norm(p0 + closest * dv);
    if (!(miss <= reach)) return -1;
    const real enter = closest - std::sqrt(reach * reach - miss * miss) / std::sqrt(vv);
    return enter <= 1 ? std::fmax(real(0), enter) : -1;
}

real inner_radius(const Model& m) {
    switch (m.kind) {
        case Kind::Point:
        case Kind::Segment:
            return 0;  // the origin itself lies in the shape
        case Kind::Points:
            return -1;
        case Kind::Sphere:
        case Kind::Capsule:
            return m.a;
        case Kind::Box:
            return std::fmin(m.a, std::fmin(m.b, m.c));
        case Kind::Cylinder:
            return std::fmin(m.a, m.b);
        case Kind::Cone:
            // The lateral surface passes m.a * m.b / sqrt(m.a^2 + 4 m.b^2) from the axis midpoint.
            return std::fmin(m.b, m.a * m.b / std::sqrt(m.a * m.a + 4 * m.b * m.b));
        case Kind::MinkowskiSum: {
            const real a = inner_radius(*m.left), b = inner_radius(*m.right);
            return a < 0 || b < 0 ? -1 : a + b;
        }
        case Kind::HullOfTwo:
            return std::fmax(inner_radius(*m.left), inner_radius(*m.right));
        case Kind::Transformed: {
            // The smallest singular value is at least |det| / |L|_F^2; the ball it maps lies
            // about the translation, so the origin keeps what |t| does not take.
            const real c = inner_radius(*m.left);
            if (c < 0) return -1;
            const real* l = m.linear;
            const real det = l[0] * (l[4] * l[8] - l[5] * l[7]) - l[1] * (l[3] * l[8] - l[5] * l[6]) +
                             l[2] * (l[3] * l[7] - l[4] * l[6]);
            real f = 0;
            for (int i = 0; i < 9; ++i) f += l[i] * l[i];
            const real t = norm(m.translation);
            if (t == 0) return f > 0 ? std::fabs(det) / f * c : -1;
            const real r = std::fabs(det) / f * c - t;
            return r > 0 ? r : -1;
        }
    }
    return -1;
}

std::string describe(const Model& m) {
    char buf[160];
    switch (m.kind) {
        case Kind::Point:
            return "point";
        case Kind::Segment:
            std::snprintf(buf, sizeof buf, "segment(%.17Lg)", m.a);
            return buf;
        case Kind::Sphere:
            std::snprintf(buf, sizeof buf, "sphere(%.17Lg)", m.a);
            return buf;
        case Kind::Box:
            std::snprintf(buf, sizeof buf, "box(%.17Lg, %.17Lg, %.17Lg)", m.a, m.b, m.c);
            return buf;
        case Kind::Capsule:
            std::snprintf(buf, sizeof buf, "capsule(r %.17Lg, h %.17Lg)", m.a, m.b);
            return buf;
        case Kind::Cylinder:
            std::snprintf(buf, sizeof buf, "cylinder(r %.17Lg, h %.17Lg)", m.a, m.b);
            return buf;
        case Kind::Cone:
            std::snprintf(buf, sizeof buf, "cone(r %.17Lg, h %.17Lg)", m.a, m.b);
            return buf;
        case Kind::Points: {
            std::string s = "points[" + std::to_string(m.points.size()) + "]{";
            for (size_t i = 0; i < m.points.size(); ++i) {
                std::snprintf(buf, sizeof buf, "%s(%.17Lg %.17Lg %.17Lg)", i ? " " : "", m.points[i].x, m.points[i].y,
                              m.points[i].z);
                s += buf;
            }
            return s + "}";
        }
        case Kind::MinkowskiSum:
            return "minkowski_sum(" + describe(*m.left) + ", " + describe(*m.right) + ")";
        case Kind::HullOfTwo:
            return "hull(" + describe(*m.left) + ", " + describe(*m.right) + ")";
        case Kind::Transformed: {
            const real* l = m.linear;
            std::string s = "transformed([";
            for (int i = 0; i < 9; ++i) {
                std::snprintf(buf, sizeof buf, "%.17Lg%s", l[i], i == 8 ? "] + (" : i % 3 == 2 ? "; " : " ");
                s += buf;
            }
            std::snprintf(buf, sizeof buf, "%.17Lg %.17Lg %.17Lg), ", m.translation.x, m.translation.y,
                          m.translation.z);
            return s + buf + describe(*m.left) + ")";
        }
    }
    return "?";
}

const char* show(const kairos_vec3& v) {
    static char ring[8][96];
    static unsigned next = 0;
    char* s = ring[next++ % 8];
    std::snprintf(s, sizeof ring[0], "(%.17g %.17g %.17g)", v.x, v.y, v.z);
    return s;
}

const char* show(const kairos_pose& p) {
    static char ring[4][200];
    static unsigned next = 0;
    char* s = ring[next++ % 4];
    std::snprintf(s, sizeof ring[0], "{p (%.17g %.17g %.17g) q (%.17g %.17g %.17g %.17g)}", p.position.x, p.position.y,
                  p.position.z, p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w);
    return s;
}

// ---- Shape checks ------------------------------------------------------------------------------

namespace {

// Support of s along d: status per the contract, output untouched on failure, and when d is
// finite a finite point whose d.x is h(d) within the model's tolerance. Returns false when the
// call failed (rightly) or the output was non-finite and that is tolerated.
bool check_support(const kairos_shape* s, const Model& m, const kairos_vec3& d, kairos_vec3& out) {
    poison(out);
    const int32_t status = observe("kairos_shape_support", [&] { return kairos_shape_support(s, d, &out); });
    Verdict v;
    if (!finite(d))
        v.require(KAIROS_ERROR_INVALID_ARGUMENT);
    else if (!m.moderate)
        v.unsure();
    v.check(status, "kairos_shape_support");
    if (status != KAIROS_OK) {
        if (!poisoned(out)) violation("kairos_shape_support failed but wrote *out");
        return false;
    }
    if (!finite(out)) {
        if (KAIROS_FUZZ_ALLOW_NONFINITE_ON_HUGE && !m.moderate) return false;
        violation("kairos_shape_support(%s, d %s) = %s, not finite", describe(m).c_str(), show(d), show(out));
    }
    const Vr dr = to_real(d);
    const real got = dot(dr, to_real(out));
    const real want = support_value(m, dr);
    const real slack = (m.tolerance + kFloor) * norm(dr) + 8 * ulp(want);
    if (!(std::fabs(got - want) <= slack))
        violation(
            "kairos_shape_support(%s, d %s) = %s: d.x = %.17Lg but the support function is %.17Lg (diff %.3Lg, "
            "tolerance %.3Lg)",
            describe(m).c_str(), show(d), show(out), got, want, got - want, slack);
    return true;
}

void check_bounds(const kairos_shape* s, const Model& m, const PoseCase* pose) {
    kairos_vec3 lo, hi;
    poison(lo);
    poison(hi);
    const int32_t status = observe("kairos_shape_bounds", [&] {
        return kairos_shape_bounds(s, pose != nullptr ? &pose->pose : nullptr, &lo, &hi);
    });
    Verdict v;
    if (pose != nullptr) expect_pose(*pose, v);
    if (!m.moderate) v.unsure();
    v.check(status, "kairos_shape_bounds");
    if (status != KAIROS_OK) {
        if (!poisoned(lo) || !poisoned(hi)) violation("kairos_shape_bounds failed but wrote min or max");
        return;
    }
    const kairos_pose identity{{0, 0, 0}, {0, 0, 0, 1}};
    const kairos_pose& at = pose != nullptr ? pose->pose : identity;
    if (!finite(lo) || !finite(hi)) {
        if (KAIROS_FUZZ_ALLOW_NONFINITE_ON_HUGE && (!m.moderate || (pose != nullptr && !pose->moderate))) return;
        violation("kairos_shape_bounds(%s, pose %s) = [%s, %s], not finite", describe(m).c_str(), show(at), show(lo),
                  show(hi));
    }
    const Placed placed = place(m, at);
    const real lo_r[3] = {lo.x, lo.y, lo.z}, hi_r[3] = {hi.x, hi.y, hi.z};
    const real where = std::fmax(std::fabs(real(at.position.x)),
                                 std::fmax(std::fabs(real(at.position.y)), std::fabs(real(at.position.z))));
    for (int axis = 0; axis < 3; ++axis) {
        Vr e;
        (axis == 0 ? e.x : axis == 1 ? e.y : e.z) = 1;
        const real want_hi = support_value(placed, e), want_lo = -support_value(placed, -1 * e);
        const real slack = m.tolerance + kRelative * m.magnitude + 16 * ulp(where) +
                           8 * ulp(std::fmax(std::fabs(want_hi), std::fabs(want_lo))) + kFloor;
        if (!(lo_r[axis] <= hi_r[axis]) || !(std::fabs(hi_r[axis] - want_hi) <= slack) ||
            !(std::fabs(lo_r[axis] - want_lo) <= slack))
            violation("kairos_shape_bounds(%s, pose %s) = [%s, %s]; axis %d should be [%.17Lg, %.17Lg] within %.3Lg",
                      describe(m).c_str(), show(at), show(lo), show(hi), axis, want_lo, want_hi, slack);
    }
}

}  // namespace

void check_shape(const kairos_shape* s, const Model& m, Input& in, bool fuzz_directions) {
    kairos_vec3 out;
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z) {
                if (x == 0 && y == 0 && z == 0) continue;
                check_support(s, m, {double(x), double(y), double(z)}, out);
            }
    for (unsigned i = 0, n = fuzz_directions ? in.pick(3) : 0; i < n; ++i) check_support(s, m, direction(in), out);
    // A zero direction gives some point of the shape: inside every support plane.
    if (check_support(s, m, {0, 0, 0}, out)) {
        const Vr p = to_real(out);
        for (const Vr& u : unit_directions()) {
            const real h = support_value(m, u);
            if (!(dot(u, p) <= h + m.tolerance + kFloor + 8 * ulp(h)))
                violation("kairos_shape_support(%s, zero direction) = %s lies outside the shape (u.x - h(u) = %.3Lg)",
                          describe(m).c_str(), show(out), dot(u, p) - h);
        }
    }
    check_bounds(s, m, nullptr);
    const PoseCase pose = make_transform(in);
    check_bounds(s, m, &pose);
}

}  // namespace kfuzz
