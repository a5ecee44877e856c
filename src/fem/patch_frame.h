// The patch's frame: its centre on the part's surface, the surface normal there (out of the
// material) and two tangents. A flat part's patch is exact; a curved part's is its local tangent
// plane at the centre (impacts are projected onto it, and how far they were from it is reported).
// Pure computation: no I/O.
#pragma once

#include <vector>

#include "common/vec.h"
#include "geometry/mesh_checks.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

struct PatchFrame {
    Vec3 centre_m = Vec3::Zero();  // m, component frame
    Vec3 e1 = Vec3::UnitX();       // unit tangent, component frame (the deck's x axis)
    Vec3 e2 = Vec3::UnitY();       // unit tangent (the deck's y axis)
    Vec3 normal = Vec3::UnitZ();   // unit normal out of the material (the deck's z axis)

    Vec3 to_local(const Vec3& p) const { return {e1.dot(p - centre_m), e2.dot(p - centre_m), normal.dot(p - centre_m)}; }
    Vec3 direction_to_local(const Vec3& v) const { return {e1.dot(v), e2.dot(v), normal.dot(v)}; }
};

// A right-handed frame with `normal` as its z axis (normalised); e1 is the component axis least
// aligned with the normal, made orthogonal to it.
PatchFrame frame_from_normal(const Vec3& centre_m, const Vec3& normal);

struct SurfacePoint {
    Vec3 point_m = Vec3::Zero();  // m, closest point of the mesh
    double distance_m = 0.0;      // m, from the query point
    int triangle = -1;            // index into mesh.triangles
};

// The point of `mesh` closest to `p` among `triangles` (all triangles when empty).
SurfacePoint closest_surface_point(const TriangleMesh& mesh, const Vec3& p, const std::vector<int>& triangles = {});

// The tangent frame at `centre_m` (a point on the surface, on triangle `triangle`): the
// area-weighted normal of the triangles within `radius_m` of the centre that face the same side
// as that triangle (normals within 60 degrees of its own).
PatchFrame tangent_frame(const TriangleMesh& mesh, const Vec3& centre_m, int triangle, double radius_m);

}  // namespace peensim
