// SPDX-License-Identifier: MIT
// The batches (kairos_distance_batch, kairos_shape_cast_batch, kairos_motion_cast_batch,
// kairos_world_move_batch) against their single calls: every result bit for bit the single
// call's, on random queries over every shape kind, on the calling thread, on a world's own
// threads and through a task hook; refused batches name the first bad query and write nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "kairos/kairos.h"

namespace {

constexpr uint32_t kSeed = 20261127;

struct Shapes {
    std::vector<kairos_shape*> all;
    Shapes() {
        kairos_shape* s = nullptr;
        auto keep = [&](int32_t status) {
            EXPECT_EQ(status, KAIROS_OK) << kairos_last_error();
            all.push_back(s);
        };
        keep(kairos_shape_box({0.5, 0.3, 0.2}, &s));
        keep(kairos_shape_sphere(0.4, &s));
        keep(kairos_shape_capsule(0.2, 0.5, &s));
        keep(kairos_shape_cylinder(0.3, 0.4, &s));
        keep(kairos_shape_cone(0.4, 0.5, &s));
        keep(kairos_shape_segment(0.6, &s));
        keep(kairos_shape_point(&s));
        const kairos_vec3 pts[6] = {{0, 0, 0.6}, {0.5, 0, 0}, {0, 0.5, 0}, {-0.5, 0, 0}, {0, -0.5, 0}, {0, 0, -0.6}};
        keep(kairos_shape_convex_hull(pts, 6, &s));
        keep(kairos_shape_triangle({-0.7, -0.5, 0}, {0.7, -0.5, 0}, {0, 0.8, 0}, &s));
        keep(kairos_shape_minkowski_sum(all[0], all[1], &s));
    }
    ~Shapes() {
        for (kairos_shape* s : all) kairos_shape_release(s);
    }
};

kairos_pose random_pose(std::mt19937_64& rng, double spread) {
    std::uniform_real_distribution<double> u(-spread, spread);
    std::normal_distribution<double> g(0, 1);
    double q[4] = {g(rng), g(rng), g(rng), g(rng)};
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    return {{u(rng), u(rng), u(rng)}, {q[0] / n, q[1] / n, q[2] / n, q[3] / n}};
}

// n random queries over every pair of kinds (both orders), positions within `spread`.
struct Queries {
    std::vector<const kairos_shape*> a, b;
    std::vector<kairos_pose> pa, pb;
    std::vector<kairos_vec3> ta, tb;
    std::vector<kairos_motion> ma, mb;
    Queries(const Shapes& shapes, std::size_t n, uint32_t seed) {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(-2, 2);
        for (std::size_t i = 0; i < n; ++i) {
            a.push_back(shapes.all[i % shapes.all.size()]);
            b.push_back(shapes.all[(i / shapes.all.size()) % shapes.all.size()]);
            pa.push_back(random_pose(rng, 1));
            pb.push_back(random_pose(rng, 1));
            ta.push_back({u(rng), u(rng), u(rng)});
            tb.push_back({u(rng), u(rng), u(rng)});
            ma.push_back({pa.back(), random_pose(rng, 1)});
            mb.push_back({pb.back(), random_pose(rng, 1)});
        }
    }
};

// Field by field (the structs have padding, which neither call defines).
template <class T>
bool same(const T& x, const T& y) {
    return std::memcmp(&x, &y, sizeof(T)) == 0;
}
bool same_bits(const kairos_vec3& x, const kairos_vec3& y) { return same(x.x, y.x) && same(x.y, y.y) && same(x.z, y.z); }
bool same_bits(const kairos_distance_result& x, const kairos_distance_result& y) {
    return same(x.distance, y.distance) && same_bits(x.point_a, y.point_a) && same_bits(x.point_b, y.point_b) &&
           same_bits(x.axis, y.axis) && x.intersecting == y.intersecting && x.iterations == y.iterations &&
           x.termination == y.termination;
}
bool same_bits(const kairos_cast_result& x, const kairos_cast_result& y) {
    return x.hit == y.hit && same(x.toi, y.toi) && same_bits(x.point, y.point) && same_bits(x.normal, y.normal) &&
           x.iterations == y.iterations && x.termination == y.termination;
}
bool same_bits(const kairos_contact& x, const kairos_contact& y) { return same(x, y); }
bool same_bits(const kairos_pose& x, const kairos_pose& y) { return same(x, y); }

// A task hook that runs each range on a thread of its own, in reverse order (a scheduler that
// shares nothing with the world's pool).
void* enqueue_reversed(kairos_task_fn* task, uint32_t count, uint32_t min_range, void* task_context, void*) {
    std::vector<std::thread> threads;
    const uint32_t step = min_range == 0 ? 1 : min_range;
    for (uint32_t end = count; end > 0;) {
        const uint32_t begin = end > step ? end - step : 0;
        threads.emplace_back([=] { task(begin, end, 0, task_context); });
        end = begin;
    }
    for (std::thread& t : threads) t.join();
    return nullptr;  // every range has run
}
void finish_nothing(void*, void*) {}

struct Pools {
    kairos_world* threads = nullptr;  // a world with 3 workers of its own
    kairos_world* hook = nullptr;     // a world whose work goes through the hook above
    Pools() {
        kairos_world_settings s;
        kairos_world_settings_init(&s);
        s.worker_count = 3;
        EXPECT_EQ(kairos_world_create(&s, &threads), KAIROS_OK) << kairos_last_error();
        kairos_world_settings_init(&s);
        s.enqueue_task = enqueue_reversed;
        s.finish_task = finish_nothing;
        EXPECT_EQ(kairos_world_create(&s, &hook), KAIROS_OK) << kairos_last_error();
    }
    ~Pools() {
        kairos_world_destroy(threads);
        kairos_world_destroy(hook);
    }
};

TEST(Batch, DistanceEqualsTheSingleCallsBitForBit) {
    const Shapes shapes;
    const std::size_t n = 2000;
    const Queries q(shapes, n, kSeed);
    kairos_query_settings qs;
    kairos_query_settings_init(&qs);
    std::vector<kairos_distance_result> single(n);
    std::size_t intersecting = 0;
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(kairos_distance(q.a[i], &q.pa[i], q.b[i], &q.pb[i], &qs, &single[i]), KAIROS_OK);
        intersecting += static_cast<std::size_t>(single[i].intersecting);
    }
    // Both verdicts are exercised.
    EXPECT_GT(intersecting, n / 10) << "seed " << kSeed;
    EXPECT_LT(intersecting, 9 * n / 10) << "seed " << kSeed;
    const Pools pools;
    for (kairos_world* workers : {static_cast<kairos_world*>(nullptr), pools.threads, pools.hook}) {
        std::vector<kairos_distance_result> batch(n);
        ASSERT_EQ(kairos_distance_batch(q.a.data(), q.pa.data(), q.b.data(), q.pb.data(), n, &qs, workers,
                                        batch.data()),
                  KAIROS_OK)
            << kairos_last_error();
        for (std::size_t i = 0; i < n; ++i)
            ASSERT_TRUE(same_bits(batch[i], single[i])) << "query " << i << " seed " << kSeed;
    }
}

