// SPDX-License-Identifier: MIT
// Tests of the world's step on the core: broad-phase pairs against brute force and against boxes
// computed here, contacts against a cast of every pair, turning objects against sampled poses,
// edits between steps, determinism, stale ids.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "casts/cast.hpp"
#include "gjk/gjk.hpp"
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

// A random convex primitive about `size` across.
ShapePtr random_shape(Rng& rng, double size) {
    const double h = size / 2;
    switch (rng.below(5)) {
        case 0:
            return ShapePtr(new SphereShape(rng.uniform(0.5, 1) * h));
        case 1:
            return ShapePtr(new BoxShape({rng.uniform(0.3, 1) * h, rng.uniform(0.3, 1) * h, rng.uniform(0.3, 1) * h}));
        case 2:
            return ShapePtr(new CapsuleShape(rng.uniform(0.2, 0.5) * h, rng.uniform(0.2, 0.5) * h));
        case 3:
            return ShapePtr(new CylinderShape(rng.uniform(0.3, 1) * h, rng.uniform(0.3, 1) * h));
        default:
            return ShapePtr(new ConeShape(rng.uniform(0.3, 1) * h, rng.uniform(0.3, 1) * h));
    }
}

// One object of a test scene: per step it moves by `velocity` and turns by `spin` radians about
// `spin_axis` (world frame).
struct Body {
    ShapePtr shape;
    Pose pose;
    Vec3 velocity;
    Vec3 spin_axis{0, 0, 1};
    double spin = 0;
    uint64_t id = 0;
    bool alive = false;
};

Pose end_of(const Body& b) {
    Pose e = b.pose;
    e.position = b.pose.position + b.velocity;
    if (b.spin != 0) e.orientation = normalized(axis_angle(b.spin_axis, b.spin) * b.pose.orientation);
    return e;
}

Transform rigid(const Pose& s) { return make_transform(s.position, s.orientation); }

std::string ids(uint64_t a, uint64_t b) {
    return "(" + std::to_string(a & 0xffffffffu) + "g" + std::to_string(a >> 32) + ", " +
           std::to_string(b & 0xffffffffu) + "g" + std::to_string(b >> 32) + ")";
}

struct Totals {
    uint64_t steps = 0, object_steps = 0, pairs = 0, contacts = 0, swaps = 0, queries = 0, rejections = 0;
    uint64_t rotating_pairs_checked = 0, rotating_contacts = 0;
};

// Three worlds (space-time, encapsulating, brute force) driven in lock step over one scene. Every
// step is checked: pairs against brute force and against boxes computed here, contacts against a
// cast of every pair, the broad phase's structure.
class Harness {
public:
    explicit Harness(uint64_t seed) : seed_(seed) {
        for (auto kind : {BroadPhaseKind::SpacetimeSap, BroadPhaseKind::EncapsulatingSap, BroadPhaseKind::BruteForce}) {
            WorldSettings s;
            s.broad_phase = kind;
            worlds_.push_back(std::make_unique<World>(s));
        }
    }
    World& sap() { return *worlds_[0]; }
    World& enc() { return *worlds_[1]; }
    World& brute() { return *worlds_[2]; }
    std::vector<Body>& bodies() { return bodies_; }
    const Totals& totals() const { return totals_; }

    void add(Body b) {
        b.alive = true;
        for (std::size_t k = 0; k < worlds_.size(); ++k) {
            const uint64_t id = worlds_[k]->add(*b.shape, b.pose, 1000 + bodies_.size());
            if (k == 0) b.id = id;
            EXPECT_EQ(id, b.id) << "the worlds must hand out the same ids";
        }
        bodies_.push_back(std::move(b));
    }
    void remove(std::size_t i) {
        bodies_[i].alive = false;
        for (auto& w : worlds_) EXPECT_TRUE(w->remove(bodies_[i].id));
    }
    void teleport(std::size_t i, const Pose& pose) {
        bodies_[i].pose = pose;
        for (auto& w : worlds_) EXPECT_TRUE(w->set_pose(bodies_[i].id, pose));
    }
    void check_structure() {
        const std::string why = sap().broad_phase().check_invariants();
        EXPECT_EQ(why, "") << "seed " << seed_ << " after step " << totals_.steps;
    }

