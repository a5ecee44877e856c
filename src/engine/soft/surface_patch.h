// The triangles of one component near one shot of the soft scheme's pool, gathered once from the
// component's BVH and reused while the shot stays within a margin of where they were gathered
// (its centre in the component's own frame, so a vibrating or turning component needs no
// regathering for its own motion). A contact step then tests a handful of triangles instead of
// walking the BVH.
#pragma once

#include <vector>

#include "collision/mesh_collider.h"
#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

// One place where a shot overlaps a component's surface, component frame.
struct SurfaceOverlap {
    int mesh_triangle = -1;
    Vec3 point_m = Vec3::Zero();  // m, the surface point closest to the centre
    Vec3 normal = Vec3::UnitZ();  // unit, from that point towards the centre
    double depth_m = 0.0;         // m, R - distance (> 0)
};

class SurfacePatch {
public:
    // Forgets what it gathered (a new shot takes the slot).
    void clear() { valid_ = false; }

    // The overlaps of a sphere of radius R (m) centred at p (m, component frame) with the mesh,
    // one per distinct contact: overlapping triangles whose normals lie within kSameContactAngle of a
    // deeper one are the same contact (neighbouring facets of one face, a faceted curve, an edge
    // shared by two triangles), the deepest kept. Appends to `out`. margin_m: how far p may move
    // before the triangles are gathered again (m).
    void overlaps(const Vec3& p, double R, double margin_m, const MeshCollider& collider, const TriangleMesh& mesh,
                  std::vector<SurfaceOverlap>& out);

    // cos of the largest angle between the normals of one contact's facets: 30 deg. A concave
    // corner (a floor meeting a wall, 90 deg) gives two contacts; a faceted cylinder's 7.5 deg
    // facets, or a face split into triangles, one.
    static constexpr double kSameContactCos = 0.8660254037844387;

private:
    bool valid_ = false;
    bool empty_ = true;           // nothing was gathered: nothing to test until the shot moves on
    Vec3 centre_ = Vec3::Zero();  // m, where the triangles were gathered (component frame)
    double reach_ = 0.0;          // m, they are every triangle within this of centre_
    // The gathered triangles: index, corners and bounding sphere (component frame), so that a
    // step reads them in one pass and skips those whose sphere the shot's cannot reach.
    struct Nearby {
        int triangle;
        Vec3 a, b, c;
        Vec3 normal;    // unit (zero for a degenerate triangle): a centre farther than R from its plane misses it
        Vec3 centre;    // m
        double radius;  // m
    };
    std::vector<int> triangles_;  // scratch of the gathering
    std::vector<Nearby> nearby_;
    std::vector<SurfaceOverlap> found_;  // scratch
};

}  // namespace peensim
