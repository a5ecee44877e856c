#include "model/enclosure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <utility>

#include "common/parallel_chunks.h"

namespace peensim {

namespace {
constexpr double kMaxCells = 8.0e6;
constexpr double kFreeSlack = 1e-3;           // of R: how much clearer than a shot radius a touched cell's centre must be to be free
constexpr std::size_t kClearanceChunks = 64;  // of the touched cells, their centres' clearance found on every core
constexpr int kProbeReach = 2;                // cells: how far a point in a surface cell looks for a free one
constexpr std::array<std::array<int, 3>, 6> kFaceNeighbours{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
}  // namespace

Enclosure::Enclosure(const TriangleMesh& world_mesh, double cell_size_m, double shot_radius_m, Clearance clearance)
    : grid_(world_mesh, DistanceGate::cell_within(world_mesh, cell_size_m, 4.0 * shot_radius_m, kMaxCells), 4.0 * shot_radius_m),
      clearance_(std::move(clearance)),
      shot_radius_(shot_radius_m) {
    // A cell at level k is at least (k - 1) cells from any surface: passable for a shot centre
    // when that clearance is at least the shot radius.
    passable_level_ = std::max(2, static_cast<int>(std::ceil(shot_radius_m / grid_.cell_size())) + 1);
    const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
    label_.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz), 0);
    // A coarse grid: a touched cell's centre lies within half a diagonal of a surface, which may
    // leave room for a shot (see the header). Each touched centre's exact clearance, out to what
    // joined() can use (two centres a cell apart, each this clear, are joined without tracing).
    if (grid_.half_diagonal() > shot_radius_m) {
        free_clearance_ = std::nextafter(static_cast<float>(shot_radius_m * (1.0 + kFreeSlack)), 1.0f);
        const double within = shot_radius_m * (1.0 + kFreeSlack) + grid_.cell_size();
        centre_clearance_.assign(label_.size(), -1.0f);
        std::vector<std::size_t> touched;
        for (int k = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i)
                    if (grid_.level(i, j, k) == 0) touched.push_back(index(i, j, k));
        for_each_chunk(kClearanceChunks, [&](std::size_t chunk) {
            const auto [begin, end] = chunk_range(touched.size(), kClearanceChunks, chunk);
            for (std::size_t n = begin; n < end; ++n) {
                const std::size_t id = touched[n];
                const int i = static_cast<int>(id % static_cast<std::size_t>(nx));
                const int j = static_cast<int>((id / static_cast<std::size_t>(nx)) % static_cast<std::size_t>(ny));
                const int k = static_cast<int>(id / (static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)));
                // Rounded down to float, so that it stays a lower bound.
                centre_clearance_[id] = std::nextafter(static_cast<float>(clearance_(grid_.cell_centre(i, j, k), within)), 0.0f);
            }
        });
        for (const std::size_t id : touched) free_centres_ += centre_clearance_[id] >= free_clearance_;
    }
    std::deque<std::array<int, 3>> queue;
    // The outside enters passable cells; in a coarse grid also any free cell that a path clear
    // by a shot radius joins to where it is (the cells between the passable ones and a gap of
    // touched cells are not passable themselves).
    const bool coarse = !centre_clearance_.empty();
    auto seed = [&](int i, int j, int k, const std::array<int, 3>* from) {
        if (label_[index(i, j, k)] == kOutside) return;
        if (!passable(i, j, k) && !(coarse && from != nullptr && free_cell(i, j, k) && passes(*from, {i, j, k}))) return;
        label_[index(i, j, k)] = kOutside;
        queue.push_back({i, j, k});
    };
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) seed(i, j, k, nullptr);
    while (!queue.empty()) {
        const std::array<int, 3> here = queue.front();
        queue.pop_front();
        for (const auto& d : kFaceNeighbours) {
            const int a = here[0] + d[0], b = here[1] + d[1], c = here[2] + d[2];
            if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
            seed(a, b, c, &here);
        }
    }
    // Grow the outside by two cells into any free cell, so free space hugging the outer walls
    // (too tight to pass) is not taken for the inside.
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<std::size_t> grow;
        for (int k = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i) {
                    if (label_[index(i, j, k)] == kOutside || !free_cell(i, j, k)) continue;
                    for (const auto& d : kFaceNeighbours) {
                        const int a = i + d[0], b = j + d[1], c = k + d[2];
                        if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
                        if (label_[index(a, b, c)] == kOutside && joined({a, b, c}, {i, j, k})) {
                            grow.push_back(index(i, j, k));
                            break;
                        }
                    }
                }
        for (std::size_t id : grow) label_[id] = kOutside;
    }
}