    // One step; false after a mismatch.
    bool step() {
        SCOPED_TRACE("seed " + std::to_string(seed_) + ", step " + std::to_string(totals_.steps));
        for (const Body& b : bodies_) {
            if (!b.alive || (b.velocity == Vec3{} && b.spin == 0)) continue;
            for (auto& w : worlds_) EXPECT_TRUE(w->move(b.id, end_of(b)));
        }
        for (auto& w : worlds_) w->step();
        int faults = 0;
        auto fault = [&](const std::string& msg) {
            if (++faults <= 6) ADD_FAILURE() << msg;
        };

        // Space-time pairs equal brute force over the same boxes, bit for bit in time.
        const auto& ref = brute().pairs();
        const auto& got = sap().pairs();
        if (ref.size() != got.size())
            fault("space-time SAP has " + std::to_string(got.size()) + " pairs, brute force " +
                  std::to_string(ref.size()));
        for (std::size_t i = 0; i < std::min(ref.size(), got.size()); ++i) {
            if (ref[i].a != got[i].a || ref[i].b != got[i].b ||
                std::bit_cast<uint64_t>(ref[i].t_first) != std::bit_cast<uint64_t>(got[i].t_first)) {
                fault("pair " + std::to_string(i) + ": space-time " + ids(got[i].a, got[i].b) + " at " +
                      std::to_string(got[i].t_first) + ", brute force " + ids(ref[i].a, ref[i].b) + " at " +
                      std::to_string(ref[i].t_first));
                break;
            }
        }
        // The encapsulating sweep: a superset whose extra pairs never overlap.
        std::size_t j = 0;
        uint64_t extra = 0;
        for (const WorldPair& p : enc().pairs()) {
            if (j < ref.size() && ref[j].a == p.a && ref[j].b == p.b) {
                ++j;
            } else if (std::isinf(p.t_first)) {
                ++extra;
            } else {
                fault("encapsulating pair " + ids(p.a, p.b) + " unknown to brute force");
            }
        }
        if (j != ref.size()) fault("encapsulating SAP missed a pair");
        EXPECT_EQ(enc().counters().false_positives, extra);
        EXPECT_EQ(sap().counters().false_positives, 0u);

        check_boxes(fault);
        check_contacts(fault);

        // Everyone moves to the end pose.
        uint64_t alive = 0;
        for (Body& b : bodies_) {
            if (!b.alive) continue;
            ++alive;
            b.pose = end_of(b);
        }
        check_structure();
        ++totals_.steps;
        totals_.object_steps += alive;
        totals_.pairs += got.size();
        totals_.contacts += sap().contacts().size();
        totals_.swaps += sap().counters().swaps;
        totals_.queries += sap().counters().narrow_phase_queries;
        totals_.rejections += sap().counters().axis_rejections;
        return faults == 0;
    }

    double per_object(uint64_t n) const {
        return static_cast<double>(n) / static_cast<double>(std::max<uint64_t>(totals_.object_steps, 1));
    }

private:
    const Body* body_of(uint64_t id) const {
        for (const Body& b : bodies_)
            if (b.alive && b.id == id) return &b;
        return nullptr;
    }

