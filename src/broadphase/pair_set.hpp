// SPDX-License-Identifier: MIT
// Pair keys (two ids in one uint64_t, the smaller first) and the set of them that the sweeps keep
// of the pairs overlapping now. Internal to broadphase/ (namespace broadphase_detail).
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace kairos::broadphase_detail {

inline uint64_t pair_key(uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    return (uint64_t{a} << 32) | b;
}

// Set of pair keys: open addressing with linear probing and backward-shift deletion, so it never
// holds tombstones and allocates only when it grows.
class PairSet {
public:
    static constexpr uint64_t kEmpty = ~uint64_t{0};  // never a key: ids are below 2^30

    std::size_t size() const { return size_; }

    // Empties the set, keeping its capacity.
    void clear() {
        std::fill(slots_.begin(), slots_.end(), kEmpty);
        size_ = 0;
    }

    bool contains(uint64_t key) const {
        if (slots_.empty()) return false;
        for (std::size_t i = home(key);; i = (i + 1) & mask_) {
            if (slots_[i] == key) return true;
            if (slots_[i] == kEmpty) return false;
        }
    }

    bool insert(uint64_t key) {
        if (2 * (size_ + 1) > slots_.size()) grow();
        std::size_t i = home(key);
        for (; slots_[i] != kEmpty; i = (i + 1) & mask_) {
            if (slots_[i] == key) return false;
        }
        slots_[i] = key;
        ++size_;
        return true;
    }

    bool erase(uint64_t key) {
        if (slots_.empty()) return false;
        std::size_t i = home(key);
        for (; slots_[i] != key; i = (i + 1) & mask_) {
            if (slots_[i] == kEmpty) return false;
        }
        // Shift back the following entries of the cluster whose home is not in (i, j].
        for (std::size_t j = (i + 1) & mask_; slots_[j] != kEmpty; j = (j + 1) & mask_) {
            const std::size_t k = home(slots_[j]);
            const bool stays = i <= j ? (i < k && k <= j) : (i < k || k <= j);
            if (stays) continue;
            slots_[i] = slots_[j];
            i = j;
        }
        slots_[i] = kEmpty;
        --size_;
        return true;
    }

    template <class F>
    void for_each(F&& f) const {
        for (uint64_t k : slots_) {
            if (k != kEmpty) f(k);
        }
    }

    // Erases every pair with an object for which removed(id) holds; `scratch` receives their keys
    // (a buffer kept by the caller, so that steady state does not allocate).
    template <class Removed>
    void erase_pairs_of(Removed&& removed, std::vector<uint64_t>& scratch) {
        scratch.clear();
        for_each([&](uint64_t k) {
            if (removed(static_cast<uint32_t>(k >> 32)) || removed(static_cast<uint32_t>(k))) scratch.push_back(k);
        });
        for (uint64_t k : scratch) erase(k);
    }

private:
    std::size_t home(uint64_t key) const {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);  // Fibonacci hashing
    }

    void grow() {
        std::vector<uint64_t> old;
        old.swap(slots_);
        const std::size_t cap = old.empty() ? 16 : 2 * old.size();
        slots_.assign(cap, kEmpty);
        mask_ = cap - 1;
        shift_ = 64 - static_cast<unsigned>(std::countr_zero(cap));
        size_ = 0;
        for (uint64_t k : old) {
            if (k != kEmpty) insert(k);
        }
    }

    std::vector<uint64_t> slots_;
    std::size_t size_ = 0;
    std::size_t mask_ = 0;
    unsigned shift_ = 63;
};

}  // namespace kairos::broadphase_detail
