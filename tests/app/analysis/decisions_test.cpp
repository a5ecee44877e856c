// What the report concludes: the Avrami rate and time to 98 % with their intervals (exact on
// known curves), the facets no shot can reach (the gear's bore, its bottom lands against the shot's
// size), the analysis window, the report's decisions agreeing with its tables and figures, the
// HTML page, and the region map's colours where the regions are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "analysis/impact_log_reader.h"
#include "analysis/student_t.h"
#include "app/analysis/analyze_job.h"
#include "app/run/run_job.h"
#include "common/random.h"
#include "geometry/mesh_checks.h"
#include "model/facet_reach.h"
#include "model/model.h"
#include "model/shot_cavity.h"
#include "output/markdown_html.h"
#include "render/camera.h"
#include "render/png_io.h"
#include "render/region_map.h"
#include "render/render_impacts_job.h"
#include "render/render_view.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::read_file;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

const std::string kSource = PEENSIM_SOURCE_DIR;

}  // namespace

namespace {

// The gear of the shipped scene with shot of `diameter` (text), its reach per triangle.
struct GearReach {
    std::shared_ptr<const Model> model;
    std::size_t gear = 0;
    std::vector<double> reach;
};

GearReach gear_reach(const std::string& diameter) {
    GearReach g;
    g.model = compile_model(parse_scene_file(kSource + "/scenes/gear.yaml", {"shot.diameter=" + diameter}));
    g.gear = static_cast<std::size_t>(g.model->component_index("gear"));
    Random rng(g.model->seed);
    ShotCavity cavity(*g.model, rng);
    g.reach = reachable_fractions(*g.model, g.gear, &cavity);
    return g;
}

// Mean reach (area-weighted) of the gear's triangles whose centroids lie within [r0, r1] of its
// axis (y, through the origin of its frame) and whose normals make `normal_test` true.
template <class Test>
double mean_reach(const GearReach& g, double r0, double r1, Test normal_test) {
    const TriangleMesh& mesh = *g.model->components[g.gear].mesh;
    double sum = 0.0, area = 0.0;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 c = (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
        const double r = std::hypot(c.x(), c.z());
        const Vec3 n = triangle_normal(mesh, t);
        if (r < r0 || r > r1 || !normal_test(n, c)) continue;
        sum += g.reach[t] * triangle_area(mesh, t);
        area += triangle_area(mesh, t);
    }
    EXPECT_GT(area, 0.0);
    return sum / area;
}

}  // namespace

TEST(FacetReach, TheBoreIsOutOfReachAndTheBottomLandsNeedSmallShot) {
    const auto radial_in = [](const Vec3& n, const Vec3& c) { return n.dot(Vec3(c.x(), 0, c.z()).normalized()) < -0.99; };
    const auto radial_out = [](const Vec3& n, const Vec3& c) { return n.dot(Vec3(c.x(), 0, c.z()).normalized()) > 0.99; };
    const auto end_face = [](const Vec3& n, const Vec3&) { return std::abs(n.y()) > 0.99; };
    // Module 2 mm, 20 teeth: bore r = 5 mm (the axle fills it), root r = 17.5 mm, tip r = 22 mm.
    // The tooth space at the root is about 2.2 mm wide (the flank is radial below the base circle
    // r_b = 18.8 mm, where the space is 2.39 mm): a 3 mm ball cannot touch its bottom, a 1 mm ball can.
    for (const char* d : {"1 mm", "2 mm", "3 mm"}) {
        const GearReach g = gear_reach(d);
        EXPECT_EQ(mean_reach(g, 4.9e-3, 5.1e-3, radial_in), 0.0) << d;     // the bore
        EXPECT_EQ(mean_reach(g, 21.9e-3, 22.1e-3, radial_out), 1.0) << d;  // the tips
        EXPECT_GT(mean_reach(g, 8e-3, 16e-3, end_face), 0.99) << d;        // the end faces, clear of the teeth
    }
    EXPECT_GT(mean_reach(gear_reach("1 mm"), 17.4e-3, 17.6e-3, radial_out), 0.3);
    EXPECT_EQ(mean_reach(gear_reach("3 mm"), 17.4e-3, 17.6e-3, radial_out), 0.0);
}

