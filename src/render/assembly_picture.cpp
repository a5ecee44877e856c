#include "render/assembly_picture.h"

#include <sstream>
#include <vector>

#include "render/offscreen_context.h"
#include "render/png_io.h"
#include "render/render_view.h"
#include "render/renderer.h"
#include "scene/schema_defaults.h"

namespace peensim {

void draw_assembly_picture(const Model& model, const SimulationState& start, const std::string& png_path, int width_px, int height_px) {
    render::OffscreenContext context({.width = width_px, .height = height_px});
    render::Renderer renderer(context);
    const ModelView view = add_model(renderer, model);
    pose_model(renderer, view, model, start.time);
    const RenderDesc desc = model.description.render.value_or(default_render());
    const render::Camera camera = scene_camera(desc, view, static_cast<double>(width_px) / height_px);
    const ShotArrays& s = start.shots;
    std::vector<double> radii;  // m, per shot (a mix)
    if (model.has_size_mix())
        for (std::size_t i = 0; i < s.size(); ++i) radii.push_back(model.shot_sizes[s.size_class[i]].radius_m);
    const render::SphereSet shot{s.x, s.y, s.z, s.active, model.shot_sizes.front().radius_m, {0.85f, 0.86f, 0.9f, 1.0f}, radii};
    std::ostringstream title;
    title << model.description.name << " (" << model.description.source_file << "): the assembly at t = 0, ";
    if (s.size() > 0 && !model.has_size_mix())
        title << s.size() << " shot of " << model.shot_sizes.front().radius_m * 2e3 << " mm placed";
    else if (s.size() > 0)
        title << s.size() << " shot of " << model.min_shot_radius_m * 2e3 << "-" << model.max_shot_radius_m * 2e3 << " mm placed";
    else
        title << "no shot placed";
    std::vector<std::string> text{title.str()};
    for (const Component& c : model.components) text.push_back(c.name + ": " + role_name(c.role));
    render::RgbaImage image;
    renderer.render(camera, {.spheres = {&shot, 1}, .text = text}, image);
    render::write_png(png_path, image);
}

}  // namespace peensim
