// The frame renderer: meshes at their poses, shot, impact flashes and the 2-D overlay, drawn
// into an OffscreenContext. This is the render/ entry point the simulator uses:
//
//   OffscreenContext context({.width = 1280, .height = 720});
//   Renderer renderer(context);
//   const MeshId part = renderer.add_mesh(part_mesh, {.colour = {0.8f, 0.6f, 0.3f, 1.0f}});
//   const MeshId chamber = renderer.add_mesh(chamber_mesh, {.cull = Cull::back});
//   const Camera camera = Camera::framing(chamber_min, chamber_max, 1280.0 / 720.0);
//   ...per frame:
//   renderer.set_pose(part, make_pose(pose.rotation, pose.translation));
//   const SphereSet shot{state.shots.x, state.shots.y, state.shots.z, state.shots.active, radius};
//   renderer.render(camera, {.spheres = {&shot, 1}, .markers = flashes, .text = lines, .colour_bar = &bar}, image);
//   write_png(path, image);   or   encoder.add_frame(image);
//
// Meshes are uploaded once (add_mesh); a frame only sends poses, sphere centres, markers and
// text, into buffers that are reused, so rendering allocates nothing once it has warmed up.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "geometry/triangle_mesh.h"
#include "render/camera.h"
#include "render/image.h"
#include "render/offscreen_context.h"
#include "render/scene_types.h"

namespace peensim::render {

struct RenderOptions {
    Rgba background{0.11f, 0.12f, 0.14f, 1.0f};
    // Text and colour bar. false: no font is needed, and a frame asking for text or a colour
    // bar is refused (std::logic_error).
    bool overlay = true;
    std::string font_path{};  // empty: find_default_font() (DejaVu Sans)
    int text_height_px = 0;   // 0: image height / 36, at least 10 px
};

struct FrameContent {
    std::span<const SphereSet> spheres{};     // shot (opaque)
    std::span<const ImpactMarker> markers{};  // flashes (blended)
    std::span<const ImpactGlow> glows{};      // impacts as sprites of a size in pixels (blended, over the markers)
    std::span<const std::string> text{};      // lines at the top left
    const ColourBar* colour_bar = nullptr;    // at the right, or none
    std::span<const Label> labels{};          // words placed in the frame
};

using MeshId = std::size_t;

class Renderer {
public:
    // Compiles the shaders and, when options.overlay is set, loads the font. Throws
    // std::runtime_error with a plain message when the font is missing ("install
    // fonts-dejavu-core or set a font path") or cannot be loaded. The context must outlive
    // the renderer.
    explicit Renderer(OffscreenContext& context, const RenderOptions& options = {});
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Uploads the mesh once (vertices in m, in the mesh's own frame); its pose starts at
    // identity. Throws std::invalid_argument for a mesh without triangles.
    MeshId add_mesh(const TriangleMesh& mesh, const MeshStyle& style);
    void set_pose(MeshId mesh, const Mat4& world_from_mesh);  // see make_pose
    void set_style(MeshId mesh, const MeshStyle& style);
    // One colour per triangle in the mesh's triangle order, or empty to go back to the style
    // colour (std::invalid_argument on a size mismatch). Uploaded now, kept until replaced.
    void set_triangle_colours(MeshId mesh, std::span<const Rgba8> colours);

    // Draws one frame: opaque meshes, spheres, markers, glows, transparent meshes, overlay; then
    // reads it into `image` (resized to the context's size, top row first).
    void render(const Camera& camera, const FrameContent& content, RgbaImage& image);
    // The same without the read-back, for a caller that reads the context itself.
    void draw(const Camera& camera, const FrameContent& content);

    OffscreenContext& context() { return context_; }

private:
    struct Layers;
    OffscreenContext& context_;
    RenderOptions options_;
    std::unique_ptr<Layers> layers_;
};

}  // namespace peensim::render
