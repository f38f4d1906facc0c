// SPDX-License-Identifier: MIT
// Shared pieces of the Kairos fuzz targets: the byte reader, generators of numbers, poses and
// point sets, the status contract of every call, and shape construction checked against an
// independent support-function model (long double) of what was asked for.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kairos/kairos.h"

// Hulls of every non-empty finite set are shapes (docs/c-api.md "Version 0.2 additions"), so with 0
// KAIROS_ERROR_DEGENERATE is accepted for count 0 only; 1 accepts it for every hull.
#ifndef KAIROS_FUZZ_ALLOW_DEGENERATE_HULL
#define KAIROS_FUZZ_ALLOW_DEGENERATE_HULL 0
#endif

// With 1, a successful call on inputs beyond the moderate range (magnitudes above
// kModerateMax or below kModerateMin) may return non-finite numbers. The contract says it must
// not (such inputs are to be rejected with a status), so this is 0: only for exploring past
// that known class of failure.
#ifndef KAIROS_FUZZ_ALLOW_NONFINITE_ON_HUGE
#define KAIROS_FUZZ_ALLOW_NONFINITE_ON_HUGE 0
#endif

// Set by tests/fuzz/CMakeLists.txt when include/kairos/kairos.h declares kairos_shape_triangle.
#ifndef KAIROS_FUZZ_HAVE_TRIANGLE
#define KAIROS_FUZZ_HAVE_TRIANGLE 0
#endif

