// SPDX-License-Identifier: MIT
// Fuzz target: sequences of world operations (create with each broad phase, add, remove,
// set_pose, move, step, contacts, overlaps, step_stats, filters, static objects, the getters,
// stale and NULL arguments) decoded from bytes, each checked against the contract; after every
// step the contacts and overlaps are checked (no pair a filter or two static objects rule out),
// and wanted pairs whose inner balls provably meet during the step must have a contact.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "fuzz_support.hpp"

namespace {

using namespace kfuzz;

constexpr size_t kMaxObjects = 16;
constexpr int kMaxOperations = 64;

struct Object {
    kairos_object_id id = 0;
    uint64_t user = 0;
    ModelPtr model;
    const kairos_shape* shape = nullptr;  // the world holds a reference while the object lives
    PoseCase pose;  // now (start of the next step)
    PoseCase end;   // end of the next step, when moving
    bool moving = false;
    bool is_static = false;
    kairos_filter filter{1, 0xffffffffu, 0};
};

// The filter rule of C_API.md, and the static rule: whether the world may test the pair at all.
bool wanted(const Object& a, const Object& b) {
    if (a.is_static && b.is_static) return false;
    if (a.filter.group != 0 && a.filter.group == b.filter.group) return a.filter.group > 0;
    return (a.filter.category_bits & b.filter.mask_bits) != 0 && (b.filter.category_bits & a.filter.mask_bits) != 0;
}

class WorldFuzz {
public:
    explicit WorldFuzz(Input& in) : in_(in) {}
    ~WorldFuzz() { kairos_world_destroy(world_); }
    void run();

private:
    bool create();
    void add();
    void remove();
    void set_pose(bool as_move);
    void move_batch();
    bool step();  // false when the step failed (rightly): the world's state is then not tracked
    void read_results(bool after_step);
    void stats();
    void null_arguments();
    void set_static_or_filter();
    void getters();
    void queries();
    // An id to act on: live, removed, random, 0, or a live one with another generation.
    kairos_object_id choose_id(Object** live_out);
    Object* find(kairos_object_id id);
    // Every pose involved is finite, unit and of moderate magnitude, every shape moderate.
    bool all_moderate() const;
    // Every live object's shape within the accuracy ranges' aspect (own_aspect), cached per model.
    bool all_within_ranges();
    bool within_ranges(const Model& m);
    std::vector<std::pair<const Model*, bool>> within_;

