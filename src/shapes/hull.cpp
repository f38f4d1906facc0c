// SPDX-License-Identifier: MIT
// Convex hull construction (quickhull on exact orientation signs) and the hull's support mapping.
//
// Construction follows Barber, Dobkin and Huhdanpaa, "The Quickhull Algorithm for Convex Hulls"
// (ACM TOMS 22(4), 1996): start from a tetrahedron of extreme points, keep for every facet the
// points strictly above it (its conflict list), repeatedly add the farthest point of a facet,
// delete the facets it sees, join it to their horizon and hand the orphaned points to the new
// facets. Points left on no conflict list are inside or on the hull.
//
// Robustness: every above/below decision that shapes the mesh is the exact sign of the
// orientation determinant of the (power-of-two rescaled) input doubles: a floating-point filter
// with a forward error bound (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast
// Robust Geometric Predicates", 1997, the orient3d bound) and, when the filter cannot decide, an
// exact evaluation with floating-point expansions. So the horizon is always one simple cycle and
// the mesh always a closed convex triangulation, whatever the input's degeneracies.
//
// Which points are vertices. Facets are triangles; coplanar neighbours may remain. A point is
// a vertex only if the facets around it span at least three distinct planes (a point in the
// relative interior of a polytope's facet lies in one facet plane, one inside an edge in two);
// when some hull points are not, the hull is rebuilt from the others, which changes neither the
// solid nor any support value. Two tolerances relative to the set's extent (the widest side of
// its bounding box), the only ones in this file:
// - kThinTolerance (1e-12; plus 64 ulps of the largest coordinate, the rounding a transform
//   leaves in a set far from the origin): a point is not kept when it lies within that distance
//   of the hull of the kept points: during construction, a point barely above some facet planes
//   but within thin of one of those facets; after it, a point that only looks flat (facet planes
//   bent by less than thin around it, or the tip of a needle facet) and lies within thin of the
//   hull of its neighbours (one such drop per neighbourhood per rebuild, at most 6 rebuilds).
//   Without it, points that rounding left a hair outside a face (the face points of a rotated
//   box) would be kept. The support is within a few thin of the maximum over all input points.
// - kFlatTolerance (1e-10): the set is Collinear when every point lies within it of the line
//   through the two extreme points along the widest axis, and Coplanar when every point lies
//   within it of the plane through that line and the point farthest from it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <vector>

#include "shapes/quickhull.hpp"
#include "shapes/shape.hpp"
#include "shapes/small_hull.hpp"

