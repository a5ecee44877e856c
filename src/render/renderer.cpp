#include "render/renderer.h"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "render/glow_layer.h"
#include "render/mesh_layer.h"
#include "render/overlay_layer.h"
#include "render/sphere_layer.h"

namespace peensim::render {

namespace {

constexpr int kTextHeightDivisor = 36;  // text height = image height / this
constexpr int kMinTextHeightPx = 10;

FontAtlas load_font(const RenderOptions& options, int image_height) {
    std::string path = options.font_path;
    if (path.empty()) {
        const std::optional<std::string> found = find_default_font();
        if (!found) {
            throw std::runtime_error(
                "render: no font for the text overlay: DejaVuSans.ttf is not in /usr/share/fonts "
                "(install fonts-dejavu-core, or set a font path, or turn the overlay off)");
        }
        path = *found;
    }
    const int px = options.text_height_px > 0 ? options.text_height_px : std::max(kMinTextHeightPx, image_height / kTextHeightDivisor);
    return FontAtlas(path, px);
}

}  // namespace

struct Renderer::Layers {
    MeshLayer meshes;
    SphereLayer spheres;
    GlowLayer glows;
    std::optional<OverlayLayer> overlay;
};

Renderer::Renderer(OffscreenContext& context, const RenderOptions& options) : context_(context), options_(options) {
    context_.make_current();
    layers_ = std::make_unique<Layers>();
    if (options_.overlay) layers_->overlay.emplace(load_font(options_, context_.height()));
}

Renderer::~Renderer() {
    // GL objects must die while their context is current.
    context_.make_current();
    layers_.reset();
}

MeshId Renderer::add_mesh(const TriangleMesh& mesh, const MeshStyle& style) {
    context_.make_current();
    return layers_->meshes.add(mesh, style);
}

void Renderer::set_pose(MeshId mesh, const Mat4& world_from_mesh) { layers_->meshes.set_pose(mesh, world_from_mesh); }

void Renderer::set_style(MeshId mesh, const MeshStyle& style) { layers_->meshes.set_style(mesh, style); }

void Renderer::set_triangle_colours(MeshId mesh, std::span<const Rgba8> colours) {
    context_.make_current();
    layers_->meshes.set_triangle_colours(mesh, colours);
}

void Renderer::draw(const Camera& camera, const FrameContent& content) {
    if (!layers_->overlay && (!content.text.empty() || content.colour_bar != nullptr || !content.labels.empty())) {
        throw std::logic_error("render: text or a colour bar requested from a renderer made without overlay");
    }
    context_.make_current();
    context_.bind_draw_target();
    const int w = context_.width();
    const int h = context_.height();
    const FrameView view{camera.view_matrix(), camera.projection_matrix(static_cast<double>(w) / static_cast<double>(h))};

    const Rgba& bg = options_.background;
    glClearColor(bg.r, bg.g, bg.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    // Colour blends by alpha; the frame's own alpha stays 1 so PNGs and video are opaque.
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);

    layers_->meshes.draw(view, /*transparent=*/false);
    for (const SphereSet& set : content.spheres) layers_->spheres.draw(view, set);
    layers_->spheres.draw(view, content.markers);
    layers_->glows.draw(view, w, h, content.glows);
    layers_->meshes.draw(view, /*transparent=*/true);
    if (layers_->overlay) layers_->overlay->draw(w, h, content.text, content.colour_bar, content.labels);
    gl::check_errors("while drawing a frame");
}

void Renderer::render(const Camera& camera, const FrameContent& content, RgbaImage& image) {
    draw(camera, content);
    context_.read_pixels(image);
}

}  // namespace peensim::render