namespace {

RunOptions short_run(const std::string& scene, const fs::path& dir, const std::string& duration) {
    RunOptions o;
    o.scene_path = kSource + "/scenes/" + scene;
    o.output_dir = dir.string();
    o.overrides = {"process.duration=" + duration};
    o.progress = false;
    o.analyze = false;
    return o;
}

nlohmann::json figures(const fs::path& dir) {
    std::ifstream in(dir / "analysis" / "figures.json");
    return nlohmann::json::parse(in);
}

}  // namespace

TEST(AnalyzeWindow, ImpactsOutsideTheWindowOrTooSlowAreLeftOut) {
    TempDir dir;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(short_run("rod.yaml", dir.path, "0.2 s"), out, err), kExitOk) << err.str();
    std::uint64_t all = 0, window = 0, fast = 0;
    {
        ImpactLogReader reader((dir.path / "impacts.csv").string());
        for (ImpactRow row; reader.next(row);) {
            ++all;
            window += row.time_s >= 0.05 && row.time_s <= 0.15;
            fast += row.vn_in_m_per_s >= 2.0;
        }
    }
    ASSERT_GT(all, window);
    ASSERT_GT(all, fast);
    AnalyzeOptions o;
    o.from_s = 0.05;
    o.to_s = 0.15;
    ASSERT_EQ(analyze_job(dir.path.string(), out, err, o), kExitOk) << err.str();
    auto j = figures(dir.path);
    EXPECT_EQ(j["components"][0]["impacts"].get<std::uint64_t>(), window);
    EXPECT_NEAR(j["duration_s"].get<double>(), 0.1, 1e-15);
    EXPECT_NEAR(j["components"][0]["impact_rate_per_s"].get<double>(), window / 0.1, 1e-6);
    EXPECT_EQ(j["window"]["from_s"].get<double>(), 0.05);
    const std::string report = read_file(dir.path / "analysis" / "report.md");
    EXPECT_NE(report.find("Analysed: from 0.05 s to 0.15 s (0.1 s; rates per this time)."), std::string::npos) << report;
    // The coverage curve's times are the log's.
    const std::string curve = read_file(dir.path / "analysis" / "rod_coverage.csv");
    EXPECT_NE(curve.find("\n0.05,0\n"), std::string::npos) << curve.substr(0, 80);
    EXPECT_NE(curve.find("\n0.15"), std::string::npos) << curve.substr(curve.size() - 40);

    AnalyzeOptions slow;
    slow.min_speed_m_per_s = 2.0;
    ASSERT_EQ(analyze_job(dir.path.string(), out, err, slow), kExitOk) << err.str();
    EXPECT_EQ(figures(dir.path)["components"][0]["impacts"].get<std::uint64_t>(), fast);
    EXPECT_NE(read_file(dir.path / "analysis" / "report.md").find("Impacts slower than 2 m/s are left out."), std::string::npos);

    // A window outside the log is an input error naming the option.
    for (auto [from, to, option] :
         {std::tuple{0.3, std::optional<double>{}, "--from"}, std::tuple{0.1, std::optional<double>{0.05}, "--to"}}) {
        AnalyzeOptions bad;
        bad.from_s = from;
        bad.to_s = to;
        std::ostringstream e;
        EXPECT_EQ(analyze_job(dir.path.string(), out, e, bad), kExitInputError);
        EXPECT_NE(e.str().find(std::string("error: ") + option), std::string::npos) << e.str();
    }
}

