#include "render/sphere_layer.h"

#include <cstddef>
#include <stdexcept>

namespace peensim::render {

namespace {

// The square sits in the plane through the centre, square to the eye-centre line; its half
// size is the radius of the cone of rays tangent to the sphere there, d r / sqrt(d^2 - r^2),
// so it covers the silhouette exactly under perspective. A sphere around the eye is skipped.
constexpr const char* kSphereVertexShader = R"GLSL(#version 330 core
layout(location = 0) in vec4 centre_radius;
layout(location = 1) in vec4 instance_colour;
uniform mat4 view;
uniform mat4 projection;
out vec3 square_point;
flat out vec3 centre;
flat out float radius;
flat out vec4 colour;
const vec2 corners[4] = vec2[4](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0), vec2(1.0, 1.0));
void main() {
    centre = (view * vec4(centre_radius.xyz, 1.0)).xyz;
    radius = centre_radius.w;
    colour = instance_colour;
    float d2 = dot(centre, centre);
    float r2 = radius * radius;
    if (d2 <= r2 * 1.0001 || radius <= 0.0 || colour.a <= 0.0) {
        square_point = vec3(0.0);
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: nothing drawn
        return;
    }
    vec3 axis = centre * inversesqrt(d2);
    vec3 helper = abs(axis.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 u = normalize(cross(helper, axis));
    vec3 v = cross(axis, u);
    float half_size = radius * sqrt(d2 / (d2 - r2));
    vec2 corner = corners[gl_VertexID];
    square_point = centre + half_size * (corner.x * u + corner.y * v);
    gl_Position = projection * vec4(square_point, 1.0);
}
)GLSL";

// Ray from the eye (the origin of view space) through the square point. The squared distance
// from the centre to the ray is computed as a vector length, not as |c|^2 - (c.d)^2, which
// would cancel in float for a 1 mm sphere 1 m away.
constexpr const char* kSphereFragmentShader = R"GLSL(#version 330 core
in vec3 square_point;
flat in vec3 centre;
flat in float radius;
flat in vec4 colour;
uniform mat4 projection;
uniform float ambient;
uniform float diffuse;
uniform float specular;
uniform vec3 light;   // view space, toward the light; zero: a headlight (the eye)
out vec4 fragment;
void main() {
    vec3 dir = normalize(square_point);
    float along = dot(dir, centre);
    vec3 off_ray = centre - along * dir;
    float half_chord2 = radius * radius - dot(off_ray, off_ray);
    if (half_chord2 < 0.0) discard;
    vec3 hit = (along - sqrt(half_chord2)) * dir;
    vec3 normal = (hit - centre) / radius;
    vec3 to_light = dot(light, light) > 0.0 ? light : -dir;
    float lambert = max(dot(normal, to_light), 0.0);
    float shine = specular * pow(max(dot(normal, normalize(to_light - dir)), 0.0), 60.0);
    fragment = vec4(colour.rgb * (ambient + diffuse * lambert) + vec3(shine), colour.a);
    vec4 clip = projection * vec4(hit, 1.0);
    gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;
}
)GLSL";

// Shot are lit from above-left of the camera, so each shows a small off-centre highlight that
// reads as a steel ball (a headlight would put a flat white spot in every ball's middle).
const Eigen::Vector3f kShotLight = Eigen::Vector3f(-0.35f, 0.45f, 1.0f).normalized();
constexpr float kShotAmbient = 0.25f;
constexpr float kShotDiffuse = 0.75f;
constexpr float kShotSpecular = 0.45f;
constexpr float kMarkerAmbient = 0.7f;
constexpr float kMarkerDiffuse = 0.3f;

}  // namespace

SphereLayer::SphereLayer()
    : program_(gl::make_program("sphere impostor", kSphereVertexShader, kSphereFragmentShader)),
      vao_(gl::make_vertex_array()),
      buffer_(gl::make_buffer()) {
    u_view_ = gl::uniform(program_, "view");
    u_projection_ = gl::uniform(program_, "projection");
    u_ambient_ = gl::uniform(program_, "ambient");
    u_diffuse_ = gl::uniform(program_, "diffuse");
    u_specular_ = gl::uniform(program_, "specular");
    u_light_ = gl::uniform(program_, "light");
    glBindVertexArray(vao_.get());
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
    gl::vertex_attribute(0, 4, GL_FLOAT, sizeof(Instance), offsetof(Instance, x), gl::Step::instance);
    gl::vertex_attribute(1, 4, GL_UNSIGNED_BYTE, sizeof(Instance), offsetof(Instance, colour), gl::Step::instance);
    glBindVertexArray(0);
    gl::check_errors("while setting up the sphere impostors");
}

void SphereLayer::draw(const FrameView& view, const SphereSet& spheres) {
    const std::size_t n = spheres.x_m.size();
    if (spheres.y_m.size() != n || spheres.z_m.size() != n || (!spheres.active.empty() && spheres.active.size() != n) ||
        (!spheres.radii_m.empty() && spheres.radii_m.size() != n)) {
        throw std::invalid_argument("render: sphere coordinate arrays differ in size");
    }
    instances_.clear();
    const Rgba8 colour = to_rgba8(spheres.colour);
    const auto radius = static_cast<float>(spheres.radius_m);
    for (std::size_t i = 0; i < n; ++i) {
        if (!spheres.active.empty() && spheres.active[i] == 0) continue;
        const float r = spheres.radii_m.empty() ? radius : static_cast<float>(spheres.radii_m[i]);
        instances_.push_back(
            {static_cast<float>(spheres.x_m[i]), static_cast<float>(spheres.y_m[i]), static_cast<float>(spheres.z_m[i]), r, colour});
    }
    draw_instances(view, kShotAmbient, kShotDiffuse, kShotSpecular, kShotLight);
}

void SphereLayer::draw(const FrameView& view, std::span<const ImpactMarker> markers) {
    instances_.clear();
    for (const ImpactMarker& m : markers) {
        if (m.colour.a <= 0.0f) continue;
        instances_.push_back({static_cast<float>(m.point_m.x()), static_cast<float>(m.point_m.y()), static_cast<float>(m.point_m.z()),
                              static_cast<float>(m.radius_m), to_rgba8(m.colour)});
    }
    if (instances_.empty()) return;
    glEnable(GL_BLEND);
    glDepthMask(GL_FALSE);
    draw_instances(view, kMarkerAmbient, kMarkerDiffuse, 0.0f, Eigen::Vector3f::Zero());
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
}

void SphereLayer::draw_instances(const FrameView& view, float ambient, float diffuse, float specular, const Eigen::Vector3f& light) {
    if (instances_.empty()) return;
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
    const auto bytes = static_cast<GLsizeiptr>(instances_.size() * sizeof(Instance));
    if (instances_.size() > buffer_capacity_) {
        buffer_capacity_ = instances_.capacity();
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(buffer_capacity_ * sizeof(Instance)), nullptr, GL_STREAM_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, instances_.data());

    glUseProgram(program_.get());
    const Eigen::Matrix4f v = gl::to_float(view.view);
    const Eigen::Matrix4f p = gl::to_float(view.projection);
    glUniformMatrix4fv(u_view_, 1, GL_FALSE, v.data());
    glUniformMatrix4fv(u_projection_, 1, GL_FALSE, p.data());
    glUniform1f(u_ambient_, ambient);
    glUniform1f(u_diffuse_, diffuse);
    glUniform1f(u_specular_, specular);
    glUniform3f(u_light_, light.x(), light.y(), light.z());
    glBindVertexArray(vao_.get());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(instances_.size()));
    glBindVertexArray(0);
}

}  // namespace peensim::render
