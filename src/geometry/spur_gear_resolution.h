// How finely a spur gear is meshed: how many segments along each part of the outline and
// along the axis. The same gear can be produced at any triangle count; every count below is
// a number of segments (not of points).
#pragma once

#include <cstddef>

#include "geometry/spur_gear_profile.h"

namespace peensim {

struct SpurGearResolution {
    int radial_flank_segments = 1;  // straight flank from root to base circle (0 when root >= base)
    int involute_segments = 4;      // along each involute flank, equal arc lengths (>= 1)
    int tooth_width_segments = 2;   // across a tooth: tip land and each row of the end faces (>= 1)
    int root_arc_segments = 2;      // along the root circle between two teeth (>= 1)
    int body_rings = 1;             // rings of quads from the bore to the root circle (>= 1)
    int axial_layers = 1;           // layers of the side walls along the face width (>= 1)
};

// Segments of about edge_m (m) everywhere, with a floor that keeps the involute recognisable
// (>= 4 involute segments, >= 2 across a tooth and along a root arc).
SpurGearResolution gear_resolution_for_edge_length(const SpurGearSpec& spec, double edge_m);

// The resolution whose triangle count is closest to target_triangles (the count grows about
// as 1 / edge_length^2, so the coarse and fine versions of a gear have similar shapes of
// triangles). Throws InputError for an impossible gear.
SpurGearResolution gear_resolution_for_triangle_count(const SpurGearSpec& spec, std::size_t target_triangles);

// Triangles spur_gear() makes at this resolution: 4 z [(c + s) R + N c] on the two end faces
// plus 2 L z [2 N + 2 (c + s)] on the outer and bore walls, N = radial + involute segments.
std::size_t gear_triangle_count(const SpurGearResolution& resolution, int teeth);

}  // namespace peensim
