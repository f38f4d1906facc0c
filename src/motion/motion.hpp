// SPDX-License-Identifier: MIT
// Motion over one step: the local origin moves linearly and the orientation turns at constant
// angular velocity about a fixed world axis along the shortest arc (docs/c-api.md, docs/algorithms.md §4).
#pragma once

#include <cmath>
#include <numbers>

#include "math/transform.hpp"

namespace kairos {

class Motion {
public:
    Motion(const Pose& start, const Pose& end) : start_(start), end_(end) {
        // The turn from start to end in world frame, q_rel = q_end * q_start^-1, taken along the
        // shortest arc: q and -q are the same rotation, and w >= 0 picks the angle in [0, pi].
        // Equal orientations (same_rotation) are no turn at all.
        if (same_rotation(start.orientation, end.orientation)) return;
        Quat rel = end.orientation * conjugate(start.orientation);
        if (rel.w < 0) rel = {-rel.x, -rel.y, -rel.z, -rel.w};
        const Vec3 v{rel.x, rel.y, rel.z};
        const double s = length(v);
        // atan2 keeps the angle accurate for tiny turns, where acos(w) would lose it.
        angle_ = 2 * std::atan2(s, rel.w);
        axis_ = s > 0 ? v / s : Vec3{0, 0, 1};
        if (!(angle_ > 0)) angle_ = 0;
    }

    const Pose& start() const { return start_; }
    const Pose& end() const { return end_; }
    Vec3 linear() const { return end_.position - start_.position; }
    // World rotation axis (unit) and total angle in [0, pi] over the step.
    Vec3 axis() const { return axis_; }
    double angle() const { return angle_; }
    bool rotates() const { return angle_ > 0; }

    // Transform at time t in [0, 1]. At t = 1 the end pose is returned exactly.
    Pose at(double t) const {
        if (t >= 1) return end_;
        Pose b;
        b.position = start_.position + t * linear();
        b.orientation = rotates() ? normalized(axis_angle(axis_, t * angle_) * start_.orientation) : start_.orientation;
        return b;
    }

    // Over [t0, t1] every point at distance <= rho from the rotation axis (through the local
    // origin) moves, relative to the origin, within a disk perpendicular to the axis of this
    // radius around where it was at t0: the chord 2 rho sin(|dangle| / 2).
    double disk_radius(double rho, double t0, double t1) const {
        const double half = 0.5 * angle_ * (t1 - t0);
        return 2 * rho * std::sin(std::fmin(std::fabs(half), 0.5 * std::numbers::pi));
    }

private:
    Pose start_, end_;
    Vec3 axis_{0, 0, 1};
    double angle_ = 0;
};

}  // namespace kairos