TEST(AnalysisReport, TheDecisionsAgreeWithTheRegionsAndTheFigures) {
    TempDir dir;
    std::ostringstream out, err;
    // 5 s (the scene's): after 1 s the least-hit tooth has too few impacts to give a time.
    ASSERT_EQ(run_job(short_run("gear.yaml", dir.path, "5 s"), out, err), kExitOk) << err.str();
    ASSERT_EQ(analyze_job(dir.path.string(), out, err), kExitOk) << err.str();
    const auto j = figures(dir.path);
    const auto& gear = j["components"][0];
    // The areas add up: peened + excluded (the bore) + out of reach = the whole surface.
    const double total = gear["area_m2"].get<double>();
    EXPECT_NEAR(gear["peened_area_m2"].get<double>() + gear["excluded_area_m2"].get<double>() + gear["unreachable_area_m2"].get<double>(),
                total, 1e-12 * total);
    const double bore = 2 * std::numbers::pi * 5e-3 * 10e-3;  // r = 5 mm, 10 mm long
    EXPECT_GT(gear["excluded_area_m2"].get<double>(), 0.9 * bore);
    EXPECT_GT(gear["unreachable_area_m2"].get<double>(), 0.0);  // the bottom lands of the tooth spaces
    // The area out of reach is a finding: the same area, and a smaller shot that would reach it.
    const auto& out_of_reach = gear["out_of_reach"];
    EXPECT_NEAR(out_of_reach["area_m2"].get<double>(), gear["unreachable_area_m2"].get<double>(), 1e-9 * total);
    EXPECT_GT(out_of_reach["half_reached_by_m"].get<double>(), out_of_reach["most_reached_by_m"].get<double>());
    EXPECT_LT(out_of_reach["half_reached_by_m"].get<double>(), 2e-3);  // the shot is 2 mm
    for (const auto& r : gear["regions"]) {
        if (!r["excluded"].get<bool>()) {
            EXPECT_NEAR(r["out_of_reach"]["area_m2"].get<double>(), r["unreachable_area_m2"].get<double>(), 1e-9 * total) << r;
        }
    }
    // "Everywhere" is when the last counted region gets there: the region with the longest time to
    // 98 % is the slowest, and with the regions' own spread (several teeth close behind it) the
    // last of them comes no earlier than it.
    double longest = 0.0, highest = 0.0;  // s: the latest region's forecast, the highest upper end
    std::string slowest;
    for (const auto& r : j["components"][0]["regions"]) {
        if (r["excluded"].get<bool>()) {
            EXPECT_EQ(r["region"], "bore");
            EXPECT_EQ(r["time_to_target"]["status"], "none");
            continue;
        }
        const auto& t = r["time_to_target"];
        ASSERT_EQ(t["status"], "forecast") << r;
        EXPECT_LT(t["low_s"].get<double>(), t["time_s"].get<double>());
        EXPECT_GT(t["high_s"].get<double>(), t["time_s"].get<double>());
        if (t["time_s"].get<double>() > longest) longest = t["time_s"].get<double>(), slowest = r["region"].get<std::string>();
        highest = std::max(highest, t["high_s"].get<double>());
    }
    EXPECT_EQ(gear["slowest_region"], slowest);
    const auto& every = gear["time_to_target_everywhere"];
    EXPECT_EQ(every["status"], "forecast");
    // Everywhere is the latest of the regions' crossings: near the latest forecast, below it by
    // what chance adds to the latest of forecasts alike (said in the report), its upper end over
    // every region's.
    const double excess = gear["forecast"]["everywhere_chance_excess_s"].get<double>();
    EXPECT_GE(excess, 0.0);
    EXPECT_GE(every["time_s"].get<double>(), longest - excess - 0.01 * longest);
    EXPECT_LT(every["time_s"].get<double>(), 1.25 * longest);
    EXPECT_GE(every["high_s"].get<double>(), highest);
    const auto& whole = gear["time_to_target"];
    EXPECT_EQ(whole["status"], "forecast");
    EXPECT_LT(whole["time_s"].get<double>(), longest);
    EXPECT_LT(whole["low_s"].get<double>(), whole["time_s"].get<double>());
    EXPECT_GT(whole["high_s"].get<double>(), whole["time_s"].get<double>());
    EXPECT_NEAR(gear["uniformity"]["value"].get<double>(), whole["time_s"].get<double>() / every["time_s"].get<double>(), 1e-12);
    EXPECT_LT(gear["uniformity"]["low"].get<double>(), gear["uniformity"]["value"].get<double>());
    EXPECT_EQ(gear["share_below_target"].get<double>(), 1.0);  // 5 s of peening: nowhere near 98 %
    // The report says it, with the command that peens until every region is there.
    const std::string report = read_file(dir.path / "analysis" / "report.md");
    EXPECT_NE(report.find("## gear: how long to peen to 98 %"), std::string::npos);
    EXPECT_NE(report.find("The last region there: **" + slowest + "**"), std::string::npos) << report;
    if (excess > 0.005 * every["time_s"].get<double>()) {
        EXPECT_NE(report.find("Several regions are forecast alike"), std::string::npos) << report;
    }
    std::ostringstream cmd;
    cmd << "peensim run " << (dir.path / "scene.resolved.yaml").string() << " -o " << dir.path.string()
        << "-until --until-coverage \"98 %\" --set \"process.duration=";
    EXPECT_NE(report.find(cmd.str()), std::string::npos) << report;
    EXPECT_NE(report.find("![gear: the slowest region, " + slowest + "](gear_slowest_region.png)"), std::string::npos);
    EXPECT_NE(report.find("| bore (excluded) |"), std::string::npos);
    EXPECT_NE(report.find("### gear: out of the shot's reach"), std::string::npos) << report;
    EXPECT_NE(report.find("![gear: out of the shot's reach, highlighted](gear_out_of_reach.png)"), std::string::npos) << report;
    // It ends with what to change, each with the command that tests it.
    const auto changes = report.find("\n## What to change\n");
    ASSERT_NE(changes, std::string::npos) << report;
    EXPECT_EQ(report.find("\n## ", changes + 1), std::string::npos) << "the last section";
    EXPECT_NE(report.find("- **Even out gear's peening.**", changes), std::string::npos) << report.substr(changes);
    EXPECT_NE(report.find("--vary \"components[gear].motion={type: rotating, axis_point: [", changes), std::string::npos);
    EXPECT_NE(report.find("axis_direction: [0, 1, 0], speed: 15 rpm}", changes), std::string::npos)
        << report.substr(changes);  // the axle's
    EXPECT_NE(report.find("--vary \"shot.diameter=2 mm,", changes), std::string::npos) << report.substr(changes);
    // The HTML page carries the pictures inside it.
    const std::string html = read_file(dir.path / "analysis" / "report.html");
    EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
    const std::string png = read_file(dir.path / "analysis" / "gear_slowest_region.png");
    ASSERT_GT(png.size(), 1000u);
    EXPECT_NE(html.find("<img src=\"data:image/png;base64," + base64(png) + "\""), std::string::npos);
    EXPECT_NE(html.find("<h2>gear: how long to peen to 98 %</h2>"), std::string::npos);
}