TEST(Batch, ShapeCastEqualsTheSingleCallsBitForBit) {
    const Shapes shapes;
    const std::size_t n = 2000;
    const Queries q(shapes, n, kSeed + 1);
    std::vector<kairos_cast_result> single(n);
    std::size_t hits = 0, hits_after_start = 0;
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(kairos_shape_cast(q.a[i], &q.pa[i], q.ta[i], q.b[i], &q.pb[i], q.tb[i], nullptr, &single[i]),
                  KAIROS_OK);
        hits += static_cast<std::size_t>(single[i].hit);
        hits_after_start += static_cast<std::size_t>(single[i].hit != 0 && single[i].toi > 0);
    }
    EXPECT_GT(hits, n / 10) << "seed " << kSeed + 1;
    EXPECT_LT(hits, 9 * n / 10) << "seed " << kSeed + 1;
    EXPECT_GT(hits_after_start, n / 20) << "seed " << kSeed + 1;
    const Pools pools;
    for (kairos_world* workers : {static_cast<kairos_world*>(nullptr), pools.threads, pools.hook}) {
        std::vector<kairos_cast_result> batch(n);
        ASSERT_EQ(kairos_shape_cast_batch(q.a.data(), q.pa.data(), q.ta.data(), q.b.data(), q.pb.data(), q.tb.data(),
                                          n, nullptr, workers, batch.data()),
                  KAIROS_OK)
            << kairos_last_error();
        for (std::size_t i = 0; i < n; ++i)
            ASSERT_TRUE(same_bits(batch[i], single[i])) << "query " << i << " seed " << kSeed + 1;
    }
    // NULL arrays: identity poses and no translation for that side.
    std::vector<kairos_cast_result> batch(n);
    ASSERT_EQ(kairos_shape_cast_batch(q.a.data(), nullptr, nullptr, q.b.data(), q.pb.data(), q.tb.data(), n, nullptr,
                                      nullptr, batch.data()),
              KAIROS_OK);
    for (std::size_t i = 0; i < n; i += 37) {
        kairos_cast_result one;
        ASSERT_EQ(kairos_shape_cast(q.a[i], nullptr, {0, 0, 0}, q.b[i], &q.pb[i], q.tb[i], nullptr, &one), KAIROS_OK);
        ASSERT_TRUE(same_bits(batch[i], one)) << "query " << i;
    }
}

