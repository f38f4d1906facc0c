// SPDX-License-Identifier: MIT
// The simplex of GJK with Johnson's sub-algorithm (docs/algorithms.md §2): the points of A - B
// kept by an iteration, their cached determinants, the closest point and the recoveries from
// rounding. Used by the distance and intersection loops (gjk.cpp) and the casts (casts/cast.cpp).
#pragma once

#include <array>
#include <bit>
#include <utility>

#include "gjk/subsets.hpp"
#include "math/math.hpp"

namespace kairos {
namespace gjk_detail {

// Threshold of rule 2 (near contact), relative to the largest squared simplex vertex norm:
// ||v|| <= 64 ulp of the simplex's size, where v carries no significant digit any more.
inline constexpr double kNearContact = (64 * 2.220446049250313e-16) * (64 * 2.220446049250313e-16);
// Threshold of rule 6 (no progress): the type's machine epsilon.
inline constexpr double kNoProgress = 2.220446049250313e-16;

// Fixed array of Vec3 left uninitialised on construction (Vec3 zeroes itself by default, and
// the simplex is built on every query; only entries written by add() are ever read).
template <int N>
struct RawVec3s {
    union {
        Vec3 v[N];
    };
    RawVec3s() {}
    Vec3& operator[](int i) { return v[i]; }
    const Vec3& operator[](int i) const { return v[i]; }
};

// The simplex of GJK: up to four points y_i of A - B with their support points on A and B, and
// Johnson's determinants Delta_i(X) and u_X = sum Delta_i(X) y_i cached per subset X (bit mask).
// The dot products y_i.y_j of the classical recursion enter through u_X, in a form that does not
// cancel (compute_subset). A slot's entries stay valid while its point stays in the simplex, so
// adding a point computes only the subsets that contain it.
struct Simplex {
    RawVec3s<4> y, pa, pb;
    double norm_sq[4];        // ||y_i||^2
    double det[16][4];        // Delta_i(X) for X a subset (bit mask) of the points present
    RawVec3s<16> u;           // u_X = sum_{i in X} Delta_i(X) y_i, per subset X (see compute_subset)
    double lambda[4];         // barycentric coordinates of v over `bits`
    unsigned bits = 0;        // current simplex
    unsigned last_all = 0;    // the points of the last add (current simplex and the ones it dropped)
    Vec3 v;                   // closest point of the current simplex to the origin
    bool want_lambda = true;  // false: triangles skip their barycentric coordinates until
                              // update_lambda() (the distance loop needs them only at the end)
    bool held = false;        // a thin tetrahedron held the origin (hold(); never cleared)
    RawVec3s<4> held_y, held_pa, held_pb;
    double held_lambda[4];
    double held_extent_sq;    // max ||y_i||^2 of the held tetrahedron

    // True when w equals a point of the last simplex before reduction (rule 5). Any such point y
    // has v.y >= ||v||^2 in exact arithmetic, so rule 1 would have fired: w comes back by rounding
    // only, and adding it again would cycle. (Points dropped earlier may legitimately return.)
    bool contains(Vec3 w) const {
        for (unsigned r = last_all; r; r &= r - 1) {
            const int i = std::countr_zero(r);
            if (y[i] == w) return true;
        }
        return false;
    }

