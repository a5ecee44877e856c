#include "model/enclosure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>

namespace peensim {

namespace {
constexpr std::array<std::array<int, 3>, 6> kFaceNeighbours{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
}

Enclosure::Enclosure(const TriangleMesh& world_mesh, double cell_size_m, double shot_radius_m)
    : grid_(world_mesh, cell_size_m, 4.0 * shot_radius_m) {
    // A cell at level k is at least (k - 1) cells from any surface: passable for a shot centre
    // when that clearance is at least the shot radius.
    passable_level_ = std::max(2, static_cast<int>(std::ceil(shot_radius_m / cell_size_m)) + 1);
    const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
    outside_.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz), 0);
    std::deque<std::array<int, 3>> queue;
    auto seed = [&](int i, int j, int k) {
        if (passable(i, j, k) && !outside_[index(i, j, k)]) {
            outside_[index(i, j, k)] = 1;
            queue.push_back({i, j, k});
        }
    };
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) seed(i, j, k);
    while (!queue.empty()) {
        const auto [i, j, k] = queue.front();
        queue.pop_front();
        for (const auto& d : kFaceNeighbours) {
            const int a = i + d[0], b = j + d[1], c = k + d[2];
            if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
            seed(a, b, c);
        }
    }
    // Grow the outside by two cells into any free cell, so free space hugging the outer walls
    // (too tight to pass) is not taken for the inside.
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<std::size_t> grow;
        for (int k = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i) {
                    if (outside_[index(i, j, k)] || grid_.level(i, j, k) == 0) continue;
                    for (const auto& d : kFaceNeighbours) {
                        const int a = i + d[0], b = j + d[1], c = k + d[2];
                        if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
                        if (outside_[index(a, b, c)]) {
                            grow.push_back(index(i, j, k));
                            break;
                        }
                    }
                }
        for (std::size_t id : grow) outside_[id] = 1;
    }
}

bool Enclosure::inside(const Vec3& p) const {
    int i, j, k;
    if (!grid_.cell_of(p, i, j, k)) return false;
    return grid_.level(i, j, k) > 0 && !outside_[index(i, j, k)];
}

bool Enclosure::escape_point(const Vec3& p, const Vec3& lo, const Vec3& hi, Vec3& where) const {
    int i0, j0, k0;
    if (!grid_.cell_of(p, i0, j0, k0)) {
        where = p;
        return true;
    }
    if (!outside_[index(i0, j0, k0)]) return false;
    // Breadth-first through free cells from p until a cell outside [lo, hi].
    std::vector<unsigned char> seen(outside_.size(), 0);
    std::deque<std::array<int, 3>> queue{{i0, j0, k0}};
    seen[index(i0, j0, k0)] = 1;
    const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
    while (!queue.empty()) {
        const auto [i, j, k] = queue.front();
        queue.pop_front();
        const Vec3 c = grid_.cell_centre(i, j, k);
        if ((c.array() < lo.array()).any() || (c.array() > hi.array()).any()) {
            where = c;
            return true;
        }
        for (const auto& d : kFaceNeighbours) {
            const int a = i + d[0], b = j + d[1], cc = k + d[2];
            if (a < 0 || b < 0 || cc < 0 || a >= nx || b >= ny || cc >= nz) continue;
            const std::size_t id = index(a, b, cc);
            if (seen[id] || grid_.level(a, b, cc) == 0) continue;
            seen[id] = 1;
            queue.push_back({a, b, cc});
        }
    }
    where = p;
    return true;
}

}  // namespace peensim
