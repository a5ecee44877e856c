#include "render/assembly_picture.h"

#include <cstdint>
#include <sstream>
#include <vector>

#include "render/offscreen_context.h"
#include "render/png_io.h"
#include "render/render_view.h"
#include "render/renderer.h"
#include "scene/schema_defaults.h"

namespace peensim {

namespace {

// A mark's ball: big enough to see in a chamber-wide view even half inside a wall, 3 % of the
// assembly's diagonal.
constexpr double kMarkShareOfDiagonal = 0.03;
constexpr double kPixelsPerCharacter = 11.5;  // px: the overlay font's mean advance, to wrap the messages

// `text` in lines of at most `width` characters, broken between words (a word longer than that
// stays whole).
std::vector<std::string> wrapped(const std::string& text, std::size_t width) {
    std::vector<std::string> lines{""};
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find(' ', start);
        if (end == std::string::npos) end = text.size();
        const std::string word = text.substr(start, end - start);
        if (!lines.back().empty() && lines.back().size() + 1 + word.size() > width) lines.push_back("    ");
        lines.back() += (lines.back().empty() || lines.back() == "    " ? "" : " ") + word;
        start = end + 1;
    }
    return lines;
}

}  // namespace

void draw_assembly_picture(const Model& model, const SimulationState& start, const std::vector<AssemblyIssue>& issues,
                           const std::string& png_path, int width_px, int height_px) {
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
    // The points where meshes cross: a red ball each, numbered at the point and in the list.
    std::vector<double> mark_x, mark_y, mark_z;
    std::vector<std::uint8_t> mark_active;
    std::vector<render::Label> labels;
    for (const AssemblyIssue& issue : issues) {
        if (!issue.at_m) continue;
        const Vec3& p = *issue.at_m;
        mark_x.push_back(p.x()), mark_y.push_back(p.y()), mark_z.push_back(p.z()), mark_active.push_back(1);
        const std::string number = std::to_string(mark_x.size());
        const auto width = static_cast<std::size_t>(width_px / kPixelsPerCharacter);
        for (const std::string& line : wrapped(number + (issue.error ? " (error): " : " (warning): ") + issue.message, width))
            text.push_back(line);
        if (const auto px = camera.project_to_pixel(p, width_px, height_px))
            labels.push_back({static_cast<float>(px->x()), static_cast<float>(px->y()) - 24.0f, number, render::Rgba8{255, 80, 60, 255}});
    }
    const double mark_radius = kMarkShareOfDiagonal * (model.world_hi - model.world_lo).norm();
    const render::SphereSet marks{mark_x, mark_y, mark_z, mark_active, mark_radius, {1.0f, 0.15f, 0.1f, 1.0f}, {}};
    const render::SphereSet sets[2] = {shot, marks};
    render::RgbaImage image;
    renderer.render(camera, {.spheres = {sets, mark_x.empty() ? 1u : 2u}, .text = text, .labels = labels}, image);
    render::write_png(png_path, image);
}

}  // namespace peensim