    // After a support point w came back (contains(w)) although Johnson's test had just dropped it:
    // in exact arithmetic that cannot happen, so the test was decided by rounding. The closest
    // point of the hull of the last simplex before reduction is found again geometrically: over
    // every proper subset, the projection of the origin with edge vectors, kept when its
    // barycentric coordinates are non-negative, the nearest such one winning (the closest point of
    // a polytope is the nearest of its faces' interior projections). True when it is nearer than
    // the current estimate by more than rounding: v, lambda and bits then describe it, and the
    // iteration can go on.
    bool refine_dropped() {
        const unsigned all = last_all;
        if ((all & ~bits) == 0) return false;  // nothing was dropped
        const double current = dot(v, v);
        const unsigned keep_bits = bits;
        const Vec3 keep_v = v;
        double keep_lambda[4];
        for (int i = 0; i < 4; ++i) keep_lambda[i] = lambda[i];
        const bool keep_want = want_lambda;
        want_lambda = true;
        double best = current * (1 - 64 * kNoProgress);
        unsigned best_s = 0;
        for (unsigned sub = 1; sub < 16u; ++sub) {
            if ((sub & ~all) != 0 || sub == 15u) continue;
            set_from_subset(sub);
            bool inside = true;
            for (unsigned r = sub; r; r &= r - 1)
                if (!(lambda[std::countr_zero(r)] >= 0)) inside = false;
            const double n2 = dot(v, v);
            if (inside && n2 < best) {
                best = n2;
                best_s = sub;
            }
        }
        if (best_s != 0) {
            set_from_subset(best_s);
        } else {
            bits = keep_bits;
            v = keep_v;
            for (int i = 0; i < 4; ++i) lambda[i] = keep_lambda[i];
        }
        want_lambda = keep_want;
        return best_s != 0;
    }

    // The recovery at a rounding stop (the distance loop, the cast loop): the hull of `all` holds
    // a point nearer than the estimate of norm^2 vv by more than rounding (64 ulp), with
    // coordinates that reproduce it within 2^-30 of the size, as the final witness points must.
    // Each success shrinks the estimate by more than rounding, so repeating it cannot cycle.
    bool nearer_in_hull(unsigned all, double vv) { return nearest_in_hull(all, vv * (1 - 64 * kNoProgress), 0x1p-60); }

    // The nearest point to the origin of the hull of the points in `all` (a subset of the slots
    // written), found by enumeration, not by Johnson's determinants: over every proper subset, the
    // origin projected on its affine hull with geometric coordinates, kept when the coordinates are
    // non-negative and reproduce the projection within sqrt(rel_sq) of the size (a sliver's
    // coordinates can be far off while its projection is right: a witness point 1e3 from where
    // the distance says). The nearest kept one
    // wins. True when it is nearer than bound_sq: v, lambda and bits then describe it, and
    // last_all = all. Otherwise nothing changes. The slow path of the rounding limit only.
    bool nearest_in_hull(unsigned all, double bound_sq, double rel_sq) {
        const unsigned keep_bits = bits, keep_last = last_all;
        const Vec3 keep_v = v;
        double keep_lambda[4];
        for (int i = 0; i < 4; ++i) keep_lambda[i] = lambda[i];
        const bool keep_want = want_lambda;
        want_lambda = true;
        double best = bound_sq;
        unsigned best_s = 0;
        for (unsigned sub = 1; sub < 15u; ++sub) {
            if ((sub & ~all) != 0) continue;
            set_from_subset(sub);
            const double n2 = dot(v, v);
            if (n2 < best && coordinates_reproduce_v(rel_sq)) {
                best = n2;
                best_s = sub;
            }
        }
        if (best_s != 0) {
            set_from_subset(best_s);
            want_lambda = keep_want;
            last_all = all;
            return true;
        }
        want_lambda = keep_want;
        bits = keep_bits;
        last_all = keep_last;
        v = keep_v;
        for (int i = 0; i < 4; ++i) lambda[i] = keep_lambda[i];
        return false;
    }

    // True when the witness points of lambda reproduce v: the point of the coordinates clamped to
    // >= 0 and normalised (as closest_points takes them) lies within sqrt(rel_sq) of the
    // simplex's size from v.
    bool coordinates_reproduce_v(double rel_sq) const {
        static constexpr auto table = per_subset([]<unsigned M>() { return &Simplex::coordinates_reproduce_v_t<M>; });
        return (this->*table[bits & 15u])(rel_sq);
    }
    template <unsigned S>
    bool coordinates_reproduce_v_t(double rel_sq) const {
        Vec3 p{};
        double m = 0, sum = 0;
        for_bits<S>([&](auto ic) {
            constexpr int i = decltype(ic)::value;
            const double l = lambda[i] > 0 ? lambda[i] : 0;
            p += l * y[i];
            sum += l;
            m = norm_sq[i] > m ? norm_sq[i] : m;
        });
        if (!(sum > 0)) return false;
        const Vec3 d = (1 / sum) * p - v;
        return dot(d, d) <= rel_sq * m;
    }

