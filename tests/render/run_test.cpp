// Rendering during a run, end to end on the rod scene: the frames have the requested size and
// count, show the part where it projects and a shot at its known place, the MP4 holds every
// frame (when ffmpeg is there; without it the run still succeeds with a note), a resumed run
// continues the sequence, and a run that does not render writes no frame. Then the impact map
// of `render-impacts` puts the hot colour on the hit triangles, its coverage map scaled to the data.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/run/run_job.h"
#include "engine/simulation.h"
#include "model/model.h"
#include "render/png_io.h"
#include "render/render_impacts_job.h"
#include "render/render_view.h"
#include "render/video_encoder.h"
#include "scene/scene_parser.h"
#include "support/shell_command.h"
#include "support/shipped_scenes.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::kRod;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

// 10 ms of the rod scene at 160x120, a frame every simulated ms (10 fps, 10 ms per video second):
// frames 0 .. 10.
std::vector<std::string> render_overrides() {
    return {"process.duration=0.01", "render.width=160", "render.height=120", "render.fps=10", "render.slow_motion=10 ms"};
}

RunOptions rod_render_run(const fs::path& dir) {
    RunOptions o;
    o.scene_path = kRod;
    o.output_dir = dir.string();
    o.overrides = render_overrides();
    o.progress = false;
    o.analyze = false;
    return o;
}

std::vector<fs::path> frames_in(const fs::path& dir) {
    std::vector<fs::path> frames;
    if (!fs::exists(dir / "frames")) return frames;
    for (const auto& e : fs::directory_iterator(dir / "frames")) frames.push_back(e.path());
    std::sort(frames.begin(), frames.end());
    return frames;
}

// The frame-0 camera of the rod scene, as the recorder builds it.
struct RodView {
    std::shared_ptr<const Model> model;
    render::Camera camera;
};
RodView rod_view() {
    RodView v;
    v.model = compile_model(parse_scene_file(kRod, render_overrides()));
    render::OffscreenContext context({.width = 160, .height = 120});
    render::Renderer renderer(context, {.overlay = false});
    const ModelView view = add_model(renderer, *v.model);
    v.camera = scene_camera(*v.model->description.render, view, 160.0 / 120.0);
    return v;
}

std::string ffprobe(const fs::path& mp4) {
    const std::string command =
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=nb_read_frames,width,height -of csv=p=0 '" +
        mp4.string() + "'";
    return peensim::testing::trimmed(peensim::testing::run_shell(command).output);
}

}  // namespace

TEST(RenderRun, RecordsFramesShowingThePartAndTheShotWhereTheyAre) {
    TempDir dir;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(rod_render_run(dir.path), out, err), kExitOk) << err.str();
    const std::vector<fs::path> frames = frames_in(dir.path);
    ASSERT_EQ(frames.size(), 11u) << out.str();
    EXPECT_EQ(frames.front().filename(), "frame_000000.png");
    EXPECT_EQ(frames.back().filename(), "frame_000010.png");
    for (const fs::path& f : frames) {
        const render::RgbaImage image = render::read_png(f.string());
        EXPECT_EQ(image.width, 160);
        EXPECT_EQ(image.height, 120);
        // Not blank: many distinct colours.
        int changes = 0;
        for (std::size_t i = 4; i < image.pixels.size(); i += 4) changes += image.pixels[i] != image.pixels[i - 4];
        EXPECT_GT(changes, 500) << f;
    }

    const RodView v = rod_view();
    const render::RgbaImage first = render::read_png(frames.front().string());
    // The rod (role part: orange) where its middle, at z = 20 mm, projects.
    const auto rod = v.camera.project_to_pixel(Vec3(0, 0, 0.02), 160, 120);
    ASSERT_TRUE(rod.has_value());
    const render::Rgba8 rc = first.at(static_cast<int>(rod->x()), static_cast<int>(rod->y()));
    EXPECT_GT(rc.r, rc.b + 60) << int(rc.r) << " " << int(rc.g) << " " << int(rc.b);
    EXPECT_GT(rc.r, rc.g);
    // At t = 0 the shot lie where the seed placed them: the one nearest the camera shows in the
    // shot's light grey at its projected centre.
    Simulation sim(v.model);
    const ShotArrays& s = sim.state().shots;
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < s.size(); ++i)
        if ((s.position(i) - v.camera.position_m).norm() < (s.position(nearest) - v.camera.position_m).norm()) nearest = i;
    const auto shot = v.camera.project_to_pixel(s.position(nearest), 160, 120);
    ASSERT_TRUE(shot.has_value());
    const render::Rgba8 sc = first.at(static_cast<int>(shot->x()), static_cast<int>(shot->y()));
    EXPECT_GT(std::min({sc.r, sc.g, sc.b}), 110) << int(sc.r) << " " << int(sc.g) << " " << int(sc.b);
    EXPECT_LT(std::max({sc.r, sc.g, sc.b}) - std::min({sc.r, sc.g, sc.b}), 40);

    // The video holds every frame at the frame size.
    if (render::ffmpeg_available() && std::system("command -v ffprobe >/dev/null 2>&1") == 0) {
        EXPECT_EQ(ffprobe(dir.path / "animation.mp4"), "160,120,11");
        EXPECT_FALSE(fs::exists(dir.path / "animation.mp4.partial"));
    }
    EXPECT_NE(out.str().find("render: 11 frames"), std::string::npos) << out.str();
}

