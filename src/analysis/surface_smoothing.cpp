#include "analysis/surface_smoothing.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include "analysis/coverage_map.h"
#include "analysis/row_runs.h"
#include "analysis/surface_kernel.h"
#include "common/parallel_chunks.h"

namespace peensim {

namespace {

constexpr std::int64_t kAxisBins = std::int64_t{1} << 20;  // bins per axis a key can name (20 bits each)
// Cubes of the surface per unit area / c^2, for sizing: a plane crosses |nx| + |ny| + |nz| <= sqrt(3)
// of them per c^2 (1.5 on average over directions).
constexpr double kPatchesPerCellArea = 1.5;
constexpr std::int64_t kMaxNeighbourCells = std::int64_t{1} << 22;  // cubes of the neighbour grid at most (16 MB)

// Fibonacci hashing: the high half of key x 2^64 / golden ratio (the table is masked to its size).
std::size_t slot_of(std::uint64_t key) { return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32); }

}  // namespace

SurfaceSmoothing::SurfaceSmoothing(const TriangleMesh& mesh, double radius_m) : mesh_(&mesh), radius_(radius_m) {
    if (!(radius_m > 0.0) || !std::isfinite(radius_m))
        throw std::invalid_argument("SurfaceSmoothing: the smoothing radius must be positive and finite");
    const std::size_t n_tri = mesh.triangle_count();
    triangle_normal_.resize(n_tri);
    triangle_facing_.resize(n_tri);
    double total_area = 0.0;  // m2
    for (std::size_t t = 0; t < n_tri; ++t) {
        const Vec3 cross = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
        const double norm = cross.norm();
        triangle_normal_[t] = norm > 0.0 ? Vec3(cross / norm) : Vec3::Zero();
        triangle_facing_[t] = static_cast<std::int8_t>(facing_of(triangle_normal_[t]));
        total_area += 0.5 * norm;
    }
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    if (!mesh.vertices.empty()) {
        lo = hi = mesh.vertices.front();
        for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    }
    // Bin side: R / 4, coarser when the surface would need too many patches or a key too many bins.
    cell_ = radius_ / kSmoothingCellsPerRadius;
    const double patches_wanted = kPatchesPerCellArea * total_area / (cell_ * cell_);
    if (patches_wanted > static_cast<double>(kMaxSmoothingPatches))
        cell_ *= std::sqrt(patches_wanted / static_cast<double>(kMaxSmoothingPatches));
    cell_ = std::max(cell_, (hi - lo).maxCoeff() / static_cast<double>(kAxisBins - 4));
    origin_ = lo - Vec3::Constant(cell_);
    inverse_cell_ = 1.0 / cell_;

    const std::size_t expected = static_cast<std::size_t>(std::min(patches_wanted, static_cast<double>(kMaxSmoothingPatches))) + 16;
    const std::size_t slots = std::bit_ceil(2 * expected);
    slots_.assign(slots, Slot{});

    // The area: each triangle cut into n^2 congruent sub-triangles of edge <= c / 2, each counted
    // at its centroid ("up" ones at (i + 1/3, j + 1/3) steps from corner A, "down" ones at
    // (i + 2/3, j + 2/3)), with area / n^2.
    const double spacing = cell_ / kSmoothingSamplesPerCell;
    std::vector<Vec3> moment;  // m3 per patch: summed area x position, while building
    std::vector<Vec3> normal_sum;
    for (std::size_t t = 0; t < n_tri; ++t) {
        const int facing = triangle_facing_[t];
        if (facing < 0) continue;
        const Vec3& a = mesh.corner(t, 0);
        const Vec3 ab = mesh.corner(t, 1) - a, ac = mesh.corner(t, 2) - a;
        const double longest = std::max({ab.norm(), ac.norm(), (ac - ab).norm()});
        const int n = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
        const Vec3 u = ab / n, v = ac / n;
        const double sub_area = 0.5 * ab.cross(ac).norm() / (static_cast<double>(n) * n);
        const Vec3& normal = triangle_normal_[t];
        std::uint64_t last_key = ~std::uint64_t{0};
        std::uint32_t patch = 0;
        for (int kind = 0; kind < 2; ++kind) {
            const double offset = kind == 0 ? 1.0 / 3.0 : 2.0 / 3.0;
            const int last = kind == 0 ? n - 1 : n - 2;
            for (int j = 0; j <= last; ++j)
                for (int i = 0; i <= last - j; ++i) {
                    const Vec3 p = a + (i + offset) * u + (j + offset) * v;
                    const std::uint64_t key = key_of(p, facing);
                    if (key != last_key) {
                        patch = insert(key);
                        last_key = key;
                        if (patch == area_.size()) {
                            area_.push_back(0.0);
                            moment.push_back(Vec3::Zero());
                            normal_sum.push_back(Vec3::Zero());
                        }
                    }
                    area_[patch] += sub_area;
                    moment[patch] += sub_area * p;
                    normal_sum[patch] += sub_area * normal;
                }
        }
    }
    const std::size_t count = area_.size();
    centroid_.resize(count);
    normal_.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
        centroid_[k] = moment[k] / area_[k];
        const double norm = normal_sum[k].norm();
        normal_[k] = norm > 0.0 ? Vec3(normal_sum[k] / norm) : Vec3::Zero();
    }
    impacts_.assign(count, ImpactSums{});
    covered_.assign(count, 0.0);
    sampled_.assign(count, 0.0);
    build_neighbour_grid();
}

