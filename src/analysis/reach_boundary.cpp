#include "analysis/reach_boundary.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <deque>
#include <vector>

#include "analysis/cube_keys.h"
#include "analysis/row_runs.h"
#include "common/flat_key_map.h"
#include "common/parallel_chunks.h"
#include "geometry/mesh_checks.h"

namespace peensim {

namespace {

using CubeSet = FlatKeyMap<std::uint8_t>;    // the keys of cubes (the values unused)
constexpr std::size_t kBoundaryChunks = 32;  // of triangles, binned on every core and joined in order

constexpr double kSameFacingCos = 0.5;  // a source within 60 degrees of a sample's normal bounds its dents

// A set of 64-bit keys as one bit per hashed key (a one-hash Bloom filter): may_hold is false for
// every key not in the set, and true for about one in kBitsPerKey of them.
class KeyBits {
public:
    static constexpr std::size_t kBitsPerKey = 16;
    // fill(mark) calls mark(key) for every key of the set (about `keys` of them).
    template <class Fill>
    KeyBits(std::size_t keys, Fill&& fill) {
        const std::size_t bits = std::bit_ceil(std::max<std::size_t>(64, kBitsPerKey * keys));
        words_.assign(bits / 64, 0);
        shift_ = 64 - std::countr_zero(bits);
        fill([&](std::uint64_t key) {
            const std::uint64_t b = bit(key);
            words_[b >> 6] |= std::uint64_t{1} << (b & 63);
        });
    }
    bool may_hold(std::uint64_t key) const {
        const std::uint64_t b = bit(key);
        return (words_[b >> 6] >> (b & 63) & 1) != 0;
    }

private:
    // Fibonacci hashing (as FlatKeyMap's): the product's top bits.
    std::uint64_t bit(std::uint64_t key) const { return (key * 0x9E3779B97F4A7C15ull) >> shift_; }
    std::vector<std::uint64_t> words_;
    int shift_ = 0;
};

}  // namespace

double disc_share_inside(double d_m, double rho_m) {
    if (!(rho_m > 0.0) || d_m >= rho_m) return 1.0;
    const double d = std::max(d_m, -rho_m) / rho_m;                    // in radii
    const double segment = std::acos(d) - d * std::sqrt(1.0 - d * d);  // / rho^2: the part beyond the line
    return 1.0 - segment / M_PI;
}

ReachBoundary::ReachBoundary(const CoverageProgress& progress, const TriangleMesh& mesh, double reach_m) : reach_m_(reach_m) {
    if (!(reach_m > 0.0)) return;
    const SampleClasses& classes = progress.classes();
    const CoverageMap& map = progress.map();
    const double inverse_reach = 1.0 / reach_m;
    const auto reachable_triangle = [&](std::size_t t) {
        const std::uint16_t k = classes.triangle_class(t);
        return k != SampleClasses::kMixed && classes.info(k).reachable;
    };
    // The cubes of side reach_m holding a sample of the triangles `of` picks that is (not)
    // `reachable`.
    const std::size_t triangles = map.triangle_count();
    const auto cubes_with = [&](bool reachable, const auto& of) {
        std::vector<CubeSet> parts(kBoundaryChunks);
        for_each_chunk(kBoundaryChunks, [&](std::size_t c) {
            const auto [begin, end] = chunk_range(triangles, kBoundaryChunks, c);
            CubeSet& cubes = parts[c];
            map.for_each_sample_row(
                begin, end, [&](std::size_t t, const Vec3& first, const Vec3& step, std::int64_t count, double, std::int64_t index) {
                    if (!of(t)) return;
                    const bool mixed = classes.triangle_class(t) == SampleClasses::kMixed;
                    for_each_cube_run(first, step, count, Vec3::Zero(), inverse_reach, [&](std::int64_t i, std::int64_t run) {
                        for (std::int64_t j = i; j < i + run; ++j)
                            if (!mixed || classes.info(classes.class_of(t, index + j)).reachable == reachable) {
                                cubes.try_emplace(cube_key_of(first + static_cast<double>(j) * step, inverse_reach), 1);
                                return;
                            }
                    });
                });
        });
        CubeSet cubes;
        for (const CubeSet& part : parts) part.for_each([&](std::uint64_t key, std::uint8_t) { cubes.try_emplace(key, 1); });
        return cubes;
    };
    // Cubes holding unreachable samples; the triangles with reachable samples whose bounding box
    // comes within reach of one.
    const CubeSet unreachable_cubes = cubes_with(false, [&](std::size_t t) { return !reachable_triangle(t); });
    if (unreachable_cubes.empty()) return;
    inverse_reach_ = inverse_reach;
    near_triangle_.assign(mesh.triangle_count(), false);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (classes.reachable_samples(t) == 0) continue;
        const Vec3 a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
        const Vec3 lo = a.cwiseMin(b).cwiseMin(c) - Vec3::Constant(reach_m), hi = a.cwiseMax(b).cwiseMax(c) + Vec3::Constant(reach_m);
        const auto from = cube_of(lo, inverse_reach), to = cube_of(hi, inverse_reach);
        bool found = false;
        for (std::int64_t z = from[2]; z <= to[2] && !found; ++z)
            for (std::int64_t y = from[1]; y <= to[1] && !found; ++y)
                for (std::int64_t x = from[0]; x <= to[0] && !found; ++x) found = unreachable_cubes.contains(cube_key(x, y, z));
        near_triangle_[t] = found;
    }
    // Cubes with reachable samples of those triangles.
    const CubeSet reachable_cubes = cubes_with(true, [&](std::size_t t) { return near_triangle_[t]; });
    // The cubes of side reach_m that are in `cubes` or next to one: only there can a sample lie
    // within reach_m of one in `cubes` (one look-up a run, not 27).
    const auto next_to = [](const CubeSet& cubes) {
        CubeSet near;
        cubes.for_each([&](std::uint64_t key, std::uint8_t) {
            const std::int64_t x = cube_axis(key, 0), y = cube_axis(key, 1), z = cube_axis(key, 2);
            for (std::int64_t dz = -1; dz <= 1; ++dz)
                for (std::int64_t dy = -1; dy <= 1; ++dy)
                    for (std::int64_t dx = -1; dx <= 1; ++dx) near.try_emplace(cube_key(x + dx, y + dy, z + dz), 1);
        });
        return near;
    };
    const CubeSet next_to_unreachable = next_to(unreachable_cubes);
    const CubeSet next_to_reachable = next_to(reachable_cubes);

