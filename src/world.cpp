// The world's object table (see world.hpp).
#include "world.hpp"

#include <algorithm>
#include <limits>

namespace kairos {

World::~World() {
    for (Object& o : objects_)
        if (o.alive) o.shape->release();
}

uint64_t World::add(const Shape& shape, const BodyState& pose, uint64_t user_data) {
    // Room for this slot's later removal, taken now so that remove() never allocates.
    if (free_slots_.capacity() < objects_.size() + 1)
        free_slots_.reserve(std::max<size_t>(2 * free_slots_.capacity(), objects_.size() + 1));
    uint32_t index;
    if (!free_slots_.empty()) {
        index = free_slots_.back();
    } else {
        if (objects_.size() >= std::numeric_limits<uint32_t>::max()) return 0;
        objects_.emplace_back();  // may throw; nothing has changed yet
        index = static_cast<uint32_t>(objects_.size() - 1);
    }
    if (!free_slots_.empty()) free_slots_.pop_back();
    Object& o = objects_[index];
    shape.retain();
    o.shape = &shape;
    o.pose = pose;
    o.end = pose;
    o.moving = false;
    o.user_data = user_data;
    o.alive = true;
    ++live_;
    return make_id(index, o.generation);
}

World::Object* World::find(uint64_t id) {
    return const_cast<Object*>(static_cast<const World*>(this)->find(id));
}

const World::Object* World::find(uint64_t id) const {
    const uint64_t index = id & 0xffffffffu;
    const uint64_t generation = id >> 32;
    if (index >= objects_.size()) return nullptr;
    const Object& o = objects_[index];
    if (!o.alive || o.generation != generation) return nullptr;
    return &o;
}

void World::remove(uint64_t id) {
    Object* o = find(id);
    if (o == nullptr) return;
    o->shape->release();
    o->shape = nullptr;
    o->alive = false;
    --live_;
    const uint32_t index = static_cast<uint32_t>(id & 0xffffffffu);
    // A slot whose generation would wrap is retired, so no old id can ever match it again.
    if (o->generation == std::numeric_limits<uint32_t>::max()) return;
    ++o->generation;
    free_slots_.push_back(index);  // never allocates: add() reserved the room
}

}  // namespace kairos
