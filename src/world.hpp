// The world's object table: objects with shapes, poses and pending moves, addressed by
// generation-checked ids. The step (broad and narrow phase) builds on this table.
#pragma once

#include <cstdint>
#include <vector>

#include "math.hpp"
#include "shape.hpp"

namespace kairos {

// Position and orientation of a body (the orientation kept as a unit quaternion, since motions
// interpolate it).
struct BodyState {
    Vec3 position;
    Quat orientation;
};

struct Contact {
    uint64_t a = 0, b = 0;  // a < b
    uint64_t user_a = 0, user_b = 0;
    double toi = 1;
    Vec3 point, normal;
};

struct StepCounters {
    uint64_t broad_phase_pairs = 0, swaps = 0, heap_operations = 0, narrow_phase_queries = 0, gjk_iterations = 0;
    double broad_phase_seconds = 0, narrow_phase_seconds = 0;
};

class World {
public:
    struct Object {
        const Shape* shape = nullptr;  // holds one reference while alive
        BodyState pose;                // pose now (start of the next step)
        BodyState end;                 // pose at the end of the next step, when `moving`
        bool moving = false;
        uint64_t user_data = 0;
        uint32_t generation = 1;  // of the current or next occupant of the slot
        bool alive = false;
    };

    World() = default;
    World(const World&) = delete;
    World& operator=(const World&) = delete;
    ~World();

    // An id packs the slot index (low 32 bits) and its generation (high 32 bits, >= 1), so 0 is
    // never an id and a removed object's id never matches the slot's next occupant.
    static uint64_t make_id(uint32_t index, uint32_t generation) { return (uint64_t{generation} << 32) | index; }

    // Adds an object (retains the shape). Returns 0 when no slot can be had (2^32 - 1 objects).
    uint64_t add(const Shape& shape, const BodyState& pose, uint64_t user_data);
    // The live object with this id, or nullptr for 0, unknown and removed ids.
    Object* find(uint64_t id);
    const Object* find(uint64_t id) const;
    // Removes a live object (releases its shape); its id becomes stale.
    void remove(uint64_t id);

    size_t live_count() const { return live_; }
    const std::vector<Object>& objects() const { return objects_; }

    std::vector<Contact> contacts;        // of the last step
    std::vector<uint64_t> overlaps;       // broad-phase pairs of the last step, 2 ids each
    StepCounters counters;                // of the last step

private:
    std::vector<Object> objects_;
    std::vector<uint32_t> free_slots_;
    size_t live_ = 0;
};

}  // namespace kairos
