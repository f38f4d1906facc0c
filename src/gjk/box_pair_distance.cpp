// SPDX-License-Identifier: MIT
#include "gjk/box_pair_distance.hpp"

#include <cmath>
#include <limits>

#include "gjk/box_axes.hpp"
#include "gjk/closed_forms.hpp"
#include "shapes/shape.hpp"

namespace kairos::gjk_detail {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A box's half extents and another's axes and centre in its frame (m[r][c]: column c is the other
// box's axis c).
struct Frame {
    double m[3][3];
    double c[3];
};

// The incident box (half extents h_inc, frame f in the reference box's frame) against the
// reference box's face x_i = sg h_ref_i. u receives the incident box's coordinates of its point
// farthest toward the face (a vertex), moved along its axes within `flat` of parallel to the face
// to the point of that edge or face nearest the face's centre line; p the point in the reference
// frame. True when p's foot on the face's plane lies within the face's rectangle.
bool face_witness(const double (&h_ref)[3], int i, double sg, const double (&h_inc)[3], const Frame& f, double flat,
                  double (&u)[3], double (&p)[3]) {
    bool free_axis[3];
    for (int j = 0; j < 3; ++j) {
        const double toward = sg * f.m[i][j];  // the axis's component along the face's normal
        free_axis[j] = 2 * h_inc[j] * std::fabs(toward) <= flat;
        u[j] = free_axis[j] ? 0.0 : (toward > 0 ? -h_inc[j] : h_inc[j]);
    }
    for (int k = 0; k < 3; ++k) p[k] = f.c[k] + u[0] * f.m[k][0] + u[1] * f.m[k][1] + u[2] * f.m[k][2];
    // A free axis: the in-plane part of p's offset from the centre line, projected on it (two free
    // axes are square to each other, so one pass projects on the face they span).
    for (int j = 0; j < 3; ++j) {
        if (!free_axis[j]) continue;
        double along = 0, len_sq = 0;
        for (int k = 0; k < 3; ++k) {
            if (k == i) continue;
            along += p[k] * f.m[k][j];
            len_sq += f.m[k][j] * f.m[k][j];
        }
        if (!(len_sq > 0.5)) continue;  // not nearly in the plane: leave the vertex
        const double step = closed_form::clamp_to(-along / len_sq, h_inc[j]);
        u[j] = step;
        for (int k = 0; k < 3; ++k) p[k] += step * f.m[k][j];
    }
    for (int k = 0; k < 3; ++k)
        if (k != i && !(std::fabs(p[k]) <= h_ref[k])) return false;
    return true;
}

}  // namespace

bool box_pair_distance(const kernels::CoreOf& ca, const Transform& pose_a, const kernels::CoreOf& cb,
                       const Transform& pose_b, LocalDistance& out, Vec3& center_offset) {
    using kernels::Core;
    if (ca.core != Core::Box || cb.core != Core::Box) return false;
    const Vec3 ha3 = static_cast<const BoxShape&>(*ca.shape).half_extents;
    const Vec3 hb3 = static_cast<const BoxShape&>(*cb.shape).half_extents;
    const kernels::RelativeFrame rf = kernels::relative_frame(pose_a, pose_b);
    const double ha[3] = {ha3.x, ha3.y, ha3.z}, hb[3] = {hb3.x, hb3.y, hb3.z};
    const double t[3] = {rf.t.x, rf.t.y, rf.t.z};
    Frame fb;  // B in A's frame
    for (int k = 0; k < 3; ++k) {
        fb.m[k][0] = rf.r.r[k].x, fb.m[k][1] = rf.r.r[k].y, fb.m[k][2] = rf.r.r[k].z;
        fb.c[k] = t[k];
    }
    const double size = ha[0] + ha[1] + ha[2] + hb[0] + hb[1] + hb[2];
    const double reach = size + std::fabs(t[0]) + std::fabs(t[1]) + std::fabs(t[2]);
    // Squares of coordinates stay finite and normal; NaN fails.
    if (!(reach < 1e140) || !(reach > 1e-140) || !(size > 1e-100 * reach)) return false;
    double abs_m[3][3];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) abs_m[r][c] = std::fabs(fb.m[r][c]);
    if (!std::isfinite(abs_m[0][0] + abs_m[1][1] + abs_m[2][2] + abs_m[0][1] + abs_m[0][2] + abs_m[1][0] + abs_m[1][2] +
                       abs_m[2][0] + abs_m[2][1]))
        return false;