TEST(Batch, MotionCastEqualsTheSingleCallsBitForBit) {
    const Shapes shapes;
    const std::size_t n = 600;
    const Queries q(shapes, n, kSeed + 2);
    kairos_query_settings qs;
    kairos_query_settings_init(&qs);
    qs.tolerance = 1e-6;
    std::vector<kairos_cast_result> single(n);
    std::size_t hits = 0;
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(kairos_motion_cast(q.a[i], &q.ma[i], q.b[i], &q.mb[i], &qs, &single[i]), KAIROS_OK);
        hits += static_cast<std::size_t>(single[i].hit);
    }
    EXPECT_GT(hits, n / 10) << "seed " << kSeed + 2;
    EXPECT_LT(hits, 9 * n / 10) << "seed " << kSeed + 2;
    const Pools pools;
    for (kairos_world* workers : {static_cast<kairos_world*>(nullptr), pools.threads, pools.hook}) {
        std::vector<kairos_cast_result> batch(n);
        ASSERT_EQ(kairos_motion_cast_batch(q.a.data(), q.ma.data(), q.b.data(), q.mb.data(), n, &qs, workers,
                                           batch.data()),
                  KAIROS_OK)
            << kairos_last_error();
        for (std::size_t i = 0; i < n; ++i)
            ASSERT_TRUE(same_bits(batch[i], single[i])) << "query " << i << " seed " << kSeed + 2;
    }
}

