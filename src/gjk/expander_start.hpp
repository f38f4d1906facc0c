// SPDX-License-Identifier: MIT
// The expansion's start (Expander's build_tetrahedron, from_seed, close_tetrahedron; the class is
// in gjk/expander.hpp, which includes this file after it): the first tetrahedron of support points
// and its working scale, or the depth 0 of a flat C. Include gjk/expander.hpp, not this file.
#pragma once

#include <cmath>

#include "gjk/expander.hpp"
#include "math/math.hpp"

namespace kairos {
namespace epa_detail {

// A tetrahedron of support points, or the depth 0 of a flat C (a point, a segment or a
// polygon: returns NearContact with out.n set). None when the tetrahedron is built.
//
// GJK's tetrahedron when it serves (from_seed); else C's extreme points along the six axes,
// which also set the working scale: the largest of them is brought near 1 (a power of two,
// exact). One support point alone can lie far inside C's extent (a triangle's corner 1e-300
// from the origin scaled the rest of a triangle 4 wide to overflow; found by fuzzing).
template <class Pair, int MaxV, int RankFrom>
Termination Expander<Pair, MaxV, RankFrom>::build_tetrahedron(CoreDepth& out) {
    out.n = normalized_or(hint_, {1, 0, 0});
    if (seed_ != nullptr && seed_->valid && from_seed()) return Termination::None;
    Vertex ext[6];
    double big = 0;
    for (int i = 0; i < 6; ++i) {
        Vec3 d{};
        (i < 2 ? d.x : (i < 4 ? d.y : d.z)) = i % 2 ? -1 : 1;
        ext[i].w = pair_(d, ext[i].a, ext[i].b);
        ++calls_;
        big = std::fmax(big, std::fmax(max_abs(ext[i].a), max_abs(ext[i].b)));
    }
    const double sc = pair_scale({big, 0, 0}, {});
    if (sc != 1) {
        double unused = 0;
        Vec3 a{}, b{};
        adopt_scale(pair_, sc, a, b, unused);
        for (Vertex& x : ext) x.a = sc * x.a, x.b = sc * x.b, x.w = x.a - x.b;
    }
    for (const Vertex& x : ext) size_ = std::fmax(size_, max_abs(x.w));
    // The two extremes farthest apart.
    int i0 = 0, i1 = 1;
    for (int i = 0; i < 6; ++i)
        for (int j = i + 1; j < 6; ++j)
            if (length(ext[j].w - ext[i].w) > length(ext[i1].w - ext[i0].w)) i0 = i, i1 = j;
    const Vec3 e = ext[i1].w - ext[i0].w;
    if (!(length(e) > floor())) {  // C is a point: touching
        flat_ = 0;
        return Termination::NearContact;
    }
    add_vertex(ext[i0]);
    add_vertex(ext[i1]);
    const Vec3 o = ext[i0].w;
    // The extreme farthest from their line, else C's supports across it.
    const Vec3 eu = normalized_or(e, {1, 0, 0});
    auto across = [&](const Vertex& x) {
        const Vec3 off = x.w - o;
        return length(off - dot(off, eu) * eu);
    };
    Vertex far = ext[0];
    for (const Vertex& x : ext)
        if (across(x) > across(far)) far = x;
    const Vec3 p = normalized_or(cross(eu, std::fabs(eu.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}), {0, 0, 1});
    if (!(across(far) > thin())) {
        const Vec3 q = cross(eu, p);
        for (const Vec3& d : {p, -p, q, -q}) {
            Vertex x;
            support(d, x);
            if (across(x) > across(far)) far = x;
        }
    }
    if (!(across(far) > thin())) {  // C is a segment: the normal across it nearest the hint
        // Orthogonalised twice (one pass leaves rounding along eu), and only a hint well off
        // the segment's line counts: a hint along it leaves rounding noise, whose direction is
        // anything (a ball centred on a capsule's segment got an axis along the capsule).
        Vec3 off = hint_ - dot(hint_, eu) * eu;
        off = off - dot(off, eu) * eu;
        out.n = length(off) > 1e-6 * length(hint_) ? normalized_or(off, p) : p;
        flat_ = 1;
        return Termination::NearContact;
    }
    add_vertex(far);
    // The extreme farthest from their plane, else C's supports along its normal.
    const Vec3 m = normalized_or(cross(verts_[1].w - o, verts_[2].w - o), {0, 0, 1});
    Vertex apex = ext[0];
    for (const Vertex& x : ext)
        if (std::fabs(dot(m, x.w - o)) > std::fabs(dot(m, apex.w - o))) apex = x;
    if (!(std::fabs(dot(m, apex.w - o)) > thin())) {
        for (const Vec3& d : {m, -m}) {
            Vertex x;
            support(d, x);
            if (std::fabs(dot(m, x.w - o)) > std::fabs(dot(m, apex.w - o))) apex = x;
        }
    }
    if (!(std::fabs(dot(m, apex.w - o)) > thin())) {  // C is flat: its plane's normal, toward the hint
        out.n = dot(m, hint_) < 0 ? -m : m;
        flat_ = 2;
        return Termination::NearContact;
    }
    add_vertex(apex);
    if (!close_tetrahedron(0)) {  // a sliver: taken as flat, across the first three points' plane
        out.n = dot(m, hint_) < 0 ? -m : m;
        flat_ = 2;
        return Termination::NoProgress;
    }
    return Termination::None;
}

// GJK's tetrahedron as the start, as van den Bergen's and Bullet's expansions do: it saves
// the six axis supports. Taken only at a scale that keeps or shrinks its points (an enlarging
// one needs the axes' bound on C, see first_scale) and when each corner stands clear of the
// opposite face by 1e-6 of its size; else C's axis extremes start (false, nothing kept).
template <class Pair, int MaxV, int RankFrom>
bool Expander<Pair, MaxV, RankFrom>::from_seed() {
    double big = 0;
    for (int i = 0; i < 4; ++i) big = std::fmax(big, std::fmax(max_abs(seed_->a[i]), max_abs(seed_->b[i])));
    const double sc = pair_scale({big, 0, 0}, {});
    if (!(sc <= 1)) return false;
    for (int i = 0; i < 4; ++i) {
        Vertex x;
        x.a = sc * seed_->a[i], x.b = sc * seed_->b[i], x.w = x.a - x.b;
        size_ = std::fmax(size_, max_abs(x.w));
        add_vertex(x);
    }
    if (!(size_ > 0) || !close_tetrahedron(1e-6 * size_)) {
        nv_ = nf_ = 0;
        size_ = 0;
        return false;
    }
    if (sc != 1) {
        double unused = 0;
        Vec3 a{}, b{};
        adopt_scale(pair_, sc, a, b, unused);
    }
    return true;
}

// The four faces of the tetrahedron verts_[0..3], each wound so that the fourth point lies
// behind it (by more than min_height when > 0), and their neighbours. False for a sliver
// (a face without a normal, or faces wound inconsistently by rounding on a tetrahedron too
// thin to orient).
template <class Pair, int MaxV, int RankFrom>
bool Expander<Pair, MaxV, RankFrom>::close_tetrahedron(double min_height) {
    const int tri[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
    for (const auto& t : tri) {
        Plane p;
        int b = t[1], c = t[2];
        bool ok = make_plane(t[0], b, c, p);
        if (ok && dot(p.n, verts_[t[3]].w) > p.off) {
            b = t[2], c = t[1];
            ok = make_plane(t[0], b, c, p);
        }
        if (ok && min_height > 0) ok = p.off - dot(p.n, verts_[t[3]].w) > min_height;
        if (!ok) return false;
        put(nf_++, t[0], b, c, p);
    }
    // Each edge's neighbour: the face holding the reverse edge.
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) {
            const int a = faces_[i].v[k], b = faces_[i].v[(k + 1) % 3];
            int across = -1, back = -1;
            for (int j = 0; j < 4 && across < 0; ++j) {
                const int e = j != i ? edge_index(faces_[j], b, a) : -1;
                if (e >= 0) across = j, back = e;
            }
            if (across < 0) return false;
            faces_[i].adj[k] = int16_t(across);
            faces_[i].back[k] = uint8_t(back);
        }
    interior_ = 0.25 * (verts_[0].w + verts_[1].w + verts_[2].w + verts_[3].w);
    return true;
}

}  // namespace epa_detail
}  // namespace kairos
