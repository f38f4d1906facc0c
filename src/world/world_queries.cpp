// SPDX-License-Identifier: MIT
// World queries (see world.hpp): a box, a ray and a cast shape against the objects at their
// current poses, through the broad phase's structure.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "casts/cast.hpp"
#include "motion/motion.hpp"
#include "motion/motion_cast.hpp"
#include "world/world.hpp"

namespace kairos {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

Transform rigid(const Pose& s) { return make_transform(s.position, s.orientation); }

Vec3 lerp(Vec3 a, Vec3 b, double t) { return (1 - t) * a + t * b; }

// The box swept over [t0, t1] of s (each coordinate linear in t: the union of the two ends),
// grown by a few ulps for the rounding of the interpolation.
Aabb piece(const SweptAabb& s, double t0, double t1) {
    const Vec3 lo0 = lerp(s.start.min, s.end.min, t0), lo1 = lerp(s.start.min, s.end.min, t1);
    const Vec3 hi0 = lerp(s.start.max, s.end.max, t0), hi1 = lerp(s.start.max, s.end.max, t1);
    Aabb b{cwise_min(lo0, lo1), cwise_max(hi0, hi1)};
    const double m = 4 * kEps * std::fmax(max_abs(b.min), max_abs(b.max));
    return {b.min - Vec3{m, m, m}, b.max + Vec3{m, m, m}};
}

// Keeps the earlier hit; at one toi the smaller id.
void keep_earliest(WorldHit& best, const WorldHit& h) {
    if (!h.hit) return;
    if (!best.hit || h.toi < best.toi || (h.toi == best.toi && h.id < best.id)) {
        const uint32_t casts = best.casts;
        best = h;
        best.casts = casts;
    }
}

}  // namespace

// The casts report a hit once the shapes are within their tolerance of each other, relative to
// their sizes (a shape cast: of the query's extent and motion and the object's; a motion cast:
// tolerance times the smaller bounding radius), so an object that far from the query's path is
// still a candidate. The broad phase's boxes carry the world's tolerance already; a query with a
// larger one needs this pad (reach: the query's extent and motion).
// The shape cast's size is seen from the ray point, so it grows with the gap g itself: a hit
// comes once g <= tolerance (g + extents), that is g <= tolerance / (1 - tolerance) extents.
double World::hit_pad(double tolerance, double reach) const {
    return tolerance / (1 - tolerance) * (reach + 2 * broad_->max_extent());
}

void World::sweep_candidates(const SweptAabb& swept, double pad, const Filter* filter,
                             std::vector<std::pair<double, uint32_t>>& out) const {
    out.clear();
    const Vec3 p{pad, pad, pad};
    const SweptAabb s{{swept.start.min - p, swept.start.max + p}, {swept.end.min - p, swept.end.max + p}};
    // The broad phase's columns run along x: a query visits every column its box touches on y
    // and z, so a long oblique sweep is split into pieces about a column wide there.
    const double cell = broad_->query_cell_size();
    std::size_t pieces = 1;
    if (cell > 0) {
        double travel = 0;
        for (int k = 1; k < 3; ++k)
            travel = std::fmax(travel, std::fmax(std::fabs(s.end.min[k] - s.start.min[k]),
                                                 std::fabs(s.end.max[k] - s.start.max[k])));
        const double n = std::ceil(travel / cell);
        if (n > 1) pieces = n < 1024 ? static_cast<std::size_t>(n) : 1024;
    }
    std::vector<uint32_t> slots;
    for (std::size_t i = 0; i < pieces; ++i) {
        const double t0 = static_cast<double>(i) / static_cast<double>(pieces);
        const double t1 = i + 1 == pieces ? 1.0 : static_cast<double>(i + 1) / static_cast<double>(pieces);
        broad_->query_box(piece(s, t0, t1), slots);
    }
    std::sort(slots.begin(), slots.end());
    slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
    for (uint32_t slot : slots) {
        const Object& o = objects_[slot];
        if (!o.alive || (filter != nullptr && !filters_collide(*filter, o.filter))) continue;
        const Aabb* box = broad_->box(slot);
        if (box == nullptr) continue;
        const Aabb grown_box{box->min - p, box->max + p};
        double t = 0;
        if (first_overlap_time(s, SweptAabb{grown_box, grown_box}, &t)) out.push_back({t, slot});
    }
    std::sort(out.begin(), out.end());
}

void World::query_box(const Aabb& q, const Filter* filter, std::vector<uint64_t>& out) const {
    out.clear();
    std::vector<uint32_t> slots;
    broad_->query_box(q, slots);
    for (uint32_t slot : slots) {
        const Object& o = objects_[slot];
        if (!o.alive || (filter != nullptr && !filters_collide(*filter, o.filter))) continue;
        Aabb b;
        bounds(*o.shape, rigid(o.pose), b.min, b.max);
        if (boxes_overlap(b, q)) out.push_back(make_id(slot, o.generation));
    }
    std::sort(out.begin(), out.end());
}

WorldHit World::ray_cast(Vec3 origin, Vec3 translation, const Filter* filter) const {
    const Vec3 end = origin + translation;
    std::vector<std::pair<double, uint32_t>> candidates;
    sweep_candidates({{origin, origin}, {end, end}}, hit_pad(settings_.tolerance, 0), filter, candidates);
    WorldHit best;
    for (const auto& [t, slot] : candidates) {
        if (best.hit && t > best.toi) break;  // boxes hold their objects: no later box hits earlier
        const Object& o = objects_[slot];
        const CastResult r = kairos::ray_cast(*o.shape, rigid(o.pose), origin, translation, settings_.tolerance,
                                              settings_.max_iterations);
        ++best.casts;
        if (r.hit)
            keep_earliest(best, {true, make_id(slot, o.generation), o.user_data, r.toi, r.point, r.normal, 0});
    }
    return best;
}

WorldHit World::shape_cast(const Shape& shape, const Pose& start, const Pose& end, const Filter* filter,
                           double tolerance, uint32_t max_iterations) const {
    SweptAabb swept;
    const Sweep sw = sweep_of(shape, start, end, nullptr, &swept.start, &swept.end);
    std::vector<std::pair<double, uint32_t>> candidates;
    // The query's extent, motion and bounding radius about its origin (a motion cast's tolerance
    // is relative to the smaller of the two radii).
    const double radius = std::sqrt(3.0) * std::fmax(max_abs(swept.start.min - start.position),
                                                     max_abs(swept.start.max - start.position));
    const double reach = std::fmax(max_abs(swept.start.max - swept.start.min), max_abs(swept.end.max - swept.end.min)) +
                         max_abs(sw.translation) + radius;
    sweep_candidates(swept, hit_pad(tolerance, reach), filter, candidates);
    const Motion motion(start, end);
    WorldHit best;
    for (const auto& [t, slot] : candidates) {
        if (best.hit && t > best.toi) break;
        const Object& o = objects_[slot];
        const Transform pose = rigid(o.pose);
        const CastResult r =
            sw.rotates ? motion_cast(shape, motion, *o.shape, Motion(o.pose, o.pose), tolerance, max_iterations)
                       : kairos::shape_cast(shape, sw.start, sw.translation, *o.shape, pose, {}, tolerance,
                                            max_iterations);
        ++best.casts;
        // The casts' normals point from the cast shape toward the object.
        if (r.hit)
            keep_earliest(best, {true, make_id(slot, o.generation), o.user_data, r.toi, r.point, -r.normal, 0});
    }
    return best;
}

}  // namespace kairos
