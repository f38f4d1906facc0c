// SPDX-License-Identifier: MIT
// The C boundary's machinery: the per-thread error message, the guard every exported function
// runs in, and validation of caller input (pointers, numbers, poses, struct sizes).
#pragma once

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <new>

#include "kairos/kairos.h"
#include "math/math.hpp"
#include "shapes/shape.hpp"

// kairos_world_settings_init as 0.1 had it (capi/world.cpp): exported only as
// kairos_world_settings_init@KAIROS_0, and in kairos_get_api's version-1 table.
extern "C" KAIROS_API void world_settings_init_0_1(kairos_world_settings* s);

namespace kairos::capi {

// A rejected call: thrown by the checks below, caught by `guarded`. The message is already in
// the thread's error buffer when this is thrown.
struct Failure {
    int32_t status;
};

// Writes "function: message" into this thread's error buffer and throws Failure{status}.
[[noreturn]] void fail(int32_t status, const char* function, const char* format, ...)
    __attribute__((format(printf, 3, 4)));

// Records a failure without throwing (used by the guard for caught exceptions).
void record_error(const char* function, const char* format, ...) __attribute__((format(printf, 2, 3)));

// Runs `body` (which returns nothing and throws Failure on bad input); maps every exception to
// a status so no C++ exception crosses the ABI.
template <class Body>
int32_t guarded(const char* function, Body&& body) noexcept {
    try {
        body();
        return KAIROS_OK;
    } catch (const Failure& f) {
        return f.status;
    } catch (const std::bad_alloc&) {
        record_error(function, "out of memory");
        return KAIROS_ERROR_OUT_OF_MEMORY;
    } catch (const std::exception& e) {
        record_error(function, "internal error: %s", e.what());
        return KAIROS_ERROR_INTERNAL;
    } catch (...) {
        record_error(function, "internal error: unknown exception");
        return KAIROS_ERROR_INTERNAL;
    }
}

// ---- Checks: each names the argument in its message -------------------------------------------

inline void require_pointer(const void* p, const char* function, const char* name) {
    if (p == nullptr) fail(KAIROS_ERROR_NULL_ARGUMENT, function, "%s is NULL", name);
}

inline double require_finite(double v, const char* function, const char* name) {
    if (!std::isfinite(v)) fail(KAIROS_ERROR_INVALID_ARGUMENT, function, "%s must be finite (got %g)", name, v);
    return v;
}

// Finite and > 0 (or >= 0 when `allow_zero`), and at most KAIROS_MAX_MAGNITUDE.
inline double require_size(double v, const char* function, const char* name, bool allow_zero = false) {
    require_finite(v, function, name);
    if (allow_zero ? !(v >= 0) : !(v > 0))
        fail(KAIROS_ERROR_INVALID_ARGUMENT, function, "%s must be %s (got %.17g)", name, allow_zero ? ">= 0" : "> 0",
             v);
    if (v > KAIROS_MAX_MAGNITUDE)
        fail(KAIROS_ERROR_INVALID_ARGUMENT, function, "%s is %g, beyond KAIROS_MAX_MAGNITUDE (%g)", name, v,
             KAIROS_MAX_MAGNITUDE);
    return v;
}

// A vector of any finite length (a direction).
Vec3 read_vec3(const kairos_vec3& v, const char* function, const char* name);
// A position, translation or length vector: finite, each coordinate within KAIROS_MAX_MAGNITUDE.
// Inline: one test decides every valid point (NaN and infinities fail its comparisons); the
// checks that name the coordinate run only on the others.
Vec3 read_point_checked(const kairos_vec3& v, const char* function, const char* name);
inline Vec3 read_point(const kairos_vec3& v, const char* function, const char* name) {
    if (std::fabs(v.x) <= KAIROS_MAX_MAGNITUDE && std::fabs(v.y) <= KAIROS_MAX_MAGNITUDE &&
        std::fabs(v.z) <= KAIROS_MAX_MAGNITUDE)
        return {v.x, v.y, v.z};
    return read_point_checked(v, function, name);
}
// A new shape whose local extent goes beyond KAIROS_MAX_MAGNITUDE (a composite of large parts)
// is refused; `s` is released first, so the caller's reference does not leak.
void require_extent(const Shape* s, const char* function, const char* what);
// Results must be finite: the input limits make them so; this is the last guard, before any
// output is written.
void require_finite_result(bool finite, const char* function);

// A pose: finite position, finite quaternion of unit length within KAIROS_QUAT_TOLERANCE
// (normalised). NULL means identity.
struct BodyPose {
    Vec3 position;
    Quat orientation;
    Transform rigid() const { return make_transform(position, orientation); }
};
// Every check with its message; read_pose takes it only for input its fast test cannot pass.
BodyPose read_pose_checked(const kairos_pose* pose, const char* function, const char* name);
// q scaled to unit length, nn = its squared length (> 0), exactly as kairos::normalized does.
// A caller's unit quaternion often has a square root of nn that rounds to 1: q / 1 is q, so the
// four divisions (about 20 cycles of latency) are skipped, bit for bit. That happens exactly when
// nn is 1 or the next double above (sqrt(1 - 2^-53) rounds to 1 - 2^-53): tested on nn itself, the
// branch does not wait for the square root.
inline Quat unit_quat(const kairos_quat& q, double nn) {
    if (nn == 1 || nn == 1 + 0x1p-52) return {q.x, q.y, q.z, q.w};
    const double n = std::sqrt(nn);
    return {q.x / n, q.y / n, q.z / n, q.w / n};
}
// The test that decides almost every pose with a few comparisons, accepting only poses the full
// checks accept (|n - 1| <= |n^2 - 1| for a length n >= 0; NaN and infinities fail every
// comparison), so both paths give one result. nn: the quaternion's squared length.
inline bool passes_pose_test(const kairos_pose& pose, double nn) {
    const kairos_vec3& p = pose.position;
    return std::fabs(p.x) <= KAIROS_MAX_MAGNITUDE && std::fabs(p.y) <= KAIROS_MAX_MAGNITUDE &&
           std::fabs(p.z) <= KAIROS_MAX_MAGNITUDE && std::fabs(nn - 1) <= KAIROS_QUAT_TOLERANCE;
}
inline double squared_length(const kairos_quat& q) { return q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w; }
// NULL is the identity pose. Inline: passes_pose_test decides almost every call.
inline BodyPose read_pose(const kairos_pose* pose, const char* function, const char* name) {
    if (pose != nullptr) {
        const double nn = squared_length(pose->orientation);
        if (passes_pose_test(*pose, nn)) {
            const kairos_vec3& p = pose->position;
            return {{p.x, p.y, p.z}, unit_quat(pose->orientation, nn)};
        }
    }
    return read_pose_checked(pose, function, name);
}
// Checks element i of an array of poses (NULL: identity poses); a failure names it "name[i]".
void check_pose_element_slow(const kairos_pose& pose, size_t i, const char* function, const char* name);
inline void check_pose_element(const kairos_pose* poses, size_t i, const char* function, const char* name) {
    if (poses != nullptr && !passes_pose_test(poses[i], squared_length(poses[i].orientation)))
        check_pose_element_slow(poses[i], i, function, name);
}
// The same checks, for the queries that need only the rigid transform. The quaternion is
// normalised as read_pose does (four divisions, not a reciprocal: folding the normalisation into
// the matrix, or multiplying by 1/n, moves answers at the rounding limit by an ulp of the
// rotation, which GjkEdges' sweep showed can move a touching contact point by 1.5e-10 of the size).
// checked_transform: a pose already accepted (a batch checks its arrays before computing).
[[gnu::always_inline]] inline Transform checked_transform(const kairos_pose& pose, double nn) {
    const kairos_vec3& p = pose.position;
    return {to_matrix(unit_quat(pose.orientation, nn)), {p.x, p.y, p.z}};
}
[[gnu::always_inline]] inline Transform checked_transform(const kairos_pose& pose) {
    return checked_transform(pose, squared_length(pose.orientation));
}
[[gnu::always_inline]] inline Transform read_transform(const kairos_pose* pose, const char* function, const char* name) {
    if (pose == nullptr) return {};
    const double nn = squared_length(pose->orientation);
    if (!passes_pose_test(*pose, nn)) read_pose_checked(pose, function, name);  // fails with the message, or accepts it
    return checked_transform(*pose, nn);
}

// Query settings (frozen struct: struct_size must equal its size). NULL means defaults.
struct QuerySettings {
    double tolerance;
    uint32_t max_iterations;
};
// The defaults of kairos_query_settings_init.
inline constexpr QuerySettings kDefaultQuerySettings{1e-10, 256};
QuerySettings read_query_settings_checked(const kairos_query_settings* s, const char* function, const char* name);
// NULL means the defaults. Inline for the same reason as read_pose: valid settings pass one test.
inline QuerySettings read_query_settings(const kairos_query_settings* s, const char* function, const char* name) {
    if (s == nullptr) return kDefaultQuerySettings;
    if (s->struct_size == sizeof(kairos_query_settings) && s->tolerance > 0 && s->tolerance < 1 &&
        s->max_iterations >= 1)
        return {s->tolerance, s->max_iterations};
    return read_query_settings_checked(s, function, name);
}

// Growing input struct: struct_size >= `known` (the first published size); bytes past `known`
// up to struct_size must be zero (a newer caller's fields this library does not know).
void require_struct_size(const void* s, uint32_t struct_size, size_t known, const char* function, const char* name);

inline const Shape& shape_of(const kairos_shape* s) { return *reinterpret_cast<const Shape*>(s); }
inline kairos_shape* handle_of(const Shape* s) { return reinterpret_cast<kairos_shape*>(const_cast<Shape*>(s)); }

inline kairos_vec3 to_c(Vec3 v) { return {v.x, v.y, v.z}; }

}  // namespace kairos::capi
