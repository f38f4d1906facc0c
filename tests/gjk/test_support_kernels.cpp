// SPDX-License-Identifier: MIT
// The support kernels GJK and the casts inline (src/gjk/support_kernels.hpp) against brute force:
// the small hull's vectorised scan picks the vertex its tie rule names on every instruction set, the cylinder's and cone's
// kernel gives support()'s point, a maximiser over their rims and apex, and the branchless sign
// of boxes, segments and caps is the product it replaced.
#include <gtest/gtest.h>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>
#include "gjk/support_kernels.hpp"
#include "gjk_test_support.hpp"
#include "shapes/small_hull.hpp"

using namespace kairos;
using kernels::BoxSupport;
using kernels::RevolutionSupport;
using kernels::SmallHullSupport;

namespace {

// The documented rule, by brute force: the largest d.v that is a number; the lowest index among
// the vertices reaching it; vertex 0 when no score is a number.
size_t expected_vertex(const std::vector<Vec3>& v, Vec3 d) {
    double top = -INFINITY;
    for (const Vec3& p : v) top = std::fmax(top, dot(d, p));
    for (size_t i = 0; i < v.size(); ++i)
        if (dot(d, v[i]) == top) return i;
    return 0;
}

}  // namespace

// Vertex arrays of 1 to 32 points on a small integer grid (many ties: equal scores on distinct
// points, duplicates), with directions along axes, diagonals, grid vectors, zero, NaN and random.
// The kernel, and on x86-64 each of its SSE2 and AVX2 forms (the latter where the processor has
// it), must return the vertex the rule names: the same on every machine.
TEST(SupportKernels, SmallHullPicksTheVertexItsTieRuleNames) {
    const uint64_t seed = 2101;
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> grid(-2, 2);
    std::uniform_real_distribution<double> u(-1, 1);
    int cases = 0, wrong = 0, tied = 0, not_first = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const size_t n = 1 + trial % 32;
        std::vector<Vec3> v(n);
        for (Vec3& p : v)
            p = trial % 3 == 2 ? Vec3{u(rng), u(rng), u(rng)}
                               : Vec3{double(grid(rng)), double(grid(rng)), 0.5 * grid(rng)};
        const std::vector<double> xyz = small_hull::layout(v);
        ASSERT_EQ(xyz.size(), 3 * small_hull::padded(n));
        for (int k = 0; k < 9; ++k) {
            Vec3 d;
            switch (k % 4) {
                case 0:
                    d = Vec3{};
                    d[int(3 * (u(rng) + 1) / 2) % 3] = u(rng) < 0 ? -1.0 : 1.0;
                    break;
                case 1:
                    d = {double(grid(rng)), double(grid(rng)), double(grid(rng))};
                    break;
                case 2:
                    d = k == 2 ? Vec3{} : Vec3{1, 1, 1};
                    break;
                default:
                    d = {u(rng), u(rng), u(rng)};
            }
            if (k == 8) d[trial % 3] = std::numeric_limits<double>::quiet_NaN();
            const size_t want = expected_vertex(v, d);
            int reaching = 0;
            for (size_t i = 0; i < n; ++i) reaching += dot(d, v[i]) == dot(d, v[want]) && !(v[i] == v[want]);
            tied += reaching > 0;
            not_first += want != 0;
            ++cases;
            const SmallHullSupport support{v.data(), xyz.data(), n};
            const Vec3 by_kernel = support(d);
            bool ok = by_kernel == v[want];
#if KAIROS_SMALL_HULL_X86
            ok = ok && small_hull::best_vertex_sse2(v.data(), n, d) == want;
            if (small_hull::has_avx2()) ok = ok && small_hull::best_vertex_avx2(xyz.data(), n, d.x, d.y, d.z) == want;
#endif
            if (!ok && ++wrong <= 10)
                ADD_FAILURE() << "seed " << seed << " trial " << trial << " n " << n << " direction " << d.x << " "
                              << d.y << " " << d.z << ": vertex " << want << " expected";
        }
    }
    std::printf("small hull support: %d scans, %d with distinct vertices tied at the top, %d won past vertex 0\n",
                cases, tied, not_first);
    EXPECT_EQ(wrong, 0);
    // The tie rule is what is tested: a good share of scans must have distinct tied vertices, and
    // the winner must not be vertex 0 most of the time (padding repeats vertex 0).
    EXPECT_GT(tied, cases / 4);
    EXPECT_LT(tied, cases);
    EXPECT_GT(not_first, cases / 2);
}