namespace kairos {

namespace {
// A hull that climbs stores first its vertices extreme along the 26 directions of
// {-1, 0, 1}^3 \ {0} (the "seeds"; fewer when some coincide, then padded with other vertices).
// Its support starts climbing from the best seed, a few edges from the answer.
constexpr size_t kSeedDirections = 26;

// Index of the best of vertices[0, n) for d; strict comparisons: ties and NaN keep the earlier.
size_t best_of(const std::vector<Vec3>& vertices, size_t n, Vec3 d, double& out_score) {
    size_t best = 0;
    out_score = dot(d, vertices[0]);
    for (size_t i = 1; i < n; ++i) {
        const double score = dot(d, vertices[i]);
        if (score > out_score) {
            out_score = score;
            best = i;
        }
    }
    return best;
}
}  // namespace

Vec3 ConvexHullShape::support(Vec3 d) const {
    if (vertices.empty()) return {};
    double best_score = 0;
    if (!soa.empty()) return small_hull::best_point(vertices.data(), soa.data(), vertices.size(), d);
    if (neighbor_offsets.empty()) return vertices[best_of(vertices, vertices.size(), d, best_score)];
    // Steepest ascent over the edge graph: on a convex polytope a vertex with no better
    // neighbour maximises the linear function d.x globally. Scores only increase, so it stops.
    auto current = static_cast<uint32_t>(best_of(vertices, std::min(kSeedDirections, vertices.size()), d, best_score));
    for (;;) {
        uint32_t next = current;
        for (uint32_t k = neighbor_offsets[current]; k < neighbor_offsets[current + 1]; ++k) {
            const uint32_t n = neighbors[k];
            const double score = dot(d, vertices[n]);
            if (score > best_score) {
                best_score = score;
                next = n;
            }
        }
        if (next == current) return vertices[current];
        current = next;
    }
}

namespace {

using namespace hull_detail;

// Relative tolerance of the Collinear / Coplanar tests (see the file comment). 1e-10 is far
// above the rounding of the distance computations (~1e-15 of the extent) and far below any
// shape a caller means as a solid.
constexpr double kFlatTolerance = 1e-10;
// Relative tolerance of "on the hull" (see the file comment): far above rounding (~1e-16 of the
// extent), far below any feature a caller means.
constexpr double kThinTolerance = 1e-12;

// ---- Which hull points are vertices --------------------------------------------------------------

// Splits the points of the mesh `faces` into the vertices to keep and the rest (`all`: every
// point of the mesh), and lists the mesh's edges. Exact part: a point whose incident facets lie
// in fewer than three exact planes (fewer than three non-coplanar edges around it) is not a
// vertex of the polytope: it goes. Thin part: a point that looks flat within `thin` (fewer than
// three edges bent by more than thin, or the apex of a needle facet) goes if it lies within
// thin of the hull of its neighbours: of their fan of triangles when it looks flat all around,
// of the segment between the two bent edges' ends when it looks like it is inside an edge, of
// the needle's long edge for a needle apex. Such a drop moves the hull by at most thin; to keep
// the drops from compounding within a round, a point goes by the thin part only when no
// neighbour goes in the same round.
void select_vertices(const std::vector<Vec3>& p, const std::vector<Face>& faces, double thin, bool keep_all,
                     std::vector<uint32_t>& kept, std::vector<uint32_t>& all,
                     std::vector<std::pair<uint32_t, uint32_t>>& edges) {
    const size_t n = p.size();
    std::vector<uint32_t> exact_bends(n, 0), thin_bends(n, 0), any_face(n, kNone);
    std::vector<std::array<uint32_t, 2>> needle(n, {kNone, kNone});
    // Whether the edge a-b between faces f and g (f holds a -> b) bends: exactly, and by thin.
    const auto bend = [&](const Face& f, const Face& g, uint32_t a, uint32_t b, bool& exact, bool& by_thin) {
        uint32_t opposite = g.v[0];
        for (uint32_t w : g.v)
            if (w != a && w != b) opposite = w;
        const Orientation o = orient(p[f.v[0]], p[f.v[1]], p[f.v[2]], p[opposite]);
        exact = o.sign != 0;
        by_thin = exact && std::fabs(o.value) > thin * length(f.normal);
    };
    edges.clear();
    for (uint32_t fi = 0; fi < faces.size(); ++fi) {
        const Face& f = faces[fi];
        if (!f.alive) continue;
        double longest = -1;
        int apex = 0;
        for (int e = 0; e < 3; ++e) {
            const double l = length_sq(p[f.v[(e + 1) % 3]] - p[f.v[e]]);
            if (l > longest) {
                longest = l;
                apex = (e + 2) % 3;
            }
        }
        if (length(f.normal) <= thin * std::sqrt(longest) && needle[f.v[apex]][0] == kNone)
            needle[f.v[apex]] = {f.v[(apex + 1) % 3], f.v[(apex + 2) % 3]};
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = f.v[e], b = f.v[(e + 1) % 3];
            if (any_face[a] == kNone) any_face[a] = fi;
            if (a > b) continue;  // each edge once, from the face where it runs upward
            edges.emplace_back(a, b);
            bool exact = false, by_thin = false;
            bend(f, faces[f.adj[e]], a, b, exact, by_thin);
            exact_bends[a] += exact;
            exact_bends[b] += exact;
            thin_bends[a] += by_thin;
            thin_bends[b] += by_thin;
        }
    }
    all.clear();
    for (uint32_t i = 0; i < n; ++i)
        if (any_face[i] != kNone) all.push_back(i);
    std::vector<uint8_t> gone(n, 0);
    if (!keep_all) {
        for (uint32_t i : all) gone[i] = exact_bends[i] < 3;
        std::vector<uint32_t> link;
        std::vector<uint8_t> link_bent;
        for (uint32_t i : all) {
            if (gone[i] || (thin_bends[i] >= 3 && needle[i][0] == kNone)) continue;
            // The neighbours in cyclic order around i; link_bent[k]: edge i-link[k] bends by thin.
            link.clear();
            link_bent.clear();
            uint32_t fi = any_face[i];
            do {
                const Face& f = faces[fi];
                int c = 0;
                while (c < 3 && f.v[c] != i) ++c;
                if (c == 3) throw std::logic_error("kairos: hull mesh is not closed around a point");
                const uint32_t next = f.v[(c + 2) % 3];  // f holds next -> i; the face across follows
                const Face& g = faces[f.adj[(c + 2) % 3]];
                bool exact = false, by_thin = false;
                bend(f, g, next, i, exact, by_thin);
                link.push_back(next);
                link_bent.push_back(by_thin);
                fi = f.adj[(c + 2) % 3];
            } while (fi != any_face[i] && link.size() <= faces.size());
            bool neighbour_gone = false;
            for (uint32_t u : link) neighbour_gone |= gone[u] != 0;
            if (neighbour_gone) continue;
            const Vec3 x = p[i];
            double dist = std::numeric_limits<double>::infinity();
            if (needle[i][0] != kNone) {
                dist = point_segment_distance(x, p[needle[i][0]], p[needle[i][1]]);
            } else if (thin_bends[i] == 0) {
                for (size_t k = 1; k + 1 < link.size(); ++k)
                    dist = std::min(dist, point_triangle_distance(x, p[link[0]], p[link[k]], p[link[k + 1]]));
            } else if (thin_bends[i] == 2) {
                uint32_t ends[2] = {kNone, kNone};
                int found = 0;
                for (size_t k = 0; k < link.size(); ++k)
                    if (link_bent[k] && found < 2) ends[found++] = link[k];
                if (found == 2) dist = point_segment_distance(x, p[ends[0]], p[ends[1]]);
            }
            if (dist <= thin) gone[i] = 1;
        }
    }
    kept.clear();
    for (uint32_t i : all)
        if (!gone[i]) kept.push_back(i);
}

}  // namespace

