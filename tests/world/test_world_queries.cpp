// SPDX-License-Identifier: MIT
// World queries (query_box, ray_cast, shape_cast) against brute force: every live object tested
// with the pair query the world uses, on random scenes of mixed kinds after steps, turns,
// teleports, removals, static objects, filters and adds not yet flushed, with every broad phase.
// Also the broad phase's own query_box against a scan of its boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "casts/cast.hpp"
#include "motion/motion.hpp"
#include "motion/motion_cast.hpp"
#include "scene_rng.hpp"
#include "shapes/shape.hpp"
#include "world/world.hpp"

namespace kairos {
namespace {

using scene::Rng;

struct ShapeRelease {
    void operator()(const Shape* s) const {
        if (s) s->release();
    }
};
using ShapePtr = std::unique_ptr<const Shape, ShapeRelease>;

// A random shape about `size` across: the primitives, points, segments and hulls (solid and flat).
ShapePtr random_shape(Rng& rng, double size) {
    const double h = size / 2;
    switch (rng.below(9)) {
        case 0: return ShapePtr(new SphereShape(rng.uniform(0.3, 1) * h));
        case 1: return ShapePtr(new BoxShape({rng.uniform(0.1, 1) * h, rng.uniform(0.1, 1) * h, rng.uniform(0.1, 1) * h}));
        case 2: return ShapePtr(new CapsuleShape(rng.uniform(0.2, 0.5) * h, rng.uniform(0.2, 0.5) * h));
        case 3: return ShapePtr(new CylinderShape(rng.uniform(0.3, 1) * h, rng.uniform(0.3, 1) * h));
        case 4: return ShapePtr(new ConeShape(rng.uniform(0.3, 1) * h, rng.uniform(0.3, 1) * h));
        case 5: return ShapePtr(new PointShape());
        case 6: return ShapePtr(new SegmentShape(rng.uniform(0.2, 1) * h));
        default: {
            // Eight points: a solid hull, or (case 8) a flat one in the plane z = 0.
            const bool flat = rng.below(2) == 0;
            std::vector<Vec3> pts;
            for (int i = 0; i < 8; ++i) {
                Vec3 p = rng.in_cube(h);
                if (flat) p.z = 0;
                pts.push_back(p);
            }
            ConvexHullShape* hull = nullptr;
            if (make_convex_hull(pts.data(), pts.size(), &hull) != HullStatus::Ok || hull == nullptr)
                return ShapePtr(new SphereShape(h));
            return ShapePtr(hull);
        }
    }
}

Transform rigid(const Pose& p) { return make_transform(p.position, p.orientation); }

Filter random_filter(Rng& rng) {
    Filter f;
    f.category_bits = 1u << rng.below(3);
    f.mask_bits = rng.below(3) == 0 ? 0xffffffffu : static_cast<uint32_t>(1 + rng.below(7));
    f.group = static_cast<int32_t>(rng.below(5)) - 2;  // -2 .. 2: some shared groups of both signs
    if (rng.below(2) == 0) f.group = 0;
    return f;
}

struct Item {
    ShapePtr shape;
    uint64_t id = 0;
    bool alive = false;
    bool is_static = false;
};

// A scene of `n` objects in a cube of half side `half`, stepped a few times with moves (some
// turning), teleports, removals, static objects and filters; then a few objects added with no
// step after them (the broad phase holds them as pending adds).
struct Scene {
    World world;
    std::vector<Item> items;

    Scene(BroadPhaseKind kind, uint64_t seed, int n, double half) : world(settings(kind)) {
        Rng rng(seed);
        for (int i = 0; i < n; ++i) add(rng, half);
        for (int step = 0; step < 4; ++step) {
            for (Item& it : items) {
                if (!it.alive) continue;
                const Object* o = world.find(it.id);
                const double r = rng.uniform(0, 1);
                if (r < 0.05 && !it.is_static) {
                    world.set_static(it.id, true);
                    it.is_static = true;
                } else if (r < 0.1) {
                    world.set_filter(it.id, random_filter(rng));
                } else if (r < 0.15) {
                    world.set_pose(it.id, {rng.in_cube(half), rng.orientation()});
                } else if (r < 0.18) {
                    world.remove(it.id);
                    it.alive = false;
                } else if (r < 0.7 && !it.is_static) {
                    Pose end = o->pose;
                    end.position = end.position + rng.in_cube(2);
                    if (rng.below(3) == 0) end.orientation = rng.orientation();
                    world.move(it.id, end);
                }
            }
            for (int i = 0; i < n / 20; ++i) add(rng, half);
            world.step();
        }
        for (int i = 0; i < n / 20; ++i) add(rng, half);  // pending in the broad phase
    }

