// SPDX-License-Identifier: MIT
// Two boxes moving by translations overlap at lambda exactly when their projections overlap on
// each of 15 axes (the separating axis theorem: the six face normals and the nine cross products
// of their edges). On each axis the projections overlap over an interval of lambda, so the first
// contact is the latest entry over the axes when it comes before the earliest exit. An axis's
// bound holds for the axis as computed, up to the rounding of its offset and widths; the widths
// of an edge axis come from the rotation's entries (an identity of exact rotations), which puts
// its bound off by about eps / angle of the reach for edges an angle apart: the nearly parallel
// ones whose error would reach a tenth of the tolerance are declined (box_cast.hpp). Squares of
// gaps below 1e-154 (shapes near 1e-150 in size) underflow and read as touching: declined too.
#include "casts/box_cast.hpp"

#include "gjk/box_axes.hpp"
#include "gjk/closed_forms.hpp"

#include <cmath>
#include <initializer_list>
#include <limits>
#include <utility>

namespace kairos::cast_detail {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Segments nearer parallel than this (the sine of their angle) are declined by capsule_pair_cast:
// the normal of their parallelogram carries a rounding of eps / sine, 2e-12 rad here.
constexpr double kParallelSine = 1e-4;

Vec3 unit_axis(int i) { return {i == 0 ? 1.0 : 0.0, i == 1 ? 1.0 : 0.0, i == 2 ? 1.0 : 0.0}; }

// The contact point on face `i` of a reference box (half extents h, at the origin of its frame,
// the face at x_i = sign h_i) touched by an incident box (half extents hi, axes the columns of m,
// centre c, in the reference frame). The incident box's feature facing the face (a vertex, an
// edge or a face: axes within `flat` of the face's plane count as parallel to it) is clipped to
// the face's rectangle, and the point is a point of what is left, moved halfway to the face's
// plane (the two touch to rounding).
Vec3 face_contact(Vec3 h, int i, double sign, Vec3 hi, const Mat3& m, Vec3 c, double flat) {
    Vec3 base = c;
    Vec3 spans[2] = {};
    int free_axes = 0;
    for (int j = 0; j < 3; ++j) {
        const Vec3 b = m.col(j);
        const double toward = -sign * b[i];  // b . (-n): the incident box's support is along -n
        if (free_axes < 2 && 2 * hi[j] * std::fabs(toward) <= flat) {
            spans[free_axes++] = hi[j] * b;
        } else {
            base += (toward >= 0 ? hi[j] : -hi[j]) * b;
        }
    }
    const int in_plane[2] = {(i + 1) % 3, (i + 2) % 3};
    Vec3 mean = base;
    if (free_axes == 1) {
        // An edge: its part over the face (Liang-Barsky), whose midpoint is taken.
        const Vec3 p0 = base - spans[0], d = 2.0 * spans[0];
        double lo = 0, hi_t = 1;
        for (int a : in_plane) {
            for (double side : {1.0, -1.0}) {
                // side (p0 + s d)_a <= h_a
                const double num = h[a] - side * p0[a], den = side * d[a];
                if (den > 0)
                    hi_t = std::fmin(hi_t, num / den);
                else if (den < 0)
                    lo = std::fmax(lo, num / den);
                else if (num < 0)
                    hi_t = -1;  // parallel to this side and outside it
            }
        }
        if (lo <= hi_t) mean = p0 + (0.5 * (lo + hi_t)) * d;
    } else if (free_axes == 2) {
        // A face: Sutherland-Hodgman against the four sides |x_a| <= h_a (a != i), then the
        // vertex mean (a point of the clipped polygon). A convex quad gains at most one vertex per
        // side; a face flat to rounding (its sides' signs alternating along a line) could gain
        // more, so the output is capped: every vertex kept is still a point of the face.
        constexpr int kCap = 16;
        Vec3 poly[kCap], next[kCap];
        int n = 4;
        poly[0] = base - spans[0] - spans[1];
        poly[1] = base + spans[0] - spans[1];
        poly[2] = base + spans[0] + spans[1];
        poly[3] = base - spans[0] + spans[1];
        for (int a : in_plane) {
            for (double side : {1.0, -1.0}) {
                int k = 0;
                for (int q = 0; q < n; ++q) {
                    const Vec3 cur = poly[q], nxt = poly[(q + 1) % n];
                    const double dc = h[a] - side * cur[a], dn = h[a] - side * nxt[a];  // >= 0 inside
                    if (dc >= 0 && k < kCap) next[k++] = cur;
                    if ((dc >= 0) != (dn >= 0) && k < kCap) next[k++] = cur + (dc / (dc - dn)) * (nxt - cur);
                }
                n = k;
                for (int q = 0; q < n; ++q) poly[q] = next[q];
            }
        }
        if (n > 0) {
            mean = Vec3{};
            for (int q = 0; q < n; ++q) mean += poly[q];
            mean = (1.0 / n) * mean;
        }
    }
    // A vertex, or rounding leaving nothing (a feature a few ulps past the face's rim): the
    // nearest point of the face's rectangle in the plane.
    for (int a : in_plane) mean[a] = std::fmax(-h[a], std::fmin(h[a], mean[a]));
    mean[i] = 0.5 * (mean[i] + sign * h[i]);
    return mean;
}

// The midpoint of the closest points of A's edge {a0 + s e_i, |s| <= ha_i} and B's edge
// {b0 + u d, |u| <= hb_j} (d unit): closed_form::closest_points with the axes turned so that e_i
// is its e_z (its form has no cancellation on nearly parallel edges).
Vec3 edge_contact(Vec3 a0, int i, double hai, Vec3 b0, Vec3 d, double hbj) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    const Vec3 c = b0 - a0;
    const closed_form::SegmentPair sp =
        closed_form::closest_points(hai, {c[i1], c[i2], c[i]}, {d[i1], d[i2], d[i]}, hbj);
    Vec3 pa = a0;
    pa[i] += sp.s;
    return 0.5 * (pa + (b0 + sp.u * d));
}

}  // namespace

