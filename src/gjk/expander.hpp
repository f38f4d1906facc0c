// SPDX-License-Identifier: MIT
// The expanding polytope algorithm (van den Bergen's EPA; docs/algorithms.md §2b) on the cores'
// configuration-space obstacle C = A - B, in A's frame, with fixed-size arrays (no allocation):
// the expansion step, its stops and its rounding rules, on the polytope of gjk/polytope.hpp. Used
// by signed_distance (penetration.cpp) only.
#pragma once

#include <cmath>
#include <cstdint>

#include "gjk/gjk.hpp"
#include "gjk/near_ranking.hpp"
#include "gjk/polytope.hpp"
#include "gjk/support_kernels.hpp"
#include "gjk/termination.hpp"
#include "math/math.hpp"

namespace kairos {
namespace epa_detail {

using namespace kernels;

// MaxV: the polytope's vertex capacity (the tetrahedron's 4 and one per expansion step). The
// default one lives on the stack (about 50 kB); the large one only on the heap (penetration.cpp).
// RankFrom: the face count from which the near faces are ranked (keep_near): only in the large
// one, whose arrays are on the heap (tests set it out of reach to compare).
template <class Pair, int MaxV = kMaxVertices, int RankFrom = (MaxV > kMaxVertices ? kRankFrom : 1 << 30)>
class Expander {
    static constexpr int kMaxV = MaxV, kMaxF = 2 * MaxV;
    static constexpr bool kRanks = RankFrom <= kMaxF;
    static_assert(kMaxV <= 256 && kMaxF <= 32767);  // uint8_t vertex and int16_t face indices

public:
    // seed (may be null): GJK's tetrahedron, tried as the start before C's axis extremes.
    Expander(Pair pair, Vec3 hint, uint32_t budget, const HeldTetrahedron* seed = nullptr)
        : pair_(pair), hint_(hint), budget_(budget), seed_(seed) {}
    // Goes on from a smaller expansion that stopped on its guard (MaxIterations), with room for
    // more vertices and `budget` support calls in all (the smaller one's count included): its
    // polytope, scale and bounds are taken over, so none of its calls is made again.
    template <int M, int R>
    Expander(const Expander<Pair, M, R>& from, uint32_t budget)
        : pair_(from.pair_),
          hint_(from.hint_),
          budget_(budget),
          seed_(from.seed_),
          calls_(from.calls_),
          size_(from.size_),
          flat_(from.flat_),
          interior_(from.interior_),
          upper_n_(from.upper_n_),
          upper_x_(from.upper_x_),
          upper_(from.upper_),
          cap_(from.cap_),
          epoch_(from.epoch_),
          listing_(from.listing_),
          n_near_(from.n_near_),
          n_written_(from.n_written_),
          n_free_(from.n_free_),
          nv_(from.nv_),
          nf_(from.nf_) {
        static_assert(M <= MaxV && (kRanks || !Expander<Pair, M, R>::kRanks));
        for (int i = 0; i < nv_; ++i) verts_[i] = from.verts_[i];
        for (int i = 0; i < nf_; ++i) {
            faces_[i] = from.faces_[i], key_[i] = from.key_[i], plane_[i] = from.plane_[i];
            mark_[i] = from.mark_[i], listed_[i] = from.listed_[i];
        }
        for (int i = 0; i < n_free_; ++i) free_[i] = from.free_[i];
        for (int i = 0; i < n_near_; ++i) near_[i] = from.near_[i];
        for (int i = 0; i < n_written_; ++i) written_[i] = from.written_[i];
        if constexpr (kRanks) ranking_.take(from.ranking_, key_, nf_);
    }

    // Whether the near faces were ranked (RankFrom reached).
    bool ranked() const { return ranking_.on(); }

    // A support value of C known before the run (the caller's scale, A's frame): `bound.depth`
    // along the unit bound.n, reached at bound.point_a - bound.point_b. It is taken as the smallest
    // support value seen, so the expansion stops once a face comes within the tolerance of it, and
    // it caps the answer (finish). `bound` must outlive run(); a larger expansion taken over from
    // this one keeps both.
    void bound_from_above(const CoreDepth* bound) { outer_ = bound; }

