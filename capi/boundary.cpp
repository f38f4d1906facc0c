// SPDX-License-Identifier: MIT
// The C boundary's error buffer and input validation (see boundary.hpp).
#include "boundary.hpp"

namespace kairos::capi {
namespace {

// A fixed buffer per thread: trivially destructible, so no TLS destructor keeps the library
// from unloading at dlclose, and recording an error never allocates.
thread_local char t_last_error[512] = "";

void write_error(const char* function, const char* format, va_list args) {
    int n = std::snprintf(t_last_error, sizeof t_last_error, "%s: ", function);
    if (n < 0 || static_cast<size_t>(n) >= sizeof t_last_error) return;
    std::vsnprintf(t_last_error + n, sizeof t_last_error - static_cast<size_t>(n), format, args);
}

}  // namespace

const char* last_error_message() { return t_last_error; }

void fail(int32_t status, const char* function, const char* format, ...) {
    va_list args;
    va_start(args, format);
    write_error(function, format, args);
    va_end(args);
    throw Failure{status};
}

void record_error(const char* function, const char* format, ...) {
    va_list args;
    va_start(args, format);
    write_error(function, format, args);
    va_end(args);
}

Vec3 read_vec3(const kairos_vec3& v, const char* function, const char* name) {
    const double c[3] = {v.x, v.y, v.z};
    static const char* const axis[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(c[i]))
            fail(KAIROS_ERROR_INVALID_ARGUMENT, function, "%s.%s must be finite (got %g)", name, axis[i], c[i]);
    return {v.x, v.y, v.z};
}

Vec3 read_point_checked(const kairos_vec3& v, const char* function, const char* name) {
    const Vec3 p = read_vec3(v, function, name);
    const double c[3] = {p.x, p.y, p.z};
    static const char* const axis[3] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i)
        if (std::fabs(c[i]) > KAIROS_MAX_MAGNITUDE)
            fail(KAIROS_ERROR_INVALID_ARGUMENT, function, "%s.%s is %g, beyond KAIROS_MAX_MAGNITUDE (%g)", name,
                 axis[i], c[i], KAIROS_MAX_MAGNITUDE);
    return p;
}

void require_extent(const Shape* s, const char* function, const char* what) {
    Vec3 lo, hi;
    bounds(*s, make_transform({}, Quat{0, 0, 0, 1}), lo, hi);
    const double extent = std::fmax(max_abs(lo), max_abs(hi));
    if (!(extent <= KAIROS_MAX_MAGNITUDE)) {  // negated: NaN fails too
        s->release();
        fail(KAIROS_ERROR_INVALID_ARGUMENT, function, "%s reaches %g from its origin, beyond KAIROS_MAX_MAGNITUDE (%g)",
             what, extent, KAIROS_MAX_MAGNITUDE);
    }
}

void require_finite_result(bool finite, const char* function) {
    if (!finite)
        fail(KAIROS_ERROR_INVALID_ARGUMENT, function,
             "the inputs together exceed the range double precision resolves (shape sizes and positions near "
             "KAIROS_MAX_MAGNITUDE): no finite result");
}

BodyPose read_pose_checked(const kairos_pose* pose, const char* function, const char* name) {
    if (pose == nullptr) return {};
    const kairos_vec3& p = pose->position;
    auto ok = [](double x) { return std::isfinite(x) && std::fabs(x) <= KAIROS_MAX_MAGNITUDE; };
    if (!(ok(p.x) && ok(p.y) && ok(p.z))) {
        // The field's name is formatted only on this path: formatted on every call it cost more
        // than the rest of the boundary of a kairos_distance together.
        char field[96];
        std::snprintf(field, sizeof field, "%s.position", name);
        read_point(p, function, field);  // fails, naming the coordinate
    }
    const Vec3 position{p.x, p.y, p.z};
    const kairos_quat& q = pose->orientation;
    const double c[4] = {q.x, q.y, q.z, q.w};
    static const char* const part[4] = {"x", "y", "z", "w"};
    for (int i = 0; i < 4; ++i)
        if (!std::isfinite(c[i]))
            fail(KAIROS_ERROR_INVALID_ARGUMENT, function, "%s.orientation.%s must be finite (got %g)", name, part[i],
                 c[i]);
    const Quat quat{q.x, q.y, q.z, q.w};
    const double n = norm(quat);
    // NaN-safe: the negated comparison also rejects a NaN length.
    if (!(std::fabs(n - 1.0) <= KAIROS_QUAT_TOLERANCE))
        fail(KAIROS_ERROR_INVALID_ARGUMENT, function,
             "%s.orientation must be a unit quaternion within %g (its length is %.17g)", name, KAIROS_QUAT_TOLERANCE,
             n);
    return {position, unit_quat(q, q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w)};
}

void check_pose_element_slow(const kairos_pose& pose, size_t i, const char* function, const char* name) {
    char element[96];
    std::snprintf(element, sizeof element, "%s[%zu]", name, i);
    read_pose_checked(&pose, function, element);
}

QuerySettings read_query_settings_checked(const kairos_query_settings* s, const char* function, const char* name) {
    if (s == nullptr) return kDefaultQuerySettings;
    if (s->struct_size != sizeof(kairos_query_settings))
        fail(KAIROS_ERROR_STRUCT_SIZE, function,
             "%s->struct_size must be %zu (got %u); call kairos_query_settings_init", name,
             sizeof(kairos_query_settings), s->struct_size);
    if (!(s->tolerance > 0 && s->tolerance < 1))  // negated: NaN fails too
        fail(KAIROS_ERROR_INVALID_ARGUMENT, function, "%s->tolerance must be in (0, 1) (got %g)", name, s->tolerance);
    if (s->max_iterations < 1)
        fail(KAIROS_ERROR_INVALID_ARGUMENT, function, "%s->max_iterations must be >= 1 (got %u)", name,
             s->max_iterations);
    return {s->tolerance, s->max_iterations};
}

void require_struct_size(const void* s, uint32_t struct_size, size_t known, const char* function, const char* name) {
    if (struct_size < known)
        fail(KAIROS_ERROR_STRUCT_SIZE, function,
             "%s->struct_size is %u, smaller than the %zu bytes of this struct; call its _init function", name,
             struct_size, known);
    const auto* bytes = static_cast<const unsigned char*>(s);
    for (size_t i = known; i < struct_size; ++i)
        if (bytes[i] != 0)
            fail(KAIROS_ERROR_STRUCT_SIZE, function,
                 "%s->struct_size is %u but byte %zu is non-zero: this library knows only the first %zu bytes", name,
                 struct_size, i, known);
}

}  // namespace kairos::capi