    // The voxels, in the cubes next to the boundary: the reachable samples of the near triangles,
    // and the unreachable samples (the sources), each voxel of the run by its first sample.
    inverse_side_ = kReachVoxelsPerRadius * inverse_reach;
    // Chunk by chunk of triangles on every core, each with its own voxels, joined in chunk order
    // below: the voxels come out numbered as one pass over the triangles in turn would number them.
    struct Voxels {
        std::vector<Voxel> voxels;
        std::vector<std::uint64_t> keys;
        FlatKeyMap<std::uint32_t> index;
    };
    std::vector<Voxels> parts(kBoundaryChunks);
    for_each_chunk(kBoundaryChunks, [&](std::size_t c) {
        Voxels& part = parts[c];
        // The number in this chunk of the voxel of key k, added (p its first sample) if new.
        const auto voxel_at = [&](std::uint64_t k, const Vec3& p, bool reachable, const Vec3& n) -> std::uint32_t {
            const auto [index, added] = part.index.try_emplace(k, static_cast<std::uint32_t>(part.voxels.size()));
            if (added) {
                Voxel v;
                v.reachable = reachable;
                for (int a = 0; a < 3; ++a) v.normal[a] = static_cast<float>(n[a]);
                if (reachable) v.point = p;
                part.voxels.push_back(v);
                part.keys.push_back(k);
            }
            return *index;
        };
        const auto voxel_of = [&](const Vec3& p, bool reachable, const Vec3& n) -> Voxel& {
            return part.voxels[voxel_at(key(p, reachable), p, reachable, n)];
        };
        const auto [begin, end] = chunk_range(triangles, kBoundaryChunks, c);
        map.for_each_sample_row(
            begin, end, [&](std::size_t t, const Vec3& first, const Vec3& step, std::int64_t count, double, std::int64_t index) {
                const bool all_reachable = reachable_triangle(t);
                if (all_reachable && !near_triangle_[t]) return;
                const bool mixed = classes.triangle_class(t) == SampleClasses::kMixed;
                const Vec3 n = triangle_normal(mesh, t);
                for_each_cube_run(first, step, count, Vec3::Zero(), inverse_reach, [&](std::int64_t i, std::int64_t run) {
                    const Vec3 p = first + static_cast<double>(i) * step;
                    const std::uint64_t cube = cube_key_of(p, inverse_reach);
                    const bool reachable_here = near_triangle_[t] && next_to_unreachable.contains(cube);
                    const bool sources_here = !all_reachable && next_to_reachable.contains(cube);
                    if (!reachable_here && !sources_here) return;
                    if (mixed) {
                        // Sample by sample (a run of one voxel of the sources holds a sample or
                        // two: cutting the cube's run into them cost more than the samples); the
                        // voxels' map is asked only when the key changes (a reachable voxel met
                        // again is left as it is; a source's number is kept for its mean).
                        std::uint64_t reachable_key = FlatKeyMap<std::uint32_t>::kEmpty;
                        std::uint64_t source_key = FlatKeyMap<std::uint32_t>::kEmpty;
                        std::uint32_t source = 0;
                        for (std::int64_t j = i; j < i + run; ++j) {
                            const Vec3 x = first + static_cast<double>(j) * step;
                            if (classes.info(classes.class_of(t, index + j)).reachable) {
                                if (!reachable_here) continue;
                                const std::uint64_t here = key(x, true);
                                if (here != reachable_key) voxel_at(here, x, true, n), reachable_key = here;
                            } else if (sources_here) {
                                const std::uint64_t here = key(x, false);
                                if (here != source_key) source = voxel_at(here, x, false, n), source_key = here;
                                Voxel& v = part.voxels[source];
                                v.point += (x - v.point) / static_cast<double>(++v.count);
                            }
                        }
                        return;
                    }
                    // One class: the voxels nest in the cubes (the sources' in the reachable
                    // ones), each voxel's run at once.
                    for_each_cube_run(p, step, run, Vec3::Zero(), (all_reachable ? 1.0 : kSourceVoxelsPerVoxel) * inverse_side_,
                                      [&](std::int64_t k, std::int64_t part_run) {
                                          const Vec3 q = p + static_cast<double>(k) * step;
                                          if (all_reachable) {
                                              voxel_of(q, true, n);
                                              return;
                                          }
                                          Voxel& v = voxel_of(q, false, n);
                                          const Vec3 mean = q + 0.5 * static_cast<double>(part_run - 1) * step;
                                          v.count += static_cast<std::uint32_t>(part_run);
                                          v.point += (mean - v.point) * (static_cast<double>(part_run) / static_cast<double>(v.count));
                                      });
                });
            });
    });
    std::size_t listed = 0;  // voxels of all chunks, some listed twice: room without growing
    for (const Voxels& part : parts) listed += part.voxels.size();
    index_.reserve(listed);
    voxels_.reserve(listed);
    for (Voxels& part : parts) {
        for (std::size_t a = 0; a < part.voxels.size(); ++a) {
            const Voxel& v = part.voxels[a];
            const auto [index, added] = index_.try_emplace(part.keys[a], static_cast<std::uint32_t>(voxels_.size()));
            if (added) {
                voxels_.push_back(v);
                continue;
            }
            // A voxel met again in a later chunk: a reachable one keeps its first sample, a source
            // takes the mean of all its samples.
            Voxel& w = voxels_[*index];
            if (w.reachable) continue;
            const std::uint32_t total = w.count + v.count;
            w.point += (v.point - w.point) * (static_cast<double>(v.count) / static_cast<double>(total));
            w.count = total;
        }
        part = {};  // the memory back
    }