TEST(MarkdownHtml, TheReportsSubsetExactly) {
    const std::string md =
        "# Title & more\n\nA **bold** `x<y` line\nwrapped.\n\n- one\n- two **b**\n\n| a | b |\n|---|---|\n| 1 | <2> |\n\n"
        "    peensim run a.yaml\n\n![the map](m.png)\n![gone](n.png)\n";
    const std::string html = markdown_to_html(md, "T", [](const std::string& src) -> std::optional<std::string> {
        if (src == "m.png") return std::string("abc");
        return std::nullopt;
    });
    const std::string body = html.substr(html.find("<body>\n") + 7);
    EXPECT_EQ(
        body,
        "<h1>Title &amp; more</h1>\n<p>A <strong>bold</strong> <code>x&lt;y</code> line wrapped.</p>\n<ul>\n<li>one</li>\n"
        "<li>two <strong>b</strong></li>\n</ul>\n<table>\n<tr><th>a</th><th>b</th></tr>\n<tr><td>1</td><td>&lt;2&gt;</td></tr>\n"
        "</table>\n<pre>peensim run a.yaml\n</pre>\n<figure><img src=\"data:image/png;base64,YWJj\" alt=\"the map\"><figcaption>the map"
        "</figcaption></figure>\n<figure><img src=\"n.png\" alt=\"gone\"><figcaption>gone</figcaption></figure>\n</body>\n</html>\n");
    EXPECT_EQ(base64(""), "");
    EXPECT_EQ(base64("f"), "Zg==");
    EXPECT_EQ(base64("fo"), "Zm8=");
    EXPECT_EQ(base64("foo"), "Zm9v");
    EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
}

