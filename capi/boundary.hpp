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
Vec3 read_point(const kairos_vec3& v, const char* function, const char* name);
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
BodyPose read_pose(const kairos_pose* pose, const char* function, const char* name);

// Query settings (frozen struct: struct_size must equal its size). NULL means defaults.
struct QuerySettings {
    double tolerance;
    uint32_t max_iterations;
};
QuerySettings read_query_settings(const kairos_query_settings* s, const char* function, const char* name);

// Growing input struct: struct_size >= `known` (the first published size); bytes past `known`
// up to struct_size must be zero (a newer caller's fields this library does not know).
void require_struct_size(const void* s, uint32_t struct_size, size_t known, const char* function, const char* name);

inline const Shape& shape_of(const kairos_shape* s) { return *reinterpret_cast<const Shape*>(s); }
inline kairos_shape* handle_of(const Shape* s) { return reinterpret_cast<kairos_shape*>(const_cast<Shape*>(s)); }

inline kairos_vec3 to_c(Vec3 v) { return {v.x, v.y, v.z}; }

}  // namespace kairos::capi