    double max_norm_sq() const {
        double m = 0;
        for (unsigned r = bits; r; r &= r - 1) {
            const int i = std::countr_zero(r);
            m = norm_sq[i] > m ? norm_sq[i] : m;
        }
        return m;
    }

    // Writes v and lambda for subset s. Johnson's determinants choose the subset; v and the
    // barycentric coordinates are then taken from the geometry, with edge vectors formed first:
    // the determinants come from dot products of whole points and lose digits on needles and
    // slivers (two points 1e-5 apart and a third far away), which moves the closest points
    // sideways by far more than the distance's own error. The determinant form stays as the
    // fallback for degenerate geometry.
    template <unsigned S>
    [[gnu::always_inline]] inline void set_from_subset_t() {
        static_assert(S < 16u);
        bits = S;
        constexpr int count = kBitCount[S];
        if constexpr (count == 0) {
            v = Vec3{};
        } else if constexpr (count == 1) {
            constexpr int i = std::countr_zero(S);
            lambda[i] = 1;
            v = y[i];
            return;
        } else {
            // Edge vectors start from the point nearest the origin. Near contact v is short while
            // other points may be far (a rim point across a cylinder): v's rounding error is then a
            // few eps of the near point's norm, not of the far one's, and two long, nearly parallel
            // edges (a far base and two near points) no longer cancel in the triangle's normal.
            if constexpr (count == 2) {
                constexpr int i0 = std::countr_zero(S), j0 = 31 - std::countl_zero(S);
                const bool swap = norm_sq[j0] < norm_sq[i0];
                const int i = swap ? j0 : i0, j = swap ? i0 : j0;
                const Vec3 e = y[j] - y[i];
                const double ee = dot(e, e);
                if (ee > 0 && std::isfinite(ee)) [[likely]] {
                    const double t = -dot(y[i], e) / ee;
                    v = y[i] + t * e;
                    // Near contact (||v|| << ||y_i||) y_i + t e cancels to eps ||y_i|| in every
                    // component; e x (y_i x e) / |e|^2 keeps each one's relative accuracy (a slab's
                    // edge 18 long and 1e-8 thick nearly through the origin: the component along the
                    // edge, 1e-18, is what picks the next support point among the slab's tied corners).
                    if (dot(v, v) < 0x1p-20 * norm_sq[i]) [[unlikely]] v = near_line_point(y[i], e, ee);
                    lambda[i] = 1 - t;
                    lambda[j] = t;
                    return;
                }
            } else if constexpr (count == 3) {
                // The origin projected on the triangle's plane. Besides the coordinates, this keeps
                // v's direction to a few eps when ||v|| << ||y|| (nearly touching parallel faces),
                // so v.w keeps its sign in the separation test. The base is rotated cyclically,
                // which keeps the orientation of n and so the signs of the coordinates.
                constexpr int i0 = std::countr_zero(S), j0 = std::countr_zero(S & (S - 1)),
                              k0 = 31 - std::countl_zero(S);
                int i = i0, j = j0, k = k0;
                if (norm_sq[j0] < norm_sq[i0] && norm_sq[j0] <= norm_sq[k0])
                    i = j0, j = k0, k = i0;
                else if (norm_sq[k0] < norm_sq[i0] && norm_sq[k0] < norm_sq[j0])
                    i = k0, j = i0, k = j0;
                const Vec3 n = cross(y[j] - y[i], y[k] - y[i]);
                const double nn = dot(n, n);
                if (nn > 0 && std::isfinite(nn)) [[likely]] {
                    const double inv = 1 / nn;
                    const Vec3 q = (dot(n, y[i]) * inv) * n;
                    v = q;
                    if (!want_lambda) return;
                    const Vec3 qi = y[i] - q, qj = y[j] - q, qk = y[k] - q;
                    lambda[i] = dot(cross(qj, qk), n) * inv;
                    lambda[j] = dot(cross(qk, qi), n) * inv;
                    lambda[k] = dot(cross(qi, qj), n) * inv;
                    return;
                }
            }
            set_from_determinants(S);
        }
    }

