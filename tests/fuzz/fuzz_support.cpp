// SPDX-License-Identifier: MIT
// Shared pieces of the Kairos fuzz targets (see fuzz_support.hpp).
#include "fuzz_support.hpp"

#include <cfloat>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

namespace kfuzz {

void violation(const char* format, ...) {
    std::fputs("kairos fuzz: contract violation: ", stderr);
    va_list args;
    va_start(args, format);
    std::vfprintf(stderr, format, args);
    va_end(args);
    std::fputc('\n', stderr);
    std::fflush(stderr);
    std::abort();
}

// ---- Bytes -------------------------------------------------------------------------------------

uint16_t Input::u16() {
    const uint16_t lo = u8();
    return static_cast<uint16_t>(lo | (uint16_t{u8()} << 8));
}
uint32_t Input::u32() {
    const uint32_t lo = u16();
    return lo | (uint32_t{u16()} << 16);
}
uint64_t Input::u64() {
    const uint64_t lo = u32();
    return lo | (uint64_t{u32()} << 32);
}
double Input::bits() {
    const uint64_t u = u64();
    double d;
    std::memcpy(&d, &u, sizeof d);
    return d;
}

uint64_t Rng::next() {
    uint64_t z = (s_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// ---- Numbers -----------------------------------------------------------------------------------

bool moderate(double v) {
    const double a = std::fabs(v);
    return a == 0 || (a >= kModerateMin && a <= kModerateMax);
}
bool moderate(const kairos_vec3& v) { return moderate(v.x) && moderate(v.y) && moderate(v.z); }
bool finite(const kairos_vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

double power_of_ten(Input& in) {
    const unsigned b = in.u8();
    int e;
    if (b < 128) {
        static const int small[7] = {0, 1, -1, 2, -2, 3, -3};
        e = small[b % 7];
    } else if (b < 176) {
        e = static_cast<int>(b % 41) - 20;
    } else if (b < 216) {
        e = 150 + static_cast<int>(b % 16) * 10;
    } else if (b < 248) {
        e = -150 - static_cast<int>(b % 16) * 10;
    } else {
        static const int extreme[8] = {308, -307, -315, -320, 100, -100, 200, -200};
        e = extreme[b % 8];
    }
    return std::pow(10.0, e);
}

double edge_value(Input& in) {
    static const double values[] = {
        0.0,
        -0.0,
        -1.0,
        std::numeric_limits<double>::quiet_NaN(),
        std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity(),
        4.9406564584124654e-324,
        DBL_MIN,
        DBL_MAX,
        -DBL_MAX,
        1e-300,
        1e300,
        1e-150,
        1e150,
        1e-15,
        1e15,
        DBL_EPSILON,
        1.0 + DBL_EPSILON,
        1.0 - DBL_EPSILON / 2,
        -1e-300,
    };
    const unsigned n = sizeof values / sizeof values[0];
    const unsigned k = in.pick(n + 1);
    return k < n ? values[k] : in.bits();
}

double length(Input& in) {
    if (in.u8() < 224) return (1.0 + 9.0 * in.fraction()) * power_of_ten(in);
    return edge_value(in);
}

kairos_vec3 small_vec(Input& in, double scale) {
    const double x = in.symmetric(), y = in.symmetric(), z = in.symmetric();
    return {scale * x, scale * y, scale * z};
}

kairos_vec3 position(Input& in) {
    const unsigned mode = in.u8();
    if (mode < 150) return small_vec(in, 4);
    if (mode < 200) return small_vec(in, power_of_ten(in));
    if (mode < 235) {
        // Far from the origin with a small offset, where positions keep few fractional bits.
        const double far = std::pow(10.0, 6 + static_cast<int>(in.pick(10)));
        const kairos_vec3 c = small_vec(in, 1);
        return {far + c.x, -far + c.y, far * 0.5 + c.z};
    }
    return {edge_value(in), edge_value(in), edge_value(in)};
}

kairos_vec3 direction(Input& in) {
    const unsigned mode = in.u8();
    if (mode < 200) return small_vec(in, power_of_ten(in));
    if (mode < 230) return {in.bits(), in.bits(), in.bits()};
    return {edge_value(in), edge_value(in), edge_value(in)};
}

// ---- Status contract ---------------------------------------------------------------------------

namespace {

char g_error_before[1024];

bool named_status(int32_t status) {
    return status == KAIROS_OK || (status < 0 && std::strcmp(kairos_status_name(status), "KAIROS_UNKNOWN_STATUS") != 0);
}

}  // namespace

void observe_before() { std::snprintf(g_error_before, sizeof g_error_before, "%s", kairos_last_error()); }

int32_t observe_after(const char* function, int32_t status) {
    if (!named_status(status))
        violation("%s returned %d, neither KAIROS_OK nor a named error (kairos_status_name says %s)", function, status,
                  kairos_status_name(status));
    if (status == KAIROS_ERROR_INTERNAL)
        violation("%s returned KAIROS_ERROR_INTERNAL: %s", function, kairos_last_error());
    const char* message = kairos_last_error();
    if (message == nullptr) violation("kairos_last_error() returned NULL after %s", function);
    if (status == KAIROS_OK) {
        if (std::strncmp(g_error_before, message, sizeof g_error_before - 1) != 0)
            violation("%s succeeded but changed kairos_last_error() from \"%s\" to \"%s\"", function, g_error_before,
                      message);
    } else {
        const size_t n = std::strlen(function);
        if (std::strncmp(message, function, n) != 0 || message[n] != ':')
            violation("%s failed with %s but kairos_last_error() is \"%s\" (must start with \"%s: \")", function,
                      kairos_status_name(status), message, function);
    }
    return status;
}

void Verdict::check(int32_t status, const char* what) const {
    if (status == KAIROS_OK) {
        if (required_ != 0)
            violation("%s returned KAIROS_OK on input it must reject (expected error mask 0x%llx)", what,
                      static_cast<unsigned long long>(required_));
        return;
    }
    const uint64_t b = bit(status);
    if (required_ != 0) {
        if ((required_ & b) == 0 && !unsure_)
            violation("%s returned %s; expected an error of mask 0x%llx (bit n = status -n)", what,
                      kairos_status_name(status), static_cast<unsigned long long>(required_));
        return;
    }
    if (!unsure_ && (allowed_ & b) == 0)
        violation("%s returned %s on valid input of moderate magnitude: %s", what, kairos_status_name(status),
                  kairos_last_error());
}

// ---- Poses and settings ------------------------------------------------------------------------

kairos_quat unit_quat(real x, real y, real z, real w) {
    const real n = std::sqrt(x * x + y * y + z * z + w * w);
    if (!(n > 0) || !std::isfinite(n)) return {0, 0, 0, 1};
    return {static_cast<double>(x / n), static_cast<double>(y / n), static_cast<double>(z / n),
            static_cast<double>(w / n)};
}

namespace {

kairos_quat fuzz_unit_quat(Input& in) {
    const double x = in.symmetric(), y = in.symmetric(), z = in.symmetric(), w = in.symmetric();
    return unit_quat(x, y, z, w);
}

}  // namespace

kairos_quat orientation(Input& in) {
    switch (in.pick(10)) {
        case 0:
            return {0, 0, 0, 1};
        case 1:
            return fuzz_unit_quat(in);
        case 2: {
            const real ax = in.symmetric(), ay = in.symmetric(), az = in.symmetric();
            const real angle = 3.14159265358979323846L * in.symmetric();
            const real n = std::sqrt(ax * ax + ay * ay + az * az);
            if (!(n > 0)) return {0, 0, 0, 1};
            const real s = std::sin(angle / 2) / n;
            return unit_quat(ax * s, ay * s, az * s, std::cos(angle / 2));
        }
        case 3: {
            static const kairos_quat turns[6] = {{1, 0, 0, 0},
                                                 {0, 1, 0, 0},
                                                 {0, 0, 1, 0},
                                                 {0, 0, 0, -1},
                                                 {0.70710678118654752, 0.70710678118654752, 0, 0},
                                                 {0, 0, 0.70710678118654752, 0.70710678118654752}};
            return turns[in.pick(6)];
        }
        case 4: {
            const kairos_quat q = fuzz_unit_quat(in);
            return {-q.x, -q.y, -q.z, -q.w};
        }
        case 5: {
            // Off unit length on both sides of KAIROS_QUAT_TOLERANCE (1e-6).
            static const double off[14] = {1e-9, 1e-7, 5e-7, 9e-7, 1.1e-6, 2e-6,  1e-5,
                                           1e-3, 0.5,  -0.5, 2,    1e3,    -1e-7, -2e-6};
            const kairos_quat q = fuzz_unit_quat(in);
            const double f = 1.0 + off[in.pick(14)];
            return {q.x * f, q.y * f, q.z * f, q.w * f};
        }
        case 6:
            return {in.bits(), in.bits(), in.bits(), in.bits()};
        case 7: {
            kairos_quat q = fuzz_unit_quat(in);
            const double bad =
                in.pick(2) == 0 ? std::numeric_limits<double>::quiet_NaN() : std::numeric_limits<double>::infinity();
            switch (in.pick(4)) {
                case 0:
                    q.x = bad;
                    break;
                case 1:
                    q.y = bad;
                    break;
                case 2:
                    q.z = bad;
                    break;
                default:
                    q.w = bad;
                    break;
            }
            return q;
        }
        case 8: {
            const kairos_quat q = fuzz_unit_quat(in);
            const double f = in.pick(2) == 0 ? 1e-200 : 1e200;
            return {q.x * f, q.y * f, q.z * f, q.w * f};
        }
        default: {
            // Nearly the identity, unnormalised but within tolerance (|q| = 1 + O(1e-9)).
            const double e = 1e-4 * in.symmetric();
            return {e, 0, 0, 1};
        }
    }
}

PoseCase classify(const kairos_pose& pose) {
    PoseCase c;
    c.pose = pose;
    const kairos_quat& q = pose.orientation;
    const bool finite_q = std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
    if (!finite(pose.position) || !finite_q) {
        c.valid = false;
        c.invalid = true;
        c.moderate = false;
        return c;
    }
    const real n = std::sqrt(real(q.x) * q.x + real(q.y) * q.y + real(q.z) * q.z + real(q.w) * q.w);
    const real off = std::fabs(n - 1);
    c.valid = off <= 0.9e-6L;
    c.invalid = off >= 1.1e-6L;
    c.moderate = moderate(pose.position);
    return c;
}

PoseCase make_transform(Input& in) {
    kairos_pose p;
    p.position = position(in);
    p.orientation = orientation(in);
    return classify(p);
}

PoseCase make_pose_near(Input& in, const kairos_pose& from) {
    kairos_pose p = from;
    switch (in.pick(5)) {
        case 0:
            break;  // the same pose: a move that does not move
        case 1: {
            const kairos_vec3 d = small_vec(in, 0.5);
            p.position = {p.position.x + d.x, p.position.y + d.y, p.position.z + d.z};
            break;
        }
        case 2: {
            const kairos_vec3 d = small_vec(in, power_of_ten(in));
            p.position = {p.position.x + d.x, p.position.y + d.y, p.position.z + d.z};
            p.orientation = orientation(in);
            break;
        }
        case 3:
            p.orientation = {-p.orientation.x, -p.orientation.y, -p.orientation.z, -p.orientation.w};
            break;
        default:
            p = make_transform(in).pose;
            break;
    }
    return classify(p);
}

void expect_pose(const PoseCase& p, Verdict& v) {
    if (p.invalid)
        v.require(KAIROS_ERROR_INVALID_ARGUMENT);
    else if (!p.valid || !p.moderate)
        v.unsure();
}

SettingsCase make_settings(Input& in) {
    SettingsCase s;
    const unsigned mode = in.pick(8);
    if (mode == 0) return s;
    s.use = true;
    kairos_query_settings_init(&s.settings);
    static const double tolerances[10] = {1e-10, 1e-6, 1e-3, 0.1, 0.5, 0.999, 1e-15, 1e-300, 1e-14, 0.25};
    static const uint32_t iterations[10] = {256, 1, 2, 3, 4, 8, 16, 64, 1000, 100000};
    if (mode == 2 || mode == 4) s.settings.tolerance = tolerances[in.pick(10)];
    if (mode == 3 || mode == 4) s.settings.max_iterations = iterations[in.pick(10)];
    if (mode == 5) {
        static const uint32_t sizes[4] = {0, 8, sizeof(kairos_query_settings) - 8, sizeof(kairos_query_settings) + 8};
        s.settings.struct_size = sizes[in.pick(4)];
    }
    if (mode == 6) {
        static const double bad[7] = {
            0, 1, -1e-10, 1.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -0.0};
        s.settings.tolerance = bad[in.pick(7)];
    }
    if (mode == 7) s.settings.max_iterations = 0;
    s.tolerance = s.settings.tolerance;
    return s;
}

void expect_settings(const SettingsCase& s, Verdict& v) {
    if (!s.use) return;
    if (s.settings.struct_size != sizeof(kairos_query_settings)) v.require(KAIROS_ERROR_STRUCT_SIZE);
    if (!(s.settings.tolerance > 0 && s.settings.tolerance < 1) || s.settings.max_iterations < 1)
        v.require(KAIROS_ERROR_INVALID_ARGUMENT);
}

}  // namespace kfuzz
