#include "analysis/unreachable_area.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace peensim {

namespace {

constexpr double kSmallestRadiusShare = 1.0 / 64.0;  // of R: below it a point is called closed off
constexpr int kBisections = 12;                      // on log(radius): 6 factors of 2 to 1.4e-3 relative

// The largest radius (m) of a shot that touches `point` of triangle t: reach is assumed monotone in
// the radius (a smaller shot fits wherever a larger one does, as the test's clearances shrink).
double largest_reaching_radius(const ReachTest& reach, const Vec3& point, std::size_t t, double R) {
    double lo = R * kSmallestRadiusShare, hi = R;  // reaches at lo, not at hi
    if (!reach(point, t, lo)) return 0.0;
    for (int k = 0; k < kBisections; ++k) {
        const double mid = std::sqrt(lo * hi);
        (reach(point, t, mid) ? lo : hi) = mid;
    }
    return lo;
}

// The diameter (m) that reaches `share` of the area of `points` ((diameter, area) pairs).
double diameter_reaching(std::vector<std::pair<double, double>> points, double share) {
    if (points.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    double total = 0.0;
    for (const auto& p : points) total += p.second;
    double reached = 0.0;
    for (const auto& [diameter, area] : points) {
        reached += area;
        if (reached >= share * total * (1.0 - 1e-12)) return diameter;
    }
    return points.back().first;
}

}  // namespace

UnreachableFindings find_unreachable_area(const CoverageMap& map, const SampleClasses& classes, const RegionSet& regions,
                                          const ReachTest& reach, double shot_radius_m, std::size_t max_points) {
    UnreachableFindings f;
    f.shot_diameter_m = 2.0 * shot_radius_m;
    f.regions.assign(regions.size(), {});
    const std::size_t triangles = map.triangle_count();
    f.triangle_share.assign(triangles, 0.0);
    const auto out_of_reach = [&](std::uint16_t k) { return !classes.info(k).reachable && !classes.info(k).excluded; };
    // The unreachable samples, counted first so that the subsample is spread evenly over them.
    std::uint64_t count = 0;
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint16_t k = classes.triangle_class(t);
        if (k != SampleClasses::kMixed && !out_of_reach(k)) continue;
        map.for_each_sample_of_triangle(t, [&](std::int64_t index, const Vec3&, double, double) {
            if (out_of_reach(classes.class_of(t, index))) ++count;
        });
    }
    if (count == 0) return f;
    const std::uint64_t stride = std::max<std::uint64_t>(1, (count + max_points - 1) / std::max<std::size_t>(1, max_points));
    std::vector<std::pair<double, double>> whole;
    std::vector<std::vector<std::pair<double, double>>> per_region(regions.size());
    std::uint64_t seen = 0;
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint16_t k = classes.triangle_class(t);
        if (k != SampleClasses::kMixed && !out_of_reach(k)) continue;
        const double sample_area = map.sample_area(t);  // m2
        double out = 0.0;
        map.for_each_sample_of_triangle(t, [&](std::int64_t index, const Vec3& point, double, double) {
            const std::uint16_t c = classes.class_of(t, index);
            if (!out_of_reach(c)) return;
            out += sample_area;
            f.whole.area_m2 += sample_area;
            for (std::uint32_t r : classes.info(c).regions) f.regions[r].area_m2 += sample_area;
            if (seen++ % stride != 0) return;
            const double d = 2.0 * largest_reaching_radius(reach, point, t, shot_radius_m);
            whole.emplace_back(d, sample_area);
            for (std::uint32_t r : classes.info(c).regions) per_region[r].emplace_back(d, sample_area);
        });
        const double area = map.triangle_area(t);
        f.triangle_share[t] = area > 0.0 ? std::min(1.0, out / area) : 0.0;
    }
    const auto fill = [](UnreachableArea& u, const std::vector<std::pair<double, double>>& points) {
        u.points = points.size();
        u.half_reached_by_m = diameter_reaching(points, 0.5);
        u.most_reached_by_m = diameter_reaching(points, 0.9);
    };
    fill(f.whole, whole);
    for (std::size_t r = 0; r < regions.size(); ++r) fill(f.regions[r], per_region[r]);
    return f;
}

}  // namespace peensim