    // The line y0 + t e's point nearest the origin (out of line: the segment case stays small).
    [[gnu::noinline]] static Vec3 near_line_point(Vec3 y0, Vec3 e, double ee) { return (1 / ee) * cross(e, cross(y0, e)); }
    // The determinant form of v and lambda over subset s (degenerate geometry, full simplex).
    [[gnu::noinline]] void set_from_determinants(unsigned s) {
        double sum = 0;
        for (unsigned r = s; r; r &= r - 1) sum += det[s][std::countr_zero(r)];
        Vec3 p{};
        for (unsigned r = s; r; r &= r - 1) {
            const int i = std::countr_zero(r);
            lambda[i] = det[s][i] / sum;
            p += lambda[i] * y[i];
        }
        v = p;
    }

    // set_from_subset_t for a subset known at run time.
    void set_from_subset(unsigned s) {
        static constexpr auto table = per_subset([]<unsigned M>() { return &Simplex::set_from_subset_t<M>; });
        (this->*table[s & 15u])();
    }

    // Goes back to subset `old_bits` of the current points after an add() whose result is not
    // trusted: v (and lambda, if wanted) by the same arithmetic as when it was first found.
    void restore(unsigned old_bits) {
        last_all = old_bits;
        set_from_subset(old_bits);
    }

    // Barycentric coordinates of v over the current simplex, after iterations with want_lambda off
    // (recomputes v by the same arithmetic, so it is unchanged). A full simplex keeps its own.
    void update_lambda() {
        if (bits == 15u || bits == 0) return;
        const bool keep = want_lambda;
        want_lambda = true;
        set_from_subset(bits);
        want_lambda = keep;
    }

    // Closest points on A and B (A's frame) from the barycentric coordinates of v. Coordinates that
    // rounding pushed below zero (ill-conditioned simplices) are clamped, so the points stay convex
    // combinations of support points: on their shapes. One instantiation per subset (the points'
    // loop unrolled); every sum is taken in the order of the slots.
    void closest_points(Vec3& out_a, Vec3& out_b) const {
        static constexpr auto table = per_subset([]<unsigned M>() { return &Simplex::closest_points_t<M>; });
        (this->*table[bits & 15u])(out_a, out_b);
    }
    template <unsigned S>
    void closest_points_t(Vec3& out_a, Vec3& out_b) const {
        double l[4] = {0, 0, 0, 0}, sum = 0;
        for_bits<S>([&](auto ic) {
            constexpr int i = decltype(ic)::value;
            l[i] = lambda[i] > 0 ? lambda[i] : 0;
            sum += l[i];
        });
        if (!(sum > 0)) {
            constexpr int i = std::countr_zero(S | 16u) & 3;
            out_a = pa[i];
            out_b = pb[i];
            return;
        }
        const double inv = 1 / sum;
        Vec3 a{}, b{};
        for_bits<S>([&](auto ic) {
            constexpr int i = decltype(ic)::value;
            a += (l[i] * inv) * pa[i];
            b += (l[i] * inv) * pb[i];
        });
        out_a = a;
        out_b = b;
    }

    enum class Outcome { Reduced, Full, Backup, Failed };

    // Adds w (with its support points) and runs Johnson's sub-algorithm on the new simplex. On
    // Reduced or Backup, v/lambda/bits describe the closest point of the kept sub-simplex; on Full
    // the origin lies in the tetrahedron (lambda are its barycentric coordinates); on Failed
    // nothing usable was found and the previous v/lambda/bits are kept. `prev_norm_sq` is
    // ||v||^2 before the call: the backup pass must improve on it.
    Outcome add(Vec3 w, Vec3 a, Vec3 b, double prev_norm_sq) {
        // One instantiation per current simplex (bits 0..14): every subset loop below is unrolled
        // at compile time.
        const int last = std::countr_zero(~bits & 15u);
        y[last] = w;
        pa[last] = a;
        pb[last] = b;
        static constexpr auto table = per_subset<15>([]<unsigned M>() { return &Simplex::add_from<M>; });
        return (this->*table[bits & 15u])(prev_norm_sq);
    }