    CoreDepth run(double tolerance) {
        CoreDepth out;
        if (nv_ == 0) {  // else taken over from a smaller expansion
            out.termination = build_tetrahedron(out);
            if (out.termination != Termination::None) return finish(out);
        }
        if (outer_ != nullptr) take_outer_bound();
        double& upper = upper_;
        for (;;) {
            // The least key among the faces; resolving raises a key, so after a resolve the face
            // is still the least when its key stays at or below the runner-up's, and the
            // runner-up is the least otherwise (a new search only when that one is unresolved).
            int f = least_resolved(false);
            // A least listed key above upper is rounding (docs/algorithms.md §2b): the faces at
            // the depth were listed out a few ulps above it. The least over all faces then.
            if (key_[f] > upper && (n_near_ > 0 || kRanks)) f = least_resolved(true);
            const Face& face = faces_[f];  // expand changes no face when it fails
            if (calls_ >= budget_ || nv_ == kMaxV) return finish(face, Termination::MaxIterations, tolerance, out);
            Vertex x;
            x.w = support(face.n, x);
            const double h = dot(face.n, x.w);
            if (h < upper) upper = h, upper_n_ = face.n, upper_x_ = x;  // depth <= C's support along any unit n
            const double gap = h - face.off;
            // Support point on the face's plane within the rounding of points of C's size.
            if (gap <= floor()) return finish(face, Termination::RepeatedSupport, tolerance, out);
            // The face's own support value first (its axis gives the depth itself, B moved by it
            // along the axis touches A), then the smallest seen, which holds the same for its
            // own axis: both bound the depth from above, the face's key from below.
            if (face.d >= 0 && h - face.d <= tolerance * h)
                return finish(face, Termination::RelativeError, tolerance, out);
            if (face.d >= 0 && upper - face.d <= tolerance * upper)
                return finish_upper(Termination::RelativeError, out);
            // No progress while C reaches beyond the face along its normal (rounding refused the
            // new point): the face's depth has no axis (a ball centred on a cone's rim got one
            // along which the cone reached 1.6e-3 past it); the smallest support value has one.
            if (!expand(x, f))
                return h - face.d > std::fmax(floor(), tolerance * h)
                           ? finish_upper(Termination::NoProgress, out)
                           : finish(face, Termination::NoProgress, tolerance, out);
            if (n_near_ >= 0 || nf_ >= kNearFrom) keep_near(upper);
        }
    }

private:
    // The face of the least key, resolved (its key its distance): among the listed faces, or
    // among all when `all` is set.
    [[gnu::always_inline]] int least_resolved(bool all) {
        const auto every = [](int j) { return j; };
        int f = -1;
        for (;;) {
            int second = -1;
            if (all)
                least_two(nf_, every, f, second);
            else
                least_two(f, second);
            if (faces_[f].resolved) break;
            resolve(faces_[f]);
            const double was = key_[f];
            key_[f] = faces_[f].d;
            if constexpr (kRanks)
                if (ranking_.on()) ranking_.resolved(f, key_[f] != was, key_);
            if (second < 0 || key_[f] <= key_[second]) break;
            f = second;
            if (faces_[f].resolved) break;
        }
        return f;
    }

    // The faces of the least and the second least key (second -1 with one face): among near_
    // when it is kept, else among all. Written with selects, not branches: which face holds the
    // least is data, and branches on it mispredict.
    void least_two(int& first, int& second) {
        if constexpr (kRanks)
            if (ranking_.on()) {
                if (!ranking_.empty() && ranking_.least_two(key_, first, second)) return;
                return least_two(nf_, [](int j) { return j; }, first, second);
            }
        if (n_near_ > 0)
            least_two(n_near_, [&](int j) { return int(near_[j]); }, first, second);
        else  // all faces: a small polytope, or none at most upper (rounding)
            least_two(nf_, [](int j) { return j; }, first, second);
    }
    template <class Index>
    [[gnu::always_inline]] void least_two(int n, Index index, int& first, int& second) const {
        least_two_keys(key_, n, index, first, second);
    }

