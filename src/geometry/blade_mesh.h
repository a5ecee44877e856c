// A generated blade: a thin, twisted, sharp-edged solid for the parts nobody ships (compressor and
// turbine blades, knife-edged fins). Its section is a symmetric biconvex lens, thickness
// t(s) = t_max 4 s (1 - s) along the chord (s = 0 .. 1), so both edges are sharp wedges of angle
// 2 atan(2 t_max / c); sections are spaced evenly along the span and turned about the span axis,
// linearly, from -twist/2 at one end to +twist/2 at the other. Chord points are cosine-spaced, so
// the facets are finest at the sharp edges. Flat lens-shaped caps close both ends: a closed solid
// with outward normals. Metres.
#pragma once

#include "geometry/axis_frame.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

struct BladeSpec {
    double chord_m = 0.02;       // m, edge to edge
    double span_m = 0.04;        // m, along the axis
    double thickness_m = 0.001;  // m, at mid-chord (less than the chord)
    double twist_rad = 0.5;      // rad, end to end (either sign)
    int span_stations = 40;      // sections along the span (>= 2)
    int chord_points = 40;       // points per side along the chord (>= 2)
    Axis axis = Axis::x;         // the span's direction; the chord lies along the next axis at mid-span
    Vec3 center_m = Vec3::Zero();
};

// Groups "surface", "end-low", "end-high". Throws InputError (field "blade") for a non-positive
// size, a thickness not below the chord, or too few stations or points.
TriangleMesh blade(const BladeSpec& spec);

}  // namespace peensim
