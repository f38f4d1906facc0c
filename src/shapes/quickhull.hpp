// SPDX-License-Identifier: MIT
// Quickhull (Barber, Dobkin and Huhdanpaa 1996) on exact orientation signs: the triangle mesh
// of a point set's hull, its faces' conflict lists and horizons (see hull.cpp's file comment for
// the robustness argument). Internal to shapes/ (namespace hull_detail); used by hull.cpp only.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "math/math.hpp"
#include "shapes/hull_predicates.hpp"

namespace kairos::hull_detail {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

struct Face {
    uint32_t v[3];    // counter-clockwise seen from outside
    uint32_t adj[3];  // adj[i]: the face across edge v[i] -> v[(i + 1) % 3]
    // Rounded (b - a) x (c - a) and, per component, |u_j v_k| + |u_k v_j|: with them the
    // orientation of q is normal . (q - a), and its error bound needs only |q - a|.
    Vec3 normal, weight;
    uint32_t outside = kNone;  // first of the points strictly above, not yet on the hull (list in next_)
    uint32_t farthest = kNone;
    double farthest_value = 0;
    bool alive = true;
};

class Quickhull {
public:
    // `thin`: a point at most this far above every face (but possibly exactly outside) is taken
    // as on the hull and dropped.
    Quickhull(const std::vector<Vec3>& p, double thin)
        : pts_(p), thin_(thin), next_(p.size(), kNone), horizon_from_(p.size(), kNone) {
        faces_.reserve(2 * p.size() + 8);  // a hull of n points has at most 2n - 4 faces
    }

    // Builds the hull of the points `ids` starting from the tetrahedron t (orient(t) < 0).
    void build(const std::vector<uint32_t>& ids, const std::array<uint32_t, 4>& t) {
        const uint32_t f[4][3] = {{t[0], t[1], t[2]}, {t[0], t[3], t[1]}, {t[0], t[2], t[3]}, {t[1], t[3], t[2]}};
        for (const auto& tri : f) new_face(tri[0], tri[1], tri[2]);
        link_all_pairs(0, 4);
        std::vector<uint32_t> candidates;
        candidates.reserve(ids.size());
        for (uint32_t i : ids)
            if (i != t[0] && i != t[1] && i != t[2] && i != t[3]) candidates.push_back(i);
        distribute(candidates, 0, 4);
        for (uint32_t i = 0; i < 4; ++i)
            if (faces_[i].outside != kNone) pending_.push_back(i);

        while (!pending_.empty()) {
            const uint32_t fi = pending_.back();
            pending_.pop_back();
            if (!faces_[fi].alive || faces_[fi].outside == kNone) continue;
            add_point(fi, faces_[fi].farthest);
        }
    }

    const std::vector<Face>& faces() const { return faces_; }

private:
    uint32_t new_face(uint32_t a, uint32_t b, uint32_t c) {
        uint32_t fi;
        if (!free_.empty()) {
            fi = free_.back();
            free_.pop_back();
        } else {
            fi = static_cast<uint32_t>(faces_.size());
            faces_.emplace_back();
        }
        Face& f = faces_[fi];
        f.v[0] = a;
        f.v[1] = b;
        f.v[2] = c;
        const Vec3 u = pts_[b] - pts_[a], v = pts_[c] - pts_[a];
        f.normal = cross(u, v);
        f.weight = {std::fabs(u.y * v.z) + std::fabs(u.z * v.y), std::fabs(u.z * v.x) + std::fabs(u.x * v.z),
                    std::fabs(u.x * v.y) + std::fabs(u.y * v.x)};
        f.adj[0] = f.adj[1] = f.adj[2] = kNone;
        f.outside = kNone;
        f.farthest = kNone;
        f.farthest_value = 0;
        f.alive = true;
        return fi;
    }