BoxCast box_box_cast(Vec3 ha, Vec3 hb, const Mat3& rot, Vec3 t, Vec3 r, double tolerance) {
    BoxCast out;
    const double size = ha.x + ha.y + ha.z + hb.x + hb.y + hb.z;
    const double reach = size + std::fabs(t.x) + std::fabs(t.y) + std::fabs(t.z);
    const double motion = std::fabs(r.x) + std::fabs(r.y) + std::fabs(r.z);
    double rot_sum = 0;
    for (int i = 0; i < 3; ++i) rot_sum += std::fabs(rot.r[i].x) + std::fabs(rot.r[i].y) + std::fabs(rot.r[i].z);
    // Also false for NaN; a reach or motion near overflow leaves the products below to GJK's care.
    if (!(reach < 1e150) || !(motion < 1e150) || !std::isfinite(rot_sum) || !(size > 0)) return out;
    // Within `band` of each other (in distance) the boxes count as touching: the start, a graze,
    // and the step's end there are left to the GJK cast, whose conventions cover them.
    const double band = 1e-9 * size;
    if (!(motion > band)) return out;
    const double tol = std::fmax(tolerance, 1e-15);
    const double parallel_sq = (0.01 * tol) * (0.01 * tol);
    const double sharp = 10 * kEps * reach / (tol * size);
    const double sharp_sq = sharp * sharp;
    // The rounding of the offsets L.t (|L| <= 1; exact on A's faces): part of the allowance that
    // keeps rounding from turning a contact into a miss (the exits are later by it, and a gap
    // within it is not a separation). The entry keeps its rounding, as the GJK cast's clips do:
    // about eps of the offsets, far below any tolerance.
    const double t_sum = std::fabs(t.x) + std::fabs(t.y) + std::fabs(t.z);

    double enter = -INFINITY, leave = INFINITY;
    bool apart_at_start = false;  // some axis separates the boxes at the start by more than the band
    const double band_sq = band * band;
    int best = -1;                  // the axis of the latest entry (0-2 A's faces, 3-5 B's, 6+ edges)
    double face_enter = -INFINITY;  // the latest entry over the face axes, and its axis
    int face_best = -1;
    // Per axis id: c = L.t, |L|^2 and B's approach speed along L, for the axes chosen at the end.
    double offsets[15], lengths_sq[15], approaches[15];
    // One axis L (not unit): c = L.t, s = L.r, w the two half widths along L summed. Miss when
    // this axis alone separates the boxes over the whole step by more than the band, Declined
    // when by less (GJK counts that as touching at the start), else Hit: the axis leaves it open.
    // Random casts make the branches on the direction and on the latest entry unpredictable:
    // both sides are computed and selected, and the axis's vector is formed again at the end.
    using Verdict = BoxCast::Verdict;
    auto axis = [&](int id, double len_sq, double c, double s, double w, double c_error) {
        // The rounding of the gap: c's, w's (a sum of four products) and the subtraction's.
        const double allow = 4 * kEps * (c_error + w) + kEps * std::fabs(c);
        const double a = std::fabs(c), gap = a - w;
        const double approach = c >= 0 ? -s : s;  // speed of B toward A along L
        const bool clear = gap > 0 && gap * gap > band_sq * len_sq;  // gap / |L| > band
        apart_at_start |= clear;
        const bool closing = approach > 0;
        // Apart and not closing: this axis decides.
        if (!closing && gap > allow) return clear ? Verdict::Miss : Verdict::Declined;
        offsets[id] = c, lengths_sq[id] = len_sq, approaches[id] = approach;
        // Closing: entry and exit; opening (touching or overlapping along L): exit only; at rest
        // (approach 0, inv infinite): neither, the exit infinite or NaN (0 * inf), not taken.
        const double inv = 1 / std::fabs(approach);
        const double in = closing ? gap * inv : -INFINITY;
        const double out_at = (closing ? a + w + allow : w - a + allow) * inv;
        leave = out_at < leave ? out_at : leave;
        const bool later = in > enter;
        enter = later ? in : enter;
        best = later ? id : best;
        if (id < 6) {
            const bool face_later = in > face_enter;
            face_enter = face_later ? in : face_enter;
            face_best = face_later ? id : face_best;
        }
        return Verdict::Hit;
    };
    // Plain arrays: Vec3's operator[] is a chain of selects when the index is not a constant.
    const double m[3][3] = {{rot.r[0].x, rot.r[0].y, rot.r[0].z},
                            {rot.r[1].x, rot.r[1].y, rot.r[1].z},
                            {rot.r[2].x, rot.r[2].y, rot.r[2].z}};
    const double ea[3] = {ha.x, ha.y, ha.z}, eb[3] = {hb.x, hb.y, hb.z};
    const double tv[3] = {t.x, t.y, t.z}, rv[3] = {r.x, r.y, r.z};
    // Written out: GCC at -O2 does not unroll the loop form, and the SAT loops below ran slower.
    const double abs_r[3][3] = {{std::fabs(m[0][0]), std::fabs(m[0][1]), std::fabs(m[0][2])},
                                {std::fabs(m[1][0]), std::fabs(m[1][1]), std::fabs(m[1][2])},
                                {std::fabs(m[2][0]), std::fabs(m[2][1]), std::fabs(m[2][2])}};
    for (int i = 0; i < 3; ++i) {  // A's faces: L = e_i
        const double w = box_axes::face_a_width(ea, eb, abs_r, i);
        if (const Verdict v = axis(i, 1, tv[i], rv[i], w, 0); v != Verdict::Hit) {
            out.verdict = v;
            return out;
        }
    }
    for (int j = 0; j < 3; ++j) {  // B's faces: L = b_j
        const Vec3 b = rot.col(j);
        const double w = box_axes::face_b_width(ea, eb, abs_r, j);
        if (const Verdict v = axis(3 + j, 1, dot(b, t), dot(b, r), w, t_sum); v != Verdict::Hit) {
            out.verdict = v;
            return out;
        }
    }
    for (int i = 0; i < 3; ++i) {  // edges: L = e_i x b_j
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            // e_i x b_j is 0 at i: the products with that component are left out, as they add nothing.
            const box_axes::EdgeAxis l = box_axes::edge_axis(m, i, j);
            const double len_sq = l.len_sq;
            // Edges at an angle a (|L| = sin a) apart: parallel ones add nothing the face axes
            // miss, and below a = tolerance / 100 the axis adds less than that share of the size.
            // The axis's direction carries rounding of eps / a, which tilts its bound by that
            // times the reach: above `sharp` within tolerance / 10 of the size. Between the two
            // the closed form would need more care than GJK: the cast is declined.
            if (len_sq <= parallel_sq) continue;
            if (len_sq < sharp_sq) return out;
            const double c = l.l1 * tv[i1] + l.l2 * tv[i2], s = l.l1 * rv[i1] + l.l2 * rv[i2];
            const double w = box_axes::edge_width(ea, eb, abs_r, i, j);
            if (const Verdict v = axis(6 + 3 * i + j, len_sq, c, s, w, t_sum); v != Verdict::Hit) {
                out.verdict = v;
                return out;
            }
        }
    }
    // The axis of a given id, as its offsets were formed.
    const auto axis_vector = [&](int id) {
        if (id < 3) return unit_axis(id);
        if (id < 6) return rot.col(id - 3);
        return box_axes::edge_axis_vector(m, (id - 6) / 3, (id - 6) % 3);
    };
    if (!apart_at_start) return out;  // touching or overlapping at the start
    // Near a graze or the step's end the verdict is within rounding of the other one.
    if (!(std::fabs(leave - enter) * motion > band) || !(std::fabs(enter - 1) * motion > band)) return out;
    if (!(enter <= leave) || !(enter <= 1)) {
        out.verdict = BoxCast::Verdict::Miss;
        return out;
    }
    if (!(enter > 0) || best < 0) return out;  // not expected after the start test; left to GJK
    // How late the entry may be: its offsets' rounding, about eps of the reach whatever |L| (an
    // edge axis's direction carries absolute rounding of eps).
    const double best_slack = 4 * kEps * reach / approaches[best];
    // The normal and feature: a face's when a face axis enters within the band of the latest, or
    // within the latest's rounding (a face resting on a face or an edge ties with the axes of the
    // edges parallel to it, and an edge axis from nearly parallel edges, nearly that face's
    // normal, can lead by its rounding: its edges' closest points then lie anywhere along them).
    // The time then sheds that rounding too, keeping to the face's entry at least.
    int id = best;
    if (id >= 6 && face_best >= 0 && !((enter - best_slack - face_enter) * motion > band)) {
        id = face_best;
        enter = std::fmax(face_enter, enter - best_slack);
    }
    const double c = offsets[id], len_sq = lengths_sq[id];
    const Vec3 l = axis_vector(id);
    const double sign = c >= 0 ? 1.0 : -1.0;
    const Vec3 n = (sign / std::sqrt(len_sq)) * l;
    const Vec3 cb = t + enter * r;  // B's centre at toi
    const double flat = band;
    Vec3 p;
    if (id < 3) {
        p = face_contact(ha, id, sign, hb, rot, cb, flat);
    } else if (id < 6) {
        // B's face toward A, in B's frame: A's axes there are rot's rows, its centre -rot^T cb.
        const int j = id - 3;
        const Vec3 pb = face_contact(hb, j, -sign, ha, transpose(rot), -mul_transpose(rot, cb), flat);
        p = cb + rot * pb;
    } else {
        const int i = (id - 6) / 3, j = (id - 6) % 3;
        const Vec3 a0 = box_axes::edge_mid_a(ha, i, n), b0 = box_axes::edge_mid_b(hb, rot, cb, j, n);
        p = edge_contact(a0, i, ha[i], b0, rot.col(j), hb[j]);
    }
    if (!is_finite(p) || !is_finite(n)) return out;
    out.verdict = BoxCast::Verdict::Hit;
    out.toi = enter;
    out.normal = n;
    out.point = p;
    return out;
}

