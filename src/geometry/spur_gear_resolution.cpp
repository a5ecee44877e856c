#include "geometry/spur_gear_resolution.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/input_error.h"

namespace peensim {

namespace {

int segments_for(double length_m, double edge_m, int at_least) {
    return std::max(at_least, static_cast<int>(std::ceil(length_m / edge_m)));
}

}  // namespace

SpurGearResolution gear_resolution_for_edge_length(const SpurGearSpec& spec, double edge_m) {
    if (!(edge_m > 0.0)) throw InputError({}, "gear", "edge length must be positive");
    const InvoluteToothProfile profile(spec);
    const double root = profile.root_radius_m();
    const double root_half_angle = profile.half_angle_rad(root);
    SpurGearResolution r;
    const double radial_flank_m = profile.base_radius_m() - root;
    r.radial_flank_segments = radial_flank_m > 0.0 ? segments_for(radial_flank_m, edge_m, 1) : 0;
    r.involute_segments = segments_for(profile.involute_length_m(), edge_m, 4);
    r.tooth_width_segments = segments_for(2.0 * root_half_angle * root, edge_m, 2);
    r.root_arc_segments = segments_for((profile.pitch_angle_rad() - 2.0 * root_half_angle) * root, edge_m, 2);
    r.body_rings = segments_for(root - spec.bore_radius_m, edge_m, 1);
    r.axial_layers = segments_for(spec.face_width_m, edge_m, 1);
    return r;
}

std::size_t gear_triangle_count(const SpurGearResolution& r, int teeth) {
    const auto z = static_cast<std::size_t>(teeth);
    const auto rows = static_cast<std::size_t>(r.radial_flank_segments + r.involute_segments);
    const auto across = static_cast<std::size_t>(r.tooth_width_segments);
    const auto root_ring = static_cast<std::size_t>(r.tooth_width_segments + r.root_arc_segments);
    const auto rings = static_cast<std::size_t>(r.body_rings);
    const auto layers = static_cast<std::size_t>(r.axial_layers);
    const std::size_t end_faces = 4 * z * (root_ring * rings + rows * across);
    const std::size_t walls = 2 * layers * z * (2 * rows + 2 * root_ring);
    return end_faces + walls;
}

SpurGearResolution gear_resolution_for_triangle_count(const SpurGearSpec& spec, std::size_t target) {
    // The count never grows with the edge length, so bisect (in log scale) for the two edge
    // lengths whose counts bracket the target, then take the closer one.
    const InvoluteToothProfile profile(spec);
    double coarse_edge_m = 2.0 * profile.tip_radius_m();  // count <= target (floors only)
    double fine_edge_m = coarse_edge_m * 1e-5;            // count > target for any sane target
    auto count_at = [&](double edge_m) { return gear_triangle_count(gear_resolution_for_edge_length(spec, edge_m), spec.teeth); };
    if (count_at(coarse_edge_m) >= target) return gear_resolution_for_edge_length(spec, coarse_edge_m);
    if (count_at(fine_edge_m) <= target) return gear_resolution_for_edge_length(spec, fine_edge_m);
    for (int i = 0; i < 60; ++i) {
        const double middle = std::sqrt(coarse_edge_m * fine_edge_m);
        if (count_at(middle) > target)
            fine_edge_m = middle;
        else
            coarse_edge_m = middle;
    }
    const auto miss = [&](double edge_m) {
        const auto n = static_cast<long long>(count_at(edge_m));
        return std::llabs(n - static_cast<long long>(target));
    };
    return gear_resolution_for_edge_length(spec, miss(fine_edge_m) < miss(coarse_edge_m) ? fine_edge_m : coarse_edge_m);
}

}  // namespace peensim