TEST(RenderRun, WithoutFfmpegTheRunSucceedsWithFramesAndANote) {
    TempDir dir;
    const std::string saved = std::getenv("PATH") ? std::getenv("PATH") : "";
    const fs::path empty = dir.path / "empty-bin";
    fs::create_directories(empty);
    setenv("PATH", empty.c_str(), 1);
    std::ostringstream out, err;
    const int code = run_job(rod_render_run(dir.path / "run"), out, err);
    setenv("PATH", saved.c_str(), 1);
    ASSERT_EQ(code, kExitOk) << err.str();
    EXPECT_EQ(frames_in(dir.path / "run").size(), 11u);
    EXPECT_FALSE(fs::exists(dir.path / "run" / "animation.mp4"));
    EXPECT_NE(out.str().find("no MP4: ffmpeg not found"), std::string::npos) << out.str();
}

TEST(RenderRun, AResumedRunContinuesTheFramesAndNoRenderMeansNoFrames) {
    TempDir dir;
    RunOptions o = rod_render_run(dir.path);
    o.overrides.push_back("accuracy.scheme=step");  // stopped after a count of time steps
    o.stop_after_steps = 150;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(o, out, err), kExitInterrupted) << err.str();
    const std::size_t before = frames_in(dir.path).size();
    EXPECT_GT(before, 1u);
    EXPECT_LT(before, 11u);
    o.stop_after_steps.reset();
    o.resume = true;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    EXPECT_EQ(frames_in(dir.path).size(), 11u);

    TempDir plain;
    RunOptions p = rod_render_run(plain.path);
    p.render = false;  // --no-render beats the scene's block
    ASSERT_EQ(run_job(p, out, err), kExitOk) << err.str();
    EXPECT_FALSE(fs::exists(plain.path / "frames"));
    EXPECT_FALSE(fs::exists(plain.path / "animation.mp4"));
}

TEST(RenderImpacts, TheHotColourLandsOnTheHitTriangles) {
    TempDir dir;
    RunOptions o = rod_render_run(dir.path);
    o.render = false;
    o.analyze = true;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    // A synthetic pattern: every rod triangle with its centroid at x > 0 hit, the others not.
    const auto model = compile_model(parse_scene_file(kRod, render_overrides()));
    const Component& rod = model->components[static_cast<std::size_t>(model->component_index("rod"))];
    {
        std::ofstream csv(dir.path / "analysis" / "rod_triangles.csv");
        csv << "triangle,impacts_per_mm2_s_smoothed,mean_vn_mps_smoothed,coverage_smoothed,smoothing_radius_mm\n";
        for (std::size_t t = 0; t < rod.mesh->triangle_count(); ++t) {
            const double x = (rod.mesh->corner(t, 0) + rod.mesh->corner(t, 1) + rod.mesh->corner(t, 2)).x() / 3.0;
            csv << t << ',' << (x > 0.0 ? 10.0 : 0.0) << ",," << (x > 0.0 ? 0.03 : 0.001) << ",0.5\n";
        }
    }
    RenderImpactsOptions r{dir.path.string(), {"impacts"}, 320, 240, std::nullopt};
    std::ostringstream out2, err2;
    ASSERT_EQ(render_impacts_job(r, out2, err2), kExitOk) << err2.str();
    const render::RgbaImage image = render::read_png((dir.path / "analysis" / "rod_map_impacts.png").string());
    ASSERT_EQ(image.width, 320);
    ASSERT_EQ(image.height, 240);
    // Top-left tile: the first view. The rod's end cap at y = -15 mm faces it.
    const render::Camera camera = render::Camera::framing_points(world_vertices(rod), 160.0 / 120.0, map_views()[0].direction);
    const Pose pose = rod.kinematics.pose(SimTime{});
    const auto hot = camera.project_to_pixel(pose.to_world(Vec3(2.5e-3, -15e-3, 20e-3)), 160, 120);
    const auto cold = camera.project_to_pixel(pose.to_world(Vec3(-2.5e-3, -15e-3, 20e-3)), 160, 120);
    ASSERT_TRUE(hot && cold);
    const render::Rgba8 h = image.at(static_cast<int>(hot->x()), static_cast<int>(hot->y()));
    const render::Rgba8 c = image.at(static_cast<int>(cold->x()), static_cast<int>(cold->y()));
    // viridis: the top is yellow (red and green high, blue low), the bottom dark purple.
    EXPECT_GT(h.g, h.b + 60) << int(h.r) << " " << int(h.g) << " " << int(h.b);
    EXPECT_GT(h.r, h.b + 40);
    EXPECT_GT(c.b, c.g + 20) << int(c.r) << " " << int(c.g) << " " << int(c.b);
    // The coverage map is scaled to its data (0 to 3 %, not 0 to 100 %): the covered half is in
    // the top colour, the rest at the bottom.
    RenderImpactsOptions cov{dir.path.string(), {"coverage"}, 320, 240, std::nullopt};
    ASSERT_EQ(render_impacts_job(cov, out2, err2), kExitOk) << err2.str();
    const render::RgbaImage coverage = render::read_png((dir.path / "analysis" / "rod_map_coverage.png").string());
    const render::Rgba8 ch = coverage.at(static_cast<int>(hot->x()), static_cast<int>(hot->y()));
    const render::Rgba8 cc = coverage.at(static_cast<int>(cold->x()), static_cast<int>(cold->y()));
    EXPECT_GT(ch.g, ch.b + 60) << int(ch.r) << " " << int(ch.g) << " " << int(ch.b);
    EXPECT_GT(cc.b, cc.g + 20) << int(cc.r) << " " << int(cc.g) << " " << int(cc.b);
    RenderImpactsOptions bad_target = cov;
    bad_target.coverage_target = 1.5;
    EXPECT_EQ(render_impacts_job(bad_target, out2, err2), kExitInputError);
    EXPECT_NE(err2.str().find("--target"), std::string::npos) << err2.str();
    // An unknown field is a clear input error.
    RenderImpactsOptions bad{dir.path.string(), {"heat"}, 320, 240, std::nullopt};
    std::ostringstream out3, err3;
    EXPECT_EQ(render_impacts_job(bad, out3, err3), kExitInputError);
    EXPECT_NE(err3.str().find("unknown field 'heat'"), std::string::npos) << err3.str();
}

