// Impact glows: a round sprite of a fixed size in pixels around the projection of each impact,
// whatever the zoom (a shot-sized disc on the surface is a few pixels in a chamber-wide view and
// disappears against the part). Drawn over the opaque scene, depth-tested at the impact point
// lifted toward the eye (so a tooth in front hides it, its own surface does not), not written to
// depth. Internal to render/.
//
// The sprite, from the centre out: a white-hot core, the impact's colour (its colour-map colour),
// a thin dark ring that makes it read on a light surface as the core does on a dark one (a disc
// laid over the scene out to half the radius), and a halo of the lightened colour that adds light
// to what is behind it out to the radius. colour.a fades the whole sprite (the recorder's trail of
// earlier frames' impacts).
#pragma once

#include <span>
#include <vector>

#include "render/gl_objects.h"
#include "render/mesh_layer.h"
#include "render/scene_types.h"

namespace peensim::render {

class GlowLayer {
public:
    GlowLayer();  // needs the target context current

    void draw(const FrameView& view, int width_px, int height_px, std::span<const ImpactGlow> glows);

private:
    struct Instance {
        float x, y, z;    // m, world
        float lift;       // m, toward the eye
        float radius_px;  // px
        Rgba8 colour;
    };

    gl::Program program_;
    GLint u_view_ = -1, u_projection_ = -1, u_viewport_ = -1;
    gl::VertexArray vao_;
    gl::Buffer buffer_;
    std::size_t buffer_capacity_ = 0;  // instances the GL buffer holds
    std::vector<Instance> instances_;  // staging, reused
};

}  // namespace peensim::render