    // Boxes computed here from the shapes' support mappings: for objects that only translate,
    // every pair whose tight boxes overlap at some moment is reported, and every reported pair's
    // boxes come within a hair (the world's tolerance margin) of each other.
    template <class Fault>
    void check_boxes(Fault& fault) {
        std::vector<std::size_t> live;
        for (std::size_t i = 0; i < bodies_.size(); ++i)
            if (bodies_[i].alive && bodies_[i].spin == 0) live.push_back(i);
        auto swept = [&](const Body& b, double grow) {
            SweptAabb s;
            bounds(*b.shape, rigid(b.pose), s.start.min, s.start.max);
            bounds(*b.shape, rigid(end_of(b)), s.end.min, s.end.max);
            const double g =
                grow * (1 + max_abs(s.start.max - s.start.min) + max_abs(s.start.max) + max_abs(s.start.min));
            for (Aabb* a : {&s.start, &s.end}) {
                a->min = a->min - Vec3{g, g, g};
                a->max = a->max + Vec3{g, g, g};
            }
            return s;
        };
        const auto& got = sap().pairs();
        auto reported = [&](uint64_t a, uint64_t b) {
            return std::binary_search(
                got.begin(), got.end(), WorldPair{a, b, 0},
                [](const WorldPair& x, const WorldPair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
        };
        for (std::size_t x = 0; x < live.size(); ++x) {
            for (std::size_t y = x + 1; y < live.size(); ++y) {
                const Body& a = bodies_[live[x]];
                const Body& b = bodies_[live[y]];
                double t = 0;
                const bool tight = first_overlap_time(swept(a, 0), swept(b, 0), &t);
                const bool near = first_overlap_time(swept(a, 1e-8), swept(b, 1e-8), &t);
                const bool rep = reported(std::min(a.id, b.id), std::max(a.id, b.id));
                if (tight && !rep) fault("missed pair " + ids(a.id, b.id) + " whose tight boxes overlap");
                if (rep && !near) fault("reported pair " + ids(a.id, b.id) + " whose boxes never come near");
            }
        }
    }

    // Contacts: exactly the pairs that a cast of every pair hits (a shape cast when both only
    // translate, else a motion cast), with the same results bit for bit (the world runs that cast,
    // or proves a miss). Pairs with a turning object also against sampled moments: every moment
    // at which the shapes intersect comes no earlier than the pair's reported contact.
    template <class Fault>
    void check_contacts(Fault& fault) {
        const auto& contacts = sap().contacts();
        for (std::size_t i = 1; i < contacts.size(); ++i) {
            const Contact& p = contacts[i - 1];
            const Contact& q = contacts[i];
            const bool ordered = p.toi < q.toi || (p.toi == q.toi && (p.a < q.a || (p.a == q.a && p.b < q.b)));
            if (!ordered) fault("contacts not sorted by (toi, a, b) at " + std::to_string(i));
        }
        auto find = [&](uint64_t a, uint64_t b) -> const Contact* {
            for (const Contact& c : contacts)
                if (c.a == a && c.b == b) return &c;
            return nullptr;
        };
        for (const Contact& c : contacts) {
            const Body* a = body_of(c.a);
            const Body* b = body_of(c.b);
            if (!(c.a < c.b) || a == nullptr || b == nullptr) {
                fault("contact " + ids(c.a, c.b) + " is not a live ordered pair");
                continue;
            }
            if (!(c.toi >= 0 && c.toi <= 1) || !(std::fabs(length(c.normal) - 1) < 1e-9))
                fault("contact " + ids(c.a, c.b) + " out of range");
            if (c.user_a != 1000 + static_cast<uint64_t>(a - bodies_.data()) ||
                c.user_b != 1000 + static_cast<uint64_t>(b - bodies_.data()))
                fault("contact " + ids(c.a, c.b) + " carries the wrong user data");
        }
        const double tol = sap().settings().tolerance;
        for (std::size_t x = 0; x < bodies_.size(); ++x) {
            for (std::size_t y = x + 1; y < bodies_.size(); ++y) {
                const Body* a = &bodies_[x];
                const Body* b = &bodies_[y];
                if (!a->alive || !b->alive) continue;
                if (b->id < a->id) std::swap(a, b);
                const Contact* c = find(a->id, b->id);
                if (a->spin == 0 && b->spin == 0) {
                    // The translation as the world sees it: end minus start (not the velocity,
                    // which differs from it by the rounding of the end position).
                    const Vec3 da = end_of(*a).position - a->pose.position;
                    const Vec3 db = end_of(*b).position - b->pose.position;
                    const CastResult r = shape_cast(*a->shape, rigid(a->pose), da, *b->shape, rigid(b->pose), db, tol,
                                                    sap().settings().max_iterations);
                    if (r.hit != (c != nullptr)) {
                        fault("pair " + ids(a->id, b->id) + ": cast of the pair says hit " + std::to_string(r.hit) +
                              " at " + std::to_string(r.toi) + ", the world " + (c ? "reports" : "does not report") +
                              " it");
                    } else if (c != nullptr && (std::bit_cast<uint64_t>(c->toi) != std::bit_cast<uint64_t>(r.toi) ||
                                                !(c->normal == r.normal) || !(c->point == r.point))) {
                        char buf[256];
                        std::snprintf(buf, sizeof buf,
                                      " toi %.17g / %.17g, normal %.17g %.17g %.17g / %.17g %.17g %.17g", c->toi, r.toi,
                                      c->normal.x, c->normal.y, c->normal.z, r.normal.x, r.normal.y, r.normal.z);
                        fault("pair " + ids(a->id, b->id) + ": contact differs from the cast of the pair:" + buf);
                    }
                    continue;
                }
                // A turning pair: the motion cast of the pair, bit for bit (a still body's motion
                // is its pose to itself, as the world has it) ...
                ++totals_.rotating_pairs_checked;
                if (c != nullptr) ++totals_.rotating_contacts;
                auto still = [](const Body& x) { return x.velocity == Vec3{} && x.spin == 0; };
                const Motion ma(a->pose, still(*a) ? a->pose : end_of(*a));
                const Motion mb(b->pose, still(*b) ? b->pose : end_of(*b));
                const CastResult r = motion_cast(*a->shape, ma, *b->shape, mb, tol, sap().settings().max_iterations);
                if (r.hit != (c != nullptr)) {
                    fault("turning pair " + ids(a->id, b->id) + ": motion cast of the pair says hit " +
                          std::to_string(r.hit) + " at " + std::to_string(r.toi) + ", the world " +
                          (c ? "reports" : "does not report") + " it");
                } else if (c != nullptr && (std::bit_cast<uint64_t>(c->toi) != std::bit_cast<uint64_t>(r.toi) ||
                                            !(c->normal == r.normal) || !(c->point == r.point))) {
                    fault("turning pair " + ids(a->id, b->id) + ": contact differs from the motion cast of the pair");
                }
                // ... and, independently, no moment sampled in the step at which the shapes
                // intersect comes before the reported contact; gjk_intersect decides each moment.
                constexpr int kSamples = 24;
                for (int k = 0; k <= kSamples; ++k) {
                    const double t = static_cast<double>(k) / kSamples;
                    Vec3 axis{};
                    if (!gjk_intersect(*a->shape, rigid(ma.at(t)), *b->shape, rigid(mb.at(t)), axis, nullptr)) continue;
                    if (c == nullptr || c->toi > t + tol) {
                        fault("turning pair " + ids(a->id, b->id) + " intersects at t = " + std::to_string(t) +
                              (c ? ", reported later at " + std::to_string(c->toi) : ", not reported"));
                    }
                    break;
                }
            }
        }
    }

    uint64_t seed_;
    std::vector<std::unique_ptr<World>> worlds_;
    std::vector<Body> bodies_;
    Totals totals_;
};

Body random_body(Rng& rng, double side, double size, double speed) {
    Body b;
    b.shape = random_shape(rng, rng.uniform(0.6, 1.4) * size);
    b.pose = {rng.in_cube(side / 2), rng.orientation()};
    b.velocity = rng.in_cube(speed);
    return b;
}

void report(const char* scene, const Harness& h) {
    const Totals& t = h.totals();
    std::printf(
        "[ scene    ] %-14s steps %llu  pairs/object/step %.3f  contacts/object/step %.3f  swaps/object/step "
        "%.2f  casts %llu  axis rejections %llu  turning pairs %llu (%llu contacts)\n",
        scene, static_cast<unsigned long long>(t.steps), h.per_object(t.pairs), h.per_object(t.contacts),
        h.per_object(t.swaps), static_cast<unsigned long long>(t.queries),
        static_cast<unsigned long long>(t.rejections), static_cast<unsigned long long>(t.rotating_pairs_checked),
        static_cast<unsigned long long>(t.rotating_contacts));
}

// ---- Hand-made cases -------------------------------------------------------------------------

TEST(World, BulletThroughAThinWall) {
    World w;
    ShapePtr wall(new BoxShape({0.01, 2, 2}));
    ShapePtr bullet(new SphereShape(0.1));
    const uint64_t wall_id = w.add(*wall, {{0, 0, 0}, {}}, 7);
    const uint64_t bullet_id = w.add(*bullet, {{-5, 0, 0}, {}}, 8);
    ASSERT_TRUE(w.move(bullet_id, {{5, 0, 0}, {}}));
    w.step();
    // Frames alone see the bullet at x = -5 and x = 5: the step finds it at x = -0.11, t = 0.489.
    ASSERT_EQ(w.contacts().size(), 1u);
    const Contact& c = w.contacts()[0];
    EXPECT_EQ(c.a, wall_id);
    EXPECT_EQ(c.b, bullet_id);
    EXPECT_EQ(c.user_a, 7u);
    EXPECT_EQ(c.user_b, 8u);
    EXPECT_NEAR(c.toi, (5 - 0.11) / 10, 1e-9);
    EXPECT_NEAR(c.normal.x, -1, 1e-9);  // from the wall toward the bullet, which comes from -x
    EXPECT_NEAR(c.point.x, -0.01, 1e-6);
    ASSERT_EQ(w.pairs().size(), 1u);
    EXPECT_NEAR(w.pairs()[0].t_first, (5 - 0.11) / 10, 1e-9);
    EXPECT_EQ(w.counters().narrow_phase_queries, 1u);
    EXPECT_EQ(w.counters().moving_objects, 1u);
    // Moved to the end pose; the move cleared.
    EXPECT_EQ(w.find(bullet_id)->pose.position, (Vec3{5, 0, 0}));
    w.step();
    EXPECT_TRUE(w.contacts().empty());
    EXPECT_TRUE(w.pairs().empty());
}

TEST(World, StaleIdsAreRejected) {
    World w;
    ShapePtr s(new SphereShape(1));
    const uint64_t a = w.add(*s, {{0, 0, 0}, {}}, 0);
    ASSERT_NE(a, 0u);
    EXPECT_TRUE(w.remove(a));
    EXPECT_FALSE(w.remove(a));
    EXPECT_FALSE(w.move(a, {{1, 0, 0}, {}}));
    EXPECT_FALSE(w.set_pose(a, {{1, 0, 0}, {}}));
    EXPECT_EQ(w.find(a), nullptr);
    EXPECT_EQ(w.find(0), nullptr);
    // The slot's next occupant has a new id; the old one stays stale.
    const uint64_t b = w.add(*s, {{0, 0, 0}, {}}, 0);
    EXPECT_NE(a, b);
    EXPECT_EQ(World::index_of(a), World::index_of(b));
    EXPECT_FALSE(w.move(a, {{1, 0, 0}, {}}));
    EXPECT_TRUE(w.move(b, {{1, 0, 0}, {}}));
    EXPECT_EQ(s->reference_count(), 2u);
    w.step();
    EXPECT_EQ(w.broad_phase().check_invariants(), "");
}

TEST(World, TeleportCancelsTheMove) {
    World w;
    ShapePtr s(new BoxShape({0.5, 0.5, 0.5}));
    const uint64_t a = w.add(*s, {{0, 0, 0}, {}}, 0);
    const uint64_t b = w.add(*s, {{3, 0, 0}, {}}, 0);
    ASSERT_TRUE(w.move(a, {{3, 0, 0}, {}}));
    ASSERT_TRUE(w.set_pose(a, {{-3, 0, 0}, {}}));
    w.step();
    EXPECT_TRUE(w.contacts().empty());
    EXPECT_EQ(w.find(a)->pose.position, (Vec3{-3, 0, 0}));
    // Teleported onto b: touching at the start of the next step, without a sweep.
    ASSERT_TRUE(w.set_pose(a, {{2.5, 0, 0}, {}}));
    w.step();
    ASSERT_EQ(w.contacts().size(), 1u);
    EXPECT_EQ(w.contacts()[0].toi, 0.0);
    EXPECT_EQ(w.contacts()[0].a, a);
    EXPECT_EQ(w.contacts()[0].b, b);
}

TEST(World, SpinningRodHitsItsNeighbour) {
    // A rod 4 long along x turns a quarter turn about z; a sphere sits at (0, 1.5, 0). The rod's
    // tip sweeps through it; frames at t = 0 and 1 see no contact only if the end is clear.
    World w;
    ShapePtr rod(new CapsuleShape(0.05, 2.0));  // axis z in its frame
    ShapePtr ball(new SphereShape(0.2));
    const Quat lying = axis_angle({0, 1, 0}, std::numbers::pi / 2);  // local z -> world -x
    const uint64_t r = w.add(*rod, {{0, 0, 0}, lying}, 0);
    const uint64_t s = w.add(*ball, {{1.2, 1.2, 0}, {}}, 0);
    const Quat turned = normalized(axis_angle({0, 0, 1}, std::numbers::pi / 2) * lying);
    ASSERT_TRUE(w.move(r, {{0, 0, 0}, turned}));
    w.step();
    EXPECT_EQ(w.counters().rotating_objects, 1u);
    ASSERT_EQ(w.contacts().size(), 1u) << "the tip passes through the ball at 45 degrees";
    EXPECT_LE(w.contacts()[0].toi, 0.5);
    EXPECT_EQ(w.contacts()[0].a, r);
    EXPECT_EQ(w.contacts()[0].b, s);
    // Still now: the loose box of the turn shrinks back to the pose, and no contact remains.
    w.step();
    EXPECT_TRUE(w.contacts().empty());
    EXPECT_EQ(w.broad_phase().check_invariants(), "");
}

// ---- Random scenes ---------------------------------------------------------------------------

TEST(World, GasMatchesBruteForceAndPairwiseCasts) {
    for (uint64_t seed : {101u, 102u}) {
        Rng rng(seed);
        Harness h(seed);
        for (int i = 0; i < 160; ++i) h.add(random_body(rng, 14, 1.0, 1.0));
        for (int s = 0; s < 4; ++s) ASSERT_TRUE(h.step()) << "seed " << seed;
        report("gas", h);
        EXPECT_GT(h.per_object(h.totals().pairs), 0.1) << "seed " << seed;
        EXPECT_LT(h.per_object(h.totals().pairs), 2.0) << "seed " << seed;
        EXPECT_GT(h.per_object(h.totals().contacts), 0.02) << "seed " << seed;
        EXPECT_LT(h.per_object(h.totals().contacts), 1.0) << "seed " << seed;
    }
}

TEST(World, PileMatchesBruteForceAndPairwiseCasts) {
    for (uint64_t seed : {111u, 112u}) {
        Rng rng(seed);
        Harness h(seed);
        for (int i = 0; i < 120; ++i) h.add(random_body(rng, 5, 1.2, 0.15));
        for (int s = 0; s < 3; ++s) ASSERT_TRUE(h.step()) << "seed " << seed;
        report("pile", h);
        EXPECT_GT(h.per_object(h.totals().pairs), 2.0) << "seed " << seed;
        EXPECT_LT(h.per_object(h.totals().pairs), 60.0) << "seed " << seed;
        EXPECT_GT(h.per_object(h.totals().contacts), 0.5) << "seed " << seed;
    }
}

TEST(World, FlockCausesNoSwap) {
    for (uint64_t seed : {121u, 122u}) {
        Rng rng(seed);
        Harness h(seed);
        const Vec3 common = rng.in_cube(1.5);
        for (int i = 0; i < 200; ++i) {
            Body b = random_body(rng, 12, 1.0, 0);
            b.velocity = common;
            h.add(std::move(b));
        }
        for (int s = 0; s < 5; ++s) ASSERT_TRUE(h.step()) << "seed " << seed;
        report("flock", h);
        EXPECT_EQ(h.totals().swaps, 0u) << "seed " << seed;
        EXPECT_GT(h.per_object(h.totals().pairs), 0.1) << "seed " << seed;
        EXPECT_LT(h.per_object(h.totals().pairs), 3.0) << "seed " << seed;
        // Resting pairs keep their separating axis: most later steps need no cast at all.
        EXPECT_GT(h.totals().rejections, 0u) << "seed " << seed;
    }
}

TEST(World, FastAndSlowMatchBruteForceAndPairwiseCasts) {
    for (uint64_t seed : {131u, 132u}) {
        Rng rng(seed);
        Harness h(seed);
        for (int i = 0; i < 180; ++i) {
            Body b = random_body(rng, 16, 0.8, 0.05);
            if (i % 10 == 0) {  // bullets: small and ten of their sizes per step
                b.shape = ShapePtr(new SphereShape(0.1));
                b.velocity = rng.on_sphere(12);
            }
            h.add(std::move(b));
        }
        for (int s = 0; s < 4; ++s) ASSERT_TRUE(h.step()) << "seed " << seed;
        report("fast and slow", h);
        EXPECT_GT(h.per_object(h.totals().pairs), 0.05) << "seed " << seed;
        EXPECT_LT(h.per_object(h.totals().pairs), 2.0) << "seed " << seed;
        EXPECT_GT(h.totals().contacts, 0u) << "seed " << seed;
    }
}

TEST(World, TurningObjectsAreNeverMissed) {
    for (uint64_t seed : {141u, 142u}) {
        Rng rng(seed);
        Harness h(seed);
        for (int i = 0; i < 120; ++i) {
            Body b = random_body(rng, 10, 1.0, 0.4);
            if (i % 3 == 0) {
                // Rods and boxes spinning up to a half turn per step.
                if (i % 2 == 0) b.shape = ShapePtr(new CapsuleShape(0.08, rng.uniform(0.8, 1.6)));
                b.spin_axis = rng.on_sphere(1);
                b.spin = rng.uniform(0.1, std::numbers::pi);
            }
            h.add(std::move(b));
        }
        for (int s = 0; s < 3; ++s) ASSERT_TRUE(h.step()) << "seed " << seed;
        report("turning", h);
        EXPECT_GT(h.totals().rotating_pairs_checked, 0u) << "seed " << seed;
        EXPECT_GT(h.totals().rotating_contacts, 0u) << "seed " << seed;
        EXPECT_LT(h.per_object(h.totals().pairs), 5.0) << "seed " << seed;
    }
}

TEST(World, AddRemoveTeleportBetweenSteps) {
    for (uint64_t seed : {151u, 152u}) {
        Rng rng(seed);
        Harness h(seed);
        for (int i = 0; i < 140; ++i) {
            Body b = random_body(rng, 12, 1.0, 0.6);
            if (i % 9 == 0) {
                b.spin_axis = rng.on_sphere(1);
                b.spin = rng.uniform(0.1, 1.0);
            }
            if (i % 7 == 0) b.velocity = {};  // standing still
            h.add(std::move(b));
        }
        h.check_structure();
        for (int s = 0; s < 5; ++s) {
            ASSERT_TRUE(h.step()) << "seed " << seed;
            auto& bodies = h.bodies();
            for (std::size_t i = 0; i < bodies.size(); ++i) {
                if (!bodies[i].alive) continue;
                const double r = rng.uniform(0, 1);
                if (r < 0.06) {
                    h.remove(i);
                } else if (r < 0.12) {
                    h.teleport(i, {rng.in_cube(6), rng.orientation()});
                } else if (r < 0.15) {
                    bodies[i].spin = 0;  // stops turning: its loose box must shrink back
                }
            }
            h.check_structure();
            const uint32_t adds = rng.below(15);
            for (uint32_t k = 0; k < adds; ++k) h.add(random_body(rng, 12, 1.0, 0.6));
            if (s % 2 == 1) h.check_structure();
        }
        report("edited", h);
        EXPECT_GT(h.per_object(h.totals().pairs), 0.1) << "seed " << seed;
        EXPECT_LT(h.per_object(h.totals().pairs), 3.0) << "seed " << seed;
    }
}

// An engine's scheduler for the task hook: each range on a thread of its own, started in reverse
// order; finish joins them. `inline_run` instead runs every range itself and returns NULL.
struct TestScheduler {
    bool inline_run = false;
    std::vector<std::thread> threads;
    uint64_t tasks = 0;
    static void* enqueue(TaskFn* task, uint32_t count, uint32_t min_range, void* task_context, void* user) {
        auto& self = *static_cast<TestScheduler*>(user);
        ++self.tasks;
        const uint32_t range = std::max<uint32_t>(min_range, 1);
        std::vector<std::pair<uint32_t, uint32_t>> ranges;
        for (uint32_t b = 0; b < count; b += range) ranges.push_back({b, std::min(count, b + range)});
        std::reverse(ranges.begin(), ranges.end());
        if (self.inline_run) {
            for (auto [b, e] : ranges) task(b, e, 0, task_context);
            return nullptr;
        }
        uint32_t worker = 0;
        for (const auto& range : ranges) {
            const uint32_t b = range.first, e = range.second, w = worker++ % 3;
            self.threads.emplace_back([=] { task(b, e, w, task_context); });
        }
        return &self;
    }
    static void finish(void* handle, void*) {
        auto& self = *static_cast<TestScheduler*>(handle);
        for (std::thread& t : self.threads) t.join();
        self.threads.clear();
    }
};

// The same scene stepped twice with one thread, with the world's own workers (2, 3, 7) and with
// an engine's scheduler (threads per range, reverse order; inline): contacts, pairs and counters
// bit for bit the same.
TEST(World, SameSceneGivesBitIdenticalResultsWhateverTheWorkers) {
    struct Run {
        std::vector<Contact> contacts;
        std::vector<WorldPair> pairs;
        std::vector<uint64_t> counts;
    };
    auto run = [](const WorldSettings& settings) {
        Run out;
        Rng rng(2026);
        World w(settings);
        std::vector<Body> bodies;
        for (int i = 0; i < 600; ++i) {
            Body b = random_body(rng, 12, 1.0, 0.8);
            if (i % 4 == 0) {
                b.spin_axis = rng.on_sphere(1);
                b.spin = rng.uniform(0.1, 2.0);
            }
            b.id = w.add(*b.shape, b.pose, static_cast<uint64_t>(i));
            if (i % 9 == 0) w.set_static(b.id, true);
            bodies.push_back(std::move(b));
        }
        for (int s = 0; s < 3; ++s) {
            for (Body& b : bodies)
                if (!w.find(b.id)->is_static) w.move(b.id, end_of(b));
            w.step();
            out.contacts.insert(out.contacts.end(), w.contacts().begin(), w.contacts().end());
            out.pairs.insert(out.pairs.end(), w.pairs().begin(), w.pairs().end());
            const StepCounters& c = w.counters();
            out.counts.insert(out.counts.end(), {c.broad_phase_pairs, c.narrow_phase_queries, c.gjk_iterations,
                                                 c.axis_rejections, c.filtered_pairs, c.contacts});
            for (Body& b : bodies)
                if (!w.find(b.id)->is_static) b.pose = end_of(b);
        }
        return out;
    };
    const Run one = run(WorldSettings{});
    ASSERT_GT(one.contacts.size(), 200u);
    TestScheduler threads, inline_run;
    inline_run.inline_run = true;
    std::vector<std::pair<std::string, WorldSettings>> variants;
    variants.push_back({"one thread again", WorldSettings{}});  // determinism itself
    for (uint32_t n : {2u, 3u, 7u}) {
        WorldSettings s;
        s.worker_count = n;
        variants.push_back({"worker_count " + std::to_string(n), s});
    }
    for (TestScheduler* sched : {&threads, &inline_run}) {
        WorldSettings s;
        s.worker_count = 3;
        s.task_hook = {&TestScheduler::enqueue, &TestScheduler::finish, sched};
        variants.push_back({sched->inline_run ? "hook, inline" : "hook, a thread per range", s});
    }
    for (const auto& [name, settings] : variants) {
        SCOPED_TRACE(name);
        const Run other = run(settings);
        ASSERT_EQ(other.contacts.size(), one.contacts.size());
        for (std::size_t i = 0; i < one.contacts.size(); ++i) {
            const Contact& p = one.contacts[i];
            const Contact& q = other.contacts[i];
            ASSERT_TRUE(p.a == q.a && p.b == q.b && p.user_a == q.user_a && p.user_b == q.user_b &&
                        std::bit_cast<uint64_t>(p.toi) == std::bit_cast<uint64_t>(q.toi) && p.point == q.point &&
                        p.normal == q.normal)
                << "contact " << i;
        }
        ASSERT_EQ(other.pairs.size(), one.pairs.size());
        for (std::size_t i = 0; i < one.pairs.size(); ++i)
            ASSERT_TRUE(one.pairs[i].a == other.pairs[i].a && one.pairs[i].b == other.pairs[i].b &&
                        std::bit_cast<uint64_t>(one.pairs[i].t_first) == std::bit_cast<uint64_t>(other.pairs[i].t_first));
        EXPECT_EQ(other.counts, one.counts);
    }
    EXPECT_EQ(threads.tasks, 6u);  // two tasks per step: the movers' motion bounds, the casts
    EXPECT_EQ(inline_run.tasks, 6u);
}


}  // namespace
}  // namespace kairos
