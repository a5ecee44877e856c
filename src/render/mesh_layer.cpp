#include "render/mesh_layer.h"

#include <stdexcept>
#include <string>

namespace peensim::render {

namespace {

constexpr const char* kMeshVertexShader = R"GLSL(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 model_view;
uniform mat4 projection;
out vec3 view_position;
void main() {
    vec4 p = model_view * vec4(position, 1.0);
    view_position = p.xyz;
    gl_Position = projection * p;
}
)GLSL";

// The flat normal comes from the screen-space derivatives of the position, which lie in the
// triangle's plane: no normal array to upload, and welded vertices (shared by neighbouring
// triangles) still shade flat. |n.v| lights both sides alike, so a cut-away chamber's inner
// walls are lit whatever their winding. gl_PrimitiveID is the triangle index of the draw call.
constexpr const char* kMeshFragmentShader = R"GLSL(#version 330 core
in vec3 view_position;
uniform vec4 colour;
uniform bool per_triangle;
uniform samplerBuffer triangle_colours;
uniform float ambient;
uniform float diffuse;
out vec4 fragment;
void main() {
    vec3 normal = normalize(cross(dFdx(view_position), dFdy(view_position)));
    float facing = abs(dot(normal, normalize(-view_position)));
    vec4 base = per_triangle ? texelFetch(triangle_colours, gl_PrimitiveID) : colour;
    fragment = vec4(base.rgb * (ambient + diffuse * facing), base.a);
}
)GLSL";

// Headlight: a wall square to the view gets ambient + diffuse = 1 (its own colour), a grazing
// one the ambient part only.
constexpr float kAmbient = 0.35f;
constexpr float kDiffuse = 0.65f;

}  // namespace

MeshLayer::MeshLayer() : program_(gl::make_program("mesh", kMeshVertexShader, kMeshFragmentShader)) {
    u_model_view_ = gl::uniform(program_, "model_view");
    u_projection_ = gl::uniform(program_, "projection");
    u_colour_ = gl::uniform(program_, "colour");
    u_per_triangle_ = gl::uniform(program_, "per_triangle");
    u_triangle_colours_ = gl::uniform(program_, "triangle_colours");
    u_ambient_ = gl::uniform(program_, "ambient");
    u_diffuse_ = gl::uniform(program_, "diffuse");
}

std::size_t MeshLayer::add(const TriangleMesh& mesh, const MeshStyle& style) {
    if (mesh.triangles.empty()) throw std::invalid_argument("render: cannot draw a mesh without triangles");
    std::vector<float> vertices;
    vertices.reserve(mesh.vertices.size() * 3);
    for (const Vec3& v : mesh.vertices) {
        vertices.push_back(static_cast<float>(v.x()));
        vertices.push_back(static_cast<float>(v.y()));
        vertices.push_back(static_cast<float>(v.z()));
    }
    std::vector<std::uint32_t> indices;
    indices.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles) {
        for (int i : t) indices.push_back(static_cast<std::uint32_t>(i));
    }

    Gpu gpu;
    gpu.vao = gl::make_vertex_array();
    gpu.vertices = gl::make_buffer();
    gpu.indices = gl::make_buffer();
    gpu.index_count = static_cast<GLsizei>(indices.size());
    gpu.triangles = mesh.triangles.size();
    gpu.style = style;
    glBindVertexArray(gpu.vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, gpu.vertices.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(), GL_STATIC_DRAW);
    gl::vertex_attribute(0, 3, GL_FLOAT, 3 * sizeof(float), 0, gl::Step::vertex);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.indices.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
    gl::check_errors("while uploading a mesh");
    meshes_.push_back(std::move(gpu));
    return meshes_.size() - 1;
}

MeshLayer::Gpu& MeshLayer::at(std::size_t mesh) {
    if (mesh >= meshes_.size()) {
        throw std::out_of_range("render: no mesh " + std::to_string(mesh) + " (" + std::to_string(meshes_.size()) + " added)");
    }
    return meshes_[mesh];
}

