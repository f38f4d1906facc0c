// SPDX-License-Identifier: MIT
// The world and its step (see world.hpp): boxes over the step, broad phase, narrow phase.
#include "world/world.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "casts/cast.hpp"
#include "gjk/gjk.hpp"
#include "motion/motion.hpp"
#include "motion/motion_cast.hpp"
#include "shapes/radius.hpp"

namespace kairos {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Transform rigid(const Pose& s) { return make_transform(s.position, s.orientation); }

// Grows a box by `m` on every side.
Aabb grown(const Aabb& b, double m) { return {b.min - Vec3{m, m, m}, b.max + Vec3{m, m, m}}; }

Aabb shifted(const Aabb& b, Vec3 d) { return {b.min + d, b.max + d}; }

double max_extent(const Aabb& b) { return max_abs(b.max - b.min); }

// Margin added to every box: the casts report a hit once the shapes are within `tolerance`
// times their size (docs/c-api.md "Tolerances"), so boxes that stay that far apart must still meet;
// and a few ulps of the coordinates for the rounding of the support points.
double box_margin(const Aabb& b, double tolerance) {
    return tolerance * max_extent(b) + 8 * kEps * std::fmax(max_abs(b.min), max_abs(b.max));
}

}  // namespace

World::World(const WorldSettings& settings)
    : settings_(settings),
      broad_(BroadPhase::create(settings.broad_phase)),
      workers_(std::make_unique<Workers>(settings.worker_count, settings.task_hook)) {}

World::~World() {
    for (Object& o : objects_)
        if (o.alive) o.shape->release();
}

Aabb World::tight_box(const Shape& shape, const Pose& pose, Vec3 translation) const {
    Aabb b;
    bounds(shape, rigid(pose), b.min, b.max);
    return grown(b, box_margin(b, settings_.tolerance) + settings_.tolerance * max_abs(translation));
}

uint64_t World::add(const Shape& shape, const Pose& pose, uint64_t user_data) {
    // Room for this slot's later removal, taken now so that remove() never allocates.
    if (free_slots_.capacity() < objects_.size() + 1)
        free_slots_.reserve(std::max<size_t>(2 * free_slots_.capacity(), objects_.size() + 1));
    const Aabb box = tight_box(shape, pose, {});
    uint32_t index;
    bool appended = false;
    if (!free_slots_.empty()) {
        index = free_slots_.back();
    } else {
        if (objects_.size() > BroadPhase::kMaxId) return 0;
        objects_.emplace_back();  // may throw; nothing has changed yet
        appended = true;
        index = static_cast<uint32_t>(objects_.size() - 1);
    }
    try {
        broad_->add(index, box, false);
    } catch (...) {
        if (appended) objects_.pop_back();
        throw;
    }
    if (!appended) free_slots_.pop_back();
    Object& o = objects_[index];
    shape.retain();
    o.shape = &shape;
    o.pose = pose;
    o.end = pose;
    o.box = box;
    o.moving = false;
    o.loose = false;
    o.is_static = false;  // a reused slot's occupant starts ordinary, with the default filter
    o.filter = Filter{};
    o.user_data = user_data;
    o.alive = true;
    ++live_;
    return make_id(index, o.generation);
}

const World::Object* World::find(uint64_t id) const {
    const uint64_t index = id & 0xffffffffu;
    const uint64_t generation = id >> 32;
    if (index >= objects_.size()) return nullptr;
    const Object& o = objects_[index];
    if (!o.alive || o.generation != generation) return nullptr;
    return &o;
}

World::Object* World::find_mutable(uint64_t id) { return const_cast<Object*>(find(id)); }

bool World::remove(uint64_t id) {
    Object* o = find_mutable(id);
    if (o == nullptr) return false;
    const uint32_t index = index_of(id);
    broad_->remove(index);
    o->shape->release();
    o->shape = nullptr;
    o->alive = false;
    o->moving = false;
    o->loose = false;
    --live_;
    // A slot whose generation would wrap is retired, so no old id can ever match it again.
    if (o->generation == std::numeric_limits<uint32_t>::max()) return true;
    ++o->generation;
    free_slots_.push_back(index);  // never allocates: add() reserved the room
    return true;
}

