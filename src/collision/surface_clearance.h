// How far a shot centre is from a component's surface, and on which side. The nearest point alone
// gives an unsigned distance and a normal pointing from the surface to the centre, which for a
// centre that has got inside a solid points further in: every correction along it pushes the shot
// deeper and its rebounds keep it inside (a trapped shot hitting the inner surface). For a solid (a
// closed, consistently wound mesh with outward normals, Component::solid), a centre on the inner
// side of the face its nearest point lies on is inside: its clearance is negative and its normal
// is the face's outward one, so it is put back out through the face it crossed. At an edge or a
// vertex the side of one face does not decide (a sharp convex edge's outside can lie behind
// either face), so there the unsigned reading stands.
#pragma once

#include "collision/mesh_collider.h"
#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

struct SurfaceClearance {
    double distance_m = 0.0;      // m, centre to surface; negative: the centre is inside the solid
    Vec3 normal = Vec3::UnitZ();  // unit, component frame, from the surface towards where the shot belongs
};

// p: the centre (component frame, m); closest: the mesh's nearest point to p (MeshCollider).
SurfaceClearance surface_clearance(const TriangleMesh& mesh, bool solid, const Vec3& p, const MeshCollider::Closest& closest);

}  // namespace peensim