namespace {

// Vertices of the flat convex polygon of the points `ids` (within `thin` of a plane spanned by the
// unit, orthogonal u and w through `origin`), in order around it. Andrew's monotone chain on the
// (rounded) coordinates along u and w with exact turn signs, so the chain is the exact hull of
// those coordinates whatever their order along a nearly straight run (a tolerance in the turn
// test dropped the extreme of such a run when rounding sorted it before its neighbours). Then,
// in rounds, a vertex within thin of the segment between its neighbours goes (the polygon moves
// by at most thin per round; a vertex whose neighbour goes waits for the next round).
std::vector<uint32_t> polygon_vertices(const std::vector<Vec3>& p, const std::vector<uint32_t>& ids, Vec3 origin,
                                       Vec3 u, Vec3 w, double thin) {
    struct Planar {
        double x, y;
        uint32_t id;
    };
    std::vector<Planar> q;
    q.reserve(ids.size());
    for (uint32_t i : ids) q.push_back({dot(p[i] - origin, u), dot(p[i] - origin, w), i});
    std::sort(q.begin(), q.end(), [](const Planar& a, const Planar& b) {
        return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.id < b.id)));
    });
    std::vector<Planar> chain;
    chain.reserve(2 * q.size());
    for (int pass = 0; pass < 2; ++pass) {
        const size_t base = chain.size();
        for (size_t k = 0; k < q.size(); ++k) {
            const Planar& x = pass == 0 ? q[k] : q[q.size() - 1 - k];
            while (chain.size() >= base + 2) {
                const Planar& o = chain[chain.size() - 2];
                const Planar& a = chain.back();
                if (orient2d(o.x, o.y, a.x, a.y, x.x, x.y) > 0) break;
                chain.pop_back();
            }
            chain.push_back(x);
        }
        chain.pop_back();  // the last point of each half starts the other
    }
    // A point repeated (or the whole set one point in these coordinates) leaves a chain of one
    // or two; the caller classified the set as flat, so at least three distinct points exist.
    std::vector<uint8_t> gone(chain.size(), 0);
    for (int round = 0; round < 6 && chain.size() > 3; ++round) {
        const size_t n = chain.size();
        size_t left = n;
        std::fill(gone.begin(), gone.begin() + static_cast<std::ptrdiff_t>(n), 0);
        for (size_t k = 0; k < n && left > 3; ++k) {
            const size_t before = (k + n - 1) % n, after = (k + 1) % n;
            if (gone[before] || gone[after]) continue;
            const Planar &a = chain[before], &x = chain[k], &b = chain[after];
            const double bx = b.x - a.x, by = b.y - a.y, len2 = bx * bx + by * by;
            const double t = len2 > 0 ? std::clamp(((x.x - a.x) * bx + (x.y - a.y) * by) / len2, 0.0, 1.0) : 0.0;
            if (std::hypot(x.x - (a.x + t * bx), x.y - (a.y + t * by)) <= thin) {
                gone[k] = 1;
                --left;
            }
        }
        if (left == n) break;
        size_t kept = 0;
        for (size_t k = 0; k < n; ++k)
            if (!gone[k]) chain[kept++] = chain[k];
        chain.resize(kept);
    }
    std::vector<uint32_t> out;
    out.reserve(chain.size());
    for (const Planar& x : chain) out.push_back(x.id);
    return out;
}

