// Space binned into cubes, each keyed into 64 bits (20 bits per cube coordinate, 3 for a facing,
// the top bit free for the caller): the grids of the coverage forecast (coverage_forecast.cpp) and
// of the reach boundary (reach_boundary.cpp). A grid spans 2^20 cubes per axis before keys repeat.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "common/flat_key_map.h"
#include "common/vec.h"

namespace peensim {

// The cube (x, y, z) with a facing 0..5 (surface_kernel.h's facing_of), or -1 for none.
inline std::uint64_t cube_key(std::int64_t x, std::int64_t y, std::int64_t z, int facing = -1) {
    const auto axis = [](std::int64_t v) { return static_cast<std::uint64_t>(v) & 0xFFFFF; };
    return axis(x) | axis(y) << 20 | axis(z) << 40 | static_cast<std::uint64_t>(facing + 1) << 60;
}

// Coordinate k (0: x, 1: y, 2: z) of a cube_key's cube, for cubes within 2^19 of the origin (the
// key keeps 20 bits, two's complement).
inline std::int64_t cube_axis(std::uint64_t key, int k) {
    const auto v = static_cast<std::int64_t>(key >> (20 * k) & 0xFFFFF);
    return v >= 0x80000 ? v - 0x100000 : v;
}

// floor(x) as an integer, for finite x within the range of int64 (std::floor is a library call
// on the baseline x86-64 instruction set, and the forecast bins tens of millions of samples).
inline std::int64_t floor_to_int(double x) {
    const auto i = static_cast<std::int64_t>(x);  // towards zero
    return static_cast<double>(i) > x ? i - 1 : i;
}

// The cube of side 1 / inverse_side (corner at the origin) holding p (m).
inline std::array<std::int64_t, 3> cube_of(const Vec3& p, double inverse_side) {
    return {floor_to_int(p.x() * inverse_side), floor_to_int(p.y() * inverse_side), floor_to_int(p.z() * inverse_side)};
}

inline std::uint64_t cube_key_of(const Vec3& p, double inverse_side) {
    const auto c = cube_of(p, inverse_side);
    return cube_key(c[0], c[1], c[2]);
}

// A cube's run [first, end) of ids.
using CubeRuns = FlatKeyMap<std::pair<std::uint32_t, std::uint32_t>>;

// Ids sorted by their cube keys -> the map from a key to its run [first, end) in `ids`: every id
// of a cube in one look-up.
template <class Id>
void index_by_cube(std::vector<std::pair<std::uint64_t, Id>>& keyed, CubeRuns& grid, std::vector<Id>& ids) {
    std::sort(keyed.begin(), keyed.end());
    ids.resize(keyed.size());
    for (std::size_t i = 0; i < keyed.size(); ++i) {
        ids[i] = keyed[i].second;
        const auto [run, added] = grid.try_emplace(keyed[i].first, {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i)});
        run->second = static_cast<std::uint32_t>(i + 1);
    }
}

}  // namespace peensim