    // Adjacency among the faces [first, first + n) by matching opposite directed edges.
    void link_all_pairs(uint32_t first, uint32_t n) {
        for (uint32_t i = first; i < first + n; ++i)
            for (int e = 0; e < 3; ++e) {
                const uint32_t a = faces_[i].v[e], b = faces_[i].v[(e + 1) % 3];
                for (uint32_t j = first; j < first + n; ++j)
                    for (int k = 0; k < 3; ++k)
                        if (faces_[j].v[k] == b && faces_[j].v[(k + 1) % 3] == a) faces_[i].adj[e] = j;
            }
    }

    // orient(face, q) from the face's cached normal. The rounding error of the normal is at most
    // ~4 eps * weight per component and the dot product adds ~4 eps * weight . |w|, so
    // 4e-15 * weight . |w| (about 18 eps) bounds the error; below 1e-280 underflow could matter.
    Orientation side(const Face& f, uint32_t q) const {
        const Vec3 a = pts_[f.v[0]];
        const Vec3 w = pts_[q] - a;
        const double det = dot(f.normal, w);
        const double permanent =
            f.weight.x * std::fabs(w.x) + f.weight.y * std::fabs(w.y) + f.weight.z * std::fabs(w.z);
        // Three correct digits or more: the value serves the thin decisions as it is.
        if (permanent > 1e-280 && std::fabs(det) > 4e-12 * permanent) return {det, det > 0 ? 1 : -1};
        return orient(a, pts_[f.v[1]], pts_[f.v[2]], pts_[q]);
    }

    // Gives each point to the first face among [first_face .. first_face + n_faces) of
    // `face_list` (or of the range, when face_list is null) that it is above by more than thin.
    // A point above none of them is dropped when it is exactly on or below all of them (it is in
    // the hull: the cone argument of quickhull) or within thin of one of their triangles (the
    // hull moves by at most thin). A point only thinly above some planes, but not near their
    // triangles, is kept: near a flat apex such a point can lie far outside the hull.
    void distribute(const std::vector<uint32_t>& points, uint32_t first_face, uint32_t n_faces,
                    const std::vector<uint32_t>* face_list = nullptr) {
        for (uint32_t q : points) {
            bool assigned = false, near = false;
            uint32_t thinly_above = kNone;
            double thinly_value = 0;
            for (uint32_t k = 0; k < n_faces && !assigned; ++k) {
                const uint32_t fi = face_list ? (*face_list)[k] : first_face + k;
                const Face& f = faces_[fi];
                const Orientation o = side(f, q);
                if (o.sign <= 0) continue;
                if (o.value > thin_ * length(f.normal)) {
                    assign(q, fi, o.value);
                    assigned = true;
                } else {
                    if (thinly_above == kNone) {
                        thinly_above = fi;
                        thinly_value = o.value;
                    }
                    near = near || point_triangle_distance(pts_[q], pts_[f.v[0]], pts_[f.v[1]], pts_[f.v[2]]) <= thin_;
                }
            }
            if (!assigned && thinly_above != kNone && !near) assign(q, thinly_above, thinly_value);
        }
    }

    void assign(uint32_t q, uint32_t fi, double value) {
        Face& f = faces_[fi];
        next_[q] = f.outside;
        f.outside = q;
        // The determinant is the distance times a per-face constant.
        if (f.farthest == kNone || value > f.farthest_value) {
            f.farthest = q;
            f.farthest_value = value;
        }
    }

