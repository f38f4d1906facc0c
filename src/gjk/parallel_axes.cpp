// SPDX-License-Identifier: MIT
// Distance of cores with parallel axes from their axial sections (parallel_axes.hpp).
#include "gjk/parallel_axes.hpp"

#include <cmath>
#include <limits>

#include "gjk/closed_forms.hpp"

namespace kairos::gjk_detail {

using kernels::Core;
using kernels::CoreOf;

bool axial_pair(const CoreOf& ca, const CoreOf& cb) {
    const auto axial = [](const CoreOf& c) { return c.core == Core::Revolution || c.core == Core::Segment; };
    return axial(ca) && axial(cb) && (ca.core == Core::Revolution || cb.core == Core::Revolution);
}

int axial_section(const CoreOf& c, double (&x)[4], double (&z)[4]) {
    if (c.core == Core::Segment) {
        const double h = kernels::segment_half_length(*c.shape);
        x[0] = x[1] = 0, z[0] = -h, z[1] = h;
        return 2;
    }
    const closed_form::Revolution v = closed_form::revolution_of(*c.shape);
    const double r = v.radius, h = v.half_height;
    x[0] = -r, z[0] = -h, x[1] = r, z[1] = -h;
    if (v.cone) {
        x[2] = 0, z[2] = h;
        return 3;
    }
    x[2] = r, z[2] = h, x[3] = -r, z[3] = h;
    return 4;
}

namespace {

// A core's reach from its origin: the farthest corner of its section (squares where they neither
// overflow nor underflow, hypot's slower care outside).
double reach(const CoreOf& c) {
    if (c.core == Core::Segment) return kernels::segment_half_length(*c.shape);
    const closed_form::Revolution v = closed_form::revolution_of(*c.shape);
    const double m = std::fmax(v.radius, v.half_height);
    if (m > 0x1p-500 && m < 0x1p500) return std::sqrt(v.radius * v.radius + v.half_height * v.half_height);
    return std::hypot(v.radius, v.half_height);
}

// How far from parallel two axial cores' axes are, against the poses' rounding.
struct AxesTurn {
    double reach_a, reach_b;
    Vec3 axis_b;  // B's axis in A's frame
    // Turning B about its centre by the angle between the axes (at most pi/2 times the sine, the
    // axis's part across A's; or the one and the other reversed) moves its support values by at
    // most this.
    double bound;
    // The rounding the poses carry: 64 ulps of their coordinates and of the reaches (no method's
    // answer is nearer). Infinite (an overflowed reach or pose) is never within it.
    double noise;
    bool within_rounding() const { return 2 * bound <= noise && noise < INFINITY; }
};

AxesTurn axes_turn(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb, const Transform& pose_b) {
    AxesTurn w;
    w.reach_a = reach(ca), w.reach_b = reach(cb);
    w.axis_b = pose_a.to_local_direction(pose_b.rotation.col(2));
    w.bound = 1.5708 * std::sqrt(w.axis_b.x * w.axis_b.x + w.axis_b.y * w.axis_b.y) * w.reach_b;
    w.noise = 64 * std::numeric_limits<double>::epsilon() *
              (w.reach_a + w.reach_b + max_abs(pose_a.translation) + max_abs(pose_b.translation));
    return w;
}

struct P2 {
    double x, z;
};

// A polygon's edge from a to a + e, with |e|^2 and its reciprocal (0 for a point).
struct Edge {
    P2 a, e;
    double ee, inv;
};

// The squared distance from p to an edge (from p's offset across the edge's line within it).
double distance_sq(const Edge& g, P2 p) {
    const double dx = p.x - g.a.x, dz = p.z - g.a.z, along = dx * g.e.x + dz * g.e.z;
    if (!(along > 0)) return dx * dx + dz * dz;
    if (!(along < g.ee)) {
        const double fx = dx - g.e.x, fz = dz - g.e.z;
        return fx * fx + fz * fz;
    }
    const double c = g.e.x * dz - g.e.z * dx;
    return c * c * g.inv;
}

// Where the nearest point of an edge to p lies: 0 at the start, 1 within, 2 at the end.
int nearest_part(const Edge& g, P2 p) {
    const double along = (p.x - g.a.x) * g.e.x + (p.z - g.a.z) * g.e.z;
    return !(along > 0) ? 0 : (!(along < g.ee) ? 2 : 1);
}

// The unit direction across A's axis toward the offset t's part across it (A's frame), or x when
// that part is zero. From t / max|t_i| (closed_form::unit_of): dividing by its length loses the
// digits of a part whose squares underflow (an offset of 5e-324 on x and y gave (1 1 0), and a depth
// along it 1.41 times too deep; fuzz_queries).
Vec3 plane_direction(Vec3 t) {
    const Vec3 across{t.x, t.y, 0};
    return max_abs(across) > 0 ? closed_form::unit_of(across) : Vec3{1, 0, 0};
}

}  // namespace

bool parallel_axes_distance(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb, const Transform& pose_b,
                            double tolerance, LocalDistance& out, Vec3& center_offset) {
    if (!axial_pair(ca, cb)) return false;
    // Most pairs are not parallel, and leave here. Parallel means within the poses' rounding: B's
    // point is then on B to rounding and the distance an upper bound, as the loop's. (Within the
    // tolerance of the distance, as the depth's closed form takes it, B's point could lie off a
    // turned B: a needle beside a cone 4141 wide at tolerance 0.25 was reported 3 % below a gap its
    // own supports proved; fuzz_queries.)
    const AxesTurn w = axes_turn(ca, pose_a, cb, pose_b);
    if (!w.within_rounding()) return false;
    const double reach_a = w.reach_a, reach_b = w.reach_b, noise = w.noise;
    const Vec3 axis_b = w.axis_b;
    const Vec3 t = pose_a.to_local_direction(pose_b.translation - pose_a.translation);
    // The plane is worked in at a power of two (exact) that brings the pair's extent to about 1,
    // where squares neither overflow nor underflow; a core below 2^-100 of that (its squares
    // would) is left to the loop.
    const double extent = reach_a + reach_b + max_abs(t);
    if (!(extent > 0) || !std::isfinite(extent) || !(std::fmin(reach_a, reach_b) >= 0x1p-100 * extent)) return false;
    const double sc = unit_scale(extent);
    double xa[4], za[4], xb[4], zb[4];
    const int na = axial_section(ca, xa, za), nb = axial_section(cb, xb, zb);
    // The plane through both axes: x toward B's axis, from A's; any through A's when they coincide.
    const Vec3 ts = sc * t;
    const Vec3 e = plane_direction(ts);
    const double off = ts.x * e.x + ts.y * e.y;
    const double flip = axis_b.z < 0 ? -1.0 : 1.0;
    P2 a[4], b[4];
    for (int k = 0; k < na; ++k) a[k] = {sc * xa[k], sc * za[k]};
    for (int k = 0; k < nb; ++k) b[k] = {sc * xb[k] + off, sc * flip * zb[k] + ts.z};
    // The sections' closest points: between two convex polygons apart, a corner of one and the
    // nearest point of an edge of the other, compared by squares (the coordinates are within
    // 2^+-100 of 1: checked above). n: from A's section toward B's.
    Edge ea[4], eb[4];
    for (int pass = 0; pass < 2; ++pass) {
        const P2* p = pass == 0 ? a : b;
        Edge* g = pass == 0 ? ea : eb;
        const int count = pass == 0 ? na : nb;
        for (int k = 0; k < count; ++k) {
            const P2 q = p[(k + 1) % count];
            g[k].a = p[k];
            g[k].e = {q.x - p[k].x, q.z - p[k].z};
            g[k].ee = g[k].e.x * g[k].e.x + g[k].e.z * g[k].e.z;
            g[k].inv = g[k].ee > 0 ? 1 / g[k].ee : 0;
        }
    }
    double best_sq = INFINITY;
    P2 corner{};
    const Edge* edge = nullptr;
    bool of_a = true;
    for (int pass = 0; pass < 2; ++pass) {
        const P2* corners = pass == 0 ? a : b;
        const Edge* edges = pass == 0 ? eb : ea;
        const int nc = pass == 0 ? na : nb, ne = pass == 0 ? nb : na;
        for (int i = 0; i < nc; ++i)
            for (int j = 0; j < ne; ++j) {
                const double d = distance_sq(edges[j], corners[i]);
                if (d < best_sq) best_sq = d, corner = corners[i], edge = &edges[j], of_a = pass == 0;
            }
    }
    if (edge == nullptr) return false;
    // Within the edge: its line's normal and the corner's offset from the line (the difference of
    // the corner and its foot would tilt by rounding over a gap 1e-12 of the size: 1e-4 rad).
    double best;
    P2 n;
    const int at_edge = nearest_part(*edge, corner);
    if (at_edge == 1) {
        const double len = std::sqrt(edge->ee);
        n = {edge->e.z / len, -edge->e.x / len};
        best = n.x * (edge->a.x - corner.x) + n.z * (edge->a.z - corner.z);
        if (best < 0) best = -best, n = {-n.x, -n.z};
    } else {
        const P2 q = at_edge == 0 ? edge->a : P2{edge->a.x + edge->e.x, edge->a.z + edge->e.z};
        best = std::sqrt((q.x - corner.x) * (q.x - corner.x) + (q.z - corner.z) * (q.z - corner.z));
        n = best > 0 ? P2{(q.x - corner.x) / best, (q.z - corner.z) / best} : P2{0, 0};
    }
    best /= sc;
    corner = {corner.x / sc, corner.z / sc};
    // Overlapping or touching within rounding: the loop's rules decide.
    if (!(best > noise) || !std::isfinite(best)) return false;
    if (!of_a) n = {-n.x, -n.z};
    const Vec3 unit = n.x * e + Vec3{0, 0, n.z};
    const Vec3 at = corner.x * e + Vec3{0, 0, corner.z};
    const Vec3 pa = of_a ? at : at - best * unit, pb = of_a ? at + best * unit : at;
    const double core = best;
    // The separation along the axis, from the shapes' supports: a lower bound of the distance,
    // which must confirm the sections' answer to the tolerance, and not exceed it beyond rounding.
    const double sep = kernels::with_pair(ca, pose_a, cb, pose_b, [&](const auto& pair, double) {
        Vec3 sa, sb;
        return -dot(unit, pair(unit, sa, sb));
    });
    if (!(sep >= core - (tolerance * core + noise)) || !(sep <= core + noise)) return false;
    center_offset = t;
    out = LocalDistance{};
    out.core = core;
    out.v = -best * unit;
    out.point_a = pa;
    out.point_b = pb;
    out.unit = unit;
    out.intersecting = false;
    out.bounded = sep > 0;
    out.iterations = 1;
    out.termination = Termination::RelativeError;
    return true;
}

// The origin's nearest boundary point of A - B lies in the axial half-plane through the origin,
// where A - B is a polygon: the least translation is along a normal of one of its edges, which are
// the edges of A's section and of B's (both signs of each are tried). Each candidate's translation is
// measured with the shapes' own supports, so it separates them whatever their placement: never
// below the depth. A turn of B by the axes' angle moves each by at most the turn's bound, which puts
// the answer within twice that of the depth.
CoaxialAnswer coaxial_depth(const CoreOf& ca, const Transform& pose_a, const CoreOf& cb, const Transform& pose_b,
                            double tolerance, bool offer_near) {
    CoaxialAnswer answer;
    if (!axial_pair(ca, cb)) return answer;
    // Within the poses' rounding, or within the tolerance of the depth (checked once it is known;
    // the depth is at most twice the reaches).
    const AxesTurn w = axes_turn(ca, pose_a, cb, pose_b);
    const double bound = w.bound;
    const bool near = offer_near && 2 * bound <= kNearlyParallel * (w.reach_a + w.reach_b);
    if (!(w.noise < INFINITY) || !(w.within_rounding() || near || 2 * bound <= 2 * tolerance * (w.reach_a + w.reach_b)))
        return answer;
    // The cones' slant normals' components (zero: no cone).
    struct Slant {
        double across = 0, up = 0;
    };
    const auto slant = [](const CoreOf& c) {
        if (c.core == Core::Segment) return Slant{};
        const closed_form::Revolution v = closed_form::revolution_of(*c.shape);
        if (!v.cone) return Slant{};
        const closed_form::Slant s = closed_form::slant_of(v.radius, v.half_height);
        return Slant{s.across, s.up};
    };
    const Slant sa = slant(ca), sb = slant(cb);
    const kernels::RelativeFrame f = kernels::relative_frame(pose_a, pose_b);
    const Vec3 axis_b = w.axis_b;
    // The plane through both axes (x toward B's, from A's), any through A's when they coincide.
    const Vec3 e = plane_direction(f.t);
    const double off = f.t.x * e.x + f.t.y * e.y;
    double candidates[12][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    int n = 4;
    for (const Slant* c : {&sa, &sb})
        if (c->across > 0)
            for (const double x : {c->across, -c->across})
                for (const double z : {c->up, -c->up}) candidates[n][0] = x, candidates[n][1] = z, ++n;
    double best = INFINITY;
    int chosen = 0;
    kernels::with_pair(ca, pose_a, cb, pose_b, [&](const auto& pair, double) {
        for (int i = 0; i < n; ++i) {
            const Vec3 u = candidates[i][0] * e + Vec3{0, 0, candidates[i][1]};
            Vec3 pa, pb;
            const double d = dot(u, pair(u, pa, pb));  // the translation of B along u that separates
            if (d < best) best = d, chosen = i;
        }
    });
    if (!(best > 0) || !std::isfinite(best)) return answer;
    const bool accepted = w.within_rounding() || 2 * bound * (1 + tolerance) <= tolerance * best;
    if (!accepted && !near) return answer;
    // The deepest points: B moved by the depth along u touches A where A's section's feature
    // along u (a vertex or an edge) meets B's along -u; across u, the middle of where they
    // overlap. point_a is that contact, point_b it less the depth along u (the supports' own
    // points lie anywhere on those features, and would not differ by the depth along u).
    const double ux = candidates[chosen][0], uz = candidates[chosen][1];
    double a_along = -INFINITY, a_lo = INFINITY, a_hi = -INFINITY, b_along = INFINITY, b_lo = INFINITY,
           b_hi = -INFINITY;
    const double flip = axis_b.z < 0 ? -1.0 : 1.0;
    const double level = 64 * std::numeric_limits<double>::epsilon() * (w.reach_a + w.reach_b + max_abs(f.t));
    for (int pass = 0; pass < 2; ++pass)
        for (const bool of_a : {true, false}) {
            double x[4], z[4];
            const int count = axial_section(of_a ? ca : cb, x, z);
            for (int k = 0; k < count; ++k) {
                const double xk = of_a ? x[k] : x[k] + off,
                             zk = of_a ? z[k] : flip * z[k] + f.t.z;  // B's, in A's frame
                const double along = ux * xk + uz * zk, across = -uz * xk + ux * zk;
                if (pass == 0) {
                    if (of_a)
                        a_along = std::fmax(a_along, along);
                    else
                        b_along = std::fmin(b_along, along);
                } else if (of_a ? along >= a_along - level : along <= b_along + level) {
                    double& lo = of_a ? a_lo : b_lo;
                    double& hi = of_a ? a_hi : b_hi;
                    lo = std::fmin(lo, across), hi = std::fmax(hi, across);
                }
            }
        }
    const double mid = 0.5 * (std::fmax(a_lo, b_lo) + std::fmin(a_hi, b_hi));
    const double px = ux * a_along - uz * mid, pz = uz * a_along + ux * mid;
    epa_detail::CoreDepth& out = answer.depth;
    out.n = ux * e + Vec3{0, 0, uz};
    out.point_a = px * e + Vec3{0, 0, pz};
    out.point_b = out.point_a - best * out.n;
    out.depth = best;
    out.iterations = uint32_t(n);
    out.termination = Termination::RelativeError;
    out.flat = false;
    answer.kind = accepted ? CoaxialAnswer::Kind::Accepted : CoaxialAnswer::Kind::Near;
    if (!accepted) answer.error = 2 * bound;
    return answer;
}

}  // namespace kairos::gjk_detail