    // Calls f(std::integral_constant<int, i>) for each bit i set in the compile-time mask S.
    template <unsigned S, class F>
    static void for_bits(F&& f) {
        [&]<int... I>(std::integer_sequence<int, I...>) {
            ((((S >> I) & 1u) ? f(std::integral_constant<int, I>{}) : void()), ...);
        }
        (std::make_integer_sequence<int, 4>{});
    }

    template <unsigned S>
    void compute_subset_t() {
        Vec3 us{};
        for_bits<S>([&](auto mc) {
            constexpr int m = decltype(mc)::value;
            constexpr unsigned x = S & ~(1u << m);
            constexpr int k = std::countr_zero(x);
            const double d = dot(u[x], y[k] - y[m]);
            det[S][m] = d;
            if constexpr (S != 15u) us += d * y[m];
        });
        if constexpr (S != 15u) u[S] = us;  // no larger subset needs u of the full set
    }

    // Johnson's test for subset S of All; comparisons are written so that NaN fails them.
    template <unsigned S, unsigned All>
    bool valid_t() const {
        bool ok = true;
        for_bits<S>([&](auto mc) { ok = ok && det[S][decltype(mc)::value] > 0; });
        for_bits<All & ~S>([&](auto jc) {
            constexpr int j = decltype(jc)::value;
            ok = ok && det[S | (1u << j)][j] <= 0;
        });
        return ok;
    }

    // A thin tetrahedron that held the origin (thickness()): its signs hold, so the shapes
    // intersect, but its coordinates are poor (contact points off the shapes by eps L / height).
    // The loop goes on with Johnson's proper subsets, as for a flat one, which usually reach
    // contact with accurate points; on a sliver holding the origin deep inside (a box 1e6 long
    // beside a cylinder) none makes progress and the rounding rules end the loop apart: it then
    // takes this tetrahedron back (take_held) for its verdict.
    void hold() {
        held = true;
        held_extent_sq = 0;
        for (int i = 0; i < 4; ++i) {
            held_extent_sq = max_of(held_extent_sq, norm_sq[i]);
            held_y[i] = y[i];
            held_pa[i] = pa[i];
            held_pb[i] = pb[i];
            held_lambda[i] = lambda[i];
        }
    }
    void take_held() {
        for (int i = 0; i < 4; ++i) {
            y[i] = held_y[i];
            pa[i] = held_pa[i];
            pb[i] = held_pb[i];
            lambda[i] = held_lambda[i];
            norm_sq[i] = dot(y[i], y[i]);
        }
        bits = last_all = 15u;
        v = Vec3{};
    }

    // add() with the new point already in slot `last`.
    template <unsigned Old>
    Outcome add_from(double prev_norm_sq) {
        constexpr int last = std::countr_zero(~Old & 15u);
        constexpr unsigned last_bit = 1u << last;
        constexpr unsigned all = Old | last_bit;
        constexpr unsigned n_sub = kSubsets.count[Old];
        const Vec3 w = y[last];
        norm_sq[last] = dot(w, w);
        det[last_bit][last] = 1;
        u[last_bit] = w;
        last_all = all;
        // Determinants of every subset holding the new point, smaller subsets first.
        [&]<size_t... T>(std::index_sequence<T...>) {
            (compute_subset_t<kSubsets.subsets[Old][T + 1] | last_bit>(), ...);
        }
        (std::make_index_sequence<n_sub - 1>{});

        // A full tetrahedron: decide by signed volumes (triple products of edge vectors) rather than
        // by the determinants, which lose every digit on flat tetrahedra and would report an
        // intersection for shapes some distance apart.
        if constexpr (all == 15u) {
            if (origin_in_tetrahedron()) {
                const Thickness t = thickness();
                if (t == Thickness::Solid) {
                    bits = 15u;
                    v = Vec3{};
                    return Outcome::Full;
                }
                if (t == Thickness::Thin) hold();
            }
        }

        // Johnson's test: the closest sub-simplex holds the new point, has positive determinants,
        // and every point left out has a non-positive determinant in the subset grown by it.
        const bool found = [&]<size_t... T>(std::index_sequence<T...>) {
            return (try_subset<kSubsets.subsets[Old][T] | last_bit, all>() || ...);
        }
        (std::make_index_sequence<n_sub>{});
        if (found) return Outcome::Reduced;
        return backup(all, prev_norm_sq);
    }