    void add_point(uint32_t start, uint32_t p) {
        // The faces p sees strictly: a connected disk whose boundary is the horizon.
        ++stamp_;
        visible_.clear();
        visible_.push_back(start);
        mark(start, 1);
        for (size_t k = 0; k < visible_.size(); ++k) {
            const Face& f = faces_[visible_[k]];
            for (uint32_t g : f.adj) {
                if (seen_stamp(g)) continue;
                const bool sees = side(faces_[g], p).sign > 0;
                mark(g, sees ? 1 : 0);
                if (sees) visible_.push_back(g);
            }
        }
        // Horizon edges a -> b (orientation of the visible face) with the kept face across.
        horizon_.clear();
        for (uint32_t fi : visible_) {
            const Face& f = faces_[fi];
            for (int e = 0; e < 3; ++e) {
                const uint32_t g = f.adj[e];
                if (seen_visible(g)) continue;
                horizon_from_[f.v[e]] = static_cast<uint32_t>(horizon_.size());
                horizon_.push_back({f.v[e], f.v[(e + 1) % 3], g});
            }
        }
        // Orphaned points, in a deterministic order; p itself joins the hull.
        orphans_.clear();
        for (uint32_t fi : visible_) {
            Face& f = faces_[fi];
            for (uint32_t q = f.outside; q != kNone; q = next_[q])
                if (q != p) orphans_.push_back(q);
            f.outside = kNone;
            f.alive = false;
        }
        for (uint32_t fi : visible_) free_.push_back(fi);

        // Walk the horizon as a cycle and cone it to p: face (a, b, p) per edge a -> b.
        new_faces_.clear();
        uint32_t e = 0;
        for (size_t k = 0; k < horizon_.size(); ++k) {
            const HorizonEdge h = horizon_[e];
            const uint32_t fi = new_face(h.a, h.b, p);
            new_faces_.push_back(fi);
            faces_[fi].adj[0] = h.across;
            Face& g = faces_[h.across];
            for (int j = 0; j < 3; ++j)
                if (g.v[j] == h.b && g.v[(j + 1) % 3] == h.a) g.adj[j] = fi;
            e = horizon_from_[h.b];
            // Exact signs make the horizon one simple cycle; anything else is a bug, not input.
            if (e == kNone) throw std::logic_error("kairos: quickhull horizon is not a cycle");
        }
        const size_t m = new_faces_.size();
        for (size_t k = 0; k < m; ++k) {
            faces_[new_faces_[k]].adj[1] = new_faces_[(k + 1) % m];      // edge b -> p
            faces_[new_faces_[k]].adj[2] = new_faces_[(k + m - 1) % m];  // edge p -> a
        }
        for (const HorizonEdge& h : horizon_) horizon_from_[h.a] = kNone;

        distribute(orphans_, 0, static_cast<uint32_t>(m), &new_faces_);
        for (uint32_t fi : new_faces_)
            if (faces_[fi].outside != kNone) pending_.push_back(fi);
    }

    void mark(uint32_t fi, int visible) {
        if (face_stamp_.size() < faces_.size()) {
            face_stamp_.resize(faces_.size(), 0);
            face_visible_.resize(faces_.size(), 0);
        }
        face_stamp_[fi] = stamp_;
        face_visible_[fi] = static_cast<uint8_t>(visible);
    }
    bool seen_stamp(uint32_t fi) const { return fi < face_stamp_.size() && face_stamp_[fi] == stamp_; }
    bool seen_visible(uint32_t fi) const { return seen_stamp(fi) && face_visible_[fi] != 0; }

    struct HorizonEdge {
        uint32_t a, b, across;
    };

    const std::vector<Vec3>& pts_;
    double thin_;
    std::vector<Face> faces_;
    std::vector<uint32_t> next_;  // per point: the next point of the same conflict list
    std::vector<uint32_t> free_, pending_, visible_, orphans_, new_faces_;
    std::vector<HorizonEdge> horizon_;
    std::vector<uint32_t> horizon_from_;  // per point: index of the horizon edge leaving it
    std::vector<uint64_t> face_stamp_;
    std::vector<uint8_t> face_visible_;
    uint64_t stamp_ = 0;
};

// Index of the point of `ids` farthest from the line through a and b (Euclidean, rounded).
uint32_t farthest_from_line(const std::vector<Vec3>& p, const std::vector<uint32_t>& ids, Vec3 a, Vec3 b,
                            double& out_dist);
// Index of the point of `ids` with the largest |orient(a, b, c, .)| (rounded): the farthest from
// the plane of a, b, c, measured without forming the plane's normal.
uint32_t farthest_from_plane(const std::vector<Vec3>& p, const std::vector<uint32_t>& ids, uint32_t a, uint32_t b,
                             uint32_t c, double& out_det);

}  // namespace kairos::hull_detail
