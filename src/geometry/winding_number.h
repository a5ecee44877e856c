// The generalised winding number of a triangle mesh about a point: the signed solid angle its
// triangles subtend, over 4 pi (Jacobson et al. 2013). 1 inside a closed mesh wound outward, 0
// outside, about 0.5 on its surface; robust to small holes and self-touching CAD exports, where a
// ray's parity is not.
#pragma once

#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

double winding_number(const TriangleMesh& mesh, const Vec3& p);  // p in the mesh's frame (m)

}  // namespace peensim