TEST(MarkdownHtml, AMarkerLineIsReplacedByItsBlockAsItStands) {
    const std::string md = "Before.\n<!-- 3D view: gear -->\n<!-- 3D view: other -->\nAfter <b>.\n";
    const std::string html = markdown_to_html(md, "T", [](const std::string&) -> std::optional<std::string> { return std::nullopt; },
                                              {{"<!-- 3D view: gear -->", "<div id=\"v\"><script>1 < 2</script></div>\n"}});
    const std::string body = html.substr(html.find("<body>\n") + 7);
    EXPECT_EQ(body,
              "<p>Before.</p>\n<div id=\"v\"><script>1 < 2</script></div>\n<p>&lt;!-- 3D view: other --&gt; After &lt;b&gt;.</p>\n"
              "</body>\n</html>\n");
}

TEST(RenderRegions, EachRegionInItsColourWhereItIs) {
    // The rod with two regions, x > 0 and x < 0, drawn from its scene file.
    TempDir dir;
    const std::vector<std::string> overrides{
        "components[rod].regions=[{name: plus-x, half_space: {normal: [1, 0, 0]}}, {name: minus-x, half_space: {normal: [-1, 0, 0]}}]"};
    RenderRegionsOptions o{kSource + "/scenes/rod.yaml", overrides, dir.path.string(), 320, 240};
    std::ostringstream out, err;
    ASSERT_EQ(render_regions_job(o, out, err), kExitOk) << err.str();
    EXPECT_NE(out.str().find("plus-x: "), std::string::npos) << out.str();
    const render::RgbaImage image = render::read_png((dir.path / "rod_region_map.png").string());
    const auto model = compile_model(parse_scene_file(kSource + "/scenes/rod.yaml", overrides));
    const Component& rod = model->components[static_cast<std::size_t>(model->component_index("rod"))];
    const render::Camera camera = render::Camera::framing_points(world_vertices(rod), 160.0 / 120.0, map_views()[0].direction);
    const Pose pose = rod.kinematics.pose(SimTime{});
    // On either side of x = 0, the centroid of the triangle that faces the first view's camera most.
    const auto centroid_where = [&](double side) {
        Vec3 best = Vec3::Zero();
        double facing = 0.0;
        for (std::size_t t = 0; t < rod.mesh->triangle_count(); ++t) {
            const Vec3 c = pose.to_world((rod.mesh->corner(t, 0) + rod.mesh->corner(t, 1) + rod.mesh->corner(t, 2)) / 3.0);
            const Vec3 local = pose.to_component(c);
            const double f = (pose.rotation * triangle_normal(*rod.mesh, t)).dot((camera.position_m - c).normalized());
            if (side * local.x() > 1.5e-3 && std::abs(local.y()) < 5e-3 && f > facing) best = c, facing = f;
        }
        EXPECT_GT(facing, 0.2) << "side " << side;
        return best;
    };
    const auto plus = camera.project_to_pixel(centroid_where(1.0), 160, 120);
    const auto minus = camera.project_to_pixel(centroid_where(-1.0), 160, 120);
    ASSERT_TRUE(plus && minus);
    const render::Rgba8 p = image.at(static_cast<int>(plus->x()), static_cast<int>(plus->y()));
    const render::Rgba8 m = image.at(static_cast<int>(minus->x()), static_cast<int>(minus->y()));
    // Region 0 orange (red high, blue low), region 1 purple (blue above red and green), shaded by the light.
    ASSERT_EQ(region_colour(0).r, 230);
    ASSERT_EQ(region_colour(1).b, 153);
    EXPECT_GT(p.r, p.b + 80) << int(p.r) << " " << int(p.g) << " " << int(p.b);
    EXPECT_GT(m.b, m.r + 20) << int(m.r) << " " << int(m.g) << " " << int(m.b);
    EXPECT_GT(m.b, m.g + 30);
    // A run directory takes no --set; a path that is neither is a clear error.
    RenderRegionsOptions bad{dir.path.string() + "/nothing.yaml", {}, dir.path.string(), 320, 240};
    std::ostringstream e;
    EXPECT_EQ(render_regions_job(bad, out, e), kExitInputError);
}