double Enclosure::centre_clearance(int i, int j, int k) const {
    if (grid_.level(i, j, k) > 0) return grid_.half_diagonal();  // untouched: its centre is farther than that from every triangle
    return centre_clearance_.empty() ? 0.0 : std::max(0.0f, centre_clearance_[index(i, j, k)]);
}

bool Enclosure::joined(const std::array<int, 3>& a, const std::array<int, 3>& b) const {
    if (grid_.level(a[0], a[1], a[2]) > 0 && grid_.level(b[0], b[1], b[2]) > 0) return true;
    return passes(a, b);
}

bool Enclosure::passes(const std::array<int, 3>& a, const std::array<int, 3>& b) const {
    // Every point of the segment lies at least (c_a + c_b - cell) / 2 from the surfaces (the
    // distance changes by no more than the point moves); nearer, the path is traced.
    const double r = shot_radius_ * (1.0 + kFreeSlack);
    if (centre_clearance(a[0], a[1], a[2]) + centre_clearance(b[0], b[1], b[2]) - grid_.cell_size() >= 2.0 * r) return true;
    return segment_clear(grid_.cell_centre(a[0], a[1], a[2]), grid_.cell_centre(b[0], b[1], b[2]), r);
}

bool Enclosure::segment_clear(const Vec3& a, const Vec3& b, double r) const {
    // Sphere tracing: every point within the clearance of x (less r) is clear, so x may move that far.
    const double tiny = 1e-6 * grid_.cell_size();
    Vec3 x = a;
    for (int step = 0; step < 64; ++step) {
        const double left = (b - x).norm();
        const double free = clearance_(x, left + r) - r;
        if (free >= left) return true;
        if (free < tiny) return false;
        x += (b - x) * (free / left);
    }
    return false;
}

bool Enclosure::probe_cell(const Vec3& p, int& i, int& j, int& k) const {
    int i0, j0, k0;
    if (!grid_.cell_of(p, i0, j0, k0)) return false;
    // An untouched cell holds no surface: p is on its centre's side. A touched one is read only
    // through a clear path, as its neighbours are (its centre may lie across a wall from p).
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
                if (a < 0 || b < 0 || c < 0 || a >= grid_.nx() || b >= grid_.ny() || c >= grid_.nz() || !free_cell(a, b, c)) continue;
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
                if (!inside_cell(x, y, z) || label_[index(x, y, z)] != kUnnumbered || !joined({a, b, c}, {x, y, z})) continue;
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

bool Enclosure::reads(const Vec3& p) const {
    int i, j, k;
    return probe_cell(p, i, j, k);
}

bool Enclosure::escape_point(const Vec3& p, const Vec3& lo, const Vec3& hi, Vec3& where) const {
    int i0, j0, k0;
    if (!probe_cell(p, i0, j0, k0)) return false;  // not read: no path is known
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
            if (seen[id] || !free_cell(a, b, cc) || !joined({i, j, k}, {a, b, cc})) continue;
            seen[id] = 1;
            queue.push_back({a, b, cc});
        }
    }
    where = p;
    return true;
}

}  // namespace peensim
