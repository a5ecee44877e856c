#include "render/region_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <span>

#include "analysis/regions.h"
#include "app/analysis/analysis_format.h"
#include "app/report_errors.h"
#include "collision/mesh_collider.h"
#include "geometry/mesh_checks.h"
#include "kernels/trajectory.h"
#include "model/facet_reach.h"
#include "model/model.h"
#include "model/shot_cavity.h"
#include "render/close_up.h"
#include "render/png_io.h"
#include "render/render_impacts_job.h"
#include "render/render_view.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

constexpr std::array<render::Rgba8, 12> kPalette{{
    {230, 97, 1, 255},
    {94, 60, 153, 255},
    {27, 158, 119, 255},
    {231, 41, 138, 255},
    {102, 166, 30, 255},
    {230, 171, 2, 255},
    {31, 120, 180, 255},
    {166, 86, 40, 255},
    {251, 154, 153, 255},
    {0, 170, 170, 255},
    {202, 178, 214, 255},
    {253, 220, 120, 255},
}};
constexpr render::Rgba8 kHighlightColour{235, 70, 40, 255};
// A region's name is drawn in a view only if its surface there faces the camera within ~75 deg.
constexpr double kLabelFacingCos = 0.25;

// Where a region's name may go: the centres of its triangles (world), nearest the centroid of its
// area first, each with its facing (world, unit). A view names the region at the first of them that
// faces the camera and that the part does not hide: a region seen from the back, or in part behind
// another piece of the part, is still named where the view shows it, and never where it does not.
struct PlacedLabel {
    struct Spot {
        Vec3 point_m;  // world
        Vec3 normal;   // world, unit
    };
    std::vector<Spot> spots;
    std::string text;
    render::Rgba8 colour;
};

// Spots a view tries before it gives up on naming a region (each costs a ray through the part's BVH).
constexpr std::size_t kLabelSpots = 48;