namespace {

// The rounded closed forms' common range: a size above 1e-100, offsets and motions below 1e100
// (products of coordinates beyond them over- or underflow), and a motion above 1e-9 of the size
// (below it the step is a touch, the GJK cast's). False for NaN.
bool in_closed_form_range(double size, Vec3 s, Vec3 r) {
    const double reach = size + std::fabs(s.x) + std::fabs(s.y) + std::fabs(s.z);
    const double motion = std::fabs(r.x) + std::fabs(r.y) + std::fabs(r.z);
    return reach < 1e100 && motion < 1e100 && size > 1e-100 && motion > 1e-9 * size;
}

// A radius below the rounding of a ray's entry into the box h grown by it (eps of the start's and
// the motion's coordinates): no edge or corner is left to round (ray_rounded_box).
bool radius_below_entry_rounding(Vec3 h, double rho, Vec3 s, Vec3 r) {
    const double reach = h.x + h.y + h.z + rho + std::fabs(s.x) + std::fabs(s.y) + std::fabs(s.z);
    const double motion = std::fabs(r.x) + std::fabs(r.y) + std::fabs(r.z);
    return rho <= 0x1p-50 * (reach + motion);
}

// A ray s + lambda r entering, at lambda, the ball of radius rho about centre (a point of the core):
// the normal from the centre toward the hit (the offset as ball_entry formed it), the point on the
// grown surface there.
BoxCast rounded_hit(Vec3 s, Vec3 r, double rho, double lambda, Vec3 offset, Vec3 centre) {
    const Vec3 n = normalized_or(offset, normalized_or(s + lambda * r - centre, {0, 0, 1}));
    BoxCast out;
    out.verdict = BoxCast::Verdict::Hit;
    out.toi = lambda;
    out.normal = n;
    out.point = centre + rho * n;
    return out;
}

}  // namespace