// Every refused batch: the status, a message naming the argument and element, out untouched.
TEST(Batch, RefusedBatchesNameTheFirstBadQueryAndWriteNothing) {
    const Shapes shapes;
    const std::size_t n = 50;
    Queries q(shapes, n, kSeed + 3);
    const kairos_distance_result pattern_d = [] {
        kairos_distance_result r;
        std::memset(&r, 0xA5, sizeof r);
        return r;
    }();
    const kairos_cast_result pattern_c = [] {
        kairos_cast_result r;
        std::memset(&r, 0x5A, sizeof r);
        return r;
    }();
    std::vector<kairos_distance_result> out_d(n, pattern_d);
    std::vector<kairos_cast_result> out_c(n, pattern_c);
    auto untouched = [&] {
        for (std::size_t i = 0; i < n; ++i)
            if (!same_bits(out_d[i], pattern_d) || !same_bits(out_c[i], pattern_c)) return false;
        return true;
    };
    auto expect_error = [&](int32_t status, int32_t want, const std::string& needle) {
        EXPECT_EQ(status, want) << kairos_last_error();
        EXPECT_NE(std::string(kairos_last_error()).find(needle), std::string::npos)
            << "message: " << kairos_last_error() << " (want " << needle << ")";
        EXPECT_TRUE(untouched());
    };
    const Pools pools;
    for (kairos_world* workers : {static_cast<kairos_world*>(nullptr), pools.threads}) {
        // NULL arrays with queries to run.
        expect_error(kairos_distance_batch(nullptr, nullptr, q.b.data(), nullptr, n, nullptr, workers, out_d.data()),
                     KAIROS_ERROR_NULL_ARGUMENT, "kairos_distance_batch: a is NULL");
        expect_error(kairos_distance_batch(q.a.data(), nullptr, q.b.data(), nullptr, n, nullptr, workers, nullptr),
                     KAIROS_ERROR_NULL_ARGUMENT, "out is NULL");
        expect_error(kairos_motion_cast_batch(q.a.data(), nullptr, q.b.data(), q.mb.data(), n, nullptr, workers,
                                              out_c.data()),
                     KAIROS_ERROR_NULL_ARGUMENT, "motions_a is NULL");
        // A NULL shape at 17, a bad pose at 23: the first is named.
        std::vector<const kairos_shape*> holes = q.b;
        holes[17] = nullptr;
        std::vector<kairos_pose> bad_poses = q.pa;
        bad_poses[23].orientation.w += 0.5;
        expect_error(kairos_distance_batch(q.a.data(), bad_poses.data(), holes.data(), nullptr, n, nullptr, workers,
                                           out_d.data()),
                     KAIROS_ERROR_NULL_ARGUMENT, "b[17] is NULL");
        expect_error(kairos_distance_batch(q.a.data(), bad_poses.data(), q.b.data(), nullptr, n, nullptr, workers,
                                           out_d.data()),
                     KAIROS_ERROR_INVALID_ARGUMENT, "poses_a[23].orientation must be a unit quaternion");
        // The last query bad: all the others were fine, still nothing is written.
        std::vector<kairos_pose> last_bad = q.pb;
        last_bad[n - 1].position.y = std::nan("");
        expect_error(kairos_distance_batch(q.a.data(), nullptr, q.b.data(), last_bad.data(), n, nullptr, workers,
                                           out_d.data()),
                     KAIROS_ERROR_INVALID_ARGUMENT, "poses_b[49].position.y must be finite");
        std::vector<kairos_vec3> far = q.tb;
        far[8].z = 1e300;
        expect_error(kairos_shape_cast_batch(q.a.data(), nullptr, nullptr, q.b.data(), nullptr, far.data(), n, nullptr,
                                             workers, out_c.data()),
                     KAIROS_ERROR_INVALID_ARGUMENT, "translations_b[8].z is 1e+300, beyond KAIROS_MAX_MAGNITUDE");
        std::vector<kairos_motion> bad_motion = q.mb;
        bad_motion[5].end.orientation.x = INFINITY;
        expect_error(kairos_motion_cast_batch(q.a.data(), q.ma.data(), q.b.data(), bad_motion.data(), n, nullptr,
                                              workers, out_c.data()),
                     KAIROS_ERROR_INVALID_ARGUMENT, "motions_b[5].end.orientation.x must be finite");
        kairos_query_settings qs;
        kairos_query_settings_init(&qs);
        qs.tolerance = 1;
        expect_error(kairos_shape_cast_batch(q.a.data(), nullptr, nullptr, q.b.data(), nullptr, nullptr, n, &qs,
                                             workers, out_c.data()),
                     KAIROS_ERROR_INVALID_ARGUMENT, "settings->tolerance must be in (0, 1)");
        // count 0 runs nothing, even with NULL arrays.
        EXPECT_EQ(kairos_distance_batch(nullptr, nullptr, nullptr, nullptr, 0, nullptr, workers, nullptr), KAIROS_OK);
        EXPECT_EQ(kairos_shape_cast_batch(nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, 0, nullptr, workers,
                                          nullptr),
                  KAIROS_OK);
        EXPECT_EQ(kairos_motion_cast_batch(nullptr, nullptr, nullptr, nullptr, 0, nullptr, workers, nullptr),
                  KAIROS_OK);
    }
}

