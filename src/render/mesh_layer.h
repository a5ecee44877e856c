// Triangle meshes on the GPU: uploaded once, drawn every frame at their current pose with a
// headlight, optionally with one colour per triangle (impact maps). Internal to render/; the
// public entry point is Renderer.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "render/gl_objects.h"
#include "render/scene_types.h"

namespace peensim::render {

struct FrameView {
    Mat4 view;        // world -> camera
    Mat4 projection;  // camera -> clip
};

class MeshLayer {
public:
    MeshLayer();  // needs the target context current

    // Uploads the mesh (vertices as float, in its own frame). Returns its index. Throws
    // std::invalid_argument for a mesh without triangles.
    std::size_t add(const TriangleMesh& mesh, const MeshStyle& style);

    void set_pose(std::size_t mesh, const Mat4& world_from_mesh);
    void set_style(std::size_t mesh, const MeshStyle& style);
    // One colour per triangle (in the mesh's triangle order), or an empty span to go back to
    // the style's colour. Throws std::invalid_argument on a size mismatch.
    void set_triangle_colours(std::size_t mesh, std::span<const Rgba8> colours);

    std::size_t size() const { return meshes_.size(); }

    // Draws the opaque meshes (colour alpha 1), or the transparent ones (blended, depth test on,
    // no depth write, so they never hide what is drawn after them).
    void draw(const FrameView& view, bool transparent);

private:
    struct Gpu {
        gl::VertexArray vao;
        gl::Buffer vertices;
        gl::Buffer indices;
        gl::Buffer colour_buffer;  // per-triangle colours, a texture buffer
        gl::Texture colour_texture;
        GLsizei index_count = 0;
        std::size_t triangles = 0;
        bool per_triangle = false;
        MeshStyle style;
        Mat4 pose = Mat4::Identity();
    };
    Gpu& at(std::size_t mesh);

    gl::Program program_;
    GLint u_model_view_ = -1, u_projection_ = -1, u_colour_ = -1, u_per_triangle_ = -1;
    GLint u_triangle_colours_ = -1, u_ambient_ = -1, u_diffuse_ = -1;
    std::vector<Gpu> meshes_;
};

}  // namespace peensim::render