    // near_, kept once the polytope has kNearFrom faces: the faces whose key is at most upper
    // (C's smallest support value seen), the only ones that can still come up as the least. A
    // face's key only grows, and the least key is at most the depth, itself at most upper: a face
    // above it is never needed, and most faces of a deep overlap lie there (C's far side). On a
    // small polytope the list costs more than the scan it saves; on a large one, from RankFrom
    // faces, the scans over it: they are ranked instead (gjk/near_ranking.hpp).
    //
    // After an expansion: the new faces (written_) replace the visible ones in their slots;
    // listed_ marks them so that no slot is listed twice.
    void keep_near(double upper) {
        if constexpr (kRanks)
            if (ranking_.on()) return ranking_.step_end(key_, nf_, upper);
        int k = 0;
        if (n_near_ < 0) {  // the first time: every face
            for (int i = 0; i < nf_; ++i) {
                listed_[i] = 0;
                if (key_[i] <= upper) near_[k++] = int16_t(i);
            }
            n_near_ = k;
            return;
        }
        ++listing_;
        for (int w = 0; w < n_written_; ++w) listed_[written_[w]] = listing_;
        for (int j = 0; j < n_near_; ++j) {  // selects: which faces stay is data
            const int i = near_[j];
            near_[k] = int16_t(i);
            k += listed_[i] != listing_ && key_[i] <= upper;
        }
        for (int w = 0; w < n_written_; ++w) {
            near_[k] = written_[w];
            k += key_[written_[w]] <= upper;
        }
        n_near_ = k;
        if constexpr (kRanks)
            if (nf_ >= RankFrom) ranking_.start(key_, nf_, near_, n_near_, upper);
    }

    // C's support point along d at the working scale (set by build_tetrahedron).
    [[gnu::always_inline]] Vec3 support(Vec3 d, Vertex& x) {
        ++calls_;
        const Vec3 w = pair_(d, x.a, x.b);
        x.w = w;
        // Plain selects (maxsd), not max_abs's NaN tests: a NaN coordinate leaves size_ as it is.
        const double ax = std::fabs(w.x), ay = std::fabs(w.y), az = std::fabs(w.z);
        size_ = ax > size_ ? ax : size_;
        size_ = ay > size_ ? ay : size_;
        size_ = az > size_ ? az : size_;
        return w;
    }
    // Rounding of a support value or a face offset of points of C's size.
    double floor() const { return 64 * kEps * size_; }
    // C thinner than this across its line or plane is taken as a segment or a polygon (depth 0,
    // off by at most this): a needle or a plate 1e-9 of its size thick makes a sliver tetrahedron
    // whose faces' normals rounding turns along the needle (a depth along it, found by fuzzing).
    double thin() const { return 1e-9 * size_; }

    int add_vertex(const Vertex& x) {
        verts_[nv_] = x;
        return nv_++;
    }

    // The plane of the triangle i, j, k (normal by that winding; offset at the corners' mean):
    // false when its normal is not defined to rounding (a sliver).
    [[gnu::always_inline]] bool make_plane(int i, int j, int k, Plane& p) const {
        const Vec3 &wi = verts_[i].w, &wj = verts_[j].w, &wk = verts_[k].w;
        const Vec3 e1 = wj - wi, e2 = wk - wi;
        const Vec3 n = cross(e1, e2);
        const double nn = dot(n, n);
        if (!(nn > (64 * kEps) * (64 * kEps) * dot(e1, e1) * dot(e2, e2))) return false;
        p.n = (1 / std::sqrt(nn)) * n;
        p.off = dot(p.n, wi + wj + wk) * (1.0 / 3);
        return true;
    }

    // Face f's nearest point to the origin (resolve_face, gjk/polytope.hpp).
    [[gnu::always_inline]] void resolve(Face& f) const {
        resolve_face(f, verts_[f.v[0]].w, verts_[f.v[1]].w, verts_[f.v[2]].w);
    }

    // The point of face f's corners (C's, A's or B's: part) with weights l.
    Vec3 combine(const Face& f, const double l[3], Vec3 Vertex::*part) const {
        return l[0] * (verts_[f.v[0]].*part) + l[1] * (verts_[f.v[1]].*part) + l[2] * (verts_[f.v[2]].*part);
    }