// Hull edges of the solid hull of `ids` by quickhull (see the file comment), with the vertices in
// `hull_vertices`. Throws std::logic_error when the mesh comes out inconsistent.
void solid_hull(const std::vector<Vec3>& p, std::vector<uint32_t> ids, std::array<uint32_t, 4> tetra, double thin,
                std::vector<uint32_t>& hull_vertices, std::vector<std::pair<uint32_t, uint32_t>>& edges) {
    for (int attempt = 0;; ++attempt) {
        Quickhull qh(p, thin);
        qh.build(ids, tetra);
        // Dropping a vertex can leave a neighbour on a flat spot, hence the rounds; exactly flat
        // spots all go in the first one. The cap is a guard: the last round keeps every vertex.
        std::vector<uint32_t> kept, all;
        select_vertices(p, qh.faces(), thin, attempt == 6, kept, all, edges);
        if (kept.size() == all.size()) {
            hull_vertices = std::move(kept);
            return;
        }
        // The tetrahedron may have used a dropped point: pick a new one among the kept.
        const uint32_t a = kept.empty() ? all[0] : kept[0];
        uint32_t b = a;
        for (uint32_t i : kept)
            if (length_sq(p[i] - p[a]) > length_sq(p[b] - p[a])) b = i;
        double unused = 0;
        const uint32_t c = kept.empty() ? a : farthest_from_line(p, kept, p[a], p[b], unused);
        double unused_det = 0;
        const uint32_t d = kept.empty() ? a : farthest_from_plane(p, kept, a, b, c, unused_det);
        const int side = orient(p[a], p[b], p[c], p[d]).sign;
        if (side == 0) {
            // Dropping removes only points within ~thin of the rest, so a set thicker than
            // kFlatTolerance keeps a tetrahedron; a guard: keep this round's hull whole.
            hull_vertices = std::move(all);
            return;
        }
        ids = std::move(kept);
        tetra = {a, b, c, d};
        if (side > 0) std::swap(tetra[1], tetra[2]);
    }
}

// Packs the chosen vertices (indices into `points`) and, for a climbing hull, the edge graph.
ConvexHullShape* pack_hull(const Vec3* points, size_t count, const std::vector<Vec3>& p,
                           const std::vector<uint32_t>& hull_vertices,
                           const std::vector<std::pair<uint32_t, uint32_t>>& edges, uint8_t dimension);

}  // namespace

