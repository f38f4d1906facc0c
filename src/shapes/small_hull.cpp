// SPDX-License-Identifier: MIT
// Small hulls' structure-of-arrays copy and their AVX2 support (see small_hull.hpp), compiled for
// AVX2 alone (the rest of the library is baseline x86-64).
#include "shapes/small_hull.hpp"

#include <cmath>

#if KAIROS_SMALL_HULL_X86
#include <immintrin.h>
#endif

namespace kairos::small_hull {

std::vector<double> layout(const std::vector<Vec3>& vertices) {
    const size_t n = vertices.size(), p = padded(n);
    std::vector<double> xyz(3 * p);
    for (size_t i = 0; i < p; ++i) {
        const Vec3& v = vertices[i < n ? i : 0];
        xyz[i] = v.x;
        xyz[p + i] = v.y;
        xyz[2 * p + i] = v.z;
    }
    return xyz;
}

#if KAIROS_SMALL_HULL_X86

namespace {

// Two lanes' running maxima (top, index) merged: the larger top, the lower index among equals.
// Each lane kept its first maximum (strict comparisons), so merging every lane this way gives the
// lowest index among all the vertices with the top score, whatever the number of lanes. Masks,
// not branches: the final merges decided by branches mispredicted on most calls.
inline void merge(__m128d& top, __m128d& at, __m128d other_top, __m128d other_at) {
    const __m128d take =
        _mm_or_pd(_mm_cmpgt_pd(other_top, top), _mm_and_pd(_mm_cmpeq_pd(other_top, top), _mm_cmplt_pd(other_at, at)));
    top = _mm_or_pd(_mm_and_pd(take, other_top), _mm_andnot_pd(take, top));
    at = _mm_or_pd(_mm_and_pd(take, other_at), _mm_andnot_pd(take, at));
}

// The two lanes of (top, at) merged into one: the winner's index.
inline size_t winner(__m128d top, __m128d at) {
    merge(top, at, _mm_unpackhi_pd(top, top), _mm_unpackhi_pd(at, at));
    return static_cast<size_t>(_mm_cvtsd_f64(at));
}

}  // namespace

// AVX2 machines: two running maxima of four lanes, eight vertices per round (four in the last
// one when n is not a multiple of eight); the same products, sums and comparisons.
__attribute__((target("avx2"))) size_t best_vertex_avx2(const double* xyz, size_t n, double x, double y, double z) {
    const size_t p = padded(n);
    const double *xs = xyz, *ys = xyz + p, *zs = xyz + 2 * p;
    const __m256d dx = _mm256_set1_pd(x), dy = _mm256_set1_pd(y), dz = _mm256_set1_pd(z);
    const __m256d step = _mm256_set1_pd(8);
    __m256d top0 = _mm256_set1_pd(-INFINITY), top1 = top0;
    __m256d at0 = _mm256_set_pd(3, 2, 1, 0), at1 = _mm256_set_pd(7, 6, 5, 4);
    __m256d i0 = at0, i1 = at1;
    size_t i = 0;
    for (; i + 8 <= p; i += 8) {
        const __m256d s0 = _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(dx, _mm256_loadu_pd(xs + i)), _mm256_mul_pd(dy, _mm256_loadu_pd(ys + i))),
            _mm256_mul_pd(dz, _mm256_loadu_pd(zs + i)));
        const __m256d s1 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, _mm256_loadu_pd(xs + i + 4)),
                                                       _mm256_mul_pd(dy, _mm256_loadu_pd(ys + i + 4))),
                                         _mm256_mul_pd(dz, _mm256_loadu_pd(zs + i + 4)));
        at0 = _mm256_blendv_pd(at0, i0, _mm256_cmp_pd(s0, top0, _CMP_GT_OQ));
        at1 = _mm256_blendv_pd(at1, i1, _mm256_cmp_pd(s1, top1, _CMP_GT_OQ));
        top0 = _mm256_max_pd(s0, top0);
        top1 = _mm256_max_pd(s1, top1);
        i0 = _mm256_add_pd(i0, step);
        i1 = _mm256_add_pd(i1, step);
    }
    if (i < p) {
        const __m256d s0 = _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(dx, _mm256_loadu_pd(xs + i)), _mm256_mul_pd(dy, _mm256_loadu_pd(ys + i))),
            _mm256_mul_pd(dz, _mm256_loadu_pd(zs + i)));
        at0 = _mm256_blendv_pd(at0, i0, _mm256_cmp_pd(s0, top0, _CMP_GT_OQ));
        top0 = _mm256_max_pd(s0, top0);
    }
    const __m256d take =
        _mm256_or_pd(_mm256_cmp_pd(top1, top0, _CMP_GT_OQ),
                     _mm256_and_pd(_mm256_cmp_pd(top1, top0, _CMP_EQ_OQ), _mm256_cmp_pd(at1, at0, _CMP_LT_OQ)));
    top0 = _mm256_blendv_pd(top0, top1, take);
    at0 = _mm256_blendv_pd(at0, at1, take);
    __m128d top = _mm256_castpd256_pd128(top0), at = _mm256_castpd256_pd128(at0);
    merge(top, at, _mm256_extractf128_pd(top0, 1), _mm256_extractf128_pd(at0, 1));
    return winner(top, at);
}

extern const bool kHasAvx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
}();

#endif

}  // namespace kairos::small_hull