    // The start (gjk/expander_start.hpp): a tetrahedron of support points, or the depth 0 of a flat C.
    [[gnu::noinline]] Termination build_tetrahedron(CoreDepth& out);
    [[gnu::noinline]] bool from_seed();
    [[gnu::noinline]] bool close_tetrahedron(double min_height);

    // Adds x: removes the faces that see it and closes the hole with faces from the horizon to x.
    // Nothing changes (false) when rounding makes the hole other than a single cycle of edges,
    // or a new face a sliver or facing inward.
    //
    // Faces x lies on within rounding are where that happens (the hole pinched at a vertex whose
    // faces are nearly coplanar): so the faces are taken as seeing x beyond a margin of a few
    // roundings, and when that fails, with the faces x lies on included, then stricter.
    bool expand(const Vertex& x, int seed) {
        for (double margin : {1.0, -1.0, 16.0, -16.0})
            if (expand(x, seed, margin * floor())) return true;
        return false;
    }
    // The visible faces are the seed's connected region of faces that see x (a walk over the
    // faces' neighbours, as in van den Bergen's and Bullet's expansions): it costs the region and
    // its rim, not every face. Its rim is the horizon.
    bool expand(const Vertex& x, int seed, double margin) {
        if (!(dot(plane_[seed].n, x.w) - plane_[seed].off > margin)) return false;
        ++epoch_;
        int vis[kMaxF];  // the faces that see x
        int n_visible = 0;
        int stack[kMaxF];
        int top = 0;
        int from[kMaxV], to[kMaxV], outside[kMaxV], outside_edge[kMaxV];
        int nh = 0;
        mark_[seed] = epoch_ * 2 + 1;
        stack[top++] = seed;
        while (top > 0) {
            const int fi = stack[--top];
            vis[n_visible++] = fi;
            const Face& f = faces_[fi];
            for (int k = 0; k < 3; ++k) {
                const int g = f.adj[k];
                if (mark_[g] < epoch_ * 2) {  // not tested in this expansion
                    const bool sees = dot(plane_[g].n, x.w) - plane_[g].off > margin;
                    mark_[g] = epoch_ * 2 + (sees ? 1 : 0);
                    if (sees) {
                        stack[top++] = g;
                        continue;
                    }
                }
                if (mark_[g] == epoch_ * 2 + 1) continue;  // shared with another visible face
                if (nh == kMaxV) return false;
                from[nh] = f.v[k], to[nh] = f.v[(k + 1) % 3], outside[nh] = g, outside_edge[nh] = f.back[k], ++nh;
            }
        }
        // One cycle: every vertex starts at most one edge, and following them visits them all.
        if (nh < 3 || n_free_ + n_visible + (kMaxF - nf_) < nh) return false;
        int start_of[kMaxV], end_of[kMaxV];  // the horizon edge leaving / reaching a vertex
        for (int i = 0; i < nh; ++i) start_of[from[i]] = start_of[to[i]] = end_of[from[i]] = end_of[to[i]] = -1;
        for (int i = 0; i < nh; ++i) {
            if (start_of[from[i]] != -1 || end_of[to[i]] != -1) return false;
            start_of[from[i]] = i, end_of[to[i]] = i;
        }
        for (int i = 0; i < nh; ++i)  // every edge's end starts an edge
            if (start_of[to[i]] < 0) return false;
        int at = 0, steps = 0;
        do {
            at = start_of[to[at]];
            ++steps;
        } while (at != 0 && steps <= nh);
        if (at != 0 || steps != nh) return false;
        // The new faces, checked before anything changes.
        const int xi = nv_;
        verts_[xi] = x;
        Slots<Plane, kMaxV> fresh;
        for (int i = 0; i < nh; ++i) {
            if (!make_plane(from[i], to[i], xi, fresh[i])) return false;
            if (!(dot(fresh[i].n, interior_) < fresh[i].off)) return false;
        }
        ++nv_;
        // The new faces take the visible faces' slots, then freed ones, then the end. A visible
        // region with vertices inside it (they leave the polytope) has fewer rim edges than faces
        // (n + 2 - 2 i for n faces around i inner vertices): its slots left over are freed.
        int slot[kMaxV];
        for (int i = 0; i < nh; ++i) slot[i] = i < n_visible ? vis[i] : (n_free_ > 0 ? free_[--n_free_] : nf_++);
        for (int h = nh; h < n_visible; ++h) {
            free_[n_free_++] = vis[h];
            key_[vis[h]] = INFINITY;
            faces_[vis[h]].resolved = true;
        }
        for (int i = 0; i < nh; ++i) put(slot[i], from[i], to[i], xi, fresh[i]);
        for (int i = 0; i < nh; ++i) {
            Face& f = faces_[slot[i]];
            f.adj[0] = int16_t(outside[i]);
            f.adj[1] = int16_t(slot[start_of[to[i]]]);  // across to -> x: the new face leaving `to`
            f.adj[2] = int16_t(slot[end_of[from[i]]]);  // across x -> from: the one reaching `from`
            f.back[0] = uint8_t(outside_edge[i]), f.back[1] = 2, f.back[2] = 1;
            Face& g = faces_[outside[i]];
            g.adj[outside_edge[i]] = int16_t(slot[i]);
            g.back[outside_edge[i]] = 0;
        }
        for (int i = 0; i < nh; ++i) written_[i] = int16_t(slot[i]);
        n_written_ = nh;
        return true;
    }
    template <class, int, int>
    friend class Expander;

