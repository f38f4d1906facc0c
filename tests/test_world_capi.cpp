// The world through the C API (the shared library only): step, contacts, overlaps, stats, ids.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "kairos/kairos.h"

namespace {

kairos_pose at(double x, double y, double z) {
    kairos_pose p;
    p.position = {x, y, z};
    p.orientation = {0, 0, 0, 1};
    return p;
}

struct WorldFixture : ::testing::Test {
    void SetUp() override {
        ASSERT_EQ(kairos_shape_sphere(0.1, &bullet), KAIROS_OK);
        ASSERT_EQ(kairos_shape_box({0.01, 2, 2}, &wall), KAIROS_OK);
        ASSERT_EQ(kairos_shape_box({0.5, 0.5, 0.5}, &cube), KAIROS_OK);
    }
    void TearDown() override {
        kairos_shape_release(bullet);
        kairos_shape_release(wall);
        kairos_shape_release(cube);
    }
    kairos_shape* bullet = nullptr;
    kairos_shape* wall = nullptr;
    kairos_shape* cube = nullptr;
};

TEST_F(WorldFixture, BulletThroughAWallInEveryBroadPhase) {
    for (int32_t bp : {KAIROS_BROAD_PHASE_SPACETIME_SAP, KAIROS_BROAD_PHASE_ENCAPSULATING_SAP, KAIROS_BROAD_PHASE_BRUTE_FORCE}) {
        SCOPED_TRACE(bp);
        kairos_world_settings s;
        kairos_world_settings_init(&s);
        s.broad_phase = bp;
        kairos_world* w = nullptr;
        ASSERT_EQ(kairos_world_create(&s, &w), KAIROS_OK);
        kairos_object_id wall_id = 0, bullet_id = 0, far_id = 0;
        kairos_pose p = at(0, 0, 0);
        ASSERT_EQ(kairos_world_add(w, wall, &p, 11, &wall_id), KAIROS_OK);
        p = at(-5, 0, 0);
        ASSERT_EQ(kairos_world_add(w, bullet, &p, 22, &bullet_id), KAIROS_OK);
        p = at(0, 50, 0);
        ASSERT_EQ(kairos_world_add(w, cube, &p, 33, &far_id), KAIROS_OK);
        p = at(5, 0, 0);
        ASSERT_EQ(kairos_world_move(w, bullet_id, &p), KAIROS_OK);
        ASSERT_EQ(kairos_world_step(w), KAIROS_OK);

        const kairos_contact* c = nullptr;
        size_t n = 0;
        ASSERT_EQ(kairos_world_contacts(w, &c, &n), KAIROS_OK);
        ASSERT_EQ(n, 1u);
        EXPECT_EQ(c[0].a, wall_id);
        EXPECT_EQ(c[0].b, bullet_id);
        EXPECT_EQ(c[0].user_a, 11u);
        EXPECT_EQ(c[0].user_b, 22u);
        EXPECT_NEAR(c[0].toi, 0.489, 1e-9);
        EXPECT_NEAR(c[0].normal.x, -1, 1e-9);

        const kairos_object_id* pairs = nullptr;
        ASSERT_EQ(kairos_world_overlaps(w, &pairs, &n), KAIROS_OK);
        ASSERT_EQ(n, 1u);
        EXPECT_EQ(pairs[0], wall_id);
        EXPECT_EQ(pairs[1], bullet_id);

        kairos_step_stats st;
        kairos_step_stats_init(&st);
        ASSERT_EQ(kairos_world_step_stats(w, &st), KAIROS_OK);
        EXPECT_EQ(st.struct_size, sizeof st);
        EXPECT_EQ(st.broad_phase_pairs, 1u);
        EXPECT_EQ(st.narrow_phase_queries, 1u);
        EXPECT_GT(st.gjk_iterations, 0u);
        EXPECT_GE(st.broad_phase_seconds, 0.0);
        EXPECT_GE(st.narrow_phase_seconds, 0.0);

        // A caller that knows only a prefix of the stats gets only that prefix written.
        unsigned char raw[sizeof(kairos_step_stats) + 8];
        std::memset(raw, 0xAB, sizeof raw);
        const uint32_t small = offsetof(kairos_step_stats, heap_operations);
        std::memcpy(raw, &small, sizeof small);
        ASSERT_EQ(kairos_world_step_stats(w, reinterpret_cast<kairos_step_stats*>(raw)), KAIROS_OK);
        uint64_t pairs_field = 0;
        std::memcpy(&pairs_field, raw + offsetof(kairos_step_stats, broad_phase_pairs), sizeof pairs_field);
        EXPECT_EQ(pairs_field, 1u);
        for (size_t i = small; i < sizeof raw; ++i) EXPECT_EQ(raw[i], 0xAB) << i;

        // The next step: the bullet rests at x = 5; nothing meets.
        ASSERT_EQ(kairos_world_step(w), KAIROS_OK);
        ASSERT_EQ(kairos_world_contacts(w, &c, &n), KAIROS_OK);
        EXPECT_EQ(n, 0u);
        kairos_world_destroy(w);
    }
}

TEST_F(WorldFixture, StaleIdsAreRejected) {
    kairos_world* w = nullptr;
    ASSERT_EQ(kairos_world_create(nullptr, &w), KAIROS_OK);
    kairos_object_id a = 0, b = 0;
    kairos_pose p = at(0, 0, 0);
    ASSERT_EQ(kairos_world_add(w, cube, &p, 0, &a), KAIROS_OK);
    ASSERT_EQ(kairos_world_remove(w, a), KAIROS_OK);
    EXPECT_EQ(kairos_world_remove(w, a), KAIROS_ERROR_STALE_ID);
    EXPECT_EQ(kairos_world_move(w, a, &p), KAIROS_ERROR_STALE_ID);
    EXPECT_EQ(kairos_world_set_pose(w, a, &p), KAIROS_ERROR_STALE_ID);
    EXPECT_EQ(kairos_world_move(w, 0, &p), KAIROS_ERROR_STALE_ID);
    ASSERT_EQ(kairos_world_add(w, cube, &p, 0, &b), KAIROS_OK);
    EXPECT_NE(a, b);  // same slot, new generation
    EXPECT_EQ(kairos_world_move(w, a, &p), KAIROS_ERROR_STALE_ID);
    EXPECT_EQ(kairos_world_move(w, b, &p), KAIROS_OK);
    EXPECT_EQ(kairos_world_step(w), KAIROS_OK);
    EXPECT_EQ(kairos_world_step(nullptr), KAIROS_ERROR_NULL_ARGUMENT);
    kairos_world_destroy(w);
}

// A grid of cubes, every other one moving onto its neighbour: the same run twice gives the
// same contacts bit for bit.
TEST_F(WorldFixture, SameSceneTwiceIsBitIdentical) {
    auto run = [&](std::vector<kairos_contact>& out) {
        kairos_world* w = nullptr;
        ASSERT_EQ(kairos_world_create(nullptr, &w), KAIROS_OK);
        std::vector<kairos_object_id> ids;
        for (int i = 0; i < 400; ++i) {
            kairos_pose p = at(1.7 * (i % 20), 1.7 * (i / 20), 0.1 * (i % 3));
            kairos_object_id id = 0;
            ASSERT_EQ(kairos_world_add(w, i % 7 == 0 ? bullet : cube, &p, static_cast<uint64_t>(i), &id), KAIROS_OK);
            ids.push_back(id);
        }
        for (int s = 1; s <= 3; ++s) {
            for (size_t i = 0; i < ids.size(); i += 2) {
                const double k = static_cast<double>(i);
                kairos_pose p = at(1.7 * static_cast<double>(i % 20) + 0.3 * s * std::sin(k),
                                   1.7 * static_cast<double>(i / 20) + 0.3 * s * std::cos(k), 0.1 * static_cast<double>(i % 3));
                ASSERT_EQ(kairos_world_move(w, ids[i], &p), KAIROS_OK);
            }
            ASSERT_EQ(kairos_world_step(w), KAIROS_OK);
            const kairos_contact* c = nullptr;
            size_t n = 0;
            ASSERT_EQ(kairos_world_contacts(w, &c, &n), KAIROS_OK);
            out.insert(out.end(), c, c + n);
        }
        kairos_world_destroy(w);
    };
    std::vector<kairos_contact> first, second;
    run(first);
    run(second);
    ASSERT_EQ(first.size(), second.size());
    ASSERT_GT(first.size(), 20u);
    EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(kairos_contact)), 0);
    for (size_t i = 1; i < first.size(); ++i) EXPECT_LT(first[i].a, first[i].b);
}

}  // namespace