    Input& in_;
    kairos_world* world_ = nullptr;
    double tolerance_ = 1e-10;
    uint32_t max_iterations_ = 256;
    std::vector<Built> shapes_;
    std::vector<Object> live_;
    std::vector<kairos_object_id> removed_;
    std::set<kairos_object_id> issued_;
    uint64_t next_user_ = 1000;
    bool stepped_ = false;              // a step succeeded: results describe it
    bool ever_filtered_ = false;        // a filter or static object was ever set
    std::vector<Object> step_objects_;  // the objects of that step, with their start and end poses
};

bool WorldFuzz::create() {
    // Room past the struct for a newer caller's tail.
    struct {
        kairos_world_settings s;
        unsigned char tail[16];
    } buf;
    std::memset(&buf, 0, sizeof buf);
    kairos_world_settings_init(&buf.s);
    Verdict v;
    bool use = true;
    switch (in_.pick(8)) {
        case 0:
            use = false;
            break;
        case 1:
        case 2:
        case 3:
            buf.s.broad_phase = static_cast<int32_t>(in_.pick(4));
            break;
        case 4: {
            static const int32_t bad[4] = {4, -1, 0x7fffffff, static_cast<int32_t>(0x80000000u)};
            buf.s.broad_phase = bad[in_.pick(4)];
            v.require(KAIROS_ERROR_INVALID_ARGUMENT);
            break;
        }
        case 5: {
            // Smaller than the first published size, or larger with a zero or non-zero tail.
            const unsigned k = in_.pick(4);
            if (k == 0)
                buf.s.struct_size = 4;
            else if (k == 1)
                buf.s.struct_size = offsetof(kairos_world_settings, worker_count) - 8;  // short of 0.1's
            else
                buf.s.struct_size = sizeof(kairos_world_settings) + 16;
            if (k == 3) buf.tail[in_.pick(16)] = static_cast<unsigned char>(1 + in_.pick(255));
            if (k != 2) v.require(KAIROS_ERROR_STRUCT_SIZE);
            buf.s.broad_phase = static_cast<int32_t>(in_.pick(4));
            break;
        }
        default: {
            buf.s.broad_phase = static_cast<int32_t>(in_.pick(4));
            const SettingsCase q = make_settings(in_);
            if (q.use) buf.s.query = q.settings;
            expect_settings(q, v);
            // Sometimes worker threads, or the 0.1 struct (its size, whatever follows).
            const unsigned w = in_.pick(16);
            if (w == 0) buf.s.worker_count = 2 + in_.pick(2);
            if (w == 1) buf.s.struct_size = offsetof(kairos_world_settings, worker_count);
            if (w == 2) {
                buf.s.worker_count = 257;
                v.require(KAIROS_ERROR_INVALID_ARGUMENT);
            }
            break;
        }
    }
    kairos_world* out;
    poison(out);
    const int32_t status =
        observe("kairos_world_create", [&] { return kairos_world_create(use ? &buf.s : nullptr, &out); });
    v.check(status, "kairos_world_create");
    if (status != KAIROS_OK) {
        if (!poisoned(out)) violation("kairos_world_create failed but wrote *out");
        return false;
    }
    if (out == nullptr) violation("kairos_world_create returned KAIROS_OK with *out NULL");
    world_ = out;
    if (use) {
        tolerance_ = buf.s.query.tolerance;
        max_iterations_ = buf.s.query.max_iterations;
    }
    return true;
}

Object* WorldFuzz::find(kairos_object_id id) {
    for (Object& o : live_)
        if (o.id == id) return &o;
    return nullptr;
}

kairos_object_id WorldFuzz::choose_id(Object** live_out) {
    kairos_object_id id = 0;
    switch (in_.pick(8)) {
        case 5:
            if (!removed_.empty())
                id = removed_[in_.pick(static_cast<unsigned>(std::min<size_t>(removed_.size(), 256)))];
            break;
        case 6:
            id = in_.pick(2) == 0 ? 0 : in_.u64();
            break;
        case 7:
            if (!live_.empty()) {
                const kairos_object_id base = live_[in_.pick(static_cast<unsigned>(live_.size()))].id;
                static const uint64_t deltas[4] = {uint64_t{1} << 32, ~uint64_t{0} << 32, 1, uint64_t{1} << 40};
                id = base + deltas[in_.pick(4)];
            }
            break;
        default:
            if (!live_.empty()) id = live_[in_.pick(static_cast<unsigned>(live_.size()))].id;
            break;
    }
    *live_out = find(id);
    return id;
}

bool WorldFuzz::all_moderate() const {
    for (const Object& o : live_) {
        if (!o.model->moderate || !o.pose.valid || !o.pose.moderate) return false;
        if (o.moving && (!o.end.valid || !o.end.moderate)) return false;
    }
    return true;
}

bool WorldFuzz::within_ranges(const Model& m) {
    for (const auto& [model, ok] : within_)
        if (model == &m) return ok;
    const real aspect = own_aspect(m);
    const bool ok = aspect <= 1e6L || std::isinf(aspect);
    within_.emplace_back(&m, ok);
    return ok;
}

bool WorldFuzz::all_within_ranges() {
    for (const Object& o : live_)
        if (!within_ranges(*o.model)) return false;
    return true;
}

void WorldFuzz::add() {
    if (live_.size() >= kMaxObjects || shapes_.empty()) return;
    const Built& shape = shapes_[in_.pick(static_cast<unsigned>(shapes_.size()))];
    const bool null_pose = in_.rare(8);
    const PoseCase pose = null_pose ? PoseCase{} : make_transform(in_);
    const unsigned null_probe = in_.rare(32) ? 1 + in_.pick(2) : 0;  // 1: shape, 2: out
    const uint64_t user = next_user_++;
    kairos_object_id out;
    poison(out);
    const int32_t status = observe("kairos_world_add", [&] {
        return kairos_world_add(world_, null_probe == 1 ? nullptr : shape.shape.get(), null_pose ? nullptr : &pose.pose,
                                user, null_probe == 2 ? nullptr : &out);
    });
    Verdict v;
    if (null_probe != 0) v.require(KAIROS_ERROR_NULL_ARGUMENT);
    expect_pose(pose, v);
    if (!shape.model->moderate) v.unsure();
    v.check(status, "kairos_world_add");
    if (status != KAIROS_OK) {
        if (!poisoned(out)) violation("kairos_world_add failed but wrote *out");
        return;
    }
    if (out == 0) violation("kairos_world_add returned id 0");
    if (!issued_.insert(out).second)
        violation("kairos_world_add returned id %llu a second time", static_cast<unsigned long long>(out));
    Object o;
    o.id = out;
    o.user = user;
    o.model = shape.model;
    o.shape = shape.shape.get();
    o.pose = pose;
    live_.push_back(o);
}

void WorldFuzz::remove() {
    Object* o;
    const kairos_object_id id = choose_id(&o);
    const int32_t status = observe("kairos_world_remove", [&] { return kairos_world_remove(world_, id); });
    Verdict v;
    if (o == nullptr) v.require(KAIROS_ERROR_STALE_ID);
    v.check(status, "kairos_world_remove");
    if (status != KAIROS_OK) return;
    removed_.push_back(id);
    live_.erase(live_.begin() + (o - live_.data()));
}

void WorldFuzz::set_pose(bool as_move) {
    Object* o;
    const kairos_object_id id = choose_id(&o);
    const kairos_pose from = o != nullptr ? o->pose.pose : kairos_pose{{0, 0, 0}, {0, 0, 0, 1}};
    const PoseCase pose = as_move ? make_pose_near(in_, from) : make_transform(in_);
    const bool null_pose = in_.rare(32);
    const char* fn = as_move ? "kairos_world_move" : "kairos_world_set_pose";
    const int32_t status = observe(fn, [&] {
        const kairos_pose* p = null_pose ? nullptr : &pose.pose;
        return as_move ? kairos_world_move(world_, id, p) : kairos_world_set_pose(world_, id, p);
    });
    // Which of several bad arguments is reported first is not part of the contract.
    Verdict v;
    if (o == nullptr) v.require(KAIROS_ERROR_STALE_ID);
    if (null_pose)
        v.require(KAIROS_ERROR_NULL_ARGUMENT);
    else if (pose.invalid || (as_move && o != nullptr && o->is_static))
        v.require(KAIROS_ERROR_INVALID_ARGUMENT);
    if (!v.expects_error()) {
        expect_pose(pose, v);
        if (!o->model->moderate) v.unsure();
    }
    v.check(status, fn);
    if (status != KAIROS_OK) return;
    if (as_move) {
        o->end = pose;
        o->moving = true;
    } else {
        o->pose = pose;
        o->moving = false;
    }
}

// kairos_world_move_batch over every object that is not static (a static one now and then, which
// refuses the batch): it succeeds when every move would, fails when one would, and a refused
// batch moves nothing (the step after it is checked against a model with no moves).
void WorldFuzz::move_batch() {
    std::vector<kairos_object_id> ids;
    std::vector<kairos_pose> ends;
    std::vector<std::pair<Object*, PoseCase>> moves;
    bool must_fail = false, may_fail = false;
    for (Object& o : live_) {
        if (o.is_static && !in_.rare(16)) continue;
        const PoseCase end = make_pose_near(in_, o.pose.pose);
        Verdict v;
        if (o.is_static) v.require(KAIROS_ERROR_INVALID_ARGUMENT);
        expect_pose(end, v);
        must_fail = must_fail || v.expects_error();
        may_fail = may_fail || !end.valid || !end.moderate || !o.model->moderate;
        ids.push_back(o.id);
        ends.push_back(end.pose);
        moves.push_back({&o, end});
    }
    const bool null_ids = !ids.empty() && in_.rare(32);
    const int32_t status = observe("kairos_world_move_batch", [&] {
        return kairos_world_move_batch(world_, null_ids ? nullptr : ids.data(), ends.data(), ids.size());
    });
    if (null_ids) must_fail = true;
    if (must_fail && status == KAIROS_OK) violation("kairos_world_move_batch accepted a batch with a bad move");
    if (!must_fail && !may_fail && status != KAIROS_OK)
        violation("kairos_world_move_batch refused valid moves: %s", kairos_last_error());
    if (status != KAIROS_OK) return;
    for (auto& [o, end] : moves) {
        o->end = end;
        o->moving = true;
    }
}

bool WorldFuzz::step() {
    const int32_t status = observe("kairos_world_step", [&] { return kairos_world_step(world_); });
    Verdict v;
    if (!all_moderate()) v.unsure();
    v.check(status, "kairos_world_step");
    if (status != KAIROS_OK) return false;
    stepped_ = true;
    step_objects_ = live_;
    for (Object& o : step_objects_)
        if (!o.moving) o.end = o.pose;
    read_results(true);
    for (Object& o : live_) {
        if (o.moving) o.pose = o.end;
        o.moving = false;
    }
    return true;
}

// Checks the contacts and overlaps of the last step (read again at any time: they stay valid
// until the next call that changes the world, which read_results is only called before).
void WorldFuzz::read_results(bool after_step) {
    const kairos_contact* contacts;
    size_t count;
    poison(contacts);
    poison(count);
    int32_t status = observe("kairos_world_contacts", [&] { return kairos_world_contacts(world_, &contacts, &count); });
    Verdict v;
    v.check(status, "kairos_world_contacts");
    const kairos_object_id* pairs;
    size_t pair_count;
    status = observe("kairos_world_overlaps", [&] { return kairos_world_overlaps(world_, &pairs, &pair_count); });
    v.check(status, "kairos_world_overlaps");
    if (count > 0 && contacts == nullptr) violation("kairos_world_contacts: %zu contacts at NULL", count);
    if (pair_count > 0 && pairs == nullptr) violation("kairos_world_overlaps: %zu pairs at NULL", pair_count);
    if (!stepped_) {
        if (count != 0 || pair_count != 0)
            violation("%zu contacts and %zu overlaps before any successful step", count, pair_count);
        return;
    }
    auto object_of = [&](kairos_object_id id) -> const Object* {
        for (const Object& o : step_objects_)
            if (o.id == id) return &o;
        return nullptr;
    };
    std::set<std::pair<kairos_object_id, kairos_object_id>> overlaps;
    for (size_t i = 0; i < pair_count; ++i) {
        const kairos_object_id a = pairs[2 * i], b = pairs[2 * i + 1];
        if (!(a < b))
            violation("kairos_world_overlaps: pair %zu is (%llu, %llu), not smaller id first", i,
                      static_cast<unsigned long long>(a), static_cast<unsigned long long>(b));
        if (object_of(a) == nullptr || object_of(b) == nullptr)
            violation("kairos_world_overlaps: pair %zu names an id that was not live during the step", i);
        if (!overlaps.insert({a, b}).second) violation("kairos_world_overlaps: pair %zu listed twice", i);
        if (object_of(a) != nullptr && object_of(b) != nullptr && !wanted(*object_of(a), *object_of(b)))
            violation("kairos_world_overlaps: pair %zu (%llu, %llu) is ruled out by the filters or both static", i,
                      static_cast<unsigned long long>(a), static_cast<unsigned long long>(b));
    }
    const bool moderate_step = [&] {
        for (const Object& o : step_objects_)
            if (!o.model->moderate || !o.pose.moderate || !o.end.moderate) return false;
        return true;
    }();
    std::set<std::pair<kairos_object_id, kairos_object_id>> touched;
    for (size_t i = 0; i < count; ++i) {
        const kairos_contact& c = contacts[i];
        if (!(c.a < c.b))
            violation("kairos_world_contacts: contact %zu has a %llu >= b %llu", i,
                      static_cast<unsigned long long>(c.a), static_cast<unsigned long long>(c.b));
        const Object* oa = object_of(c.a);
        const Object* ob = object_of(c.b);
        if (oa == nullptr || ob == nullptr)
            violation("kairos_world_contacts: contact %zu names an id not in the step", i);
        if (c.user_a != oa->user || c.user_b != ob->user)
            violation("kairos_world_contacts: contact %zu carries user data %llu, %llu instead of %llu, %llu", i,
                      static_cast<unsigned long long>(c.user_a), static_cast<unsigned long long>(c.user_b),
                      static_cast<unsigned long long>(oa->user), static_cast<unsigned long long>(ob->user));
        const bool all_finite = std::isfinite(c.toi) && finite(c.point) && finite(c.normal);
        if (!all_finite) {
            if (KAIROS_FUZZ_ALLOW_NONFINITE_ON_HUGE && !moderate_step) continue;
            violation("kairos_world_contacts: contact %zu has a non-finite toi, point or normal", i);
        }
        if (!(c.toi >= 0 && c.toi <= 1))
            violation("kairos_world_contacts: contact %zu toi %.17g outside [0, 1]", i, c.toi);
        if (!(std::fabs(norm(to_real(c.normal)) - 1) < 1e-6L))
            violation("kairos_world_contacts: contact %zu normal %s is not unit (toi %.17g); A %s %s -> %s, B %s %s -> %s",
                      i, show(c.normal), c.toi, describe(*oa->model).c_str(), show(oa->pose.pose), show(oa->end.pose),
                      describe(*ob->model).c_str(), show(ob->pose.pose), show(ob->end.pose));
        if (i > 0) {
            const kairos_contact& p = contacts[i - 1];
            const bool ordered = p.toi < c.toi || (p.toi == c.toi && (p.a < c.a || (p.a == c.a && p.b < c.b)));
            if (!ordered)
                violation("kairos_world_contacts: contacts %zu and %zu are out of order or repeat a pair", i - 1, i);
        }
        if (!touched.insert({c.a, c.b}).second) violation("kairos_world_contacts: pair of contact %zu listed twice", i);
        if (overlaps.count({c.a, c.b}) == 0)
            violation("kairos_world_contacts: contact %zu's pair is not among the broad-phase overlaps", i);
    }
    if (!after_step || !moderate_step) return;
    // No missed contacts: the ball about each origin inside its shape turns with it, so when two
    // such balls meet at some time t the pair touches by then.
    for (size_t i = 0; i < step_objects_.size(); ++i)
        for (size_t j = i + 1; j < step_objects_.size(); ++j) {
            const Object &a = step_objects_[i], &b = step_objects_[j];
            if (!wanted(a, b)) continue;
            const real ra = inner_radius(*a.model), rb = inner_radius(*b.model);
            if (ra < 0 || rb < 0) continue;
            // Pairs whose sizes differ by more than 1e6 are beyond the ranges where docs/c-api.md
            // states the accuracy; a rotating ball sweeping into a slab 1e19 wide is missed there
            // (an open finding: tests/fuzz/findings/README.md).
            if (!(a.model->magnitude <= 1e6L * b.model->magnitude && b.model->magnitude <= 1e6L * a.model->magnitude))
                continue;
            const real r = ra + rb;
            const Vr p0 = to_real(b.pose.pose.position) - to_real(a.pose.pose.position);
            const Vr p1 = to_real(b.end.pose.position) - to_real(a.end.pose.position);
            const Vr dv = p1 - p0;
            const real where = std::fmax(norm(to_real(a.pose.pose.position)), norm(to_real(b.pose.pose.position))) +
                               norm(to_real(a.end.pose.position)) + norm(to_real(b.end.pose.position));
            const real reach = r * (1 - 1e-6L) - 64 * ulp(where);
            const real enter = first_within(p0, dv, reach);
            if (enter < 0) continue;
            const kairos_object_id lo = std::min(a.id, b.id), hi = std::max(a.id, b.id);
            const kairos_contact* found = nullptr;
            for (size_t k = 0; k < count; ++k)
                if (contacts[k].a == lo && contacts[k].b == hi) found = &contacts[k];
            if (found == nullptr)
                violation(
                    "kairos_world_step: no contact for ids %llu and %llu, whose inner balls (radii sum %.17Lg) "
                    "meet at t = %.17Lg (tolerance %g): A %s %s -> %s, B %s %s -> %s (%s broad-phase pair)",
                    static_cast<unsigned long long>(a.id), static_cast<unsigned long long>(b.id), r, enter, tolerance_,
                    describe(*a.model).c_str(), show(a.pose.pose), show(a.end.pose), describe(*b.model).c_str(),
                    show(b.pose.pose), show(b.end.pose), overlaps.count({lo, hi}) ? "a" : "not a");
            // Beyond the tolerance, a toi found by support planes may be late by their rounding,
            // eps times the shapes' extent and position, over the relative speed (a box 1e20 wide:
            // 2e-9 of the step; negligible for shapes of moderate size).
            const real speed = norm(dv);
            const real plane_rounding =
                speed > 0 ? 64 * 2.220446049250313e-16L * (a.model->magnitude + b.model->magnitude + where) / speed : 0;
            if (!(found->toi <= enter + tolerance_ + 1e-9L + plane_rounding))
                violation(
                    "kairos_world_step: contact of ids %llu and %llu at toi %.17g, but their inner balls meet at "
                    "t = %.17Lg already (tolerance %g, max_iterations %u): A %s %s -> %s, B %s %s -> %s",
                    static_cast<unsigned long long>(lo), static_cast<unsigned long long>(hi), found->toi, enter,
                    tolerance_, max_iterations_, describe(*a.model).c_str(), show(a.pose.pose), show(a.end.pose),
                    describe(*b.model).c_str(), show(b.pose.pose), show(b.end.pose));
        }
}

void WorldFuzz::stats() {
    struct {
        kairos_step_stats s;
        unsigned char tail[32];
    } buf;
    poison(buf);
    kairos_step_stats_init(&buf.s);
    Verdict v;
    uint32_t size = sizeof(kairos_step_stats);
    switch (in_.pick(4)) {
        case 0:
            break;
        case 1:
            size = 4 + in_.pick(static_cast<unsigned>(sizeof(kairos_step_stats) - 4));
            break;
        case 2:
            size = sizeof(kairos_step_stats) + in_.pick(33);
            break;
        default:
            size = in_.pick(4);
            v.require(KAIROS_ERROR_STRUCT_SIZE);
            break;
    }
    buf.s.struct_size = size;
    const auto before = buf;
    const int32_t status = observe("kairos_world_step_stats", [&] { return kairos_world_step_stats(world_, &buf.s); });
    v.check(status, "kairos_world_step_stats");
    if (status != KAIROS_OK) {
        if (std::memcmp(&before, &buf, sizeof buf) != 0) violation("kairos_world_step_stats failed but wrote *out");
        return;
    }
    if (buf.s.struct_size != size)
        violation("kairos_world_step_stats changed struct_size %u to %u", size, buf.s.struct_size);
    const auto* a = reinterpret_cast<const unsigned char*>(&before);
    const auto* b = reinterpret_cast<const unsigned char*>(&buf);
    for (size_t i = std::min<size_t>(size, sizeof(kairos_step_stats)); i < sizeof buf; ++i)
        if (a[i] != b[i]) violation("kairos_world_step_stats wrote byte %zu past struct_size %u", i, size);
    if (size >= sizeof(kairos_step_stats)) {
        const kairos_step_stats& s = buf.s;
        if (!(std::isfinite(s.broad_phase_seconds) && s.broad_phase_seconds >= 0 &&
              std::isfinite(s.narrow_phase_seconds) && s.narrow_phase_seconds >= 0))
            violation("kairos_world_step_stats: times %g, %g", s.broad_phase_seconds, s.narrow_phase_seconds);
        const kairos_object_id* pairs;
        size_t pair_count;
        // The broad phase's pairs include those the filters and static objects then rule out.
        if (kairos_world_overlaps(world_, &pairs, &pair_count) == KAIROS_OK && stepped_ &&
            (ever_filtered_ ? s.broad_phase_pairs < pair_count : s.broad_phase_pairs != pair_count))
            violation("kairos_world_step_stats: broad_phase_pairs %llu but kairos_world_overlaps lists %zu",
                      static_cast<unsigned long long>(s.broad_phase_pairs), pair_count);
    }
}

void WorldFuzz::null_arguments() {
    Verdict null;
    null.require(KAIROS_ERROR_NULL_ARGUMENT);
    const kairos_contact* contacts;
    size_t count;
    kairos_object_id id;
    kairos_step_stats stats;
    kairos_step_stats_init(&stats);
    const kairos_pose pose{{0, 0, 0}, {0, 0, 0, 1}};
    int32_t status;
    switch (in_.pick(8)) {
        case 0:
            status = observe("kairos_world_step", [&] { return kairos_world_step(nullptr); });
            null.check(status, "kairos_world_step(NULL)");
            break;
        case 1:
            status =
                observe("kairos_world_contacts", [&] { return kairos_world_contacts(nullptr, &contacts, &count); });
            null.check(status, "kairos_world_contacts(NULL, ...)");
            break;
        case 2:
            status = observe("kairos_world_contacts", [&] { return kairos_world_contacts(world_, nullptr, &count); });
            null.check(status, "kairos_world_contacts(w, NULL, ...)");
            break;
        case 3: {
            const kairos_object_id* pairs;
            status = observe("kairos_world_overlaps", [&] { return kairos_world_overlaps(world_, &pairs, nullptr); });
            null.check(status, "kairos_world_overlaps(w, pairs, NULL)");
            break;
        }
        case 4:
            status = observe("kairos_world_step_stats", [&] { return kairos_world_step_stats(world_, nullptr); });
            null.check(status, "kairos_world_step_stats(w, NULL)");
            break;
        case 5:
            status = observe("kairos_world_add", [&] {
                return kairos_world_add(nullptr, shapes_.empty() ? nullptr : shapes_[0].shape.get(), &pose, 0, &id);
            });
            null.check(status, "kairos_world_add(NULL, ...)");
            break;
        case 6:
            status = observe("kairos_world_remove", [&] { return kairos_world_remove(nullptr, 1); });
            null.check(status, "kairos_world_remove(NULL, ...)");
            break;
        default:
            status = observe("kairos_world_create", [&] { return kairos_world_create(nullptr, nullptr); });
            null.check(status, "kairos_world_create(settings, NULL)");
            break;
    }
}

// set_static or set_filter on a live, stale or made-up id, with good and bad values.
void WorldFuzz::set_static_or_filter() {
    Object* o;
    const kairos_object_id id = choose_id(&o);
    Verdict v;
    if (o == nullptr) v.require(KAIROS_ERROR_STALE_ID);
    if (in_.pick(2) == 0) {
        static const int32_t values[8] = {0, 1, 0, 1, 0, 1, 2, -1};
        const int32_t value = values[in_.pick(8)];
        if (value != 0 && value != 1) v.require(KAIROS_ERROR_INVALID_ARGUMENT);
        const int32_t status = observe("kairos_world_set_static", [&] { return kairos_world_set_static(world_, id, value); });
        v.check(status, "kairos_world_set_static");
        if (status != KAIROS_OK) return;
        o->is_static = value == 1;
        ever_filtered_ = true;
        if (o->is_static) o->moving = false;  // a pending move is cancelled
        return;
    }
    const bool null_filter = in_.rare(16);
    kairos_filter f;
    f.category_bits = in_.pick(2) == 0 ? 1u << in_.pick(4) : static_cast<uint32_t>(in_.u64());
    f.mask_bits = in_.pick(2) == 0 ? 0xffffffffu : static_cast<uint32_t>(in_.u64());
    static const int32_t groups[8] = {0, 0, 0, 1, -1, 2, -2, 0x7fffffff};
    f.group = groups[in_.pick(8)];
    if (null_filter) v.require(KAIROS_ERROR_NULL_ARGUMENT);
    const int32_t status =
        observe("kairos_world_set_filter", [&] { return kairos_world_set_filter(world_, id, null_filter ? nullptr : &f); });
    v.check(status, "kairos_world_set_filter");
    if (status == KAIROS_OK) {
        o->filter = f;
        ever_filtered_ = true;
    }
}

// The pose and user data of an id: the world's pose now (the same position, the same rotation
// as a unit quaternion) and the user data given to add; nothing written on error.
void WorldFuzz::getters() {
    Object* o;
    const kairos_object_id id = choose_id(&o);
    Verdict v;
    if (o == nullptr) v.require(KAIROS_ERROR_STALE_ID);
    kairos_pose pose;
    poison(pose);
    int32_t status = observe("kairos_world_get_pose", [&] { return kairos_world_get_pose(world_, id, &pose); });
    v.check(status, "kairos_world_get_pose");
    if (status != KAIROS_OK) {
        if (!poisoned(pose)) violation("kairos_world_get_pose failed but wrote *out");
    } else {
        const kairos_pose& want = o->pose.pose;
        if (std::memcmp(&pose.position, &want.position, sizeof pose.position) != 0)
            violation("kairos_world_get_pose: position %s, set %s", show(pose), show(want));
        const kairos_quat& q = pose.orientation;
        const kairos_quat& g = want.orientation;
        const double qq = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
        const double gg = g.x * g.x + g.y * g.y + g.z * g.z + g.w * g.w;
        const double dotqg = q.x * g.x + q.y * g.y + q.z * g.z + q.w * g.w;
        if (!(std::fabs(qq - 1) <= 1e-14) || !(dotqg >= (1 - 1e-14) * std::sqrt(gg)))
            violation("kairos_world_get_pose: orientation %s, set %s", show(pose), show(want));
    }
    uint64_t user = 0x5a5a5a5a5a5a5a5aull;
    status = observe("kairos_world_get_user_data", [&] { return kairos_world_get_user_data(world_, id, &user); });
    v.check(status, "kairos_world_get_user_data");
    if (status != KAIROS_OK && user != 0x5a5a5a5a5a5a5a5aull) violation("kairos_world_get_user_data failed but wrote *out");
    if (status == KAIROS_OK && user != o->user)
        violation("kairos_world_get_user_data: %llu, added with %llu", static_cast<unsigned long long>(user),
                  static_cast<unsigned long long>(o->user));
}

// World queries against brute force over the pair queries at the objects' current poses (rays:
// kairos_ray_cast with the world's settings; shape casts: kairos_shape_cast or, for a turn,
// kairos_motion_cast), and their contract: statuses, nothing written on failure, ranges, ids.
void WorldFuzz::queries() {
    kairos_filter filter{1u << in_.pick(3), in_.pick(2) ? 0xffffffffu : in_.pick(8),
                         static_cast<int32_t>(in_.pick(5)) - 2};
    const bool use_filter = in_.pick(2) == 0;
    auto sees = [&](const Object& o) {
        if (!use_filter) return true;
        if (filter.group != 0 && filter.group == o.filter.group) return filter.group > 0;
        return (filter.category_bits & o.filter.mask_bits) != 0 && (o.filter.category_bits & filter.mask_bits) != 0;
    };
    auto in_range = [](const kairos_vec3& v) {
        return std::fabs(v.x) <= KAIROS_MAX_MAGNITUDE && std::fabs(v.y) <= KAIROS_MAX_MAGNITUDE &&
               std::fabs(v.z) <= KAIROS_MAX_MAGNITUDE;  // NaN fails
    };
    // Brute force is compared only within the accuracy ranges (docs/c-api.md): beyond them a pair
    // query may report a hit a rounding of the shape's size away (a slab 1e10 wide and 0.006 thick
    // 'hit' by a ray 6 from it), which the world's box culling rightly skips.
    const bool exact = all_moderate() && all_within_ranges();
    const unsigned kind = in_.pick(3);
    if (kind == 2) {
        kairos_vec3 lo = position(in_), hi = lo;
        const kairos_vec3 d = small_vec(in_, 4);
        hi.x += std::fabs(d.x);
        hi.y += std::fabs(d.y);
        hi.z += std::fabs(d.z);
        if (in_.rare(8)) std::swap(lo.y, hi.y);
        kairos_object_id ids[kMaxObjects];
        poison(ids);
        size_t count;
        poison(count);
        const size_t capacity = in_.pick(kMaxObjects + 1);
        const int32_t status = observe("kairos_world_query_box", [&] {
            return kairos_world_query_box(world_, lo, hi, use_filter ? &filter : nullptr, capacity ? ids : nullptr,
                                          capacity, &count);
        });
        Verdict v;
        if (!in_range(lo) || !in_range(hi) || !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z))
            v.require(KAIROS_ERROR_INVALID_ARGUMENT);
        v.check(status, "kairos_world_query_box");
        if (status != KAIROS_OK) {
            if (!poisoned(count) || !poisoned(ids)) violation("kairos_world_query_box failed but wrote an output");
            return;
        }
        for (size_t i = capacity; i < kMaxObjects; ++i) {
            kairos_object_id untouched;
            poison(untouched);
            if (ids[i] != untouched) violation("kairos_world_query_box wrote past capacity %zu", capacity);
        }
        // Brute force: the tight boxes kairos_shape_bounds gives at the current poses.
        std::vector<kairos_object_id> want;
        for (const Object& o : live_) {
            if (!sees(o)) continue;
            kairos_vec3 bmin, bmax;
            if (kairos_shape_bounds(o.shape, &o.pose.pose, &bmin, &bmax) != KAIROS_OK) return;  // beyond range
            if (bmin.x <= hi.x && lo.x <= bmax.x && bmin.y <= hi.y && lo.y <= bmax.y && bmin.z <= hi.z &&
                lo.z <= bmax.z)
                want.push_back(o.id);
        }
        std::sort(want.begin(), want.end());
        if (count != want.size()) violation("kairos_world_query_box: %zu ids, brute force finds %zu", count, want.size());
        for (size_t i = 0; i < count && i < capacity; ++i)
            if (ids[i] != want[i])
                violation("kairos_world_query_box: id %zu is %llu, brute force says %llu", i,
                          static_cast<unsigned long long>(ids[i]), static_cast<unsigned long long>(want[i]));
        return;
    }
    // A ray, or a shape following a motion.
    const Built* cast_shape = nullptr;
    kairos_motion motion{};
    SettingsCase settings;
    kairos_vec3 origin{}, translation{};
    Verdict v;
    if (kind == 0) {
        origin = position(in_);
        translation = in_.pick(4) == 0 ? direction(in_) : small_vec(in_, 8);
        if (!in_range(origin) || !in_range(translation)) v.require(KAIROS_ERROR_INVALID_ARGUMENT);
    } else {
        if (shapes_.empty()) return;
        cast_shape = &shapes_[in_.pick(static_cast<unsigned>(shapes_.size()))];
        const PoseCase start = make_transform(in_);
        PoseCase end = in_.pick(2) ? make_pose_near(in_, start.pose) : start;
        if (in_.pick(2)) {  // a pure translation
            end.pose.orientation = start.pose.orientation;
            end.pose.position.x += 3;
            end = classify(end.pose);
        }
        motion = {start.pose, end.pose};
        settings = make_settings(in_);
        expect_pose(start, v);
        expect_pose(end, v);
        expect_settings(settings, v);
        if (!cast_shape->model->moderate || !start.moderate || !end.moderate) v.unsure();
    }
    if (!exact) v.unsure();
    const bool exact_cast = exact && (cast_shape == nullptr || within_ranges(*cast_shape->model));
    kairos_world_hit hit;
    poison(hit);
    const char* fn = kind == 0 ? "kairos_world_ray_cast" : "kairos_world_shape_cast";
    const int32_t status = observe(fn, [&] {
        return kind == 0 ? kairos_world_ray_cast(world_, origin, translation, use_filter ? &filter : nullptr, &hit)
                         : kairos_world_shape_cast(world_, cast_shape->shape.get(), &motion,
                                                   use_filter ? &filter : nullptr,
                                                   settings.use ? &settings.settings : nullptr, &hit);
    });
    v.check(status, fn);
    if (status != KAIROS_OK) {
        if (!poisoned(hit)) violation("%s failed but wrote *out", fn);
        return;
    }
    if (hit.hit == 0) {
        if (hit.id != 0 || hit.user_data != 0 || hit.toi != 1)
            violation("%s: a miss with id %llu, toi %.17g", fn, static_cast<unsigned long long>(hit.id), hit.toi);
    } else {
        const Object* o = find(hit.id);
        if (hit.hit != 1 || o == nullptr || !sees(*o) || hit.user_data != o->user)
            violation("%s: hit %d on id %llu (user data %llu), not a live object the filter sees", fn, hit.hit,
                      static_cast<unsigned long long>(hit.id), static_cast<unsigned long long>(hit.user_data));
        if (!(hit.toi >= 0 && hit.toi <= 1)) violation("%s: toi %.17g", fn, hit.toi);
        const double nn = hit.normal.x * hit.normal.x + hit.normal.y * hit.normal.y + hit.normal.z * hit.normal.z;
        if (!(std::fabs(nn - 1) <= 1e-6)) violation("%s: normal %s is not unit", fn, show(hit.normal));
    }
    if (!exact_cast || v.expects_error()) return;
    // Brute force: the earliest hit of the pair query over every object the filter sees (ties:
    // the smaller id). A shape cast is the shape cast or the motion cast, as the world picks.
    const kairos_query_settings world_settings{sizeof(kairos_query_settings), tolerance_, max_iterations_};
    // A shape cast without settings takes the world's, as the rays always do.
    const kairos_query_settings* cast_settings = settings.use ? &settings.settings : &world_settings;
    const int variants = kind == 0 ? 1 : 2;
    for (int variant = 0; variant < variants; ++variant) {
        int hit_any = 0;
        double best = 1;
        kairos_object_id best_id = 0;
        for (const Object& o : live_) {
            if (!sees(o)) continue;
            kairos_cast_result r;
            int32_t st;
            if (kind == 0) {
                st = kairos_ray_cast(o.shape, &o.pose.pose, origin, translation, &world_settings, &r);
            } else if (variant == 0) {
                const kairos_vec3 t{motion.end.position.x - motion.start.position.x,
                                    motion.end.position.y - motion.start.position.y,
                                    motion.end.position.z - motion.start.position.z};
                st = kairos_shape_cast(cast_shape->shape.get(), &motion.start, t, o.shape, &o.pose.pose, {0, 0, 0},
                                       cast_settings, &r);
            } else {
                const kairos_motion still{o.pose.pose, o.pose.pose};
                st = kairos_motion_cast(cast_shape->shape.get(), &motion, o.shape, &still,
                                        cast_settings, &r);
            }
            if (st != KAIROS_OK) return;  // beyond range: no brute-force answer
            // The iteration guard's answer is a conservative hit at the last bound, however far
            // the shapes are; the world casts only the objects near the path, so no comparison.
            if (r.termination == KAIROS_TERMINATION_MAX_ITERATIONS) return;
            if (r.hit && (!hit_any || r.toi < best || (r.toi == best && o.id < best_id))) {
                hit_any = 1;
                best = r.toi;
                best_id = o.id;
            }
        }
        if (hit_any == hit.hit && (!hit_any || (best_id == hit.id && best == hit.toi))) return;  // agrees
        if (variant + 1 == variants)
            violation("%s: hit %d id %llu toi %.17g; brute force hit %d id %llu toi %.17g", fn, hit.hit,
                      static_cast<unsigned long long>(hit.id), hit.toi, hit_any,
                      static_cast<unsigned long long>(best_id), best);
    }
}