// Called for every area and coverage sample (tens of millions on a part): a multiplication and a
// truncation per axis (bins are counted from origin_, below every vertex, so the values are >= 0
// on the surface; a point off it is clamped to the grid).
std::uint64_t SurfaceSmoothing::key_of(const Vec3& p, int facing) const {
    std::uint64_t key = static_cast<std::uint64_t>(facing) << 60;
    constexpr double top = static_cast<double>(kAxisBins - 1);
    for (int k = 0; k < 3; ++k) {
        const double f = (p[k] - origin_[k]) * inverse_cell_;
        const auto i = static_cast<std::uint64_t>(f > 0.0 ? (f < top ? f : top) : 0.0);
        key |= i << (20 * k);
    }
    return key;
}

std::int64_t SurfaceSmoothing::find(std::uint64_t key) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t s = slot_of(key) & mask;; s = (s + 1) & mask) {
        if (slots_[s].key_plus_one == 0) return -1;
        if (slots_[s].key_plus_one == key + 1) return slots_[s].patch;
    }
}

// The patch of `key`, a new one (index = the patch count) if it has none yet.
std::uint32_t SurfaceSmoothing::insert(std::uint64_t key) {
    if (2 * (area_.size() + 1) > slots_.size()) {  // keep the table at most half full
        std::vector<Slot> old(2 * slots_.size());
        std::swap(old, slots_);
        const std::size_t mask = slots_.size() - 1;
        for (const Slot& slot : old) {
            if (slot.key_plus_one == 0) continue;
            std::size_t t = slot_of(slot.key_plus_one - 1) & mask;
            while (slots_[t].key_plus_one != 0) t = (t + 1) & mask;
            slots_[t] = slot;
        }
    }
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t s = slot_of(key) & mask;; s = (s + 1) & mask) {
        if (slots_[s].key_plus_one == key + 1) return slots_[s].patch;
        if (slots_[s].key_plus_one == 0) {
            slots_[s] = {key + 1, static_cast<std::uint32_t>(area_.size())};
            return slots_[s].patch;
        }
    }
}

void SurfaceSmoothing::build_neighbour_grid() {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    if (!centroid_.empty()) {
        lo = hi = centroid_.front();
        for (const Vec3& c : centroid_) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
    }
    grid_min_ = lo;
    // An impact's centroid lies in its patch's bin (or, placed by the fallback, in a neighbouring
    // one): within 3 c of the patch's area centroid. Cubes of R + 3 c hold every patch within
    // reach of a point in the 27 cubes around it.
    grid_cell_ = radius_ + 3.0 * cell_;
    for (;;) {
        std::int64_t total = 1;
        for (int k = 0; k < 3; ++k) {
            grid_dims_[k] = static_cast<std::int64_t>(std::floor((hi[k] - lo[k]) / grid_cell_)) + 1;
            total *= grid_dims_[k];
        }
        if (total <= kMaxNeighbourCells) break;
        grid_cell_ *= 1.25;
    }
    const auto cube_of = [&](const Vec3& p) {
        std::int64_t index = 0;
        for (int k = 2; k >= 0; --k) {
            const auto i =
                std::clamp(static_cast<std::int64_t>(std::floor((p[k] - grid_min_[k]) / grid_cell_)), std::int64_t{0}, grid_dims_[k] - 1);
            index = index * grid_dims_[k] + i;
        }
        return static_cast<std::size_t>(index);
    };
    grid_start_.assign(static_cast<std::size_t>(grid_dims_[0] * grid_dims_[1] * grid_dims_[2]) + 1, 0);
    for (const Vec3& c : centroid_) ++grid_start_[cube_of(c) + 1];
    for (std::size_t g = 1; g < grid_start_.size(); ++g) grid_start_[g] += grid_start_[g - 1];
    grid_patch_.assign(centroid_.size(), 0);
    std::vector<std::uint32_t> fill(grid_start_.begin(), grid_start_.end() - 1);
    for (std::size_t k = 0; k < centroid_.size(); ++k) grid_patch_[fill[cube_of(centroid_[k])]++] = static_cast<std::uint32_t>(k);
}