    // Slot s: the face i, j, k on plane p, unresolved; its neighbours are set by the caller.
    void put(int s, int i, int j, int k, const Plane& p) {
        Face& f = faces_[s];
        f.v[0] = uint8_t(i), f.v[1] = uint8_t(j), f.v[2] = uint8_t(k);
        f.n = p.n;
        f.d = f.off = p.off;
        f.resolved = false;
        mark_[s] = 0;
        key_[s] = p.off;
        plane_[s] = p;
        if constexpr (kRanks) ranking_.put(s, key_);
    }

    // The caller's bound (bound_from_above) at the working scale (a power of two: exact), when
    // below every support value seen.
    void take_outer_bound() {
        const double sc = pair_.scale, u = sc * outer_->depth;
        if (std::isfinite(u)) cap_ = u;
        if (u < upper_ && std::isfinite(u)) {
            upper_ = u;
            upper_n_ = outer_->n;
            upper_x_.a = sc * outer_->point_a;
            upper_x_.b = sc * outer_->point_b;
            upper_x_.w = upper_x_.a - upper_x_.b;
        }
        outer_ = nullptr;
    }

    // The smallest support value seen and its axis: an upper bound of the depth (B moved by it
    // along upper_n_ no longer overlaps), exact along that axis.
    [[gnu::noinline]] CoreDepth finish_upper(Termination t, CoreDepth& out) {
        const double u = dot(upper_n_, upper_x_.w);
        out.depth = u > 0 ? u : 0;
        out.n = upper_n_;
        out.point_a = upper_x_.a;
        out.point_b = upper_x_.a - out.depth * upper_n_;
        out.termination = t;
        return finish(out);
    }
    // The nearest face's nearest point to the origin, as a combination of its corners. On an
    // edge, the axis reported is the direction to that point, not the face's normal, which the
    // stopping rules tested: a support call checks it (but not at the guard, whose depth is a
    // bound). Should C reach farther along it than the depth (a cone 1e4 times wider than thick,
    // by 1.2 % of the depth, in one argument order; a ball centred on a hull's apex, by 13 times:
    // found by fuzzing), the smaller of its support value and the smallest seen is reported with
    // its axis (each bounds the depth from above, exactly along its axis). A point within
    // rounding of the origin has no direction: the face's normal then.
    [[gnu::noinline]] CoreDepth finish(const Face& f, Termination t, double tolerance, CoreDepth& out) {
        // Stopped by rounding before the polytope held the origin: the smallest support value
        // seen. Stopped by the guard there: depth 0 at the nearest face, as with no value seen. A
        // guard-stopped depth is a bound from below (never deeper than the shapes overlap along
        // any axis); the smallest support value bounds it from above, and was 3.8e-6 too deep for
        // a point 1.9e-6 inside a ball of radius 2.7e-3 at 16 support calls (fuzzing).
        const bool seen = dot(upper_n_, upper_n_) > 0;
        if (f.d < 0 && seen && t != Termination::MaxIterations) return finish_upper(t, out);
        // A face deeper than the caller's bound by more than the tolerance: only rounding puts a
        // lower bound above an upper one (sliver faces of a segment in a solid passed it by
        // 1.6e-12 to 2.2e-9 of the depth). The depth then lies between the polytope's other bounds
        // and the smallest support value seen, which has its axis: a bound, reported as a rounding
        // stop, or the guard's. (Not applied to the expansion's own support values: answers
        // within rounding of them far from the origin, where that rounding exceeds floor(), would
        // change.)
        if (f.d > 0 && !(f.d <= cap_ * (1 + tolerance)))
            return finish_upper(t == Termination::MaxIterations ? t : Termination::NoProgress, out);
        double l[3];
        weights(f, l);
        out.point_a = combine(f, l, &Vertex::a);
        out.point_b = combine(f, l, &Vertex::b);
        out.depth = f.d > 0 ? f.d : 0;
        out.n = f.n;
        out.termination = t;
        // The origin still beyond the polytope (the guard, with no support value seen): depth 0 at
        // one point of the nearest face, whose two parts stand for the common point.
        if (!(f.d > 0)) out.point_b = out.point_a;
        const Vec3 q = combine(f, l, &Vertex::w);
        if (!f.edge || !(length(q) > floor())) return finish(out);
        out.n = normalized_or(q, f.n);  // so that a - b = depth n holds
        if (t == Termination::MaxIterations) return finish(out);
        if (calls_ >= budget_) return seen ? finish_upper(t, out) : finish(out);
        Vertex y;
        const double hq = dot(out.n, support(out.n, y));
        if (hq - f.d <= std::fmax(floor(), tolerance * hq)) return finish(out);
        if (seen && upper_ <= hq) return finish_upper(t, out);
        out.depth = hq;
        out.point_a = y.a;
        out.point_b = y.a - hq * out.n;
        return finish(out);
    }
    // Back to the caller's scale. A flat C has depth 0; its deepest points are a common point of
    // the cores, which the caller has from GJK (flat set).
    CoreDepth finish(CoreDepth& out) {
        if (flat_ >= 0) {
            out.depth = 0;
            out.flat = true;
        }
        const double inv = 1 / pair_.scale;
        out.depth *= inv;
        out.point_a = inv * out.point_a;
        out.point_b = inv * out.point_b;
        out.iterations = calls_;
        return out;
    }