TEST(RenderRun, ThePeensimBinaryDoesNotLinkOpenGL) {
    // OSMesa (and the LLVM it brings, ~50 MB resident) is loaded only by a run that renders:
    // the binary itself must not depend on it.
    if (std::system("command -v ldd >/dev/null 2>&1") != 0) GTEST_SKIP() << "no ldd";
    const std::string text = peensim::testing::run_shell(std::string("ldd '") + PEENSIM_BINARY + "'").output;
    EXPECT_NE(text.find("libc.so"), std::string::npos) << text;
    EXPECT_EQ(text.find("libOSMesa"), std::string::npos) << text;
    EXPECT_EQ(text.find("libLLVM"), std::string::npos) << text;
}

namespace {

// Light grey, the shot's colour: bright and without hue.
int shot_pixels(const render::RgbaImage& image) {
    int n = 0;
    for (std::size_t i = 0; i + 3 < image.pixels.size(); i += 4) {
        const auto r = image.pixels[i], g = image.pixels[i + 1], b = image.pixels[i + 2];
        n += std::min({r, g, b}) > 150 && std::max({r, g, b}) - std::min({r, g, b}) < 30;
    }
    return n;
}

}  // namespace

// Shot emitted during the run (a nozzle's) are drawn too: the state grows past the shot count the
// recorder started with (zero here; the frames once wrote past its arrays).
TEST(RenderRun, ShotEmittedDuringTheRunAreDrawn) {
    TempDir dir;
    RunOptions o;
    o.scene_path = std::string(PEENSIM_SOURCE_DIR) + "/scenes/nozzle-almen.yaml";
    o.output_dir = dir.path.string();
    o.overrides = {"process.duration=6 ms",
                   "render={width: 320, height: 180, fps: 10, slow_motion: 5 ms, video: none, "
                   "camera: {position: [40 mm, -50 mm, 30 mm], look_at: [0, 0, 8 mm]}}"};
    o.progress = false;
    o.analyze = false;
    std::ostringstream out, err;
    ASSERT_EQ(run_job(o, out, err), kExitOk) << err.str();
    const std::vector<fs::path> frames = frames_in(dir.path);
    ASSERT_EQ(frames.size(), 13u) << out.str();  // a frame every 0.5 ms (slow_motion / fps), 0 to 6 ms
    // At 6 ms the jet is full (~15 shot in the air); at t = 0 at most the first has left the nozzle.
    EXPECT_GT(shot_pixels(render::read_png(frames.back().string())), shot_pixels(render::read_png(frames.front().string())) + 10);
}