BoxCast ray_capsule(double h, double rho, Vec3 s, Vec3 r) {
    BoxCast out;
    // The preconditions of ray_rounded_box for the box (0, 0, h) grown by rho, and its start test.
    const double size = h + rho;
    if (!(rho >= 0) || !in_closed_form_range(size, s, r) || radius_below_entry_rounding({0, 0, h}, rho, s, r))
        return out;
    const double band = 1e-9 * size;
    const Vec3 core{0, 0, closed_form::clamp_to(s.z, h)};
    if (!(closed_form::safe_length(s - core) - rho > band)) return out;
    // The capsule lies in the infinite cylinder of radius rho about the z axis: a ray that never
    // enters it misses. Entering it at |z| <= h is entering the side. Entering it past an end (or
    // starting in it past one) is entering that end's ball first: within the cylinder, the plane
    // z = +-h is crossed inside the ball, and the other end lies beyond the side.
    out.verdict = BoxCast::Verdict::Miss;
    const closed_form::BallEntry side = closed_form::ball_entry({s.x, s.y, 0}, {r.x, r.y, 0}, rho);
    if (!(side.lambda >= 0)) return out;
    const double z = s.z + side.lambda * r.z;
    Vec3 centre{0, 0, z};
    double lambda = side.lambda;
    Vec3 offset = side.offset;
    if (!(std::fabs(z) <= h)) {
        centre.z = z > 0 ? h : -h;
        const closed_form::BallEntry cap = closed_form::ball_entry(s - centre, r, rho);
        if (!(cap.lambda >= 0)) return out;
        lambda = cap.lambda, offset = cap.offset;
    }
    return rounded_hit(s, r, rho, lambda, offset, centre);
}