template <typename Visit>
void SurfaceSmoothing::for_each_patch_near(const Vec3& p, Visit&& visit) const {
    std::int64_t lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
        const double f = std::floor((p[k] - grid_min_[k]) / grid_cell_);
        const auto i = static_cast<std::int64_t>(std::clamp(f, -2.0, static_cast<double>(grid_dims_[k] + 1)));
        lo[k] = std::max<std::int64_t>(i - 1, 0);
        hi[k] = std::min(i + 1, grid_dims_[k] - 1);
    }
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
            for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
                const auto g = static_cast<std::size_t>((z * grid_dims_[1] + y) * grid_dims_[0] + x);
                for (std::uint32_t k = grid_start_[g]; k < grid_start_[g + 1]; ++k) visit(grid_patch_[k]);
            }
}

std::int64_t SurfaceSmoothing::patch_for(const Vec3& p, const Vec3& unit_normal, int facing) const {
    const std::int64_t direct = find(key_of(p, facing));
    if (direct >= 0) return direct;
    // The surface only grazes this bin: the nearest patch around that faces the same way.
    std::int64_t best = -1;
    double best_d2 = 4.0 * cell_ * cell_;  // m2: no farther than 2 c
    for_each_patch_near(p, [&](std::uint32_t q) {
        const double d2 = (centroid_[q] - p).squaredNorm();
        if (d2 < best_d2 && normal_[q].dot(unit_normal) > 0.0) best_d2 = d2, best = q;
    });
    return best;
}

void SurfaceSmoothing::add_impact(const Vec3& point_m, std::size_t triangle, double vn_m_per_s, double energy_J) {
    const int facing = triangle < triangle_facing_.size() ? triangle_facing_[triangle] : -1;
    const std::int64_t patch = facing < 0 ? -1 : patch_for(point_m, triangle_normal_[triangle], facing);
    if (patch < 0) {
        ++unplaced_;
        return;
    }
    const auto k = static_cast<std::size_t>(patch);
    ImpactSums& sums = impacts_[k];
    sums.count += 1.0;
    sums.point_sum += point_m;
    sums.energy_J += energy_J;
    sums.vn_sum += vn_m_per_s;
}

// Row by row: the samples of a row lie on a line, so the runs of them that fall in one bin are
// found in closed form (where the line crosses the next bin boundary on each axis) and counted at
// once, their covered ones by a popcount. A sample on a boundary may be counted in the bin beside
// it: its position is off by rounding only.
void SurfaceSmoothing::add_coverage(const CoverageMap& coverage) {
    if (coverage.triangle_count() != triangle_facing_.size())
        throw std::invalid_argument("SurfaceSmoothing::add_coverage: the coverage map is of another mesh");
    coverage.for_each_sample_row(
        [&](std::size_t t, const Vec3& first, const Vec3& step, std::int64_t count, double area_m2, std::int64_t index) {
            const int facing = triangle_facing_[t];
            if (facing < 0) return;
            for_each_cube_run(first, step, count, origin_, inverse_cell_, [&](std::int64_t i, std::int64_t run) {
                const Vec3 p = first + static_cast<double>(i) * step;
                const std::int64_t patch = patch_for(p, triangle_normal_[t], facing);
                if (patch < 0) return;
                const auto k = static_cast<std::size_t>(patch);
                sampled_[k] += static_cast<double>(run) * area_m2;
                covered_[k] += static_cast<double>(coverage.covered_samples(index + i, run)) * area_m2;
            });
        });
}