HullStatus make_convex_hull(const Vec3* points, size_t count, ConvexHullShape** out_shape) {
    if (count == 0) return HullStatus::Empty;
    for (size_t i = 0; i < count; ++i)
        if (!is_finite(points[i])) return HullStatus::NonFinite;
    if (count >= kNone) throw std::bad_alloc();  // indices are 32-bit

    // Rescale by a power of two (exact) so that products in the predicates cannot overflow.
    double largest = 0;
    for (size_t i = 0; i < count; ++i) largest = std::fmax(largest, max_abs(points[i]));
    int exponent = 0;
    std::frexp(largest, &exponent);
    std::vector<Vec3> p(count);
    for (size_t i = 0; i < count; ++i)
        p[i] = {std::ldexp(points[i].x, -exponent), std::ldexp(points[i].y, -exponent),
                std::ldexp(points[i].z, -exponent)};

    // Extreme points along the widest axis of the bounding box (first index on ties).
    Vec3 lo = p[0], hi = p[0];
    for (const Vec3& x : p) {
        lo = cwise_min(lo, x);
        hi = cwise_max(hi, x);
    }
    const Vec3 size = hi - lo;
    const int axis = size.x >= size.y ? (size.x >= size.z ? 0 : 2) : (size.y >= size.z ? 1 : 2);
    const double extent = size[axis];
    std::vector<uint32_t> hull_vertices;
    std::vector<std::pair<uint32_t, uint32_t>> edges;  // (smaller, larger) per hull edge
    if (!(extent > 0)) {                               // one point, repeated
        hull_vertices = {0};
        *out_shape = pack_hull(points, count, p, hull_vertices, edges, 0);
        return HullStatus::Ok;
    }
    const double tolerance = kFlatTolerance * extent;
    // Plus the rounding a caller's transform leaves in coordinates of this magnitude (64 ulps of
    // the largest): a small box far from the origin has faces only that flat.
    double magnitude = 0;
    for (const Vec3& x : p) magnitude = std::fmax(magnitude, max_abs(x));
    const double thin = kThinTolerance * extent + 64 * std::numeric_limits<double>::epsilon() * magnitude;

    std::vector<uint32_t> ids(count);
    for (size_t i = 0; i < count; ++i) ids[i] = static_cast<uint32_t>(i);
    uint32_t i0 = 0, i1 = 0;
    for (uint32_t i : ids) {
        if (p[i][axis] < p[i0][axis]) i0 = i;
        if (p[i][axis] > p[i1][axis]) i1 = i;
    }
    double line_dist = 0;
    const uint32_t i2 = farthest_from_line(p, ids, p[i0], p[i1], line_dist);
    const Vec3 u = normalized_or(p[i1] - p[i0], {1, 0, 0});
    if (!(line_dist > tolerance)) {
        // A segment: the extreme points along the line.
        uint32_t first = i0, last = i0;
        for (uint32_t i : ids) {
            if (dot(p[i] - p[i0], u) < dot(p[first] - p[i0], u)) first = i;
            if (dot(p[i] - p[i0], u) > dot(p[last] - p[i0], u)) last = i;
        }
        hull_vertices = {std::min(first, last), std::max(first, last)};
        edges = {{hull_vertices[0], hull_vertices[1]}};
        *out_shape = pack_hull(points, count, p, hull_vertices, edges, 1);
        return HullStatus::Ok;
    }
    // The point farthest from the plane of i0, i1, i2, by the orientation determinant (its
    // rounding is relative to the points' own products). A plane normal taken from the rounded
    // cross product would not do: for a nearly collinear triple its direction can be off by
    // eps / sin(angle), enough to pick a point of the plane itself as the farthest.
    const double area2 = length(cross(p[i1] - p[i0], p[i2] - p[i0]));
    double best_det = 0;
    const uint32_t i3 = farthest_from_plane(p, ids, i0, i1, i2, best_det);
    const int s = orient(p[i0], p[i1], p[i2], p[i3]).sign;
    if (s == 0 || !(best_det > tolerance * area2)) {
        // A flat polygon, in the plane through i0 spanned by u and the part of i2 - i0 across u
        // (well defined: i2 is more than kFlatTolerance * extent from the line).
        const Vec3 across = p[i2] - p[i0];
        const Vec3 w = normalized_or(across - dot(across, u) * u, {0, 1, 0});
        hull_vertices = polygon_vertices(p, ids, p[i0], u, w, thin);
        for (size_t k = 0; k < hull_vertices.size(); ++k) {
            const uint32_t a = hull_vertices[k], b = hull_vertices[(k + 1) % hull_vertices.size()];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
        *out_shape = pack_hull(points, count, p, hull_vertices, edges, 2);
        return HullStatus::Ok;
    }
    std::array<uint32_t, 4> tetra{i0, i1, i2, i3};
    if (s > 0) std::swap(tetra[1], tetra[2]);
    try {
        solid_hull(p, std::move(ids), tetra, thin, hull_vertices, edges);
    } catch (const std::logic_error&) {
        // A guard for a mesh that rounding left inconsistent (none known): every input point,
        // with no edge graph, still gives the exact support.
        hull_vertices.resize(count);
        for (size_t i = 0; i < count; ++i) hull_vertices[i] = static_cast<uint32_t>(i);
        edges.clear();
        *out_shape = pack_hull(points, count, p, hull_vertices, edges, 3);
        (*out_shape)->neighbor_offsets.clear();
        (*out_shape)->neighbors.clear();
        return HullStatus::Ok;
    }
    *out_shape = pack_hull(points, count, p, hull_vertices, edges, 3);
    return HullStatus::Ok;
}

HullStatus make_triangle(Vec3 a, Vec3 b, Vec3 c, ConvexHullShape** out_shape) {
    if (!is_finite(a) || !is_finite(b) || !is_finite(c)) return HullStatus::NonFinite;
    const Vec3 pts[3] = {a, b, c};
    ConvexHullShape* hull = nullptr;
    make_convex_hull(pts, 3, &hull);
    std::unique_ptr<ConvexHullShape, void (*)(ConvexHullShape*)> owned(hull, [](ConvexHullShape* h) { h->release(); });
    if (hull->dimension != 2 || hull->vertices.size() != 3) return HullStatus::Collinear;
    *out_shape = owned.release();
    return HullStatus::Ok;
}

namespace {

ConvexHullShape* pack_hull(const Vec3* points, size_t count, const std::vector<Vec3>& p,
                           const std::vector<uint32_t>& hull_vertices,
                           const std::vector<std::pair<uint32_t, uint32_t>>& edges, uint8_t dimension) {
    // Vertex order: input order; a climbing hull puts its seeds first (then input order).
    const bool climbs = hull_vertices.size() > ConvexHullShape::kHillClimbThreshold;
    std::vector<uint32_t> order;
    order.reserve(hull_vertices.size());
    std::vector<uint8_t> placed(count, 0);
    if (climbs) {
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    if (dx == 0 && dy == 0 && dz == 0) continue;
                    const Vec3 dir{double(dx), double(dy), double(dz)};
                    uint32_t best = hull_vertices[0];
                    for (uint32_t i : hull_vertices)
                        if (dot(dir, p[i]) > dot(dir, p[best])) best = i;
                    if (!placed[best]) order.push_back(best);
                    placed[best] = 1;
                }
    }
    for (uint32_t i : hull_vertices)
        if (!placed[i]) order.push_back(i);

    auto shape = std::make_unique<ConvexHullShape>();
    shape->dimension = dimension;
    shape->vertices.reserve(order.size());
    std::vector<uint32_t> index_of(count, kNone);
    for (uint32_t i : order) {
        index_of[i] = static_cast<uint32_t>(shape->vertices.size());
        shape->vertices.push_back(points[i]);
    }
    if (climbs) {
        // Edge graph in compressed rows, neighbours of each vertex in increasing order.
        const size_t nv = hull_vertices.size();
        auto& offsets = shape->neighbor_offsets;
        auto& adjacent = shape->neighbors;
        offsets.assign(nv + 1, 0);
        for (const auto& [a, b] : edges) {
            ++offsets[index_of[a] + 1];
            ++offsets[index_of[b] + 1];
        }
        for (size_t i = 0; i < nv; ++i) offsets[i + 1] += offsets[i];
        adjacent.resize(offsets[nv]);
        std::vector<uint32_t> fill(offsets.begin(), offsets.end() - 1);
        for (const auto& [a, b] : edges) {
            adjacent[fill[index_of[a]]++] = index_of[b];
            adjacent[fill[index_of[b]]++] = index_of[a];
        }
        for (size_t i = 0; i < nv; ++i) std::sort(adjacent.begin() + offsets[i], adjacent.begin() + offsets[i + 1]);
    } else {
        shape->soa = small_hull::layout(shape->vertices);
    }
    return shape.release();
}

}  // namespace

}  // namespace kairos