    template <unsigned S, unsigned All>
    [[gnu::always_inline]] inline bool try_subset() {
        if constexpr (S == 15u) {
            return false;  // decided geometrically
        } else {
            if (!valid_t<S, All>()) return false;
            set_from_subset_t<S>();
            return true;
        }
    }

    // Backup: among all subsets with positive determinants (singletons always qualify), the one
    // whose affine closest point is nearest the origin; it must improve on prev_norm_sq.
    Outcome backup(unsigned all, double prev_norm_sq) {
        double best = prev_norm_sq;
        unsigned best_s = 0;
        for (unsigned s = 1; s < 15u; ++s) {
            if ((s & ~all) != 0) continue;
            bool positive = true;
            double sum = 0;
            for (unsigned r = s; r; r &= r - 1) {
                const double d = det[s][std::countr_zero(r)];
                if (!(d > 0)) positive = false;
                sum += d;
            }
            if (!positive) continue;
            Vec3 p{};
            for (unsigned r = s; r; r &= r - 1) {
                const int i = std::countr_zero(r);
                p += (det[s][i] / sum) * y[i];
            }
            const double n2 = dot(p, p);
            if (n2 < best) {
                best = n2;
                best_s = s;
            }
        }
        if (best_s == 0) return Outcome::Failed;
        set_from_subset(best_s);
        return Outcome::Backup;
    }

    // Johnson's determinants of subset s (|s| >= 2) from those of its subsets, and u_s:
    //   Delta_m(s) = sum_{i in X} Delta_i(X) (y_i.y_k - y_i.y_m) = u_X . (y_k - y_m),
    // X = s \ {m}, k = min X, u_X = sum_{i in X} Delta_i(X) y_i (cached per subset). Taking the
    // edge y_k - y_m before the dot product keeps the digits that the difference of two whole dot
    // products y_i.y_k and y_i.y_m loses when points cluster (curved surfaces near convergence:
    // points 1e-5 apart gave closest points off by 1e-4 relative with the classical form).
    // Recomputes every cached quantity of the points in `all` (after they were moved): the same
    // arithmetic, in the same order, as add() on those points.
    template <unsigned All>
    void recompute_all_t() {
        for_bits<All>([&](auto ic) {
            constexpr int i = decltype(ic)::value;
            norm_sq[i] = dot(y[i], y[i]);
            det[1u << i][i] = 1;
            u[1u << i] = y[i];
        });
        [&]<unsigned... T>(std::integer_sequence<unsigned, T...>) {
            ((std::popcount(kSubsets.subsets[All][T]) >= 2 ? compute_pair_or_more_t<kSubsets.subsets[All][T]>()
                                                         : void()),
             ...);
        }(std::make_integer_sequence<unsigned, kSubsets.count[All]>{});
    }
    template <unsigned S>
    void compute_pair_or_more_t() {
        if constexpr (std::popcount(S) >= 2) compute_subset_t<S>();
    }
    void recompute_all(unsigned all) {
        static constexpr auto table = per_subset([]<unsigned M>() { return &Simplex::recompute_all_t<M>; });
        (this->*table[all & 15u])();
    }