namespace {

// One patch's share of the kernel sums at x (unit normal n): its area and coverage samples at
// their centroid, its impacts at theirs. at() and at_triangles() both add up through this, so
// their sums agree to the bit.
inline void add_patch(SmoothedSums& s, const Vec3& x, const Vec3& n, double r2, double inv_r2, const Vec3& centroid, const Vec3& normal,
                      double area_m2, double covered_m2, double sampled_m2, double count, const Vec3& point_sum, double energy_J,
                      double vn_sum) {
    const double facing = n.dot(normal);
    if (facing <= 0.0) return;
    const double d2 = (centroid - x).squaredNorm();
    if (d2 < r2) {
        const double w = quartic(d2, inv_r2) * facing;
        s.area_m2 += w * area_m2;
        s.covered_m2 += w * covered_m2;
        s.sampled_m2 += w * sampled_m2;
    }
    if (count > 0.0) {
        const double dq2 = (point_sum / count - x).squaredNorm();
        if (dq2 >= r2) return;
        const double w = quartic(dq2, inv_r2) * facing;
        s.impacts += w * count;
        s.impacts_sq += w * w * count;
        s.energy_J += w * energy_J;
        s.vn_sum_m_per_s += w * vn_sum;
    }
}

}  // namespace

SmoothedSums SurfaceSmoothing::at(const Vec3& x, const Vec3& n) const {
    SmoothedSums s;
    if (centroid_.empty() || !(n.squaredNorm() > 0.0)) return s;
    const double r2 = radius_ * radius_, inv_r2 = 1.0 / r2;
    for_each_patch_near(x, [&](std::uint32_t p) {
        const ImpactSums& hits = impacts_[p];
        add_patch(s, x, n, r2, inv_r2, centroid_[p], normal_[p], area_[p], covered_[p], sampled_[p], hits.count, hits.point_sum,
                  hits.energy_J, hits.vn_sum);
    });
    return s;
}

namespace {

// A neighbour cube's triangles share the patches for_each_patch_near visits; at_triangles copies
// those that can reach the cube (in the order it visits them) into arrays once for all of them.
struct NearPatches {
    std::vector<Vec3> centroid, normal, point_sum;  // m, unit, m (the impacts' summed points)
    std::vector<double> area, covered, sampled;     // m2
    std::vector<double> count, energy, vn;          // -, J, m/s: the impacts' sums
    void clear() {
        for (auto* v : {&centroid, &normal, &point_sum}) v->clear();
        for (auto* v : {&area, &covered, &sampled, &count, &energy, &vn}) v->clear();
    }
};

// m2, the squared distance from p to the box [lo, hi].
double squared_distance_to_box(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double d = std::max({lo[k] - p[k], p[k] - hi[k], 0.0});
        d2 += d * d;
    }
    return d2;
}

// Below this many triangles in a neighbour cube, copying its patches costs more than it saves.
constexpr std::size_t kGatherFrom = 4;

}  // namespace