bool World::set_pose(uint64_t id, const Pose& pose) {
    Object* o = find_mutable(id);
    if (o == nullptr) return false;
    const Aabb box = tight_box(*o->shape, pose, {});
    broad_->teleport(index_of(id), box);
    o->pose = pose;
    o->end = pose;
    o->box = box;
    o->moving = false;
    o->loose = false;
    return true;
}

bool World::move(uint64_t id, const Pose& end) {
    Object* o = find_mutable(id);
    if (o == nullptr || o->is_static) return false;
    if (!o->moving) moved_.push_back(index_of(id));  // may throw; nothing has changed yet
    o->end = end;
    o->moving = true;
    return true;
}

bool World::set_static(uint64_t id, bool is_static) {
    Object* o = find_mutable(id);
    if (o == nullptr) return false;
    if (is_static && o->moving) {  // its slot may stay in moved_: the step skips still objects
        o->end = o->pose;
        o->moving = false;
    }
    // The broad phase keeps pairs of two static objects out of its per-step work. Its moves are
    // given only inside step(), so it has none pending here and cannot refuse.
    broad_->set_static(index_of(id), is_static);
    o->is_static = is_static;
    return true;
}

bool World::set_filter(uint64_t id, const Filter& filter) {
    Object* o = find_mutable(id);
    if (o == nullptr) return false;
    o->filter = filter;
    return true;
}

// The motion of a moving object over the step and its boxes at t = 0 and t = 1, each coordinate
// linear in between, holding the shape at every moment of the step.
// Translation only: the tight boxes at both ends (a box translated linearly is exact).
// Turning (docs/algorithms.md §4): relative to its origin the shape at time t lies in its start
// shape grown by the disk of radius 2 rho sin(angle / 2) perpendicular to the axis, and also in
// its end shape grown by that disk (turning back from the end); and within the ball of radius
// sqrt(rho^2 + h^2) (h the extent along the axis). The box of the intersection of the three,
// carried along by the origin's linear motion, holds the shape throughout.
World::Sweep World::sweep_of(const Shape& shape, const Pose& pose, const Pose& end, const Aabb* box_now,
                             Aabb* out_start, Aabb* out_end) const {
    const Motion motion(pose, end);
    Sweep s;
    s.start = rigid(pose);
    s.translation = motion.linear();
    // The same orientation (q or -q) is a translation: Motion reads no turn (same_rotation).
    if (!motion.rotates()) {
        *out_start = box_now != nullptr ? *box_now : tight_box(shape, pose, {});
        *out_end = tight_box(shape, end, s.translation);
        return s;
    }
    s.rotates = true;
    s.axis = motion.axis();
    const Vec3 local_axis = s.start.to_local_direction(s.axis);
    const double rho = extreme_radius(shape, local_axis);
    s.disk = motion.disk_radius(rho, 0, 1);
    const double h =
        std::fmax(dot(local_axis, support(shape, local_axis)), -dot(local_axis, support(shape, -local_axis)));
    const double ball = std::sqrt(rho * rho + h * h);
    Aabb rel0, rel1;
    bounds(shape, Transform{s.start.rotation, {}}, rel0.min, rel0.max);
    bounds(shape, Transform{to_matrix(end.orientation), {}}, rel1.min, rel1.max);
    Aabb rel;
    for (int k = 0; k < 3; ++k) {
        // The disk's half extent along world axis k.
        const double e = s.disk * std::sqrt(std::fmax(0.0, 1 - s.axis[k] * s.axis[k]));
        rel.min[k] = std::fmax(-ball, std::fmax(rel0.min[k], rel1.min[k]) - e);
        rel.max[k] = std::fmin(ball, std::fmin(rel0.max[k], rel1.max[k]) + e);
        if (!(rel.min[k] <= rel.max[k])) rel.min[k] = rel.max[k] = 0.5 * (rel.min[k] + rel.max[k]);  // rounding
    }
    const Aabb box0 = shifted(rel, pose.position);
    const Aabb box1 = shifted(rel, end.position);
    const double m = box_margin(box0, settings_.tolerance) + box_margin(box1, settings_.tolerance) +
                     settings_.tolerance * max_abs(s.translation);
    *out_start = grown(box0, m);
    *out_end = grown(box1, m);
    return s;
}