    Pair pair_;
    Vec3 hint_;
    uint32_t budget_;
    const HeldTetrahedron* seed_;
    uint32_t calls_ = 0;
    double size_ = 0;
    int flat_ = -1;  // the dimension of a flat C (0, 1, 2), or -1
    Vec3 interior_;
    Vec3 upper_n_;
    Vertex upper_x_;
    double upper_ = INFINITY;  // the smallest support value of C along a unit direction (upper_n_)
    const CoreDepth* outer_ = nullptr;  // bound_from_above's, until run() takes it
    double cap_ = INFINITY;             // its depth at the working scale, once taken
    Slots<Vertex, kMaxV> verts_;
    // Face i, its ranking distance (faces_[i].d) and its plane, kept apart so that the scans
    // over every face read them contiguously.
    Slots<Face, kMaxF> faces_;
    Slots<double, kMaxF> key_;
    Slots<Plane, kMaxF> plane_;
    // mark_[i] == 2 epoch_ + 1: face i sees the point being added; 2 epoch_: it does not.
    Slots<uint32_t, kMaxF> mark_;
    uint32_t epoch_ = 0;
    int free_[kMaxF];  // slots of faces that left the polytope (key_ INFINITY, never reached)
    int16_t near_[kMaxF];        // the faces that can come up as the least (keep_near)
    int16_t written_[kMaxV];  // the slots the last expansion wrote
    uint32_t listed_[kMaxF];     // == listing_: written by the last expansion
    uint32_t listing_ = 0;
    int n_near_ = -1, n_written_ = 0;  // n_near_ -1: near_ not kept yet
    NearRanking<kRanks ? kMaxF : 1> ranking_;  // from RankFrom faces on
    int n_free_ = 0;
    int nv_ = 0, nf_ = 0;
};

}  // namespace epa_detail
}  // namespace kairos

#include "gjk/expander_start.hpp"  // the out-of-class definitions of the start