    // How far a tetrahedron's signed volume can be trusted. Flat: thinner than 1e-10 of its
    // longest edge from y0 (|vol| <= 1e-10 L A, A the largest of the faces' parallelograms at y0):
    // the volume may be rounding noise (coplanar support points, common on flat faces, disks and
    // curved rims, whose coordinates carry eps of their distance from the origin; signed volumes of
    // 1e-16 gave "inside" for an origin far outside the points' polygon), and says nothing about
    // whether it holds the origin. Thin: not flat, but |vol| <= 1e-10 |e1||e2||e3|: the signs hold,
    // the barycentric coordinates are poor. The height, not the edges' product, decides flatness:
    // a sliver with nearly parallel long edges (a box 1e6 long beside a cylinder) has a volume far
    // above its noise though far below the product of its edges. Squares only.
    enum class Thickness { Solid, Thin, Flat };
    Thickness thickness() const {
        const Vec3 e1 = y[1] - y[0], e2 = y[2] - y[0], e3 = y[3] - y[0];
        const Vec3 n1 = cross(e2, e3);
        const double vol_sq = dot(e1, n1) * dot(e1, n1);
        const double l1 = dot(e1, e1), l2 = dot(e2, e2), l3 = dot(e3, e3);
        const Vec3 n2 = cross(e3, e1), n3 = cross(e1, e2);
        const double area_sq = max_of(max_of(dot(n1, n1), dot(n2, n2)), dot(n3, n3));
        if (!(vol_sq > 1e-20 * (max_of(max_of(l1, l2), l3) * area_sq))) return Thickness::Flat;
        return vol_sq > 1e-20 * (l1 * l2 * l3) ? Thickness::Solid : Thickness::Thin;
    }
    bool flat_tetrahedron() const { return thickness() == Thickness::Flat; }

    // v within rounding of the origin relative to the support points on A and B, not to the y:
    // each y = a - b carries eps of |a| and |b|. A simplex 1e-3 across about the origin, between
    // shapes of unit size, stopped on a failed sub-simplex 4.4e-16 from it, and the verdict
    // "apart" came out for a needle box 6e-7 deep in a cylinder (one argument order; a hard-input
    // sweep).
    bool touches_at_points_rounding() const {
        double reach_sq = 0;
        for (unsigned q = bits; q; q &= q - 1) {
            const int i = std::countr_zero(q);
            reach_sq = max_of(reach_sq, max_of(dot(pa[i], pa[i]), dot(pb[i], pb[i])));
        }
        return dot(v, v) <= kNearContact * reach_sq;
    }

    // Barycentric coordinates of the origin in the tetrahedron y0..y3 by signed volumes; true when
    // all are >= 0 (the origin inside or on the boundary) and the tetrahedron has volume.
    bool origin_in_tetrahedron() {
        const Vec3 e1 = y[1] - y[0], e2 = y[2] - y[0], e3 = y[3] - y[0];
        const double vol = dot(e1, cross(e2, e3));
        const double v1 = -dot(y[0], cross(e2, e3));
        const double v2 = -dot(e1, cross(y[0], e3));
        const double v3 = -dot(e1, cross(e2, y[0]));
        const double v0 = dot(y[1], cross(y[2], y[3]));
        // Signs first (no division on the common outside case); NaN fails the comparisons.
        if (!(vol > 0 ? (v0 >= 0 && v1 >= 0 && v2 >= 0 && v3 >= 0)
                      : vol < 0 && (v0 <= 0 && v1 <= 0 && v2 <= 0 && v3 <= 0)))
            return false;
        const double sum = v0 + v1 + v2 + v3;
        const double inv = sum != 0 ? 1 / sum : 0;
        lambda[0] = v0 * inv;
        lambda[1] = v1 * inv;
        lambda[2] = v2 * inv;
        lambda[3] = v3 * inv;
        if (inv == 0) lambda[0] = lambda[1] = lambda[2] = lambda[3] = 0.25;
        return true;
    }
};

}  // namespace gjk_detail
}  // namespace kairos
