// Generated boxes: a closed box (a plate, a block) and a box with one face left out (a
// chamber whose missing floor is the sonotrode). Metres; axis-aligned.
#pragma once

#include <Eigen/Core>

#include "geometry/triangle_mesh.h"

namespace peensim {

struct BoxSpec {
    Vec3 size_m = Vec3::Ones();                           // m, edge lengths along x, y, z
    Vec3 center_m = Vec3::Zero();                         // m
    Eigen::Vector3i divisions = Eigen::Vector3i::Ones();  // quads along x, y, z on every face (>= 1)
};

enum class BoxFace { minus_x, plus_x, minus_y, plus_y, minus_z, plus_z };

// Which way the normals of a surface point.
enum class Facing {
    outward,  // out of the enclosed volume (a solid body)
    inward,   // into the enclosed volume (the walls of a cavity, as seen by the shot inside)
};

// Closed box, outward normals, one group per face named "-x", "+x", "-y", "+y", "-z", "+z".
// Throws InputError (field "box") for a non-positive size or division.
TriangleMesh box(const BoxSpec& spec);

// The same box without open_face; normals as `facing` says (inward for a chamber).
TriangleMesh box_open(const BoxSpec& spec, BoxFace open_face, Facing facing);

}  // namespace peensim
