#include "model/enclosure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <utility>

namespace peensim {

namespace {
constexpr double kMaxCells = 8.0e6;
constexpr int kProbeReach = 2;  // cells: how far a point in a surface cell looks for a free one
constexpr std::array<std::array<int, 3>, 6> kFaceNeighbours{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
}  // namespace

Enclosure::Enclosure(const TriangleMesh& world_mesh, double cell_size_m, double shot_radius_m, Clearance clearance)
    : grid_(world_mesh, DistanceGate::cell_within(world_mesh, cell_size_m, 4.0 * shot_radius_m, kMaxCells), 4.0 * shot_radius_m),
      clearance_(std::move(clearance)) {
    // A cell at level k is at least (k - 1) cells from any surface: passable for a shot centre
    // when that clearance is at least the shot radius.
    passable_level_ = std::max(2, static_cast<int>(std::ceil(shot_radius_m / grid_.cell_size())) + 1);
    const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
    label_.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz), 0);
    std::deque<std::array<int, 3>> queue;
    auto seed = [&](int i, int j, int k) {
        if (passable(i, j, k) && label_[index(i, j, k)] != kOutside) {
            label_[index(i, j, k)] = kOutside;
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
                    if (label_[index(i, j, k)] == kOutside || grid_.level(i, j, k) == 0) continue;
                    for (const auto& d : kFaceNeighbours) {
                        const int a = i + d[0], b = j + d[1], c = k + d[2];
                        if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
                        if (label_[index(a, b, c)] == kOutside) {
                            grow.push_back(index(i, j, k));
                            break;
                        }
                    }
                }
        for (std::size_t id : grow) label_[id] = kOutside;
    }
}

bool Enclosure::segment_clear(const Vec3& a, const Vec3& b) const {
    // Sphere tracing: every point within the clearance of x is free, so x may move that far.
    const double tiny = 1e-6 * grid_.cell_size();
    Vec3 x = a;
    for (int step = 0; step < 64; ++step) {
        const double left = (b - x).norm();
        const double free = clearance_(x, left);
        if (free >= left) return true;
        if (free < tiny) return false;
        x += (b - x) * (free / left);
    }
    return false;
}

bool Enclosure::probe_cell(const Vec3& p, int& i, int& j, int& k) const {
    int i0, j0, k0;
    if (!grid_.cell_of(p, i0, j0, k0)) return false;
    if (grid_.level(i0, j0, k0) > 0) {
        i = i0, j = j0, k = k0;
        return true;
    }
    // Free cells around, nearest centre first.
    struct Candidate {
        double distance2;
        int i, j, k;
    };
    std::array<Candidate, (2 * kProbeReach + 1) * (2 * kProbeReach + 1) * (2 * kProbeReach + 1)> near{};
    std::size_t n = 0;
    for (int c = k0 - kProbeReach; c <= k0 + kProbeReach; ++c)
        for (int b = j0 - kProbeReach; b <= j0 + kProbeReach; ++b)
            for (int a = i0 - kProbeReach; a <= i0 + kProbeReach; ++a) {
                if (a < 0 || b < 0 || c < 0 || a >= grid_.nx() || b >= grid_.ny() || c >= grid_.nz() || grid_.level(a, b, c) == 0) continue;
                near[n++] = {(grid_.cell_centre(a, b, c) - p).squaredNorm(), a, b, c};
            }
    std::sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(n),
              [](const Candidate& x, const Candidate& y) { return x.distance2 < y.distance2; });
    for (std::size_t q = 0; q < n; ++q)
        if (segment_clear(p, grid_.cell_centre(near[q].i, near[q].j, near[q].k))) {
            i = near[q].i, j = near[q].j, k = near[q].k;
            return true;
        }
    return false;
}

int Enclosure::region(const Vec3& p) {
    int i0, j0, k0;
    if (!probe_cell(p, i0, j0, k0) || !inside_cell(i0, j0, k0)) return -1;
    unsigned char& here = label_[index(i0, j0, k0)];
    if (here == kUnnumbered) {
        // Breadth-first through the inside cells joined to this one, face to face.
        const unsigned char number = next_region_;
        if (next_region_ < kLastRegion) ++next_region_;
        const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
        here = number;
        std::deque<std::array<int, 3>> open{{i0, j0, k0}};
        while (!open.empty()) {
            const auto [a, b, c] = open.front();
            open.pop_front();
            for (const auto& d : kFaceNeighbours) {
                const int x = a + d[0], y = b + d[1], z = c + d[2];
                if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) continue;
                if (!inside_cell(x, y, z) || label_[index(x, y, z)] != kUnnumbered) continue;
                label_[index(x, y, z)] = number;
                open.push_back({x, y, z});
            }
        }
    }
    return here - kFirstRegion;
}

bool Enclosure::in_region(const Vec3& p, int number) const {
    int i, j, k;
    return number >= 0 && probe_cell(p, i, j, k) && inside_cell(i, j, k) && label_[index(i, j, k)] == number + kFirstRegion;
}

bool Enclosure::inside(const Vec3& p) const {
    int i, j, k;
    return probe_cell(p, i, j, k) && inside_cell(i, j, k);
}

bool Enclosure::escape_point(const Vec3& p, const Vec3& lo, const Vec3& hi, Vec3& where) const {
    int i0, j0, k0;
    if (!probe_cell(p, i0, j0, k0)) {
        where = p;
        return true;
    }
    if (label_[index(i0, j0, k0)] != kOutside) return false;
    // Breadth-first through free cells from p until a cell outside [lo, hi].
    std::vector<unsigned char> seen(label_.size(), 0);
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
