// When a ballistic centre first lies in an axis-aligned box: the exact time a flight enters an
// outlet (a shot sink), or leaves the chamber's bounds. Per axis the centre is a parabola, so the
// times it lies within [lo, hi] on that axis are at most two intervals bounded by the roots of
// x(t) = lo and x(t) = hi; the first time in all three is one of those roots (or the start).
#pragma once

#include <optional>

#include "common/vec.h"
#include "kernels/trajectory.h"

namespace peensim {

// The first time in [ta, tb] at which path's centre lies in [lo, hi] (m, same frame), or none.
// ta itself if it is inside at ta.
std::optional<double> first_time_inside_box(const Trajectory& path, const Vec3& lo, const Vec3& hi, double ta, double tb);

// The first time in [ta, tb] at which path's centre lies outside [lo, hi] (ta if it is outside
// at ta), or none.
std::optional<double> first_time_outside_box(const Trajectory& path, const Vec3& lo, const Vec3& hi, double ta, double tb);

}  // namespace peensim