    using Object = World::Object;
    static WorldSettings settings(BroadPhaseKind kind) {
        WorldSettings s;
        s.broad_phase = kind;
        return s;
    }
    void add(Rng& rng, double half) {
        Item it;
        it.shape = random_shape(rng, rng.uniform(0.5, 3));
        it.id = world.add(*it.shape, {rng.in_cube(half), rng.orientation()}, 1000 + items.size());
        it.alive = it.id != 0;
        items.push_back(std::move(it));
    }
    bool sees(const Filter* f, const Object& o) const { return f == nullptr || filters_collide(*f, o.filter); }
};

constexpr BroadPhaseKind kKinds[] = {BroadPhaseKind::SpacetimeSap, BroadPhaseKind::EncapsulatingSap,
                                     BroadPhaseKind::BruteForce, BroadPhaseKind::SpacetimeSapQueued};

std::string label(BroadPhaseKind kind, uint64_t seed) {
    return std::string(to_string(kind)) + ", seed " + std::to_string(seed);
}

// Brute force: the earliest hit over every live object the filter admits (ties: smaller id).
template <class Cast>
WorldHit brute_earliest(const Scene& s, const Filter* f, Cast&& cast) {
    WorldHit best;
    for (const Item& it : s.items) {
        if (!it.alive) continue;
        const World::Object* o = s.world.find(it.id);
        if (o == nullptr || !s.sees(f, *o)) continue;
        const CastResult r = cast(*o);
        if (!r.hit) continue;
        if (!best.hit || r.toi < best.toi || (r.toi == best.toi && it.id < best.id)) {
            best.hit = true;
            best.id = it.id;
            best.toi = r.toi;
        }
    }
    return best;
}

TEST(WorldQueries, QueryBoxMatchesBruteForce) {
    for (BroadPhaseKind kind : kKinds) {
        const uint64_t seed = 0x5eed0100 + static_cast<uint64_t>(kind);
        SCOPED_TRACE(label(kind, seed));
        Scene s(kind, seed, 400, 25);
        Rng rng(seed ^ 0xabc);
        std::size_t found = 0, empty = 0, queries = 0;
        for (int q = 0; q < 300; ++q) {
            // Small, long, point-like, and larger than the scene.
            Vec3 c = rng.in_cube(30), h = rng.in_cube(3);
            h = {std::fabs(h.x), std::fabs(h.y), std::fabs(h.z)};
            if (q % 10 == 0) h = {0, 0, 0};
            if (q % 10 == 1) h.x = 40;
            if (q % 37 == 2) h = {60, 60, 60};
            const Aabb box{c - h, c + h};
            Filter filter = random_filter(rng);
            const Filter* f = rng.below(2) == 0 ? nullptr : &filter;
            std::vector<uint64_t> got;
            s.world.query_box(box, f, got);
            std::vector<uint64_t> want;
            for (const Item& it : s.items) {
                if (!it.alive) continue;
                const World::Object* o = s.world.find(it.id);
                if (o == nullptr || !s.sees(f, *o)) continue;
                Aabb b;
                bounds(*it.shape, rigid(o->pose), b.min, b.max);
                if (boxes_overlap(b, box)) want.push_back(it.id);
            }
            std::sort(want.begin(), want.end());
            ASSERT_EQ(got, want) << "query " << q;
            found += got.size();
            empty += got.empty() ? 1 : 0;
            ++queries;
        }
        // The queries exercise both outcomes.
        EXPECT_GT(found, queries);
        EXPECT_GT(empty, queries / 20);
        EXPECT_LT(empty, queries * 9 / 10);
    }
}

TEST(WorldQueries, RayCastMatchesBruteForce) {
    for (BroadPhaseKind kind : kKinds) {
        const uint64_t seed = 0x5eed0200 + static_cast<uint64_t>(kind);
        SCOPED_TRACE(label(kind, seed));
        Scene s(kind, seed, 600, 8);
        Rng rng(seed ^ 0xdef);
        const double tol = s.world.settings().tolerance;
        const uint32_t max_it = s.world.settings().max_iterations;
        int hits = 0, rays = 0;
        uint64_t casts = 0;
        for (int q = 0; q < 300; ++q) {
            const Vec3 origin = rng.in_cube(10);
            Vec3 d = rng.direction() * rng.uniform(1, 40);
            if (q % 7 == 0) d = {d.x, 0, 0};  // along the columns
            if (q % 11 == 0) d = {0, 0, 0};   // a point: a hit only inside an object
            Filter filter = random_filter(rng);
            const Filter* f = rng.below(3) == 0 ? &filter : nullptr;
            const WorldHit got = s.world.ray_cast(origin, d, f);
            const WorldHit want =
                brute_earliest(s, f, [&](const World::Object& o) { return ray_cast(*o.shape, rigid(o.pose), origin, d, tol, max_it); });
            ASSERT_EQ(got.hit, want.hit) << "ray " << q;
            if (got.hit) {
                ASSERT_EQ(got.id, want.id) << "ray " << q;
                ASSERT_EQ(got.toi, want.toi) << "ray " << q;
                EXPECT_EQ(got.user_data, s.world.find(got.id)->user_data);
                EXPECT_NEAR(length(got.normal), 1, 1e-12);
                ++hits;
            }
            casts += got.casts;
            ++rays;
        }
        EXPECT_GT(hits, rays / 5);
        EXPECT_LT(hits, rays * 19 / 20);
        // The broad phase keeps most objects out: far fewer casts than rays times objects.
        EXPECT_LT(casts, static_cast<uint64_t>(rays) * s.world.live_count() / 4);
    }
}

TEST(WorldQueries, ShapeCastMatchesBruteForce) {
    for (BroadPhaseKind kind : kKinds) {
        const uint64_t seed = 0x5eed0300 + static_cast<uint64_t>(kind);
        SCOPED_TRACE(label(kind, seed));
        Scene s(kind, seed, 400, 7);
        Rng rng(seed ^ 0x123);
        const uint32_t max_it = 256;
        int hits = 0, turning_hits = 0, casts = 0;
        for (int q = 0; q < 160; ++q) {
            // A quarter at a coarse tolerance, far above the world's: hits come that far before
            // contact, from objects whose boxes the path misses by less.
            const double tol = q % 4 == 3 ? 0.3 : 1e-8;
            const ShapePtr shape = random_shape(rng, rng.uniform(0.5, 2));
            const Pose start{rng.in_cube(9), rng.orientation()};
            Pose end{start.position + rng.direction() * rng.uniform(1, 20), start.orientation};
            const bool turning = q % 3 == 0;
            if (turning) end.orientation = rng.orientation();
            Filter filter = random_filter(rng);
            const Filter* f = rng.below(3) == 0 ? &filter : nullptr;
            const WorldHit got = s.world.shape_cast(*shape, start, end, f, tol, max_it);
            const Motion motion(start, end);
            const WorldHit want = brute_earliest(s, f, [&](const World::Object& o) {
                return motion.rotates() ? motion_cast(*shape, motion, *o.shape, Motion(o.pose, o.pose), tol, max_it)
                                        : shape_cast(*shape, rigid(start), motion.linear(), *o.shape, rigid(o.pose), {},
                                                     tol, max_it);
            });
            ASSERT_EQ(got.hit, want.hit) << "cast " << q;
            if (got.hit) {
                ASSERT_EQ(got.id, want.id) << "cast " << q;
                ASSERT_EQ(got.toi, want.toi) << "cast " << q;
                EXPECT_NEAR(length(got.normal), 1, 1e-9);
                ++hits;
                turning_hits += turning ? 1 : 0;
            }
            ++casts;
        }
        EXPECT_GT(hits, casts / 5);
        EXPECT_LT(hits, casts * 19 / 20);
        EXPECT_GT(turning_hits, 3);
    }
}

// The normal points out of the object hit, against the motion: a ball dropped onto a slab.
TEST(WorldQueries, HitNormalsPointOutOfTheObjectHit) {
    World world;
    const ShapePtr slab(new BoxShape({10, 10, 0.5}));
    const ShapePtr ball(new SphereShape(1));
    const uint64_t floor = world.add(*slab, {{0, 0, -0.5}, {0, 0, 0, 1}}, 7);
    world.set_static(floor, true);
    const WorldHit ray = world.ray_cast({1, 2, 5}, {0, 0, -10}, nullptr);
    ASSERT_TRUE(ray.hit);
    EXPECT_EQ(ray.id, floor);
    EXPECT_EQ(ray.user_data, 7u);
    EXPECT_NEAR(ray.toi, 0.5, 1e-12);
    EXPECT_NEAR(ray.normal.z, 1, 1e-12);
    EXPECT_NEAR(ray.point.z, 0, 1e-9);
    const WorldHit cast = world.shape_cast(*ball, {{1, 2, 5}, {0, 0, 0, 1}}, {{1, 2, -5}, {0, 0, 0, 1}}, nullptr, 1e-10, 256);
    ASSERT_TRUE(cast.hit);
    EXPECT_NEAR(cast.toi, 0.4, 1e-9);
    EXPECT_NEAR(cast.normal.z, 1, 1e-9);
    EXPECT_NEAR(cast.point.z, 0, 1e-6);
    // Filtered out: a query whose mask excludes the floor's category sees nothing.
    const Filter none{1, 2, 0};
    EXPECT_FALSE(world.ray_cast({1, 2, 5}, {0, 0, -10}, &none).hit);
    // Started inside: toi 0.
    const WorldHit inside = world.ray_cast({0, 0, -0.5}, {0, 0, 1}, nullptr);
    ASSERT_TRUE(inside.hit);
    EXPECT_EQ(inside.toi, 0);
}

// The broad phase alone: query_box against a scan of its boxes, after adds (some never flushed),
// removes (some never flushed), teleports, moves and steps, static changes; every kind.
TEST(WorldQueries, BroadPhaseQueryBoxMatchesAScan) {
    for (BroadPhaseKind kind : kKinds) {
        const uint64_t seed = 0x5eed0400 + static_cast<uint64_t>(kind);
        SCOPED_TRACE(label(kind, seed));
        Rng rng(seed);
        auto bp = BroadPhase::create(kind);
        ASSERT_NE(bp, nullptr);
        std::vector<char> present(600, 0);
        auto random_box = [&](double spread) {
            const Vec3 c = rng.in_cube(spread);
            const Vec3 h{rng.uniform(0, 2), rng.uniform(0, 2), rng.uniform(0, 2)};
            return Aabb{c - h, c + h};
        };
        for (int round = 0; round < 12; ++round) {
            for (uint32_t id = 0; id < present.size(); ++id) {
                const double r = rng.uniform(0, 1);
                if (!present[id] && r < 0.3) {
                    present[id] = bp->add(id, random_box(30), rng.below(4) == 0);
                } else if (present[id] && r < 0.05) {
                    present[id] = !bp->remove(id);
                } else if (present[id] && r < 0.1) {
                    bp->teleport(id, random_box(30));
                } else if (present[id] && r < 0.12) {
                    bp->set_static(id, rng.below(2) == 0);
                } else if (present[id] && r < 0.5 && round % 2 == 0) {
                    const Aabb& b = *bp->box(id);
                    const Vec3 d = rng.in_cube(3);
                    bp->move(id, {b.min + d, b.max + d});
                }
            }
            if (round % 2 == 0) bp->step();  // odd rounds leave adds and removes pending
            ASSERT_EQ(bp->check_invariants(), "") << "round " << round;
            for (int q = 0; q < 50; ++q) {
                const Aabb box = random_box(35);
                std::vector<uint32_t> got;
                bp->query_box(box, got);
                std::sort(got.begin(), got.end());
                ASSERT_TRUE(std::adjacent_find(got.begin(), got.end()) == got.end()) << "an id twice";
                std::vector<uint32_t> want;
                for (uint32_t id = 0; id < present.size(); ++id)
                    if (present[id] && boxes_overlap(*bp->box(id), box)) want.push_back(id);
                ASSERT_EQ(got, want) << "round " << round << ", query " << q;
            }
        }
    }
}

}  // namespace
}  // namespace kairos
