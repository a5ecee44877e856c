// Every coverage sample of a component sorted into a class: whether a shot can touch it (reach)
// and which regions hold it. Coverage, its forecast and "run until coverage" count the peened
// area: the samples a shot can reach outside every excluded region. Reach is decided per sample,
// not per triangle, so a triangle can be partly reachable: on the shipped gear a 2 mm shot touches
// the end face next to the axle only beyond 5.95 mm from the axis (axle radius 4.95 mm plus the shot
// radius), and the triangles there span 5 to 8.1 mm; counted whole, they held coverage at 98.4 %
// for ever.
//
// Reach is probed at the vertices of a grid of sub-triangles at most probe_spacing_m on a side on
// each triangle: a sub-triangle whose three vertices agree gives all its samples that answer, one
// whose vertices disagree has each of its samples tested. The boundary is so placed at the
// samples' resolution while the test runs about once per probe cell; an island of the other answer
// lying entirely between the vertices of one cell (smaller than a cell) is missed.
//
// Regions: a triangle lying wholly in its regions (its shares all 1, regions.h) gives its samples
// its regions; the samples of a triangle crossing a region boundary are placed one by one.
// Pure computation: no file I/O.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "analysis/coverage_map.h"
#include "analysis/regions.h"
#include "common/byte_stream.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

// Whether a shot of radius shot_radius_m (m) can touch the point point_m (component frame, m) of
// triangle `triangle` (model/facet_reach.h gives the assembly's). Called from several threads at
// once (the triangles are probed on every core): it must be safe so.
using ReachTest = std::function<bool(const Vec3& point_m, std::size_t triangle, double shot_radius_m)>;

struct SampleClass {
    bool reachable = false;
    bool excluded = false;               // in at least one excluded region
    std::vector<std::uint32_t> regions;  // the regions holding its samples, increasing
    double area_m2 = 0.0;                // m2, of its samples
    bool peened() const { return reachable && !excluded; }
};

class SampleClasses {
public:
    static constexpr std::uint16_t kMixed = 0xFFFF;  // a triangle whose samples are of several classes

    // map: the component's coverage map; regions: of the same mesh; reach: the test;
    // shot_radius_m (m): the shot's (a mix's smallest); probe_spacing_m (m): see above.
    SampleClasses(const CoverageMap& map, const TriangleMesh& mesh, const RegionSet& regions, const ReachTest& reach, double shot_radius_m,
                  double probe_spacing_m);
    SampleClasses() = default;

    // Every figure as bytes and back (sample_classes_bytes.cpp): a sweep's runs of one assembly and
    // shot share the classes (app/analysis/coverage_geometry_cache.h). read_bytes throws
    // std::runtime_error (the reader's) on bytes that are not a whole set of `triangles` triangles
    // and `regions` regions.
    void write_bytes(ByteWriter& out) const;
    static SampleClasses read_bytes(ByteReader& in, std::size_t triangles, std::size_t regions);

    std::size_t size() const { return classes_.size(); }
    const SampleClass& info(std::uint16_t k) const { return classes_[k]; }
    // The class of sample `index` (numbering of CoverageMap::for_each_sample_row) of triangle t.
    std::uint16_t class_of(std::size_t t, std::int64_t index) const {
        const std::uint16_t k = triangle_class_[t];
        return k != kMixed ? k : sample_class_[static_cast<std::size_t>(mixed_start_[t] + (index - first_sample_[t]))];
    }
    // The class of all samples of triangle t, or kMixed.
    std::uint16_t triangle_class(std::size_t t) const { return triangle_class_[t]; }

    double peened_area_m2() const { return peened_area_m2_; }                           // m2
    double reachable_area_m2() const { return reachable_area_m2_; }                     // m2
    double region_peened_area_m2(std::size_t r) const { return region_peened_m2_[r]; }  // m2
    // m2, out of reach in region r: outside excluded regions (all of it for an excluded region)
    double region_unreachable_area_m2(std::size_t r) const { return region_unreachable_m2_[r]; }
    // The area coverage counts in region r (m2): its peened area, or for an excluded region (for
    // information) its reachable area; counts(k, r): whether class k's samples count there.
    double region_counted_area_m2(std::size_t r) const { return region_counted_m2_[r]; }
    bool counts(std::uint16_t k, std::size_t r) const { return classes_[k].reachable && (region_excluded_[r] || !classes_[k].excluded); }
    bool region_excluded(std::size_t r) const { return region_excluded_[r]; }
    // The classes whose samples lie in region r.
    const std::vector<std::uint16_t>& classes_of_region(std::size_t r) const { return region_classes_[r]; }
    // Samples of triangle t a shot can reach, and that are peened.
    std::int64_t reachable_samples(std::size_t t) const { return reachable_samples_[t]; }
    std::int64_t peened_samples(std::size_t t) const { return peened_samples_[t]; }

    std::size_t region_count() const { return region_peened_m2_.size(); }
    std::uint64_t reach_tests() const { return reach_tests_; }    // how many times the test ran
    std::uint64_t sample_tests() const { return sample_tests_; }  // of them, on samples of mixed probe cells

private:
    std::uint16_t class_for(bool reachable, const std::vector<std::uint32_t>& regions, bool excluded);

    std::vector<SampleClass> classes_;
    std::vector<std::uint16_t> triangle_class_;    // per triangle
    std::vector<std::int64_t> mixed_start_;        // per triangle: into sample_class_ (-1: uniform)
    std::vector<std::int64_t> first_sample_;       // per triangle: its first sample's index
    std::vector<std::uint16_t> sample_class_;      // the samples of the mixed triangles
    std::vector<std::int64_t> reachable_samples_;  // per triangle
    std::vector<std::int64_t> peened_samples_;     // per triangle
    std::vector<double> region_peened_m2_;         // per region, m2
    std::vector<double> region_counted_m2_;        // per region, m2
    std::vector<double> region_unreachable_m2_;    // per region, m2
    std::vector<bool> region_excluded_;            // per region
    std::vector<std::vector<std::uint16_t>> region_classes_;
    double peened_area_m2_ = 0.0;
    double reachable_area_m2_ = 0.0;
    std::uint64_t reach_tests_ = 0;
    std::uint64_t sample_tests_ = 0;
};

}  // namespace peensim
