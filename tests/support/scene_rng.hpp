// SPDX-License-Identifier: MIT
// The random source of the scene tests and benchmarks: splitmix64, a fixed, portable sequence
// for a given seed (the same scenes on every machine and standard library).
#pragma once

#include <cstdint>

#include "math/math.hpp"

namespace kairos::scene {

class Rng {
public:
    explicit Rng(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(next() >> 11) * 0x1p-53); }
    uint32_t below(uint32_t n) { return static_cast<uint32_t>(next() % n); }
    bool chance(double p) { return uniform(0, 1) < p; }
    Vec3 in_cube(double h) { return {uniform(-h, h), uniform(-h, h), uniform(-h, h)}; }
    // Uniform direction times a length (rejection from the cube).
    Vec3 on_sphere(double r) {
        for (;;) {
            const Vec3 v = in_cube(1);
            const double l = length(v);
            if (l > 0.1 && l <= 1) return (r / l) * v;
        }
    }
    // Unit direction, v / |v| (rounds differently from on_sphere(1); benchmarks rely on this one).
    Vec3 direction() {
        for (;;) {
            const Vec3 v{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
            const double l = length(v);
            if (l > 0.1 && l <= 1) return v / l;
        }
    }
    Quat orientation() {
        for (;;) {
            const Quat q{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
            const double n = norm(q);
            if (n > 0.1 && n <= 1) return normalized(q);
        }
    }

private:
    uint64_t state_;
};

}  // namespace kairos::scene
