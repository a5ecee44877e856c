// Many spheres (shot, impact markers) drawn as ray-cast impostors: one camera-facing square per
// sphere, instanced, whose fragment shader intersects the view ray with the true sphere and
// writes its depth. Four vertices per sphere instead of hundreds of triangles, exact silhouettes
// at any zoom, and correct intersections with walls and other spheres. Internal to render/.
#pragma once

#include <span>
#include <vector>

#include "render/gl_objects.h"
#include "render/mesh_layer.h"
#include "render/scene_types.h"

namespace peensim::render {

class SphereLayer {
public:
    SphereLayer();  // needs the target context current

    // Opaque, shaded like polished steel.
    void draw(const FrameView& view, const SphereSet& spheres);
    // Blended over the scene (colour.a), depth-tested but not written; headlight, mostly flat,
    // so a marker's middle shows its colour-map colour exactly.
    void draw(const FrameView& view, std::span<const ImpactMarker> markers);

private:
    struct Instance {
        float x, y, z, radius;  // m, world
        Rgba8 colour;
    };
    void draw_instances(const FrameView& view, float ambient, float diffuse, float specular, const Eigen::Vector3f& light);

    gl::Program program_;
    GLint u_view_ = -1, u_projection_ = -1, u_ambient_ = -1, u_diffuse_ = -1, u_specular_ = -1, u_light_ = -1;
    gl::VertexArray vao_;
    gl::Buffer buffer_;
    std::size_t buffer_capacity_ = 0;  // instances the GL buffer holds
    std::vector<Instance> instances_;  // staging, reused: no allocation once it has grown
};

}  // namespace peensim::render
