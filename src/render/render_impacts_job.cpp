#include "render/render_impacts_job.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "analysis/area_percentile.h"
#include "app/report_errors.h"
#include "app/run/run_job.h"
#include "common/csv_column.h"
#include "model/model.h"
#include "render/map_mesh.h"
#include "render/png_io.h"
#include "render/render_view.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// The smoothed columns (app/analysis/map_smoothing.h): the raw per-triangle ones show the tessellation.
const std::array<MapField, 3> kFields{{
    {"impacts", "impacts_per_mm2_s_smoothed", "impacts per mm2 per s"},
    {"speed", "mean_vn_mps_smoothed", "mean normal speed (m/s)"},
    {"coverage", "coverage_smoothed", "coverage (SAE J2277)"},
}};
constexpr const char* kRadiusColumn = "smoothing_radius_mm";
// Sub-triangles of the map mesh: no longer than the smoothing radius / this (the field varies no
// faster; render/map_mesh.h).
constexpr double kMapSpacingPerRadius = 3.0;

const std::array<MapView, 4> kViews{{
    {"front-above", Vec3(0.34, 0.81, -0.47)},
    {"back-above", Vec3(-0.34, -0.81, -0.47)},
    {"from below (sonotrode side)", Vec3(0.2, 0.3, 1.0)},
    {"side", Vec3(-1.0, 0.15, -0.2)},
}};

// One column of <component>_triangles.csv, NaN for an empty cell; a missing file or column says
// to analyse the run (again).
std::vector<double> read_column(const fs::path& csv, const std::string& column) {
    const std::string run = csv.parent_path().parent_path().string();
    if (!fs::exists(csv)) throw std::runtime_error(csv.string() + ": not found (run `peensim analyze " + run + "` first)");
    try {
        return read_csv_numbers(csv, column);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(std::string(e.what()) + " (written by an older peensim? run `peensim analyze " + run + "` again)");
    }
}

// The colour scale's top: the value that 98 % of the part's area does not exceed (values above are
// drawn in the top colour).
double robust_top(const TriangleMesh& mesh, const std::vector<double>& values) {
    std::vector<std::pair<double, double>> by_value;  // (value, area m2)
    for (std::size_t t = 0; t < values.size(); ++t)
        if (std::isfinite(values[t]))
            by_value.emplace_back(values[t],
                                  0.5 * (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0)).norm());
    return area_percentile(std::move(by_value), 0.98);
}

std::string percent_text(double fraction) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g %%", fraction * 100.0);
    return text;
}

// The target the run's analysis measured against (analysis/figures.json), else 98 % (SAE J2277).
double analysed_target(const fs::path& dir) {
    std::ifstream in(dir / "analysis" / "figures.json");
    if (!in) return 0.98;
    const auto figures = nlohmann::json::parse(in, nullptr, false);
    if (figures.is_discarded()) return 0.98;
    const auto it = figures.find("target_coverage");
    return it != figures.end() && it->is_number() ? it->get<double>() : 0.98;
}

}  // namespace

// The coverage scale's top: the smoothed coverage's maximum (smoothing leaves no single-triangle
// spike to set it), rounded up to two significant digits so that the label reads well.
double coverage_scale_top(const std::vector<double>& values) {
    double max = 0.0;
    for (double v : values)
        if (std::isfinite(v)) max = std::max(max, v);
    if (!(max > 0.0)) return 0.01;  // nothing covered: a 1 % scale, all of it at the bottom
    const double unit = std::pow(10.0, std::floor(std::log10(max)) - 1.0);
    return std::min(1.0, std::ceil(max / unit * (1.0 - 1e-12)) * unit);
}

std::span<const MapField> map_fields() { return kFields; }
std::span<const MapView> map_views() { return kViews; }

std::vector<render::Rgba8> field_colours(std::span<const double> values, double max) {
    const render::ColourMap map = render::ColourMap::viridis();
    std::vector<render::Rgba8> colours;
    colours.reserve(values.size());
    for (double v : values) colours.push_back(std::isfinite(v) ? map.map8(v, 0.0, max) : render::Rgba8{128, 128, 128, 255});
    return colours;
}