void World::step() {
    const auto t0 = std::chrono::steady_clock::now();
    counters_ = StepCounters{};
    if (sweeps_.size() < objects_.size()) {
        sweeps_.resize(objects_.size());
        swept_.resize(objects_.size(), 0);
    }

    // Boxes a turn left loose shrink back to the pose once the object stops turning.
    for (uint32_t index : loose_) {
        Object& o = objects_[index];
        if (!o.alive || !o.loose || o.moving) continue;
        o.box = tight_box(*o.shape, o.pose, {});
        broad_->teleport(index, o.box);
        o.loose = false;
    }
    loose_.clear();

    // Moving objects: their motion and boxes. Objects that stay still cost nothing here.
    std::size_t w = 0;
    for (uint32_t index : moved_) {
        Object& o = objects_[index];
        if (!o.alive || !o.moving || swept_[index]) continue;
        if (o.end.position == o.pose.position && o.end.orientation.x == o.pose.orientation.x &&
            o.end.orientation.y == o.pose.orientation.y && o.end.orientation.z == o.pose.orientation.z &&
            o.end.orientation.w == o.pose.orientation.w) {
            o.pose = o.end;  // equal, but the caller's bits: -0 for 0 (get_pose returns what was given)
            o.moving = false;
            if (o.loose) {
                o.box = tight_box(*o.shape, o.pose, {});
                broad_->teleport(index, o.box);
                o.loose = false;
            }
            continue;
        }
        swept_[index] = 1;  // sweeps_[index] is filled below
        moved_[w++] = index;
    }
    moved_.resize(w);
    // Their motion bounds on any worker (independent per object), then the broad phase's moves
    // in order.
    motion_boxes_.resize(moved_.size());
    auto sweep_range = [this](uint32_t begin, uint32_t end) {
        for (uint32_t i = begin; i < end; ++i) {
            const uint32_t index = moved_[i];
            const Object& o = objects_[index];
            // A box left loose by an earlier turn shrinks to the pose first.
            sweeps_[index] = sweep_of(*o.shape, o.pose, o.end, o.loose ? nullptr : &o.box, &motion_boxes_[i].start,
                                      &motion_boxes_[i].end);
        }
    };
    workers_->run(static_cast<uint32_t>(moved_.size()), 256, sweep_range);
    for (std::size_t i = 0; i < moved_.size(); ++i) {
        const uint32_t index = moved_[i];
        broad_->move(index, motion_boxes_[i].start, motion_boxes_[i].end);
        objects_[index].box = motion_boxes_[i].end;  // what the broad phase holds after the step
        ++counters_.moving_objects;
        if (sweeps_[index].rotates) ++counters_.rotating_objects;
    }

    const std::vector<BroadPhasePair>& bp_pairs = broad_->step();
    const BroadPhaseCounters& bc = broad_->counters();
    counters_.broad_phase_pairs = bc.pairs;
    counters_.false_positives = bc.false_positives;
    counters_.swaps = bc.swaps + bc.teleport_swaps;
    counters_.heap_operations = bc.heap_pushes + bc.heap_pops + bc.heap_updates + bc.heap_removes;
    const auto t1 = std::chrono::steady_clock::now();
    counters_.broad_phase_seconds = std::chrono::duration<double>(t1 - t0).count();

    narrow_phase(bp_pairs);

    // Every object moves to its end pose; the pending moves clear.
    for (uint32_t index : moved_) {
        Object& o = objects_[index];
        o.pose = o.end;
        o.moving = false;
        swept_[index] = 0;
        o.loose = sweeps_[index].rotates;
        if (o.loose) loose_.push_back(index);
    }
    moved_.clear();
    counters_.narrow_phase_seconds = seconds_since(t1);
}

