#include "analysis/sample_classes.h"

#include <algorithm>
#include <cmath>

#include "common/parallel_chunks.h"

namespace peensim {

namespace {

// The probe grid of one triangle: m subdivisions per edge, vertex (a, b) at A + (a/m) AB + (b/m) AC.
struct ProbeGrid {
    int m = 1;
    std::vector<std::int8_t> reach;  // per vertex: 1 reachable, 0 not
    std::size_t vertex(int a, int b) const {
        // Row a holds m - a + 1 vertices (b = 0 .. m - a).
        return static_cast<std::size_t>(a * (m + 1) - a * (a - 1) / 2 + b);
    }
    // The answer for the cell holding (u, v): 1 or 0 where its three vertices agree, -1 where not.
    int cell_answer(double u, double v) const {
        const double U = std::clamp(u * m, 0.0, static_cast<double>(m)), V = std::clamp(v * m, 0.0, static_cast<double>(m));
        int a = std::min(static_cast<int>(U), m - 1), b = std::min(static_cast<int>(V), m - 1 - a);
        if (b < 0) b = 0;
        const bool up = (U - a) + (V - b) <= 1.0 || a + b == m - 1;
        const int r0 = up ? reach[vertex(a, b)] : reach[vertex(a + 1, b + 1)];
        const int r1 = reach[vertex(a + 1, b)], r2 = reach[vertex(a, b + 1)];
        return r0 == r1 && r1 == r2 ? r0 : -1;
    }
};

bool all_one(const std::vector<double>& shares) {
    return std::all_of(shares.begin(), shares.end(), [](double f) { return f >= 1.0 - 1e-12; });
}

}  // namespace

std::uint16_t SampleClasses::class_for(bool reachable, const std::vector<std::uint32_t>& regions, bool excluded) {
    for (std::size_t k = 0; k < classes_.size(); ++k)
        if (classes_[k].reachable == reachable && classes_[k].regions == regions) return static_cast<std::uint16_t>(k);
    if (classes_.size() >= kMixed) throw std::runtime_error("coverage: more than 65534 combinations of regions and reach on one part");
    SampleClass c;
    c.reachable = reachable;
    c.excluded = excluded;
    c.regions = regions;
    classes_.push_back(std::move(c));
    return static_cast<std::uint16_t>(classes_.size() - 1);
}

SampleClasses::SampleClasses(const CoverageMap& map, const TriangleMesh& mesh, const RegionSet& regions, const ReachTest& reach,
                             double shot_radius_m, double probe_spacing_m) {
    const std::size_t triangles = map.triangle_count();
    triangle_class_.assign(triangles, 0);
    mixed_start_.assign(triangles, -1);
    first_sample_.assign(triangles, 0);
    reachable_samples_.assign(triangles, 0);
    peened_samples_.assign(triangles, 0);

    // Per triangle: the regions holding it and their shares (to see which triangles cross a boundary).
    std::vector<std::vector<std::uint32_t>> tri_regions(triangles);
    std::vector<std::vector<double>> tri_shares(triangles);
    for (std::size_t r = 0; r < regions.size(); ++r)
        for (const RegionShare& s : regions.shares(r)) {
            tri_regions[static_cast<std::size_t>(s.triangle)].push_back(static_cast<std::uint32_t>(r));
            tri_shares[static_cast<std::size_t>(s.triangle)].push_back(s.fraction);
        }
    const auto excluded_of = [&regions](const std::vector<std::uint32_t>& rs) {
        return std::any_of(rs.begin(), rs.end(), [&regions](std::uint32_t r) { return regions.excluded(r); });
    };

    // The reach tests, triangle by triangle on every core (they are most of the cost: a distance
    // query to every component each), into one result per triangle.
    struct TriangleReach {
        ProbeGrid grid;
        int reached = 0;                   // probe vertices a shot reaches
        std::vector<std::int8_t> samples;  // a triangle whose probes disagree: each sample's answer
        std::uint64_t tests = 0, sample_tests = 0;
    };
    std::vector<TriangleReach> reach_of(triangles);
    constexpr std::size_t kProbeChunks = 64;
    for_each_chunk(kProbeChunks, [&](std::size_t chunk) {
        const auto [begin, end] = chunk_range(triangles, kProbeChunks, chunk);
        for (std::size_t t = begin; t < end; ++t) {
            const std::int64_t samples = map.samples_of_triangle(t);
            if (samples == 0) continue;  // degenerate: no samples, no area
            TriangleReach& out = reach_of[t];
            ProbeGrid& grid = out.grid;
            const Vec3 a = mesh.corner(t, 0), ab = mesh.corner(t, 1) - a, ac = mesh.corner(t, 2) - a;
            const double longest = std::max({ab.norm(), ac.norm(), (ac - ab).norm()});
            // Probes: never finer than the samples themselves.
            const int n_samples = static_cast<int>(std::lround(std::sqrt(static_cast<double>(samples))));
            grid.m = std::clamp(static_cast<int>(std::ceil(longest / probe_spacing_m)), 1, std::max(1, n_samples));
            grid.reach.assign(static_cast<std::size_t>((grid.m + 1) * (grid.m + 2) / 2), 0);
            for (int i = 0; i <= grid.m; ++i)
                for (int j = 0; i + j <= grid.m; ++j) {
                    const Vec3 p = a + (static_cast<double>(i) / grid.m) * ab + (static_cast<double>(j) / grid.m) * ac;
                    const bool r = reach(p, t, shot_radius_m);
                    ++out.tests;
                    grid.reach[grid.vertex(i, j)] = r ? 1 : 0;
                    out.reached += r ? 1 : 0;
                }
            const int vertices = static_cast<int>(grid.reach.size());
            if (out.reached == 0 || out.reached == vertices) continue;
            // Probes that disagree: each sample of a cell whose vertices disagree is tested.
            out.samples.resize(static_cast<std::size_t>(samples));
            const std::int64_t first = map.first_sample_of_triangle(t);
            map.for_each_sample_of_triangle(t, [&](std::int64_t index, const Vec3& p, double u, double v) {
                int r = grid.cell_answer(u, v);
                if (r < 0) {
                    r = reach(p, t, shot_radius_m) ? 1 : 0;
                    ++out.tests;
                    ++out.sample_tests;
                }
                out.samples[static_cast<std::size_t>(index - first)] = static_cast<std::int8_t>(r);
            });
        }
    });

    std::vector<std::uint32_t> sample_regions;
    for (std::size_t t = 0; t < triangles; ++t) {
        first_sample_[t] = map.first_sample_of_triangle(t);
        const std::int64_t samples = map.samples_of_triangle(t);
        if (samples == 0) continue;  // degenerate: no samples, no area
        const TriangleReach& probed = reach_of[t];
        reach_tests_ += probed.tests;
        sample_tests_ += probed.sample_tests;
        const int vertices = static_cast<int>(probed.grid.reach.size());
        const int reached = probed.reached;
        const bool regions_uniform = all_one(tri_shares[t]);
        const bool reach_uniform = reached == 0 || reached == vertices;
        const double sample_area = map.sample_area(t);
        if (regions_uniform && reach_uniform) {
            const bool r = reached == vertices;
            const std::uint16_t k = class_for(r, tri_regions[t], excluded_of(tri_regions[t]));
            triangle_class_[t] = k;
            classes_[k].area_m2 += sample_area * static_cast<double>(samples);
            reachable_samples_[t] = r ? samples : 0;
            peened_samples_[t] = classes_[k].peened() ? samples : 0;
            continue;
        }
        // A triangle crossing a boundary of reach or of a region: sample by sample.
        triangle_class_[t] = kMixed;
        mixed_start_[t] = static_cast<std::int64_t>(sample_class_.size());
        sample_class_.resize(sample_class_.size() + static_cast<std::size_t>(samples));
        std::uint16_t last = kMixed;
        map.for_each_sample_of_triangle(t, [&](std::int64_t index, const Vec3& p, double, double) {
            const int r =
                reach_uniform ? (reached == vertices ? 1 : 0) : probed.samples[static_cast<std::size_t>(index - first_sample_[t])];
            const std::vector<std::uint32_t>* rs = &tri_regions[t];
            if (!regions_uniform) {
                regions.regions_at(p, t, sample_regions);
                std::sort(sample_regions.begin(), sample_regions.end());
                rs = &sample_regions;
            }
            // Consecutive samples mostly share a class: try the last one first.
            std::uint16_t k = last;
            if (k == kMixed || classes_[k].reachable != (r == 1) || classes_[k].regions != *rs)
                k = class_for(r == 1, *rs, excluded_of(*rs));
            last = k;
            sample_class_[static_cast<std::size_t>(mixed_start_[t] + (index - first_sample_[t]))] = k;
            classes_[k].area_m2 += sample_area;
            reachable_samples_[t] += r;
            peened_samples_[t] += classes_[k].peened() ? 1 : 0;
        });
        reach_of[t] = {};  // done with it: the memory back
    }

    region_peened_m2_.assign(regions.size(), 0.0);
    region_counted_m2_.assign(regions.size(), 0.0);
    region_unreachable_m2_.assign(regions.size(), 0.0);
    region_excluded_.assign(regions.size(), false);
    for (std::size_t r = 0; r < regions.size(); ++r) region_excluded_[r] = regions.excluded(r);
    region_classes_.assign(regions.size(), {});
    for (std::size_t k = 0; k < classes_.size(); ++k) {
        const SampleClass& c = classes_[k];
        if (c.reachable) reachable_area_m2_ += c.area_m2;
        if (c.peened()) peened_area_m2_ += c.area_m2;
        for (std::uint32_t r : c.regions) {
            region_classes_[r].push_back(static_cast<std::uint16_t>(k));
            if (c.peened()) region_peened_m2_[r] += c.area_m2;
            if (counts(static_cast<std::uint16_t>(k), r)) region_counted_m2_[r] += c.area_m2;
            // Out of reach where the region would count it: outside excluded regions, unless it is one.
            if (!c.reachable && (region_excluded_[r] || !c.excluded)) region_unreachable_m2_[r] += c.area_m2;
        }
    }
}

}  // namespace peensim
