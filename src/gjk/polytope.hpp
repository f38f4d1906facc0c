// SPDX-License-Identifier: MIT
// The expanding polytope's data (docs/algorithms.md §2b): its vertices, faces and planes in
// fixed-size arrays, and the depth it answers with. The algorithm is in gjk/expander.hpp.
#pragma once

#include <cmath>
#include <cstdint>

#include "gjk/termination.hpp"
#include "math/math.hpp"

namespace kairos {
namespace epa_detail {

inline constexpr double kEps = 2.220446049250313e-16;
// Vertex capacities: the expansion's usual one (128 steps), and the large one a curved pair's
// expansion goes on in when it used up the usual one (252 steps in all: the most uint8_t indices
// allow).
inline constexpr int kMaxVertices = 4 + 128;
inline constexpr int kMaxVerticesLarge = 256;
inline constexpr int kNearFrom = 24;  // faces from which the expansion keeps its near faces apart
inline constexpr int kRankFrom = 128;  // faces from which it finds them in a heap, not a list

struct Vertex {
    Vec3 w, a, b;  // w = a - b: C's point, A's and B's support points (A's frame, working scale)
};
struct Face {
    uint8_t v[3];  // counter-clockwise seen from outside
    Vec3 n;        // outward unit normal
    // The origin's distance to the triangle once resolved (not its plane: a sliver's plane, tilted
    // by rounding, can pass nearer the origin than any of its points), or the plane's offset
    // n . x when the origin lies beyond it (< 0).
    double d;
    double off;     // n . x for x on the face
    // The triangle's nearest point to the origin as a combination of the corners: on an edge, the
    // weights; inside, the corners' area coordinates, not yet normalised (weights()).
    double l[3];
    bool edge;      // that point is on an edge (the origin's projection falls outside)
    bool resolved;  // d, l and edge are known (see resolve); until then d is the plane's offset
    int16_t adj[3];  // the face across edge k (v[k] -> v[k + 1]), by slot
    uint8_t back[3];  // the index of edge k in face adj[k] (where it runs v[k + 1] -> v[k])
};

// Where the origin's nearest point on face f (corners w0, w1, w2) lies: the area coordinates of
// its projection p = off n, or, when p falls outside the triangle, the nearest point of its edges,
// whose distance (above the plane's) becomes f.d. Done only for faces that come up as the nearest
// (most never do): d can only grow, so a face whose d is resolved and least is the nearest.
[[gnu::always_inline]] inline void resolve_face(Face& f, Vec3 w0, Vec3 w1, Vec3 w2) {
    f.resolved = true;
    const Vec3 w[3] = {w0, w1, w2};
    const Vec3 p = f.off * f.n;
    bool inside = true;
    for (int c = 0; c < 3; ++c) {
        f.l[c] = dot(f.n, cross(w[(c + 1) % 3] - p, w[(c + 2) % 3] - p));
        inside = inside && f.l[c] >= 0;
    }
    f.edge = !(inside || f.off < 0);
    if (!f.edge) return;
    double best = INFINITY;
    for (int c = 0; c < 3; ++c) {
        const Vec3 e = w[(c + 1) % 3] - w[c];
        const double ee = dot(e, e);
        double t = ee > 0 ? -dot(w[c], e) / ee : 0;
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
        const double dist = length(w[c] + t * e);
        if (dist < best) {
            best = dist;
            f.l[c] = 1 - t, f.l[(c + 1) % 3] = t, f.l[(c + 2) % 3] = 0;
        }
    }
    if (best > f.d) f.d = best;
}

// The weights of a resolved face's nearest point (f.l normalised when inside; equal thirds
// when rounding leaves no positive area).
inline void weights(const Face& f, double l[3]) {
    double sum = 0;
    for (int c = 0; c < 3; ++c) sum += (l[c] = f.l[c]);
    if (f.edge) return;
    const double s = sum > 0 ? 1 / sum : 0;
    for (int c = 0; c < 3; ++c) l[c] = sum > 0 ? (l[c] > 0 ? l[c] * s : 0) : 1.0 / 3;
}

// The index k of the edge a -> b of face f (v[k] == a, v[k + 1] == b), or -1.
inline int edge_index(const Face& f, int a, int b) {
    for (int k = 0; k < 3; ++k)
        if (f.v[k] == a && f.v[(k + 1) % 3] == b) return k;
    return -1;
}

struct Plane {
    Vec3 n;
    double off;
};

// Fixed storage whose slots start uninitialised: Vec3 zeroes itself, and zeroing the polytope's
// arrays (30 kB) cost more than the expansion of a box pair. A slot is written before it is read.
template <class T, int N>
class Slots {
public:
    T& operator[](int i) { return slot_[i].t; }
    const T& operator[](int i) const { return slot_[i].t; }

private:
    union Slot {
        T t;
        Slot() {}
    };
    Slot slot_[N];
};

// The cores' depth in A's frame at the caller's scale: a - b = depth * n for the deepest points.
struct CoreDepth {
    double depth = 0;
    Vec3 n, point_a, point_b;
    uint32_t iterations = 0;
    Termination termination = Termination::None;
    bool flat = false;  // C has no interior (or a sliver's): point_a and point_b unset
};

// The least and the second least key among key[index(0 .. n - 1)] (second -1 when n is 1), by selects:
// which face is least is data, and branches on it mispredict.
template <class Keys, class Index>
[[gnu::always_inline]] inline void least_two_keys(const Keys& key, int n, Index index, int& first, int& second) {
    int f1 = index(0), f2 = -1;
    double m1 = key[f1], m2 = INFINITY;
    for (int j = 1; j < n; ++j) {
        const int i = index(j);
        const double k = key[i];
        const bool below1 = k < m1, below2 = k < m2;
        f2 = below1 ? f1 : (below2 ? i : f2);
        m2 = below1 ? m1 : (below2 ? k : m2);
        f1 = below1 ? i : f1;
        m1 = below1 ? k : m1;
    }
    first = f1;
    second = f2;
}

}  // namespace epa_detail
}  // namespace kairos