namespace {

// True when the plane with normal v (from A toward B) separates A and B over the whole step:
// A's support along v and B's along -v move linearly with the origins (the turns add at most
// their disks' extents along v), so separation at t = 0 and at t = 1 is separation throughout.
// `slack` keeps pairs a cast would call touching within its tolerance.
struct SweptSupport {
    double lo0, hi0;  // extent along v at t = 0 (turns included)
    double shift;     // v . translation
};

SweptSupport swept_support(const Shape& s, const Transform& start, Vec3 translation, bool rotates, Vec3 axis,
                           double disk, Vec3 v) {
    SweptSupport r;
    r.hi0 = dot(v, support(s, start, v));
    r.lo0 = dot(v, support(s, start, -v));
    if (rotates) {
        const Vec3 across = v - dot(v, axis) * axis;
        const double e = disk * length(across);
        r.hi0 += e;
        r.lo0 -= e;
    }
    r.shift = dot(v, translation);
    return r;
}

}  // namespace

void World::narrow_job(const NarrowJob& job, NarrowOutcome& out) const {
    out = NarrowOutcome{};
    const double tol = settings_.tolerance;
    const uint32_t max_it = settings_.max_iterations;
    const uint32_t ia = job.ia, ib = job.ib;
    const Object& oa = objects_[ia];
    const Object& ob = objects_[ib];
    Sweep still_a, still_b;
    auto sweep = [&](const Object& o, uint32_t index, Sweep& still) -> const Sweep& {
        if (swept_[index]) return sweeps_[index];
        still = Sweep{};
        still.start = rigid(o.pose);
        return still;
    };
    const Sweep& sa = sweep(oa, ia, still_a);
    const Sweep& sb = sweep(ob, ib, still_b);

    const Vec3 seed = job.seed;
    if (dot(seed, seed) > 0) {
        // A separating axis from an earlier step: if its plane separates the two over the
        // whole step, there is no contact and no cast is needed.
        const Vec3 v = seed;
        const SweptSupport a = swept_support(*oa.shape, sa.start, sa.translation, sa.rotates, sa.axis, sa.disk, v);
        const SweptSupport b = swept_support(*ob.shape, sb.start, sb.translation, sb.rotates, sb.axis, sb.disk, v);
        // The casts call shapes touching within tolerance times their size (the motion cast:
        // times the sum of their bounding radii, at most sqrt(3) times a box's reach from
        // the origin), so only a wider gap rules a contact out.
        auto reach = [](const Object& o, const Sweep& sw) {
            return std::sqrt(3.0) *
                   std::fmax(max_abs(o.box.min - sw.start.translation), max_abs(o.box.max - sw.start.translation));
        };
        const double size = max_extent(oa.box) + max_extent(ob.box) + max_abs(sa.translation) +
                            max_abs(sb.translation) + max_abs(sb.start.translation - sa.start.translation) +
                            (sa.rotates || sb.rotates ? reach(oa, sa) + reach(ob, sb) : 0.0);
        const double slack = 4 * tol * size + 16 * kEps * (std::fabs(a.hi0) + std::fabs(b.lo0) + size);
        // Comparisons written so that NaN never separates.
        if (a.hi0 + slack < b.lo0 && a.hi0 + a.shift + slack < b.lo0 + b.shift) {
            out.kind = NarrowOutcome::Rejected;
            out.keep_axis = true;
            out.axis = v;
            return;
        }
    }

    CastResult& r = out.cast;
    if (!sa.rotates && !sb.rotates) {
        r = kairos::shape_cast(*oa.shape, sa.start, sa.translation, *ob.shape, sb.start, sb.translation, tol, max_it);
    } else {
        // A turn: the motion cast (conservative advancement, docs/algorithms.md §4). It takes no
        // cached axis, so the cached one serves only the separating-plane test above.
        const Motion ma(oa.pose, swept_[ia] ? oa.end : oa.pose);
        const Motion mb(ob.pose, swept_[ib] ? ob.end : ob.pose);
        r = motion_cast(*oa.shape, ma, *ob.shape, mb, tol, max_it);
    }
    if (r.hit) {
        out.kind = NarrowOutcome::Hit;
        out.keep_axis = true;
        out.axis = r.normal;
        return;
    }
    // Missed: keep a separating axis of the end poses (the next step's start) for the next step,
    // found from the old axis or from the line between the origins.
    out.kind = NarrowOutcome::Missed;
    Vec3 axis = seed;
    if (!(dot(axis, axis) > 0))
        axis = (sb.start.translation + sb.translation) - (sa.start.translation + sa.translation);
    uint32_t it = 0;
    const Pose end_a = swept_[ia] ? oa.end : oa.pose;
    const Pose end_b = swept_[ib] ? ob.end : ob.pose;
    if (!gjk_intersect(*oa.shape, rigid(end_a), *ob.shape, rigid(end_b), axis, &it)) {
        out.keep_axis = true;
        out.axis = axis;
    }
    out.extra_iterations = it;
}

