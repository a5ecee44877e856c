// Closest point on a triangle to a point (Ericson, Real-Time Collision Detection, 5.1.5),
// with the feature it lies on. The feature matters: a sphere touching a shared edge or
// vertex gets the same closest point from each neighbouring triangle, and the engine
// merges those into one contact.
#pragma once

#include "common/vec.h"

namespace peensim {

enum class TriangleFeature : unsigned char { face, edge_ab, edge_bc, edge_ca, vertex_a, vertex_b, vertex_c };

struct ClosestPoint {
    Vec3 point;
    TriangleFeature feature;
};

inline ClosestPoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return {a, TriangleFeature::vertex_a};
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return {b, TriangleFeature::vertex_b};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {a + (d1 / (d1 - d3)) * ab, TriangleFeature::edge_ab};
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return {c, TriangleFeature::vertex_c};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {a + (d2 / (d2 - d6)) * ac, TriangleFeature::edge_ca};
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return {b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b), TriangleFeature::edge_bc};
    const double denom = 1.0 / (va + vb + vc);
    return {a + ab * (vb * denom) + ac * (vc * denom), TriangleFeature::face};
}

}  // namespace peensim