// A world moved by one batch steps exactly as one moved call by call; a refused batch moves nothing.
TEST(Batch, WorldMoveBatchEqualsSingleMovesAndIsAllOrNothing) {
    const Shapes shapes;
    std::mt19937_64 rng(kSeed + 4);
    const std::size_t n = 300;
    kairos_world* by_batch = nullptr;
    kairos_world* by_call = nullptr;
    ASSERT_EQ(kairos_world_create(nullptr, &by_batch), KAIROS_OK);
    ASSERT_EQ(kairos_world_create(nullptr, &by_call), KAIROS_OK);
    std::vector<kairos_object_id> ids(n), ids_call(n);
    std::vector<kairos_pose> start(n);
    for (std::size_t i = 0; i < n; ++i) {
        start[i] = random_pose(rng, 6);
        kairos_shape* s = shapes.all[i % shapes.all.size()];
        ASSERT_EQ(kairos_world_add(by_batch, s, &start[i], i, &ids[i]), KAIROS_OK);
        ASSERT_EQ(kairos_world_add(by_call, s, &start[i], i, &ids_call[i]), KAIROS_OK);
        ASSERT_EQ(ids[i], ids_call[i]);
    }
    ASSERT_EQ(kairos_world_set_static(by_batch, ids[0], 1), KAIROS_OK);
    ASSERT_EQ(kairos_world_set_static(by_call, ids[0], 1), KAIROS_OK);
    std::size_t total_contacts = 0;
    for (int step = 0; step < 5; ++step) {
        // Every object but the static one, twice for some (the last end pose counts).
        std::vector<kairos_object_id> which;
        std::vector<kairos_pose> ends;
        for (std::size_t i = 1; i < n; ++i) {
            which.push_back(ids[i]);
            ends.push_back(random_pose(rng, 6));
            if (i % 7 == 0) {
                which.push_back(ids[i]);
                ends.push_back(random_pose(rng, 6));
            }
        }
        // A refused batch first: a static id at 40, a stale id at 90; nothing moves.
        std::vector<kairos_object_id> bad = which;
        bad[40] = ids[0];
        bad[90] = 12345;
        EXPECT_EQ(kairos_world_move_batch(by_batch, bad.data(), ends.data(), bad.size()), KAIROS_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(kairos_last_error()).find("ids[40] is"), std::string::npos) << kairos_last_error();
        bad[40] = which[40];
        EXPECT_EQ(kairos_world_move_batch(by_batch, bad.data(), ends.data(), bad.size()), KAIROS_ERROR_STALE_ID);
        EXPECT_NE(std::string(kairos_last_error()).find("ids[90] is 12345"), std::string::npos)
            << kairos_last_error();
        std::vector<kairos_pose> bad_ends = ends;
        bad_ends[100].orientation.w = 7;
        EXPECT_EQ(kairos_world_move_batch(by_batch, which.data(), bad_ends.data(), which.size()),
                  KAIROS_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(kairos_last_error()).find("ends[100].orientation"), std::string::npos)
            << kairos_last_error();

        ASSERT_EQ(kairos_world_move_batch(by_batch, which.data(), ends.data(), which.size()), KAIROS_OK)
            << kairos_last_error();
        for (std::size_t i = 0; i < which.size(); ++i) ASSERT_EQ(kairos_world_move(by_call, which[i], &ends[i]), KAIROS_OK);
        ASSERT_EQ(kairos_world_step(by_batch), KAIROS_OK);
        ASSERT_EQ(kairos_world_step(by_call), KAIROS_OK);
        const kairos_contact *cb = nullptr, *cc = nullptr;
        size_t nb = 0, nc = 0;
        ASSERT_EQ(kairos_world_contacts(by_batch, &cb, &nb), KAIROS_OK);
        ASSERT_EQ(kairos_world_contacts(by_call, &cc, &nc), KAIROS_OK);
        ASSERT_EQ(nb, nc);
        for (size_t k = 0; k < nb; ++k) ASSERT_TRUE(same_bits(cb[k], cc[k])) << "step " << step << " contact " << k;
        total_contacts += nb;
        for (std::size_t i = 0; i < n; ++i) {
            kairos_pose pb, pc;
            ASSERT_EQ(kairos_world_get_pose(by_batch, ids[i], &pb), KAIROS_OK);
            ASSERT_EQ(kairos_world_get_pose(by_call, ids[i], &pc), KAIROS_OK);
            ASSERT_TRUE(same_bits(pb, pc)) << "object " << i;
        }
    }
    EXPECT_GT(total_contacts, 5u) << "seed " << kSeed + 4;
    // A refused batch leaves the next step with nothing moving.
    std::vector<kairos_object_id> one_stale = {ids[3], 0};
    std::vector<kairos_pose> two = {random_pose(rng, 6), random_pose(rng, 6)};
    kairos_pose before;
    ASSERT_EQ(kairos_world_get_pose(by_batch, ids[3], &before), KAIROS_OK);
    EXPECT_EQ(kairos_world_move_batch(by_batch, one_stale.data(), two.data(), 2), KAIROS_ERROR_STALE_ID);
    ASSERT_EQ(kairos_world_step(by_batch), KAIROS_OK);
    kairos_pose after;
    ASSERT_EQ(kairos_world_get_pose(by_batch, ids[3], &after), KAIROS_OK);
    EXPECT_TRUE(same_bits(before, after));
    EXPECT_EQ(kairos_world_move_batch(nullptr, ids.data(), two.data(), 1), KAIROS_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(kairos_world_move_batch(by_batch, nullptr, two.data(), 1), KAIROS_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(kairos_world_move_batch(by_batch, ids.data(), nullptr, 1), KAIROS_ERROR_NULL_ARGUMENT);
    EXPECT_EQ(kairos_world_move_batch(by_batch, nullptr, nullptr, 0), KAIROS_OK);
    kairos_world_destroy(by_batch);
    kairos_world_destroy(by_call);
}

}  // namespace