// The cylinder's and cone's kernel is support() of the shape, bit for bit, and a maximiser: no
// point of the rims or the apex (sampled every 0.1 degree) reaches farther along d beyond
// rounding, and the point is on the shape (a rim's disk or the apex). Directions: axes, a hair (1e-300 .. 1e-3) off the axis, zero, random.
TEST(SupportKernels, CylinderAndConeKernelIsTheShapesSupport) {
    const uint64_t seed = 2102;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const CylinderShape cylinder(0.7, 1.3);
    const ConeShape cone(0.9, 0.6);
    const RevolutionSupport kernel[2] = {{0.7, 1.3, false}, {0.9, 0.6, true}};
    const Shape* shapes[2] = {&cylinder, &cone};
    int different = 0, beaten = 0, outside = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        Vec3 d{u(rng), u(rng), u(rng)};
        if (trial % 4 == 1) d = {std::pow(10.0, -300 + 297 * (u(rng) + 1) / 2), 0, u(rng) < 0 ? -1.0 : 1.0};
        if (trial % 4 == 2) d = trial % 8 == 2 ? Vec3{} : Vec3{0, 0, u(rng) < 0 ? -1.0 : 1.0};
        for (int s = 0; s < 2; ++s) {
            const Vec3 got = kernel[s](d), want = support(*shapes[s], d);
            if (!(got == want) && ++different <= 10)
                ADD_FAILURE() << "seed " << seed << " trial " << trial << " shape " << s << ": kernel differs";
            const double r = s == 0 ? 0.7 : 0.9, h = s == 0 ? 1.3 : 0.6, reach = dot(d, got);
            // The point is the shape's: on a rim (a cap's plane, within the radius) or the apex.
            const bool on_cap = (got.z == -h || (s == 0 && got.z == h)) && std::hypot(got.x, got.y) <= r * (1 + 1e-15);
            if (!(on_cap || (s == 1 && got == Vec3{0, 0, h})) && ++outside <= 10)
                ADD_FAILURE() << "seed " << seed << " trial " << trial << " shape " << s << ": point " << got.x << " "
                              << got.y << " " << got.z << " is not on the shape";
            double best = s == 1 ? dot(d, Vec3{0, 0, h}) : -INFINITY;
            for (int k = 0; k < 3600; ++k) {
                const double a = k * (M_PI / 1800);
                best = std::fmax(best, dot(d, Vec3{r * std::cos(a), r * std::sin(a), -h}));
                if (s == 0) best = std::fmax(best, dot(d, Vec3{r * std::cos(a), r * std::sin(a), h}));
            }
            if (best > reach + 1e-15 * (r + h) * std::sqrt(dot(d, d)) && ++beaten <= 10)
                ADD_FAILURE() << "seed " << seed << " trial " << trial << " shape " << s << ": a rim point reaches "
                              << best - reach << " farther";
        }
    }
    EXPECT_EQ(different, 0);
    EXPECT_EQ(beaten, 0);
    EXPECT_EQ(outside, 0);
}

// toward(d, h) is support_sign(d) * h bit for bit (the masked sign flip it replaced a branch
// with): for directions of every class (signed zeros, subnormals, infinities, NaNs of both signs)
// and non-NaN sizes, zero and infinite ones included. Then the box's support, by the shape and by
// the kernel, against brute force over its eight corners: the corner reaching farthest along d,
// with +h on every axis where d is zero or NaN (the tie rule that keeps a zero direction's point
// on the shape).
TEST(SupportKernels, BranchlessSignIsTheProductBitForBit) {
    const double nan = std::numeric_limits<double>::quiet_NaN(), tiny = std::numeric_limits<double>::denorm_min();
    const double ds[] = {0.0,   -0.0,   tiny,     -tiny,     1e-300, -1e-300, 1.0,       -1.0,
                         1e300, -1e300, INFINITY, -INFINITY, nan,    -nan,    0x1p-1022, -0x1p-1022};
    const double hs[] = {0.0, -0.0, tiny, 1e-300, 0.5, 1.0, 1e300, INFINITY};
    int pairs = 0, wrong = 0, flipped = 0;
    for (double d : ds)
        for (double h : hs) {
            const double got = toward(d, h), want = support_sign(d) * h;
            ++pairs;
            flipped += std::signbit(got) != std::signbit(h);
            if (std::bit_cast<uint64_t>(got) != std::bit_cast<uint64_t>(want) && ++wrong <= 10)
                ADD_FAILURE() << "toward(" << d << ", " << h << ") = " << got << ", the product " << want;
        }
    EXPECT_EQ(wrong, 0);
    // Both outcomes occur: the sign is flipped for the negative directions only.
    EXPECT_GT(flipped, pairs / 4);
    EXPECT_LT(flipped, pairs / 2);

    const uint64_t seed = 2103;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    const Vec3 half{0.5, 1.5, 0.25};
    const BoxShape box(half);
    const BoxSupport kernel{half};
    int cases = 0, off = 0, with_zero = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        Vec3 d{u(rng), u(rng), u(rng)};
        for (int i = 0; i < 3; ++i) {
            const int pick = int(8 * (u(rng) + 1)) % 8;
            if (pick == 0) d[i] = 0.0;
            if (pick == 1) d[i] = -0.0;
            if (pick == 2) d[i] = (u(rng) < 0 ? -1 : 1) * tiny;
        }
        bool zero = false;
        Vec3 want;
        for (int i = 0; i < 3; ++i) {
            zero = zero || d[i] == 0;
            // Brute force over the two faces along axis i (the component scaled by 2^1000, exactly,
            // so a subnormal one does not round its products to zero); a zero component keeps +h.
            const double di = std::ldexp(d[i], 1000);
            want[i] = di * -half[i] > di * half[i] ? -half[i] : half[i];
        }
        with_zero += zero;
        ++cases;
        const Vec3 a = kernel(d), b = support(box, d);
        if ((!(a == want) || !(b == want) || std::signbit(a.x) != std::signbit(want.x) ||
             std::signbit(a.y) != std::signbit(want.y) || std::signbit(a.z) != std::signbit(want.z)) &&
            ++off <= 10)
            ADD_FAILURE() << "seed " << seed << " trial " << trial << ": direction " << d.x << " " << d.y << " " << d.z
                          << " gave the corner " << a.x << " " << a.y << " " << a.z;
    }
    EXPECT_EQ(off, 0);
    // Zero components (the tie rule) and none both occur.
    EXPECT_GT(with_zero, cases / 4);
    EXPECT_LT(with_zero, cases);
}