Vec3 centroid(const TriangleMesh& mesh, std::size_t t) { return (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0; }

// A label for the triangles with weights w (their share of the region), or nothing for no area.
std::optional<PlacedLabel> place_label(const Component& part, const std::vector<RegionShare>& shares, std::string text,
                                       render::Rgba8 colour) {
    const TriangleMesh& mesh = *part.mesh;
    Vec3 sum = Vec3::Zero();
    double area = 0.0;
    for (const RegionShare& s : shares) {
        const auto t = static_cast<std::size_t>(s.triangle);
        const double a = s.fraction * triangle_area(mesh, t);
        sum += a * centroid(mesh, t);
        area += a;
    }
    if (!(area > 0.0)) return std::nullopt;
    const Vec3 c = sum / area;
    std::vector<std::pair<double, std::size_t>> nearest;  // (squared distance to c, triangle)
    for (const RegionShare& s : shares)
        if (s.fraction > 0.0)
            nearest.emplace_back((centroid(mesh, static_cast<std::size_t>(s.triangle)) - c).squaredNorm(),
                                 static_cast<std::size_t>(s.triangle));
    const std::size_t kept = std::min(nearest.size(), kLabelSpots);
    std::partial_sort(nearest.begin(), nearest.begin() + static_cast<std::ptrdiff_t>(kept), nearest.end());
    const Pose pose = part.kinematics.pose(SimTime{});
    PlacedLabel label{{}, std::move(text), colour};
    for (std::size_t k = 0; k < kept; ++k) {
        const std::size_t t = nearest[k].second;
        label.spots.push_back({pose.to_world(centroid(mesh, t)), pose.rotation * triangle_normal(mesh, t)});
    }
    return label;
}

// Whether the part itself hides `point_m` (world, on its surface) from the eye at `eye_m` (world):
// a region may face the camera and still lie behind another piece of the part (a bracket's inner
// corner), and its name drawn there names nothing the view shows. A thin ray (a sphere of a
// millionth of the distance) swept from the eye to 2 % short of the point, where its own surface is.
bool hidden_by_the_part(const Component& part, const Vec3& eye_m, const Vec3& point_m) {
    const Pose pose = part.kinematics.pose(SimTime{});
    const Vec3 from = pose.to_component(eye_m), to = pose.to_component(point_m);
    const Trajectory ray{from, to - from, Vec3::Zero(), 0.0};
    MeshCollider::Hit hit;
    MeshCollider::SweepCounters counters;
    return part.collider->first_hit(ray, 1e-6 * (to - from).norm(), 0.0, 0.98, hit, counters) != ToiStatus::miss;
}

// Draws component ci alone in its triangle colours from the four map views, tiled 2 x 2 into `image`
// (the last replaced by `close_up` when given).
void draw_four_views(const Model& model, std::size_t ci, const std::vector<render::Rgba8>& colours, const std::vector<PlacedLabel>& labels,
                     const std::vector<std::string>& title, int width_px, int height_px, render::RgbaImage& image,
                     const std::optional<CloseUp>& close_up = std::nullopt) {
    const int tile_w = width_px / 2, tile_h = height_px / 2;
    render::OffscreenContext context({.width = tile_w, .height = tile_h});
    render::Renderer renderer(context);
    const ModelView view = add_model(renderer, model);
    for (std::size_t j = 0; j < model.components.size(); ++j) {
        render::MeshStyle style;
        style.colour = role_colour(model.components[j].role);
        style.visible = j == ci;
        renderer.set_style(view.meshes[j], style);
    }
    renderer.set_triangle_colours(view.meshes[ci], colours);
    const std::vector<Vec3> points = world_vertices(model.components[ci]);
    image.resize(2 * tile_w, 2 * tile_h);
    render::RgbaImage tile;
    std::vector<render::Label> placed;
    const std::span<const MapView> views = map_views();
    for (std::size_t v = 0; v < views.size(); ++v) {
        const bool close = close_up && v + 1 == views.size();
        render::Camera camera =
            close ? render::Camera::framing_points(close_up->points_m, static_cast<double>(tile_w) / tile_h, close_up->direction)
                  : render::Camera::framing_points(points, static_cast<double>(tile_w) / tile_h, views[v].direction);
        if (close) {
            // The whole part in the depth range: the camera may stand inside its bounds.
            Vec3 lo = points.front(), hi = lo;
            for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
            camera.fit_depth_range(lo, hi);
        }
        placed.clear();
        for (const PlacedLabel& l : labels)
            for (const PlacedLabel::Spot& spot : l.spots) {
                // Faces away, or so nearly edge-on (beyond ~75 deg) that the view shows a sliver of it.
                if (!(spot.normal.dot((camera.position_m - spot.point_m).normalized()) > kLabelFacingCos)) continue;
                const auto px = camera.project_to_pixel(spot.point_m, tile_w, tile_h);
                if (!px || px->x() < 0.0 || px->y() < 0.0 || px->x() >= tile_w || px->y() >= tile_h) continue;
                if (hidden_by_the_part(model.components[ci], camera.position_m, spot.point_m)) continue;
                placed.push_back({static_cast<float>(px->x()), static_cast<float>(px->y()), l.text, l.colour});
                break;
            }
        std::vector<std::string> text = title;
        text.push_back(close ? close_up->name : views[v].name);
        renderer.render(camera, {.text = text, .labels = placed}, tile);
        render::blit(tile, image, static_cast<int>(v % 2) * tile_w, static_cast<int>(v / 2) * tile_h);
    }
}

// A triangle's colour darkened by the share of it no shot reaches (all of it: kUnreachableColour).
render::Rgba8 shade_unreachable(render::Rgba8 c, double reach) {
    const double r = std::clamp(reach, 0.0, 1.0);
    const auto mix = [r](std::uint8_t x, std::uint8_t dark) { return static_cast<std::uint8_t>(std::lround(r * x + (1.0 - r) * dark)); };
    return {mix(c.r, kUnreachableColour.r), mix(c.g, kUnreachableColour.g), mix(c.b, kUnreachableColour.b), 255};
}

double unreachable_area(const TriangleMesh& mesh, const std::vector<double>& reach) {
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) area += (1.0 - reach[t]) * triangle_area(mesh, t);
    return area;
}

}  // namespace

render::Rgba8 region_colour(std::size_t r) { return kPalette[r % kPalette.size()]; }

render::Rgba8 excluded_colour(render::Rgba8 c) {
    const auto dim = [](std::uint8_t x) { return static_cast<std::uint8_t>((x + 2 * 120) / 3); };
    return {dim(c.r), dim(c.g), dim(c.b), 255};
}

