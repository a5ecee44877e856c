// Space binned into cubes, each keyed into 64 bits (20 bits per cube coordinate, 3 for a facing,
// the top bit free for the caller): the grids of the coverage forecast (coverage_forecast.cpp) and
// of the reach boundary (reach_boundary.cpp). A grid spans 2^20 cubes per axis before keys repeat.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "common/vec.h"

namespace peensim {

// The cube (x, y, z) with a facing 0..5 (surface_kernel.h's facing_of), or -1 for none.
inline std::uint64_t cube_key(std::int64_t x, std::int64_t y, std::int64_t z, int facing = -1) {
    const auto axis = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0xFFFFF; };
    return axis(x) | axis(y) << 20 | axis(z) << 40 | static_cast<std::uint64_t>(facing + 1) << 60;
}

// The cube of side 1 / inverse_side (corner at the origin) holding p (m).
inline std::array<std::int64_t, 3> cube_of(const Vec3& p, double inverse_side) {
    return {static_cast<std::int64_t>(std::floor(p.x() * inverse_side)), static_cast<std::int64_t>(std::floor(p.y() * inverse_side)),
            static_cast<std::int64_t>(std::floor(p.z() * inverse_side))};
}

inline std::uint64_t cube_key_of(const Vec3& p, double inverse_side) {
    const auto c = cube_of(p, inverse_side);
    return cube_key(c[0], c[1], c[2]);
}

}  // namespace peensim