void World::narrow_phase(const std::vector<BroadPhasePair>& bp_pairs) {
    contacts_.clear();
    pairs_.clear();
    next_axes_.clear();
    jobs_.clear();
    // Sequential: the wanted pairs, their ids and their cached axes (a merge with axes_, both
    // sorted by key).
    std::size_t cursor = 0;
    for (const BroadPhasePair& p : bp_pairs) {
        if (!pair_wanted(p.a, p.b)) {
            ++counters_.filtered_pairs;
            continue;
        }
        uint32_t ia = p.a, ib = p.b;
        uint64_t id_a = make_id(ia, objects_[ia].generation), id_b = make_id(ib, objects_[ib].generation);
        if (id_b < id_a) {
            std::swap(ia, ib);
            std::swap(id_a, id_b);
        }
        pairs_.push_back({id_a, id_b, p.t_first});
        const uint64_t key = (uint64_t{p.a} << 32) | p.b;
        while (cursor < axes_.size() && axes_[cursor].key < key) ++cursor;
        Vec3 seed{};
        if (cursor < axes_.size() && axes_[cursor].key == key && axes_[cursor].id_a == id_a &&
            axes_[cursor].id_b == id_b)
            seed = axes_[cursor].axis;
        jobs_.push_back({ia, ib, id_a, id_b, key, seed});
    }
    // Any worker: the casts, each writing its own outcome.
    outcomes_.resize(jobs_.size());
    // The objects of a later job are loaded ahead: they are scattered over the world's arrays,
    // and at 1e5 objects the casts wait on memory (two threads then share its bandwidth).
    auto cast_range = [this](uint32_t begin, uint32_t end) {
        constexpr uint32_t kAhead = 4;
        for (uint32_t i = begin; i < end; ++i) {
            if (i + kAhead < end) {
                const NarrowJob& later = jobs_[i + kAhead];
                __builtin_prefetch(&objects_[later.ia]);
                __builtin_prefetch(&objects_[later.ib]);
                __builtin_prefetch(&sweeps_[later.ia]);
                __builtin_prefetch(&sweeps_[later.ib]);
            }
            narrow_job(jobs_[i], outcomes_[i]);
        }
    };
    workers_->run(static_cast<uint32_t>(jobs_.size()), 32, cast_range);
    // Sequential again, in pair order: contacts, axes for the next step, counters.
    for (std::size_t i = 0; i < jobs_.size(); ++i) {
        const NarrowJob& j = jobs_[i];
        const NarrowOutcome& o = outcomes_[i];
        if (o.kind == NarrowOutcome::Rejected) {
            ++counters_.axis_rejections;
        } else {
            ++counters_.narrow_phase_queries;
            counters_.gjk_iterations += o.cast.iterations + o.extra_iterations;
        }
        if (o.kind == NarrowOutcome::Hit) {
            const CastResult& r = o.cast;
            contacts_.push_back(
                {j.id_a, j.id_b, objects_[j.ia].user_data, objects_[j.ib].user_data, r.toi, r.point, r.normal});
        }
        if (o.keep_axis) next_axes_.push_back({j.key, j.id_a, j.id_b, o.axis});
    }
    axes_.swap(next_axes_);

    std::sort(contacts_.begin(), contacts_.end(), [](const Contact& x, const Contact& y) {
        if (x.toi != y.toi) return x.toi < y.toi;
        if (x.a != y.a) return x.a < y.a;
        return x.b < y.b;
    });
    std::sort(pairs_.begin(), pairs_.end(),
              [](const WorldPair& x, const WorldPair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    overlap_ids_.resize(2 * pairs_.size());
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
        overlap_ids_[2 * i] = pairs_[i].a;
        overlap_ids_[2 * i + 1] = pairs_[i].b;
    }
    counters_.contacts = contacts_.size();
}

}  // namespace kairos