void MeshLayer::set_pose(std::size_t mesh, const Mat4& world_from_mesh) { at(mesh).pose = world_from_mesh; }

void MeshLayer::set_style(std::size_t mesh, const MeshStyle& style) { at(mesh).style = style; }

void MeshLayer::set_triangle_colours(std::size_t mesh, std::span<const Rgba8> colours) {
    Gpu& gpu = at(mesh);
    if (colours.empty()) {
        gpu.per_triangle = false;
        return;
    }
    if (colours.size() != gpu.triangles) {
        throw std::invalid_argument("render: " + std::to_string(colours.size()) + " triangle colours for a mesh of " +
                                    std::to_string(gpu.triangles) + " triangles");
    }
    const auto bytes = static_cast<GLsizeiptr>(colours.size() * sizeof(Rgba8));
    if (gpu.colour_buffer.get() == 0) {
        gpu.colour_buffer = gl::make_buffer();
        gpu.colour_texture = gl::make_texture();
        glBindBuffer(GL_TEXTURE_BUFFER, gpu.colour_buffer.get());
        glBufferData(GL_TEXTURE_BUFFER, bytes, colours.data(), GL_DYNAMIC_DRAW);
        glBindTexture(GL_TEXTURE_BUFFER, gpu.colour_texture.get());
        glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA8, gpu.colour_buffer.get());
        glBindTexture(GL_TEXTURE_BUFFER, 0);
    } else {
        glBindBuffer(GL_TEXTURE_BUFFER, gpu.colour_buffer.get());
        glBufferSubData(GL_TEXTURE_BUFFER, 0, bytes, colours.data());
    }
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    gpu.per_triangle = true;
    gl::check_errors("while uploading triangle colours");
}

void MeshLayer::draw(const FrameView& view, bool transparent) {
    bool any = false;
    for (const Gpu& gpu : meshes_) any = any || (gpu.style.visible && (gpu.style.colour.a < 1.0f) == transparent);
    if (!any) return;

    glUseProgram(program_.get());
    const Eigen::Matrix4f projection = gl::to_float(view.projection);
    glUniformMatrix4fv(u_projection_, 1, GL_FALSE, projection.data());
    glUniform1i(u_triangle_colours_, 0);
    glActiveTexture(GL_TEXTURE0);
    if (transparent) {
        glEnable(GL_BLEND);
        glDepthMask(GL_FALSE);
    }
    for (const Gpu& gpu : meshes_) {
        if (!gpu.style.visible || (gpu.style.colour.a < 1.0f) != transparent) continue;
        // model-view in double, then float: a 25 um vibration stays exact next to a 0.1 m scene.
        const Eigen::Matrix4f model_view = gl::to_float(view.view * gpu.pose);
        glUniformMatrix4fv(u_model_view_, 1, GL_FALSE, model_view.data());
        const Rgba& c = gpu.style.colour;
        glUniform4f(u_colour_, c.r, c.g, c.b, c.a);
        glUniform1i(u_per_triangle_, gpu.per_triangle ? 1 : 0);
        glUniform1f(u_ambient_, gpu.style.lit ? kAmbient : 1.0f);
        glUniform1f(u_diffuse_, gpu.style.lit ? kDiffuse : 0.0f);
        glBindTexture(GL_TEXTURE_BUFFER, gpu.per_triangle ? gpu.colour_texture.get() : 0);
        if (gpu.style.cull == Cull::none) {
            glDisable(GL_CULL_FACE);
        } else {
            glEnable(GL_CULL_FACE);
            glCullFace(gpu.style.cull == Cull::back ? GL_BACK : GL_FRONT);
        }
        glBindVertexArray(gpu.vao.get());
        glDrawElements(GL_TRIANGLES, gpu.index_count, GL_UNSIGNED_INT, nullptr);
    }
    glBindVertexArray(0);
    glDisable(GL_CULL_FACE);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    if (transparent) {
        glDisable(GL_BLEND);
        glDepthMask(GL_TRUE);
    }
}

}  // namespace peensim::render
