// Placement of a generated shape whose natural axis is local w: the shape is built in local
// coordinates (u, v, w) and mapped to the world by a cyclic permutation of (x, y, z) plus an
// origin. Cyclic permutations are rotations (never mirrors), so a triangle wound
// counter-clockwise around its outward normal stays so after the mapping.
#pragma once

#include "common/vec.h"

namespace peensim {

enum class Axis { x, y, z };

inline const char* axis_name(Axis a) { return a == Axis::x ? "x" : a == Axis::y ? "y" : "z"; }
inline Vec3 axis_unit(Axis a) { return a == Axis::x ? Vec3::UnitX() : a == Axis::y ? Vec3::UnitY() : Vec3::UnitZ(); }

struct AxisFrame {
    Axis axis = Axis::z;           // the world axis that local w maps to
    Vec3 origin_m = Vec3::Zero();  // m, world position of local (0, 0, 0)

    // axis z: (u, v, w) -> (x, y, z); axis x: -> (y, z, x) = (u, v, w); axis y: -> (z, x, y) = (u, v, w).
    Vec3 to_world(double u, double v, double w) const {
        switch (axis) {
            case Axis::x: return origin_m + Vec3(w, u, v);
            case Axis::y: return origin_m + Vec3(v, w, u);
            case Axis::z: break;
        }
        return origin_m + Vec3(u, v, w);
    }
};

}  // namespace peensim