std::vector<SmoothedSums> SurfaceSmoothing::at_triangles() const {
    // Each triangle's own sums, at() at its centroid: on every core, the same on any number. A fine
    // mesh has many triangles in each cube of the neighbour grid, and at() would walk the same 27
    // cubes of patches (a tenth of them within reach) for each: the triangles are taken cube by
    // cube instead, the patches that can reach the cube copied once into arrays in at()'s order,
    // and each triangle's sums added up over those in that order (the same bytes as at()).
    const std::size_t n = triangle_normal_.size();
    std::vector<SmoothedSums> sums(n);
    std::vector<Vec3> centroid(n);
    for (std::size_t t = 0; t < n; ++t) centroid[t] = (mesh_->corner(t, 0) + mesh_->corner(t, 1) + mesh_->corner(t, 2)) / 3.0;
    // (cube, triangle), the cube of a centroid inside the grid or just around it (as
    // for_each_patch_near finds it; a centroid farther out is evaluated by at() on its own).
    constexpr std::uint64_t kOutside = ~std::uint64_t{0};
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order(n);
    for (std::size_t t = 0; t < n; ++t) {
        std::uint64_t key = 0;
        for (int k = 2; k >= 0 && key != kOutside; --k) {
            const double f = std::floor((centroid[t][k] - grid_min_[k]) / grid_cell_);
            key = f > -2.0 && f < static_cast<double>(grid_dims_[k] + 1)
                      ? key * static_cast<std::uint64_t>(grid_dims_[k] + 3) + static_cast<std::uint64_t>(f + 2.0)
                      : kOutside;
        }
        order[t] = {centroid_.empty() ? kOutside : key, static_cast<std::uint32_t>(t)};
    }
    std::sort(order.begin(), order.end());
    const double r2 = radius_ * radius_, inv_r2 = 1.0 / r2;
    // Patches no point of the cube can reach are left out: beyond R of it, with a margin far
    // above any rounding of the distances at() computes.
    const double reach2 = r2 * (1.0 + 1e-6);
    constexpr std::size_t kChunks = 64;
    for_each_chunk(kChunks, [&](std::size_t c) {
        const auto [begin, end] = chunk_range(n, kChunks, c);
        NearPatches near;
        for (std::size_t run = begin; run < end;) {
            std::size_t run_end = run + 1;
            while (run_end < end && order[run_end].first == order[run].first) ++run_end;
            const std::uint64_t key = order[run].first;
            if (key == kOutside || run_end - run < kGatherFrom) {
                for (std::size_t k = run; k < run_end; ++k) {
                    const std::uint32_t t = order[k].second;
                    sums[t] = at(centroid[t], triangle_normal_[t]);
                }
                run = run_end;
                continue;
            }
            // The cube's box, from any of its centroids.
            const Vec3& p = centroid[order[run].second];
            Vec3 box_lo, box_hi;
            for (int k = 0; k < 3; ++k) {
                const double i = std::floor((p[k] - grid_min_[k]) / grid_cell_);
                box_lo[k] = grid_min_[k] + i * grid_cell_;
                box_hi[k] = grid_min_[k] + (i + 1.0) * grid_cell_;
            }
            near.clear();
            for_each_patch_near(p, [&](std::uint32_t q) {
                const ImpactSums& hits = impacts_[q];
                const Vec3 hit_centroid = hits.count > 0.0 ? Vec3(hits.point_sum / hits.count) : Vec3::Zero();
                const bool area_reaches = squared_distance_to_box(centroid_[q], box_lo, box_hi) < reach2;
                const bool hits_reach = hits.count > 0.0 && squared_distance_to_box(hit_centroid, box_lo, box_hi) < reach2;
                if (!area_reaches && !hits_reach) return;
                near.centroid.push_back(centroid_[q]);
                near.normal.push_back(normal_[q]);
                near.point_sum.push_back(hits.point_sum);
                near.area.push_back(area_[q]);
                near.covered.push_back(covered_[q]);
                near.sampled.push_back(sampled_[q]);
                near.count.push_back(hits.count);
                near.energy.push_back(hits.energy_J);
                near.vn.push_back(hits.vn_sum);
            });
            const std::size_t m = near.area.size();
            for (std::size_t k = run; k < run_end; ++k) {
                const std::uint32_t t = order[k].second;
                const Vec3& x = centroid[t];
                const Vec3& normal = triangle_normal_[t];
                if (!(normal.squaredNorm() > 0.0)) continue;  // a degenerate triangle: zero sums, as at()
                SmoothedSums s;                               // local: kept in registers, not reloaded past every store
                for (std::size_t j = 0; j < m; ++j)
                    add_patch(s, x, normal, r2, inv_r2, near.centroid[j], near.normal[j], near.area[j], near.covered[j], near.sampled[j],
                              near.count[j], near.point_sum[j], near.energy[j], near.vn[j]);
                sums[t] = s;
            }
            run = run_end;
        }
    });
    return sums;
}

std::size_t SurfaceSmoothing::memory_bytes() const {
    return (centroid_.capacity() + normal_.capacity() + triangle_normal_.capacity()) * sizeof(Vec3) +
           impacts_.capacity() * sizeof(ImpactSums) + (area_.capacity() + covered_.capacity() + sampled_.capacity()) * sizeof(double) +
           slots_.capacity() * sizeof(Slot) + (grid_start_.capacity() + grid_patch_.capacity()) * sizeof(std::uint32_t) +
           triangle_facing_.capacity();
}

}  // namespace peensim
