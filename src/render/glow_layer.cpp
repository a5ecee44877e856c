#include "render/glow_layer.h"

#include <cstddef>

namespace peensim::render {

namespace {

// The square's corners are offset in clip space by radius_px pixels (times w, so that the
// perspective divide leaves exactly that many pixels): the sprite's size ignores the distance.
constexpr const char* kGlowVertexShader = R"GLSL(#version 330 core
layout(location = 0) in vec4 centre_lift;
layout(location = 1) in float radius_px;
layout(location = 2) in vec4 instance_colour;
uniform mat4 view;
uniform mat4 projection;
uniform vec2 viewport;
out vec2 corner;
flat out vec4 colour;
const vec2 corners[4] = vec2[4](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));
void main() {
    vec3 centre = (view * vec4(centre_lift.xyz, 1.0)).xyz;
    float distance = length(centre);
    colour = instance_colour;
    corner = corners[gl_VertexID];
    if (distance <= centre_lift.w || colour.a <= 0.0 || radius_px <= 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: nothing drawn
        return;
    }
    vec4 clip = projection * vec4(centre * (1.0 - centre_lift.w / distance), 1.0);
    clip.xy += corner * radius_px * 2.0 / viewport * clip.w;
    gl_Position = clip;
}
)GLSL";

// Premultiplied output, blended as ONE, ONE_MINUS_SRC_ALPHA: the disc (r < 0.5) is laid over the
// scene (alpha = its opacity), the halo (r > 0.5) adds light to it (alpha 0), so that it shows on
// the dark background, a grey wall and the orange part alike.
constexpr const char* kGlowFragmentShader = R"GLSL(#version 330 core
in vec2 corner;
flat in vec4 colour;
out vec4 fragment;
void main() {
    float r = length(corner);
    if (r > 1.0) discard;
    // A white-hot core (to r ~ 0.3), the colour (to 0.45), a thin dark ring (0.45 - 0.55).
    float core = 1.0 - smoothstep(0.16, 0.32, r);
    float ring = smoothstep(0.4, 0.47, r) * (1.0 - smoothstep(0.5, 0.58, r));
    vec3 disc = mix(mix(colour.rgb, vec3(1.0), 0.9 * core), vec3(0.0), 0.65 * ring);
    float opacity = colour.a * (1.0 - smoothstep(0.52, 0.58, r));
    // The halo: the colour lightened (the slowest, darkest impacts too), falling off outward.
    float halo = colour.a * 0.7 * exp(-9.0 * (r - 0.5) * (r - 0.5)) * smoothstep(0.45, 0.55, r) * (1.0 - smoothstep(0.85, 1.0, r));
    vec3 light = mix(colour.rgb, vec3(1.0), 0.5) * halo;
    fragment = vec4(disc * opacity + light, opacity);
}
)GLSL";

}  // namespace

GlowLayer::GlowLayer()
    : program_(gl::make_program("impact glow", kGlowVertexShader, kGlowFragmentShader)),
      vao_(gl::make_vertex_array()),
      buffer_(gl::make_buffer()) {
    u_view_ = gl::uniform(program_, "view");
    u_projection_ = gl::uniform(program_, "projection");
    u_viewport_ = gl::uniform(program_, "viewport");
    glBindVertexArray(vao_.get());
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
    gl::vertex_attribute(0, 4, GL_FLOAT, sizeof(Instance), offsetof(Instance, x), gl::Step::instance);
    gl::vertex_attribute(1, 1, GL_FLOAT, sizeof(Instance), offsetof(Instance, radius_px), gl::Step::instance);
    gl::vertex_attribute(2, 4, GL_UNSIGNED_BYTE, sizeof(Instance), offsetof(Instance, colour), gl::Step::instance);
    glBindVertexArray(0);
    gl::check_errors("while setting up the impact glows");
}

void GlowLayer::draw(const FrameView& view, int width_px, int height_px, std::span<const ImpactGlow> glows) {
    instances_.clear();
    for (const ImpactGlow& g : glows) {
        if (g.colour.a <= 0.0f || g.radius_px <= 0.0f) continue;
        instances_.push_back({static_cast<float>(g.point_m.x()), static_cast<float>(g.point_m.y()), static_cast<float>(g.point_m.z()),
                              static_cast<float>(g.lift_m), g.radius_px, to_rgba8(g.colour)});
    }
    if (instances_.empty()) return;
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
    if (instances_.size() > buffer_capacity_) {
        buffer_capacity_ = instances_.capacity();
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(buffer_capacity_ * sizeof(Instance)), nullptr, GL_STREAM_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(instances_.size() * sizeof(Instance)), instances_.data());
    glUseProgram(program_.get());
    const Eigen::Matrix4f v = gl::to_float(view.view);
    const Eigen::Matrix4f p = gl::to_float(view.projection);
    glUniformMatrix4fv(u_view_, 1, GL_FALSE, v.data());
    glUniformMatrix4fv(u_projection_, 1, GL_FALSE, p.data());
    glUniform2f(u_viewport_, static_cast<float>(width_px), static_cast<float>(height_px));
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // premultiplied; the frame's alpha kept
    glDepthMask(GL_FALSE);
    glBindVertexArray(vao_.get());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(instances_.size()));
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // the renderer's (renderer.cpp)
    glDisable(GL_BLEND);
}

}  // namespace peensim::render