void WorldFuzz::run() {
    if (!create()) return;
    ShapeBuilder builder(in_, /*max_depth=*/1, /*thorough=*/false);
    for (unsigned i = 0, n = 1 + in_.pick(3); i < n; ++i) shapes_.push_back(builder.build_or_sphere());
    for (int op = 0; op < kMaxOperations && in_.remaining() > 0; ++op) {
        switch (in_.pick(16)) {
            case 0:
            case 1:
            case 2:
            case 3:
                add();
                break;
            case 4:
                remove();
                break;
            case 5:
            case 6:
                set_pose(false);
                break;
            case 7:
            case 8:
            case 9:
            case 10:
                set_pose(true);
                break;
            case 11:
                if (!step()) return;
                break;
            case 12:
                // Every object moves a little (or not at all), then the step: many movers at once,
                // one call each or one batch.
                if (in_.pick(2) == 0) {
                    move_batch();
                    if (!step()) return;
                    break;
                }
                for (Object& o : live_) {
                    if (o.is_static) continue;
                    const PoseCase end = make_pose_near(in_, o.pose.pose);
                    const int32_t status =
                        observe("kairos_world_move", [&] { return kairos_world_move(world_, o.id, &end.pose); });
                    Verdict v;
                    expect_pose(end, v);
                    if (!o.model->moderate) v.unsure();
                    v.check(status, "kairos_world_move");
                    if (status == KAIROS_OK) {
                        o.end = end;
                        o.moving = true;
                    }
                }
                if (!step()) return;
                break;
            case 13:
                read_results(false);
                break;
            case 14:
                stats();
                break;
            default:
                switch (in_.pick(6)) {
                    case 0:
                        null_arguments();
                        break;
                    case 1:
                        shapes_.clear();  // the world's own references keep its shapes alive
                        break;
                    case 2:
                        set_static_or_filter();
                        break;
                    case 3:
                        getters();
                        break;
                    default:
                        queries();
                        break;
                }
                break;
        }
    }
    step();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    Input in(data, size);
    WorldFuzz fuzz(in);
    fuzz.run();
    return 0;
}