BoxCast ray_rounded_box(Vec3 h, double rho, Vec3 s, Vec3 r) {
    BoxCast out;
    const double size = h.x + h.y + h.z + rho;
    if (!(rho >= 0) || !in_closed_form_range(size, s, r)) return out;
    const double band = 1e-9 * size, motion = std::fabs(r.x) + std::fabs(r.y) + std::fabs(r.z);
    // A start within the band of the rounded box, or in it, is the GJK cast's (touching at the start).
    const double gap = closed_form::safe_length(s - closed_form::box_nearest(h, s)) - rho;
    if (!(gap > band)) return out;
    // A radius below the rounding of the entry point (eps of the start's and the motion's
    // coordinates) leaves no edge or corner to round: the entry is on the grown box's face, as for a
    // plain box; the edges' capsules would be tested against an entry rounded farther from them
    // than their radius (a ball of radius 1e-150 cast into a box through one of its edges missed
    // it; found by fuzzing).
    const bool plain = radius_below_entry_rounding(h, rho, s, r);
    // The slab test against the box grown by rho on every axis, which holds the rounded box.
    const Vec3 e{h.x + rho, h.y + rho, h.z + rho};
    double enter = 0, leave = 1;
    int axis = -1;  // the slab entered last (-1: the start is in the grown box)
    for (int k = 0; k < 3; ++k) {
        if (r[k] == 0) {
            if (std::fabs(s[k]) > e[k]) {
                out.verdict = BoxCast::Verdict::Miss;
                return out;
            }
            continue;
        }
        double lo = (-e[k] - s[k]) / r[k], hi = (e[k] - s[k]) / r[k];
        if (lo > hi) std::swap(lo, hi);
        if (lo > enter) enter = lo, axis = k;
        if (hi < leave) leave = hi;
    }
    if (!(enter <= leave)) {
        // Missing the grown box misses the rounded one (it lies inside); a plain box grazed
        // within the band is declined: rounding can make it either.
        if (rho == 0 && !((enter - leave) * motion > band)) return out;
        out.verdict = BoxCast::Verdict::Miss;
        return out;
    }
    Vec3 p = s + enter * r;
    int outside = 0;
    for (int k = 0; k < 3; ++k) outside += std::fabs(p[k]) > h[k];
    if (axis >= 0 && (plain || outside <= 1)) {
        // On a face of the grown box within the box's extent across it: the rounded box's face.
        if (rho == 0 && !((leave - enter) * motion > band)) return out;  // a graze of a plain box
        // The slab's face the ray enters through is the one it moves toward (r's sign, exact);
        // p's own sign carries the rounding of s + enter r, eps |s|, which from a start 1e18
        // sizes away is all there is of it (found by fuzzing: a normal along the motion).
        Vec3 n{};
        n[axis] = r[axis] > 0 ? -1 : 1;
        p[axis] = n[axis] * e[axis];
        out.verdict = BoxCast::Verdict::Hit;
        out.toi = enter;
        out.normal = n;
        out.point = p;
        return out;
    }
    if (plain) return out;  // a plain box entered at once on two slabs: left to GJK
    // Near an edge or a corner: the capsules of the edges at the entry's corner, or in an edge's
    // region (two coordinates past the box) that edge's alone (Ericson §5.5.7). Inside the grown
    // box every coordinate lies within rho past the box, so a ray from an edge's region meets its
    // capsule no later than the rest of the rounded box: leaving into a face's region it crosses
    // the plane between them within rho of the edge; into the corner's region, where the rounded
    // box is the capsule's cap ball, and on into another edge's, the distance to that edge,
    // convex along the ray, is within rho when the ray leaves the first edge's region (the one
    // coordinate past the box there) and wherever it meets that edge's cylinder, so within rho at
    // the plane between the two edges' regions too, where it equals the distance to the corner:
    // in the ball before the other cylinder. A corner's region tests its three capsules.
    // The region and the corner come from p's signs, rounded by eps |s|: from a start far beyond
    // the box (that rounding past rho) the choice is arbitrary, and so is the true entry within
    // that rounding; the normal still opposes r (a ball's offset at its entry does).
    Vec3 corner;
    for (int k = 0; k < 3; ++k) corner[k] = p[k] >= 0 ? h[k] : -h[k];
    double best = INFINITY;
    Vec3 best_offset{}, best_centre{};
    closed_form::BallEntry corner_ball;  // the entry's corner's ball, formed once when a cap is it
    bool corner_ball_done = false;
    for (int m = 0; m < 3; ++m) {
        if (outside == 2 && std::fabs(p[m]) > h[m]) continue;  // not the edge of the entry's region
        // The capsule along axis m through the corner: its circle across m, then a cap ball when
        // the circle is entered past the edge's end.
        Vec3 s2 = s - corner, r2 = r;
        s2[m] = 0, r2[m] = 0;
        const closed_form::BallEntry cyl = closed_form::ball_entry(s2, r2, rho);
        if (!(cyl.lambda >= 0)) continue;
        const double along = s[m] + cyl.lambda * r[m];
        Vec3 centre = corner;
        double lambda = cyl.lambda;
        Vec3 offset = cyl.offset;
        if (std::fabs(along) <= h[m]) {
            centre[m] = along;
        } else {
            centre[m] = along >= 0 ? h[m] : -h[m];
            closed_form::BallEntry cap;
            if (centre[m] != corner[m]) {
                cap = closed_form::ball_entry(s - centre, r, rho);
            } else {
                if (!corner_ball_done)
                    corner_ball = closed_form::ball_entry(s - corner, r, rho), corner_ball_done = true;
                cap = corner_ball;
            }
            lambda = cap.lambda, offset = cap.offset;
        }
        if (lambda >= 0 && lambda < best) best = lambda, best_offset = offset, best_centre = centre;
    }
    if (!(best <= 1)) {
        out.verdict = BoxCast::Verdict::Miss;
        return out;
    }
    return rounded_hit(s, r, rho, best, best_offset, best_centre);
}

