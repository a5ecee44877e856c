// The sonotrode as the event-driven scheme sees it: its working face (the top plane facing into
// the chamber, the triangles every throw starts from) becomes one exactly solvable vibrating plane
// (vibrating_plane_toi), and the rest of its mesh (sides, rims, anything below) a static BVH that
// the scheme sweeps with the radius grown by the amplitude, then settles by conservative
// advancement on the moving mesh. Built once per run from the compiled model.
#pragma once

#include <memory>
#include <vector>

#include "collision/mesh_collider.h"
#include "geometry/triangle_mesh.h"
#include "kernels/vibrating_plane_toi.h"
#include "model/model.h"

namespace peensim {

struct SonotrodeFace {
    VibratingPlane plane;                // world, at the phase of the component's kinematics
    std::vector<unsigned char> on_face;  // per triangle of the sonotrode mesh: 1 if in the face
    int face_triangles = 0;
    // The other triangles (may be empty: nullptr), in the sonotrode's frame, source facets kept.
    std::shared_ptr<const TriangleMesh> rest_mesh;
    std::shared_ptr<const MeshCollider> rest_collider;

    // Whether a point of the plane (m, sonotrode frame) lies on the face: within `tolerance` (m)
    // of one of its triangles. Fills the sonotrode-mesh triangle it lies on.
    bool contains(const Component& sonotrode, const Vec3& point_component, double tolerance, int& triangle) const;
};

// up: unit, world, from the sonotrode into the chamber (shot_cavity's sonotrode_up). The face is
// every triangle whose normal is parallel to `up` (within 1e-6 rad) in the highest such plane.
SonotrodeFace build_sonotrode_face(const Component& sonotrode, const Vec3& up);

}  // namespace peensim