namespace kfuzz {

using real = long double;

// Inputs whose every non-zero magnitude lies in [kModerateMin, kModerateMax] must succeed when
// valid; beyond, a valid input may also be rejected with any known error status.
constexpr double kModerateMax = 1e30;
constexpr double kModerateMin = 1e-30;

// Prints "kairos fuzz: contract violation: ..." to stderr and aborts: libFuzzer saves the input.
[[noreturn]] void violation(const char* format, ...) __attribute__((format(printf, 1, 2)));

// ---- Bytes -------------------------------------------------------------------------------------

// Reads the fuzz input front to back. Past the end every read gives 0, and every choice below
// maps 0 to its plain case (valid, simple), so a short input means a simple, valid scene.
class Input {
public:
    Input(const uint8_t* data, size_t size) : p_(data), end_(data + size) {}
    size_t remaining() const { return static_cast<size_t>(end_ - p_); }
    uint8_t u8() { return p_ < end_ ? *p_++ : 0; }
    uint16_t u16();
    uint32_t u32();
    uint64_t u64();
    double bits();  // any double, NaN and infinities included
    unsigned pick(unsigned n) { return n <= 1 ? 0u : u8() % n; }
    bool rare(unsigned n) { return u8() % n == n - 1; }    // about 1 in n, never on zero bytes
    double fraction() { return u16() / 65535.0; }          // [0, 1]
    double symmetric() { return 2.0 * fraction() - 1.0; }  // [-1, 1]

private:
    const uint8_t* p_;
    const uint8_t* end_;
};

// splitmix64: fills many points from one seed, so a few bytes give a large point set.
class Rng {
public:
    explicit Rng(uint64_t seed) : s_(seed) {}
    uint64_t next();
    double symmetric() { return static_cast<double>(next() >> 11) * 0x1p-52 - 1.0; }  // [-1, 1)

private:
    uint64_t s_;
};

// ---- Numbers -----------------------------------------------------------------------------------

bool moderate(double v);  // finite, and 0 or within [kModerateMin, kModerateMax]
bool moderate(const kairos_vec3& v);
bool finite(const kairos_vec3& v);
double power_of_ten(Input& in);                  // mostly 1e-3..1e3; sometimes 1e+-20, 1e150..1e300, 1e-300..1e-150
double length(Input& in);                        // a size: mostly in (0, 1e3]; sometimes 0, < 0, NaN, inf, tiny, huge
double edge_value(Input& in);                    // 0, -0, +-inf, NaN, denormals, DBL_MIN/MAX, 1e+-300, ...
kairos_vec3 small_vec(Input& in, double scale);  // components in [-scale, scale]
kairos_vec3 position(Input& in);                 // mostly within a few units; sometimes far, huge or non-finite
kairos_vec3 direction(Input& in);                // any finite or non-finite vector, zero and tiny included

// ---- Status contract ---------------------------------------------------------------------------

// What a call may return. Errors an input must cause are `required`; a status outside them is a
// violation unless the input is also `unsure` (borderline or beyond the moderate range), which
// admits any known status; with neither, only KAIROS_OK (or an `allowed` extra) is right.
class Verdict {
public:
    void require(int32_t error) { required_ |= bit(error); }
    void allow(int32_t error) { allowed_ |= bit(error); }
    void unsure() { unsure_ = true; }
    bool expects_error() const { return required_ != 0; }
    // Aborts when status breaks the expectation; `what` names the call in the report.
    void check(int32_t status, const char* what) const;

private:
    static uint64_t bit(int32_t error) { return error < 0 && error > -64 ? uint64_t{1} << -error : 0; }
    uint64_t required_ = 0, allowed_ = 0;
    bool unsure_ = false;
};

// Runs one library call: its status must be KAIROS_OK or a named negative status, never
// KAIROS_ERROR_INTERNAL; a failure's message must start with "<function>: "; a success must
// leave kairos_last_error() as it was.
template <class Call>
int32_t observe(const char* function, Call&& call);
void observe_before();
int32_t observe_after(const char* function, int32_t status);

template <class Call>
int32_t observe(const char* function, Call&& call) {
    observe_before();
    return observe_after(function, call());
}

// Fills an output with a byte pattern, so "untouched on failure" is a memcmp.
template <class T>
void poison(T& v) {
    __builtin_memset(static_cast<void*>(&v), 0xA5, sizeof v);
}
template <class T>
bool poisoned(const T& v) {
    T p;
    poison(p);
    return __builtin_memcmp(&p, &v, sizeof v) == 0;
}

// ---- Poses and settings ------------------------------------------------------------------------

// q / |q| (computed in long double); the identity for a zero or non-finite q.
kairos_quat unit_quat(real x, real y, real z, real w);

struct PoseCase {
    kairos_pose pose{{0, 0, 0}, {0, 0, 0, 1}};
    bool valid = true;     // finite with |q| within KAIROS_QUAT_TOLERANCE, beyond doubt
    bool invalid = false;  // definitely rejected (non-finite, or |q| clearly off 1)
    bool moderate = true;
};
// A rotation: identity, normalised fuzz quaternion, axis-angle, half turns, -q; or a bad one:
// scaled off unit length by 1e-9 .. 1e3, raw bits, non-finite, tiny.
kairos_quat orientation(Input& in);
PoseCase make_transform(Input& in);
PoseCase make_pose_near(Input& in, const kairos_pose& from);  // a small step from `from`
PoseCase classify(const kairos_pose& pose);
// Adds the pose's expectation (INVALID_ARGUMENT, unsure) to a verdict.
void expect_pose(const PoseCase& p, Verdict& v);

struct SettingsCase {
    kairos_query_settings settings{};
    bool use = false;          // false: pass NULL (defaults)
    double tolerance = 1e-10;  // what the query works with when valid
};
SettingsCase make_settings(Input& in);
void expect_settings(const SettingsCase& s, Verdict& v);

// ---- Shapes and their model --------------------------------------------------------------------

struct Vr {
    real x = 0, y = 0, z = 0;
};
Vr to_real(const kairos_vec3& v);
real dot(const Vr& a, const Vr& b);
real norm(const Vr& a);
Vr operator+(const Vr& a, const Vr& b);
Vr operator-(const Vr& a, const Vr& b);
Vr operator*(real s, const Vr& a);
// ulp-sized slack: 2^-52 of |x|.
real ulp(real x);
inline real max3(real a, real b, real c) { return a > b ? (a > c ? a : c) : (b > c ? b : c); }
// The largest |component|.
real biggest(const kairos_vec3& v);

// Relative slack of every support comparison (1e-9 of the sizes involved), and an absolute one of a
// few denormals.
constexpr real kRelative = 1e-9L;
constexpr real kFloor = 1e-320L;

enum class Kind { Point, Segment, Sphere, Box, Capsule, Cylinder, Cone, Points, MinkowskiSum, HullOfTwo, Transformed };

// What a shape should be, independent of the library: its support function
// h(d) = max over the shape of d.x, in long double.
struct Model {
    Kind kind = Kind::Point;
    real a = 0, b = 0, c = 0;  // sphere r=a; box a,b,c; capsule/cylinder/cone r=a, h=b; segment h=a
    std::vector<Vr> points;    // hull or triangle
    std::shared_ptr<const Model> left, right;
    real linear[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    Vr translation;
    real magnitude = 0;  // bound on |x| over the shape (local frame)
    real tolerance = 0;  // slack of |d.support(d) - h(d)| for unit d
    bool moderate = true;
};
using ModelPtr = std::shared_ptr<const Model>;
real support_value(const Model& m, const Vr& d);  // local frame

// A posed shape's support function in the world frame: h(R^T d) + d.p, R from the normalised q.
struct Placed {
    const Model* model = nullptr;
    real rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    Vr position;
};
Placed place(const Model& m, const kairos_pose& pose);
Placed place(const Model& m, const kairos_quat& q, const Vr& position);
real support_value(const Placed& p, const Vr& d);
// Lower bound of the distance: the gap between the shapes along unit u (negative: overlap along u).
real gap(const Placed& a, const Placed& b, const Vr& u);
// The pose of a motion at time t (docs/c-api.md: the position linear in t; the orientation turning at
// constant angular velocity about a fixed world axis along the shortest arc).
void motion_at(const kairos_motion& m, real t, kairos_quat& q_out, Vr& p_out);
// Radius of a ball about the local origin that lies inside the shape: 0 when the origin alone is
// known to, -1 when nothing is known.
real inner_radius(const Model& m);
// The first t in [0, 1] at which |p0 + t dv| <= reach (two points, p0 apart at t = 0, moving
// apart by dv over the step), or -1 when they never come that close. From the closest approach:
// the quadratic's discriminant cancels badly on long paths.
real first_within(const Vr& p0, const Vr& dv, real reach);
// The 26 directions of {-1, 0, 1}^3 without 0, unit.
const std::vector<Vr>& unit_directions();

// Aspect of a convex set given by its width w(d) = h(d) + h(-d): its longest width over the
// largest width across that direction. The longest direction comes from a hill climb on w from the
// widest of the 26 test directions: a needle's width along d is about its length times |cos|, so
// the test directions alone can be far from its axis and read a needle as a fat shape. The climb
// ends at steps of 1e-8 rad, so aspects up to about 1e8 read true; a flat shape's aspect is that of
// its outline (about 1), a segment's is infinite.
template <class Width>
real aspect_of(const Width& width) {
    Vr axis;
    real longest = -1;
    for (const Vr& d : unit_directions()) {
        const real w = width(d);
        if (w > longest) longest = w, axis = d;
    }
    if (!(longest > 0)) return 1;  // a point: no direction is longer
    const Vr basis[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    // A move must gain more than rounding (a round shape's width is flat, and its rounding noise
    // would let the climb wander for ever: found by fuzzing), and each step size makes at most 16.
    for (real step = 0.25L; step > 1e-8L; step *= 0.5L) {
        bool moved = true;
        for (int moves = 0; moved && moves < 16; ++moves) {
            moved = false;
            for (const Vr& e : basis)
                for (real sign : {real(1), real(-1)}) {
                    Vr c = axis + (sign * step) * e;
                    c = (1 / norm(c)) * c;
                    const real w = width(c);
                    if (w > longest * (1 + 1e-18L)) longest = w, axis = c, moved = true;
                }
        }
    }
    // Two unit vectors across the axis.
    const Vr& e = std::fabs(axis.x) < 0.6L ? basis[0] : basis[1];
    Vr u{axis.y * e.z - axis.z * e.y, axis.z * e.x - axis.x * e.z, axis.x * e.y - axis.y * e.x};
    u = (1 / norm(u)) * u;
    const Vr v{axis.y * u.z - axis.z * u.y, axis.z * u.x - axis.x * u.z, axis.x * u.y - axis.y * u.x};
    real across = 0;
    for (int k = 0; k < 12; ++k) {
        const real t = k * 3.14159265358979323846L / 12;
        across = std::fmax(across, width(std::cos(t) * u + std::sin(t) * v));
    }
    return across > 0 ? longest / across : INFINITY;
}

// Aspect of one shape by itself, in its local frame (aspect_of). A pair can hide a needle: a hull
// of nearly collinear points 1e9 times longer than thick, across a disk, makes an A - B of aspect
// about 1e4, while GJK's simplices still take the needle's support points, whose slivers carry
// errors of eps times the needle's own aspect (docs/c-api.md counts each shape's aspect). An
// exactly one-dimensional shape (a segment) reads infinite; its two support points make exact
// simplices, so callers let it pass.
real own_aspect(const Model& m);

// An owned reference to a shape (released on destruction; copies retain).
class ShapeRef {
public:
    ShapeRef() = default;
    explicit ShapeRef(kairos_shape* s) : s_(s) {}
    ShapeRef(const ShapeRef& o) : s_(o.s_) { kairos_shape_retain(s_); }
    ShapeRef(ShapeRef&& o) noexcept : s_(o.s_) { o.s_ = nullptr; }
    ShapeRef& operator=(ShapeRef o) noexcept {
        kairos_shape* t = s_;
        s_ = o.s_;
        o.s_ = t;
        return *this;
    }
    ~ShapeRef() { kairos_shape_release(s_); }
    kairos_shape* get() const { return s_; }

private:
    kairos_shape* s_ = nullptr;
};

struct Built {
    ShapeRef shape;
    ModelPtr model;
};

// Decodes and builds shapes, checking each constructor's status contract and each built shape
// against its model (support in many directions, bounds at two poses). Composites take their
// parts from the shapes built so far or build new ones, up to max_depth levels.
class ShapeBuilder {
public:
    // thorough: also probe each shape's support along fuzz directions (tiny, huge, non-finite);
    // the query and world targets leave that to fuzz_shapes and spend their inputs on their own calls.
    ShapeBuilder(Input& in, int max_depth, bool thorough) : in_(in), max_depth_(max_depth), thorough_(thorough) {}
    // A shape, or nothing when the constructor (rightly) failed.
    std::optional<Built> build(int depth = 0);
    // build(), with a unit sphere when construction failed.
    Built build_or_sphere();
    const std::vector<Built>& pool() const { return pool_; }

private:
    std::optional<Built> primitive(unsigned kind);
    std::optional<Built> convex_hull();
    std::optional<Built> triangle();
    std::optional<Built> composite(unsigned kind, int depth);
    std::optional<Built> part(int depth);
    std::optional<Built> finish(const char* function, int32_t status, kairos_shape* out, const Verdict& verdict,
                                std::shared_ptr<Model> model);

    Input& in_;
    int max_depth_;
    bool thorough_;
    std::vector<Built> pool_;
};

// Checks a built shape against its model: support finite and within tolerance of h(d) for the
// 26 unit directions, fuzz directions if asked (non-finite ones must be rejected) and the zero direction;
// bounds finite, ordered and tight at the identity and a fuzz pose.
void check_shape(const kairos_shape* s, const Model& m, Input& in, bool fuzz_directions = true);

// A point set for kairos_shape_convex_hull: 0..64 points from one of several generators
// (random, lattice, duplicates, coplanar, collinear, nearly coplanar/collinear with 1e-9..1e-15
// perturbations, sphere, box with face points, raw bits) placed by a scale (tiny to huge), a
// rotation and an offset (possibly far from the origin).
std::vector<kairos_vec3> hull_points(Input& in);

// For reports: a model as its constructor calls ("minkowski_sum(sphere(1), box(1, 2, 3))"), and
// vectors and poses with %.17g per component.
std::string describe(const Model& m);
const char* show(const kairos_vec3& v);
const char* show(const kairos_pose& p);

}  // namespace kfuzz
