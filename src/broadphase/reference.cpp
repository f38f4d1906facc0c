// SPDX-License-Identifier: MIT
// The reference broad phases: brute force (the exact 4D test of every pair) and the encapsulating
// sweep (plain sweep and prune on the boxes swept over the whole step).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "broadphase/box_time.hpp"
#include "broadphase/factories.hpp"

namespace kairos {

namespace {

using broadphase_detail::union_box;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Objects present, as a sorted list of ids kept by each flush.
class ListedBroadPhase : public BroadPhase {
protected:
    explicit ListedBroadPhase(BroadPhaseKind kind) : BroadPhase(kind) {}
    void on_flush() override {
        std::size_t w = 0;
        for (uint32_t id : ids_) {
            if (records_[id].state != State::PendingRemove) ids_[w++] = id;
        }
        ids_.resize(w);
        ids_.insert(ids_.end(), pending_adds_.begin(), pending_adds_.end());
        std::sort(ids_.begin(), ids_.end());
    }
    void on_teleport(uint32_t, const Aabb&) override {}
    std::vector<uint32_t> ids_;
};

class BruteForceBroadPhase final : public ListedBroadPhase {
public:
    BruteForceBroadPhase() : ListedBroadPhase(BroadPhaseKind::BruteForce) {}

private:
    void on_step() override {
        for (std::size_t x = 0; x < ids_.size(); ++x) {
            const Record& ra = records_[ids_[x]];
            const SweptAabb sa{ra.box, ra.box_end};
            for (std::size_t y = x + 1; y < ids_.size(); ++y) {
                const Record& rb = records_[ids_[y]];
                if (ra.is_static && rb.is_static) continue;
                double t = 0;
                if (first_overlap_time(sa, SweptAabb{rb.box, rb.box_end}, &t)) pairs_.push_back({ids_[x], ids_[y], t});
            }
        }
    }
};

// The talks' simple solution: sweep and prune along x on the boxes swept over the whole step.
class EncapsulatingSap final : public ListedBroadPhase {
public:
    EncapsulatingSap() : ListedBroadPhase(BroadPhaseKind::EncapsulatingSap) {}

private:
    void on_step() override {
        swept_.resize(records_.size());
        for (uint32_t id : ids_) swept_[id] = union_box(records_[id].box, records_[id].box_end);
        order_ = ids_;
        std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
            return swept_[a].min.x != swept_[b].min.x ? swept_[a].min.x < swept_[b].min.x : a < b;
        });
        active_.clear();
        for (uint32_t id : order_) {
            const Aabb& box = swept_[id];
            std::size_t w = 0;
            for (uint32_t other : active_) {
                const Aabb& ob = swept_[other];
                if (ob.max.x < box.min.x) continue;  // closed off for good: the mins only grow
                active_[w++] = other;
                if (records_[id].is_static && records_[other].is_static) continue;
                if (!boxes_overlap(box, ob)) continue;
                double t = kInf;
                const SweptAabb sa{records_[id].box, records_[id].box_end};
                const SweptAabb sb{records_[other].box, records_[other].box_end};
                if (!first_overlap_time(sa, sb, &t)) t = kInf;
                pairs_.push_back({std::min(id, other), std::max(id, other), t});
            }
            active_.resize(w);
            active_.push_back(id);
        }
    }
    std::vector<Aabb> swept_;
    std::vector<uint32_t> order_, active_;
};

}  // namespace

namespace broadphase_detail {

std::unique_ptr<BroadPhase> make_encapsulating_sap() { return std::make_unique<EncapsulatingSap>(); }
std::unique_ptr<BroadPhase> make_brute_force() { return std::make_unique<BruteForceBroadPhase>(); }

}  // namespace broadphase_detail

}  // namespace kairos