int render_regions_job(const RenderRegionsOptions& o, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] {
        const fs::path input(o.input);
        const bool run_dir = fs::is_directory(input);
        if (run_dir && !fs::exists(input / "scene.resolved.yaml"))
            throw std::runtime_error(o.input + ": not a peensim run directory (no scene.resolved.yaml) nor a scene file");
        if (run_dir && !o.overrides.empty())
            throw InputError({"--set"}, "", "a run directory's scene is the one it ran: expected --set only with a scene file");
        const SceneDescription scene =
            run_dir ? parse_scene_file((input / "scene.resolved.yaml").string()) : parse_scene_file(o.input, o.overrides);
        const fs::path dir = !o.output_dir.empty() ? fs::path(o.output_dir) : run_dir ? input / "analysis" : fs::path(".");
        fs::create_directories(dir);
        const auto model = compile_model(scene);
        std::unique_ptr<ShotCavity> cavity;
        if (model->sonotrode >= 0) {
            Random rng(model->seed);
            cavity = std::make_unique<ShotCavity>(*model, rng);
        }
        int written = 0;
        render::RgbaImage image;
        for (std::size_t ci = 0; ci < scene.components.size(); ++ci) {
            const ComponentDesc& desc = scene.components[ci];
            if (!is_logged(scene, desc)) continue;
            const Component& part = model->components[ci];
            const TriangleMesh& mesh = *part.mesh;
            const RegionSet regions(mesh, desc.regions);
            const std::vector<double> reach = reachable_fractions(*model, ci, cavity.get());
            std::vector<render::Rgba8> colours(mesh.triangle_count(), kNoRegionColour);
            for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
                const int r = regions.dominant_region(t);
                if (r >= 0) {
                    const auto ri = static_cast<std::size_t>(r);
                    colours[t] = regions.excluded(ri) ? excluded_colour(region_colour(ri)) : region_colour(ri);
                }
                colours[t] = shade_unreachable(colours[t], reach[t]);
            }
            std::vector<PlacedLabel> labels;
            out << desc.name << ": " << regions.size() << " region(s)\n";
            for (std::size_t r = 0; r < regions.size(); ++r) {
                const std::string name = regions.name(r) + (regions.excluded(r) ? " (excluded)" : "");
                out << "  " << name << ": " << fmt(regions.area_m2(r) * 1e6) << " mm2 on " << regions.shares(r).size() << " triangles\n";
                if (regions.shares(r).empty()) continue;
                // White names over a dark shadow: readable on every region colour.
                if (auto l = place_label(part, regions.shares(r), name, render::Rgba8{255, 255, 255, 255})) labels.push_back(std::move(*l));
            }
            const double total = [&] {
                double a = 0.0;
                for (std::size_t t = 0; t < mesh.triangle_count(); ++t) a += triangle_area(mesh, t);
                return a;
            }();
            const double dark = unreachable_area(mesh, reach);
            out << "  out of the shot's reach: " << fmt(dark * 1e6) << " mm2 (" << fmt(100.0 * dark / total, 3) << " % of "
                << fmt(total * 1e6) << " mm2)\n";
            const std::vector<std::string> title{desc.name + ": " + std::to_string(regions.size()) +
                                                 " regions (grey: in none; dark: out of the shot's reach, " + fmt(100.0 * dark / total, 3) +
                                                 " % of the area)"};
            draw_four_views(*model, ci, colours, labels, title, o.width_px, o.height_px, image);
            const fs::path png = dir / (desc.name + "_region_map.png");
            render::write_png(png.string(), image);
            out << "wrote " << png.string() << "\n";
            ++written;
        }
        if (written == 0) throw std::runtime_error(o.input + ": no logged component to draw");
        return 0;
    });
}

void draw_region_highlight(const Model& model, std::size_t ci, std::span<const double> weight, std::span<const double> reach,
                           const std::string& label, const std::string& title, const std::string& png_path, int width_px, int height_px) {
    const Component& part = model.components[ci];
    std::vector<render::Rgba8> colours(part.mesh->triangle_count(), kNoRegionColour);
    std::vector<RegionShare> shares;
    for (std::size_t t = 0; t < colours.size(); ++t) {
        if (weight[t] >= 0.5) colours[t] = kHighlightColour;
        if (weight[t] > 0.0) shares.push_back({static_cast<int>(t), weight[t]});
        if (!reach.empty()) colours[t] = shade_unreachable(colours[t], reach[t]);
    }
    std::vector<PlacedLabel> labels;
    if (!shares.empty())
        if (auto l = place_label(part, shares, label, render::Rgba8{255, 255, 255, 255})) labels.push_back(std::move(*l));
    render::RgbaImage image;
    draw_four_views(model, ci, colours, labels, {title}, width_px, height_px, image, close_up_of(part, weight, label));
    render::write_png(png_path, image);
}

}  // namespace peensim