    // Each axis's separation less its rounding (eps of the reach per unit of the axis, which an
    // edge axis of length sin(angle) divides): the largest is a lower bound of the distance.
    const double unit_error = 8 * kEps * reach;
    double lower = -INFINITY, face_sep = -INFINITY, edge_sep = -INFINITY;
    int face = -1, edge = -1;
    double face_sign = 1, edge_sign = 1;
    for (int i = 0; i < 3; ++i) {  // A's faces
        const double sep = std::fabs(t[i]) - box_axes::face_a_width(ha, hb, abs_m, i);
        if (sep > face_sep) face_sep = sep, face = i, face_sign = t[i] >= 0 ? 1.0 : -1.0;
    }
    for (int j = 0; j < 3; ++j) {  // B's faces
        const double c = fb.m[0][j] * t[0] + fb.m[1][j] * t[1] + fb.m[2][j] * t[2];
        const double sep = std::fabs(c) - box_axes::face_b_width(ha, hb, abs_m, j);
        if (sep > face_sep) face_sep = sep, face = 3 + j, face_sign = c >= 0 ? 1.0 : -1.0;
    }
    lower = face_sep - unit_error;
    for (int i = 0; i < 3; ++i) {  // edges: L = e_i x b_j
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            const box_axes::EdgeAxis l = box_axes::edge_axis(fb.m, i, j);
            if (!(l.len_sq > 1e-6)) continue;  // nearly parallel edges: the axis's direction is too rough
            const double len = std::sqrt(l.len_sq);
            const double c = l.l1 * t[i1] + l.l2 * t[i2];
            const double sep = (std::fabs(c) - box_axes::edge_width(ha, hb, abs_m, i, j)) / len;
            if (sep - unit_error / len > lower) lower = sep - unit_error / len;
            if (sep > edge_sep) edge_sep = sep, edge = 3 * i + j, edge_sign = c >= 0 ? 1.0 : -1.0;
        }
    }
    const double allowance = 64 * kEps * reach;
    if (!(lower > allowance)) return false;  // overlapping, or touching within rounding

    // A candidate pair of points (one on each box, A's frame) is the distance when its distance
    // is within the allowance of a lower bound: the axes' (`lower`), or the separation along the
    // pair's own direction, from the boxes' supports (a vertex by an edge, whose direction is
    // none of the 15). On success the unit is `axis`, or the pair's direction when that is zero.
    Vec3 pa, pb, unit;
    auto certify = [&](Vec3 qa, Vec3 qb, Vec3 axis) {
        const Vec3 gap = qb - qa;
        const double len = length(gap);
        if (!(len > 0) || !is_finite(gap)) return false;
        bool ok = len <= lower + allowance;
        const Vec3 dir = (1 / len) * gap;
        if (!ok) {
            const double reach_a = ha[0] * std::fabs(dir.x) + ha[1] * std::fabs(dir.y) + ha[2] * std::fabs(dir.z);
            double reach_b = 0;
            for (int k = 0; k < 3; ++k)
                reach_b += hb[k] * std::fabs(fb.m[0][k] * dir.x + fb.m[1][k] * dir.y + fb.m[2][k] * dir.z);
            ok = dot(dir, rf.t) - reach_a - reach_b >= len - allowance;
            axis = Vec3{};
        }
        if (!ok) return false;
        pa = qa, pb = qb;
        unit = dot(axis, axis) > 0 ? axis : dir;
        return true;
    };
    auto clamp_to_box = [](const double(&h)[3], const double(&p)[3]) {
        return Vec3{closed_form::clamp_to(p[0], h[0]), closed_form::clamp_to(p[1], h[1]),
                    closed_form::clamp_to(p[2], h[2])};
    };
    // Axes within rounding of parallel to a face (moving along them changes the height by 4 eps of
    // the reach at most): the incident feature is an edge or a face. Any wider, and the witness
    // point's height would carry that much error into the answer.
    const double flat = 4 * kEps * reach;
    bool found = false;
    // A face's witness first when its axis is among the best (a face resting on a face ties with
    // the axes of edges parallel to it). The incident point's nearest point of the face's box is
    // its foot on the face when that lies within the face, else on the face's rim.
    if (face_sep >= edge_sep - allowance) {
        double u[3], p[3];
        if (face < 3) {
            const int i = face;
            const bool over = face_witness(ha, i, face_sign, hb, fb, flat, u, p);
            Vec3 axis{};
            axis[i] = face_sign;
            found = certify(clamp_to_box(ha, p), {p[0], p[1], p[2]}, over ? axis : Vec3{});
        } else {
            // B's face toward A, in B's frame: A's axes are the rows of B's matrix, its centre
            // -m^T t. A's point comes back in A's own coordinates (u), B's through B's pose in A.
            const int j = face - 3;
            Frame fa;
            for (int r = 0; r < 3; ++r) {
                for (int c = 0; c < 3; ++c) fa.m[r][c] = fb.m[c][r];
                fa.c[r] = -(fb.m[0][r] * t[0] + fb.m[1][r] * t[1] + fb.m[2][r] * t[2]);
            }
            const bool over = face_witness(hb, j, -face_sign, ha, fa, flat, u, p);
            found =
                certify({u[0], u[1], u[2]}, rf.t + rf.r * clamp_to_box(hb, p), over ? face_sign * rf.r.col(j) : Vec3{});
        }
    }
    if (!found && edge >= 0 && edge_sep >= face_sep - allowance) {
        const int i = edge / 3, j = edge % 3, i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        const Vec3 l = box_axes::edge_axis_vector(fb.m, i, j);
        const Vec3 n = (edge_sign / length(l)) * l;
        const Vec3 a0 = box_axes::edge_mid_a(ha3, i, n), b0 = box_axes::edge_mid_b(hb3, rf.r, rf.t, j, n);
        // closed_form::closest_points with the axes turned so that e_i is its e_z.
        const Vec3 d = rf.r.col(j), c = b0 - a0;
        const closed_form::SegmentPair sp =
            closed_form::closest_points(ha[i], {c[i1], c[i2], c[i]}, {d[i1], d[i2], d[i]}, hb[j]);
        Vec3 qa = a0;
        qa[i] += sp.s;
        found = certify(qa, b0 + sp.u * d, n);
    }
    if (!found || !is_finite(pa) || !is_finite(pb)) return false;
    center_offset = rf.t;
    out = LocalDistance{};
    out.core = length(pb - pa);
    out.v = -out.core * unit;
    out.point_a = pa;
    out.point_b = pb;
    out.unit = unit;
    out.intersecting = false;
    out.bounded = true;
    out.iterations = 1;
    out.termination = Termination::RelativeError;
    return true;
}

}  // namespace kairos::gjk_detail