BoxCast capsule_pair_cast(double ha, double hb, const Mat3& rot, Vec3 t, Vec3 r, double ra, double rb,
                          double tolerance) {
    BoxCast out;
    // Axes within tolerance / 100 rad of parallel count as parallel (the parallelogram is then no
    // wider than that share of B's length).
    const double parallel = 0.01 * tolerance;
    const double rho = ra + rb;
    const Vec3 d = rot.col(2);
    // ray_capsule's range for the pieces, checked before the slabs can read a miss.
    const double size = ha + hb + rho;
    if (!in_closed_form_range(size, t, r)) return out;
    // B's centre q = t + lambda r against Q, the parallelogram {s e_z - u d} of A's segment less
    // B's, grown by rho: the union of the prism over Q (|n.x| <= rho, n normal to Q) and the
    // capsules of Q's four edges, so the first entry is the least over those five pieces (a point's
    // nearest in Q is inside it or on an edge). Parallel segments make Q a segment along e_z.
    const double sine = std::hypot(d.x, d.y);
    BoxCast best;
    best.verdict = BoxCast::Verdict::Miss;
    bool declined = false;
    auto take = [&](const BoxCast& piece, auto&& to_a_frame) {
        if (piece.verdict == BoxCast::Verdict::Declined) declined = true;
        if (piece.verdict != BoxCast::Verdict::Hit || !(best.verdict != BoxCast::Verdict::Hit || piece.toi < best.toi))
            return;
        best = piece;
        best.normal = to_a_frame(piece.normal);
    };
    auto same = [](Vec3 v) { return v; };
    auto from_b = [&](Vec3 v) { return rot * v; };
    if (sine <= parallel) {
        // Q lies within hb sine of its long axis, the segment along e_z of half length ha + hb |d.z|:
        // that segment grown by rho + hb sine holds Q grown by rho, so its entry is never later, and
        // earlier by at most hb sine over the approach.
        take(ray_capsule(ha + hb * std::fabs(d.z), rho + hb * sine, t, r), same);
    } else if (!(sine >= kParallelSine)) {
        return out;  // nearly parallel: Q's normal carries the rounding of eps / sine
    } else {
        // The prism: q's coordinates on e_z, -d and n (by the dual basis), each linear in lambda,
        // give a slab test (Cyrus-Beck). Q grown by rho lies within the prism's sides moved out by
        // rho (rho |dual| in those coordinates): a ray missing that misses. An entry through a face
        // |n.x| = rho is the first contact: before it n.x > rho along the ray, out of every edge's
        // capsule. Any other entry lies on a side, within rho of its edge: the capsules decide.
        const Vec3 n = (1 / sine) * Vec3{-d.y, d.x, 0};  // e_z x d, unit
        const Vec3 dual_s = (1 / sine) * cross(-1.0 * d, n), dual_u = (1 / sine) * cross(n, Vec3{0, 0, 1});
        const Vec3 axes[3] = {dual_s, dual_u, n};
        const double half[3] = {ha, hb, rho};
        const double grown[3] = {ha + rho * length(dual_s), hb + rho * length(dual_u), rho};
        double x0[3], dx[3];
        for (int k = 0; k < 3; ++k) x0[k] = dot(axes[k], t), dx[k] = dot(axes[k], r);
        // The slab test against half extents h: the entry's lambda and axis (-1: the start is in).
        auto slabs = [&](const double(&h)[3], double& enter) {
            double leave = 1;
            int axis = -1;
            enter = 0;
            for (int k = 0; k < 3; ++k) {
                if (dx[k] == 0) {
                    if (std::fabs(x0[k]) > h[k]) enter = 2;
                    continue;
                }
                double lo = (-h[k] - x0[k]) / dx[k], hi = (h[k] - x0[k]) / dx[k];
                if (lo > hi) std::swap(lo, hi);
                if (lo > enter) enter = lo, axis = k;
                if (hi < leave) leave = hi;
            }
            return enter <= leave ? axis : 3;
        };
        double enter = 0;
        if (slabs(grown, enter) == 3) {
            out.verdict = BoxCast::Verdict::Miss;
            return out;
        }
        // A start in the prism, or within 1e-9 of the size of its faces, is the GJK cast's (touching
        // or overlapping at the start), as ray_capsule leaves a start in or by a capsule.
        const double band = 1e-9 * size;
        if (std::fabs(x0[0]) <= ha && std::fabs(x0[1]) <= hb && std::fabs(x0[2]) <= rho + band) return out;
        if (slabs(half, enter) == 2) {
            best.verdict = BoxCast::Verdict::Hit;
            best.toi = enter;
            best.normal = dx[2] < 0 ? n : -1.0 * n;
        } else {
            // The edges along e_z (u = +-hb: centred at -u d) in A's axes; along d (s = +-ha: centred
            // at s e_z) in B's. An edge whose line the ray's line passes farther than rho from cannot
            // be met: |offset.m| / |m| > rho, m = r x e, with k's rounding (eps of |offset| |m| per
            // term) taken off first; squares that overflow or underflow keep the edge.
            auto beyond = [&](Vec3 offset, Vec3 e) {
                const Vec3 m = cross(r, e);
                const double slack = 8 * kEps * (std::fabs(offset.x) + std::fabs(offset.y) + std::fabs(offset.z)) *
                                     (std::fabs(m.x) + std::fabs(m.y) + std::fabs(m.z));
                const double k = std::fabs(dot(offset, m)) - slack;
                return k > 0 && k * k > rho * rho * dot(m, m) && std::isfinite(k * k);
            };
            for (const double u : {hb, -hb})
                if (!beyond(t + u * d, {0, 0, 1})) take(ray_capsule(ha, rho, t + u * d, r), same);
            for (const double sa : {ha, -ha})
                if (!beyond(t - Vec3{0, 0, sa}, d))
                    take(ray_capsule(hb, rho, mul_transpose(rot, t - Vec3{0, 0, sa}), mul_transpose(rot, r)), from_b);
        }
    }
    if (declined || best.verdict != BoxCast::Verdict::Hit) {
        if (!declined) out.verdict = BoxCast::Verdict::Miss;
        return out;
    }
    // The contact: the segments' closest points at toi, each pushed out by its radius along the
    // normal; they agree to rounding, the midpoint is taken.
    const closed_form::SegmentPair cp = closed_form::closest_points(ha, t + best.toi * r, d, hb);
    out.verdict = BoxCast::Verdict::Hit;
    out.toi = best.toi;
    out.normal = best.normal;
    out.point = 0.5 * ((cp.p + ra * best.normal) + (cp.q - rb * best.normal));
    if (!is_finite(out.point) || !is_finite(out.normal)) return BoxCast{};
    return out;
}

}  // namespace kairos::cast_detail
