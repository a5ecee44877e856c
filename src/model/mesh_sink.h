// A sink of any shape: a closed mesh (world frame) whose volume collects a shot when its centre
// enters it (a duct's mouth, a hopper, a cabinet's extraction). The mesh is no obstacle: shot are
// not stopped by its surface, they are taken out as their centre crosses it.
//
// Inside: the mesh's winding number at the point (the sum of its triangles' solid angles over
// 4 pi: 1 inside a closed mesh, 0 outside, whatever its shape), after a bounding-box test that
// rejects most shot for the price of six comparisons. The entry along a flight: the first time
// the centre comes within 1 nm of the surface (MeshCollider::first_hit's exact swept-sphere walk
// with that radius), from outside.
#pragma once

#include <memory>
#include <string>

#include "collision/mesh_collider.h"
#include "geometry/triangle_mesh.h"
#include "model/shot_flow.h"

namespace peensim {

class MeshSink final : public ShotSink {
public:
    static constexpr double kSurfaceReach = 1e-9;  // m: a centre this close to the surface has entered

    // `mesh` in the world frame; closed (every edge shared by two triangles), else
    // std::invalid_argument.
    MeshSink(std::string name, std::shared_ptr<const TriangleMesh> mesh);
    const std::string& name() const override { return name_; }
    bool contains(const Vec3& p) const override;
    std::optional<double> first_entry(const Trajectory& path, double ta, double tb) const override;

    // -, the winding number of the mesh about p (1 inside, 0 outside a closed outward mesh).
    double winding_number(const Vec3& p) const;

private:
    std::string name_;
    std::shared_ptr<const TriangleMesh> mesh_;
    std::unique_ptr<MeshCollider> collider_;
    Vec3 lo_, hi_;  // m, the mesh's bounding box
};

}  // namespace peensim
