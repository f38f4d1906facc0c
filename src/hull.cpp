// Convex hull construction and hull support (placeholder until the hull is written).
#include "shape.hpp"
namespace kairos {
Vec3 ConvexHullShape::support(Vec3 d) const {
    size_t best = 0;
    for (size_t i = 1; i < vertices.size(); ++i)
        if (dot(d, vertices[i]) > dot(d, vertices[best])) best = i;
    return vertices.empty() ? Vec3{} : vertices[best];
}
HullStatus make_convex_hull(const Vec3*, size_t, ConvexHullShape**) { return HullStatus::TooFewPoints; }
}  // namespace kairos