    // Vector propagation from the sources through the reachable voxels, while within reach.
    std::deque<std::uint32_t> queue;
    for (std::uint32_t i = 0; i < voxels_.size(); ++i) {
        Voxel& v = voxels_[i];
        if (v.reachable) continue;
        v.source = i, v.source_d2 = 0.0f;
        queue.push_back(i);
    }
    // A voxel whose first sample lies beyond reach may still hold samples within it: out to reach
    // plus the voxel's diagonal (each sample's own distance decides, in distance()).
    const double reach2 = std::pow(reach_m + std::sqrt(3.0) / inverse_side_, 2);
    // A voxel queued again for a better source is passed on once per source: passing it on twice
    // from the same one changes nothing (a neighbour's distance only ever falls).
    std::vector<std::uint32_t> passed_on(voxels_.size(), kNoSource);
    // Of a voxel's 26 neighbours most are not reachable voxels (the surface passes through a third
    // of them, some of those sources): one bit per hashed key of the reachable voxels, 16 bits a
    // voxel, answers most of those look-ups from 2 MB where the map's keys and values take 24 MB
    // (704 k voxels on the shipped gear; 19 M look-ups, 2 M of them found).
    const KeyBits reachable_keys(voxels_.size(), [&](const auto& mark) {
        index_.for_each([&](std::uint64_t k, std::uint32_t) {
            if ((k & kReachableKeyBit) != 0) mark(k);
        });
    });
    while (!queue.empty()) {
        const std::uint32_t from_index = queue.front();
        queue.pop_front();
        const Voxel& from = voxels_[from_index];
        if (passed_on[from_index] == from.source) continue;
        passed_on[from_index] = from.source;
        const Voxel& source = voxels_[from.source];
        const Vec3 source_point = source.point;
        const Vec3 source_normal(source.normal[0], source.normal[1], source.normal[2]);
        const std::uint32_t source_index = from.source;
        // The neighbours by the voxel's own coordinates (a source's point, its samples' mean, lies
        // in the reachable voxel grid's cube of those).
        const auto c = cube_of(from.point, inverse_side_);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const std::uint64_t neighbour = cube_key(c[0] + dx, c[1] + dy, c[2] + dz) | kReachableKeyBit;
                    if (!reachable_keys.may_hold(neighbour)) continue;
                    const std::uint32_t* it = index_.find(neighbour);
                    if (it == nullptr) continue;
                    Voxel& to = voxels_[*it];
                    if (Vec3(to.normal[0], to.normal[1], to.normal[2]).dot(source_normal) < kSameFacingCos) continue;
                    const auto d2 = static_cast<float>((to.point - source_point).squaredNorm());
                    if (!(d2 < to.source_d2) || !(d2 < reach2)) continue;
                    to.source = source_index, to.source_d2 = d2;
                    queue.push_back(*it);
                }
    }
    // The cubes holding a voxel with a source (a voxel's first sample lies in it, and the voxels
    // nest in the cubes).
    for (const Voxel& v : voxels_)
        if (v.reachable && v.source != kNoSource) source_cubes_.try_emplace(cube_key_of(v.point, inverse_reach), 1);
}

std::uint32_t ReachBoundary::source_near(const Vec3& x) const {
    const std::uint32_t* it = index_.find(key(x, true));
    return it == nullptr || voxels_[*it].source == kNoSource ? kNoSource : *it;
}

double ReachBoundary::distance(const Vec3& x, std::uint32_t voxel) const {
    if (voxel == kNoSource) return std::numeric_limits<double>::infinity();
    const Voxel& v = voxels_[voxel];
    const Vec3& s = voxels_[v.source].point;
    // To the boundary as a straight line through the source, across the direction from it to the
    // voxel's own point (the nearest point of a line lies square to it): not to the source itself,
    // which for a sample beside the voxel's point lies off to the side.
    const Vec3 across = v.point - s;
    const double length = across.norm();
    const double d = length > 0.0 ? std::max(0.0, (x - s).dot(across) / length) : (x - s).norm();
    return d < reach_m_ ? d : std::numeric_limits<double>::infinity();
}

}  // namespace peensim
