// SPDX-License-Identifier: MIT
// The support of a small convex hull (at most ConvexHullShape::kHillClimbThreshold vertices) by
// brute force over its vertices, vectorised with the widest vector unit the running processor has
// (chosen at run time; the library is built for baseline x86-64): SSE2 on the vertices as stored,
// AVX2 on a structure-of-arrays copy.
//
// Contract: the answer is the lowest index among the vertices whose score d.v is largest, the
// score computed as dot() does ((d.x v.x + d.y v.y) + d.z v.z, no fused multiply-add), so every
// instruction set gives the same vertex bit for bit. Scores that are NaN never win; when none is
// a number the answer is vertex 0.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <emmintrin.h>
#define KAIROS_SMALL_HULL_X86 1
#endif

#include "math/math.hpp"

namespace kairos::small_hull {

// The structure-of-arrays copy: x of every vertex, then y, then z, each block `padded(n)` long,
// the padding repeating vertex 0 (its score ties vertex 0's, which has the lower index).
inline constexpr size_t padded(size_t n) { return (n + 3) & ~size_t{3}; }
std::vector<double> layout(const std::vector<Vec3>& vertices);

#if KAIROS_SMALL_HULL_X86
// Whether this processor runs AVX2: read once, when the library loads (the processor does not
// change while it runs). Before that (another library's constructor) it reads false and SSE2
// answers, which by the contract is the same vertex.
extern const bool kHasAvx2;
inline bool has_avx2() { return kHasAvx2; }
// AVX2 form over layout()'s array; call it only where has_avx2(). The direction comes in three
// registers (a Vec3 argument goes through memory).
size_t best_vertex_avx2(const double* xyz, size_t n, double dx, double dy, double dz);

// SSE2 form (every x86-64 processor) over the vertices as stored: two interleaved running maxima
// (odd indices in lane 0, even in lane 1) with their indices, selected by masks, not branches
// (the winner changes unpredictably, and a mispredicted branch per vertex cost more than the
// product). Each lane keeps its first maximum; the final choice takes the lower index on a tie.
// Inline: the distance and cast loops call it once per iteration per shape.
inline size_t best_vertex_sse2(const Vec3* v, size_t n, Vec3 d) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "vertices are read as packed doubles");
    const __m128d dx = _mm_set1_pd(d.x), dy = _mm_set1_pd(d.y), dz = _mm_set1_pd(d.z);
    __m128d top = _mm_set1_pd(-INFINITY);
    __m128i best = _mm_setzero_si128();
    __m128i index = _mm_set_epi64x(0, 1);  // lane 0 odd stream, lane 1 even
    const __m128i step = _mm_set_epi64x(2, 2);
    size_t i = 0;
    for (; i + 1 < n; i += 2) {
        // v[i] and v[i + 1]: six doubles in a row, read as three pairs and regrouped by axis.
        const double* p = &v[i].x;
        const __m128d l0 = _mm_loadu_pd(p), l1 = _mm_loadu_pd(p + 2), l2 = _mm_loadu_pd(p + 4);
        // Lane 0 v[i + 1], lane 1 v[i].
        const __m128d x = _mm_shuffle_pd(l1, l0, 1), y = _mm_shuffle_pd(l2, l0, 2), z = _mm_shuffle_pd(l2, l1, 1);
        const __m128d score = _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, x), _mm_mul_pd(dy, y)), _mm_mul_pd(dz, z));
        // NaN compares false and max_pd(NaN, top) is top: a NaN score never wins.
        const __m128i higher = _mm_castpd_si128(_mm_cmpgt_pd(score, top));
        best = _mm_or_si128(_mm_and_si128(higher, index), _mm_andnot_si128(higher, best));
        top = _mm_max_pd(score, top);
        index = _mm_add_epi64(index, step);
    }
    double odd_top = _mm_cvtsd_f64(top), even_top = _mm_cvtsd_f64(_mm_unpackhi_pd(top, top));
    size_t odd = static_cast<size_t>(_mm_cvtsi128_si64(best));
    size_t even = static_cast<size_t>(_mm_cvtsi128_si64(_mm_unpackhi_epi64(best, best)));
    if (i < n) {  // the last vertex of an odd count, in the even stream
        const double s = dot(d, v[i]);
        even = s > even_top ? i : even;
        even_top = s > even_top ? s : even_top;
    }
    return odd_top > even_top || (odd_top == even_top && odd < even) ? odd : even;
}
#endif

// The best vertex for direction d (the contract above): v the vertices, xyz layout()'s array of
// the same n vertices, 1 <= n <= 32.
inline size_t best_vertex(const Vec3* v, const double* xyz, size_t n, Vec3 d) {
#if KAIROS_SMALL_HULL_X86
    return has_avx2() ? best_vertex_avx2(xyz, n, d.x, d.y, d.z) : best_vertex_sse2(v, n, d);
#else
    (void)xyz;
    size_t best = 0;
    double top = -INFINITY;
    for (size_t i = 0; i < n; ++i) {
        const double s = dot(d, v[i]);
        if (s > top) {
            top = s;
            best = i;
        }
    }
    return best;
#endif
}

// The best vertex itself (the same point, bit for bit). Under AVX2 it is read from the copy just
// scanned: the vertex's own row was not read by the scan, and over a set of casts between
// different hulls that load missed the cache (the hottest instruction of a hull32 cast's loop).
inline Vec3 best_point(const Vec3* v, const double* xyz, size_t n, Vec3 d) {
#if KAIROS_SMALL_HULL_X86
    if (has_avx2()) {
        const size_t i = best_vertex_avx2(xyz, n, d.x, d.y, d.z), p = padded(n);
        return {xyz[i], xyz[p + i], xyz[2 * p + i]};
    }
    return v[best_vertex_sse2(v, n, d)];
#else
    return v[best_vertex(v, xyz, n, d)];
#endif
}

}  // namespace kairos::small_hull