int render_impacts_job(const RenderImpactsOptions& options, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] {
        const fs::path dir(options.output_dir);
        const fs::path scene_path = dir / "scene.resolved.yaml";
        if (!fs::exists(scene_path))
            throw std::runtime_error(options.output_dir + ": not a peensim run directory (no scene.resolved.yaml)");
        std::vector<const MapField*> fields;
        for (const MapField& f : kFields)
            if (options.fields.empty() || std::find(options.fields.begin(), options.fields.end(), f.name) != options.fields.end())
                fields.push_back(&f);
        for (const std::string& name : options.fields)
            if (std::none_of(kFields.begin(), kFields.end(), [&](const MapField& f) { return f.name == name; }))
                throw InputError({}, "--field", "unknown field '" + name + "'; expected impacts, speed or coverage");
        const double target = options.coverage_target.value_or(analysed_target(dir));
        if (!(target > 0.0 && target <= 1.0))
            throw InputError({}, "--target", "expected a coverage in (0, 1] (e.g. 0.98 or 98 %), got " + std::to_string(target));

        const auto model = compile_model(parse_scene_file(scene_path.string()));
        const int tile_w = options.width_px / 2, tile_h = options.height_px / 2;
        render::OffscreenContext context({.width = tile_w, .height = tile_h});
        render::Renderer renderer(context);
        const ModelView view = add_model(renderer, *model);
        render::RgbaImage tile, image;
        int written = 0;
        for (std::size_t i = 0; i < model->components.size(); ++i) {
            const Component& part = model->components[i];
            if (!part.logged) continue;
            const fs::path csv = dir / "analysis" / (part.name + "_triangles.csv");
            const std::vector<Vec3> points = world_vertices(part);
            const std::vector<double> radius_mm = read_column(csv, kRadiusColumn);
            const double radius_m = radius_mm.empty() ? 0.0 : radius_mm.front() * 1e-3;
            if (!(radius_m > 0.0)) throw std::runtime_error(csv.string() + ": no smoothing radius (rerun the analysis)");
            char radius_line[64];
            std::snprintf(radius_line, sizeof radius_line, "smoothed over a %.3g mm radius", radius_m * 1e3);
            // Only the part, drawn as its map mesh: it is seen from all sides, with nothing in front of it.
            for (std::size_t j = 0; j < model->components.size(); ++j) {
                render::MeshStyle style;
                style.colour = role_colour(model->components[j].role);
                style.visible = false;
                renderer.set_style(view.meshes[j], style);
            }
            std::optional<render::MeshId> map_id;
            for (const MapField* field : fields) {
                const std::vector<double> values = read_column(csv, field->column);
                if (values.size() != part.mesh->triangle_count())
                    throw std::runtime_error(csv.string() + ": " + std::to_string(values.size()) + " triangles, the mesh has " +
                                             std::to_string(part.mesh->triangle_count()) + " (a different mesh? rerun the analysis)");
                if (field->name == "coverage" && std::all_of(values.begin(), values.end(), [](double v) { return std::isnan(v); })) {
                    out << part.name << ": no coverage (the material has no yield_stress)\n";
                    continue;
                }
                const bool coverage = field->name == "coverage";
                double max = coverage ? coverage_scale_top(values) : robust_top(*part.mesh, values);
                if (!(max > 0.0)) max = 1.0;
                const MapMesh map = map_mesh(*part.mesh, values, radius_m / kMapSpacingPerRadius);
                if (!map_id) {  // the same sub-triangles for every field of the part
                    map_id = renderer.add_mesh(map.mesh, {.colour = role_colour(part.role)});
                    const Pose pose = part.kinematics.pose(SimTime{});
                    renderer.set_pose(*map_id, render::make_pose(pose.rotation, pose.translation));
                }
                renderer.set_triangle_colours(*map_id, field_colours(map.values, max));
                render::ColourBar bar{render::ColourMap::viridis(), 0.0, max, field->title};
                if (coverage) {  // in per cent, the target marked
                    bar.title += ", %";
                    bar.label_scale = 100.0;
                    bar.label_unit = " %";
                    bar.mark = target;
                    bar.mark_label = "target " + percent_text(target);
                }
                image.resize(2 * tile_w, 2 * tile_h);
                for (std::size_t v = 0; v < kViews.size(); ++v) {
                    const render::Camera camera =
                        render::Camera::framing_points(points, static_cast<double>(tile_w) / tile_h, kViews[v].direction);
                    const std::vector<std::string> text{part.name + ": " + field->title, kViews[v].name, radius_line};
                    renderer.render(camera, {.text = text, .colour_bar = &bar}, tile);
                    render::blit(tile, image, static_cast<int>(v % 2) * tile_w, static_cast<int>(v / 2) * tile_h);
                }
                const fs::path png = dir / "analysis" / (part.name + "_map_" + field->name + ".png");
                render::write_png(png.string(), image);
                out << "wrote " << png.string() << "\n";
                ++written;
            }
            if (map_id) renderer.set_style(*map_id, {.visible = false});
        }
        if (written == 0) throw std::runtime_error(options.output_dir + ": no logged component to draw");
        return 0;
    });
}

}  // namespace peensim
