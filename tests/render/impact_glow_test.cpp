// Impacts made visible (render/glow_layer.h, the frame recorder's trail) and the colour bar's
// marked value: known input, known pixels. A glow brightens the pixels around the projection of
// its point, is the same size in pixels whatever the camera's distance and is hidden behind a
// part in front; in a run's frames an impact at a known place glows in the frames after it,
// fading, and is gone after kTrailFrames; a mark lies across the bar at its value, or is noted
// under the bar when above the scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "geometry/box_mesh.h"
#include "model/model.h"
#include "render/frame_recorder.h"
#include "render/png_io.h"
#include "render/render_impacts_job.h"
#include "render/render_view.h"
#include "render/renderer.h"
#include "scene/scene_parser.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::TempDir;
using namespace peensim;
using namespace peensim::render;

namespace {

constexpr int kGlowWidth = 320, kGlowHeight = 240;

TriangleMesh unit_box(const Vec3& centre, double size) {
    BoxSpec spec;
    spec.size_m = Vec3::Constant(size);
    spec.center_m = centre;
    return box(spec);
}

Camera camera_at(double distance_m) {
    Camera camera;
    camera.position_m = Vec3(0.0, -distance_m, 0.0);
    camera.look_at_m = Vec3::Zero();
    camera.fit_depth_range(Vec3(-2, -2, -2), Vec3(2, 2, 2));
    return camera;
}

int luminance(const Rgba8& c) { return (2 * c.r + 5 * c.g + c.b) / 8; }

// Pixels of `a` and `b` that differ, and the brightest of `a` among them, within `radius` px of `centre`.
struct Difference {
    int changed = 0;
    int brightest = 0;
};
Difference compare(const RgbaImage& a, const RgbaImage& b, const Vec2& centre, double radius) {
    Difference d;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (std::hypot(x + 0.5 - centre.x(), y + 0.5 - centre.y()) > radius) continue;
            if (a.at(x, y) == b.at(x, y)) continue;
            ++d.changed;
            d.brightest = std::max(d.brightest, luminance(a.at(x, y)));
        }
    return d;
}

// Pixels that differ anywhere.
int changed_pixels(const RgbaImage& a, const RgbaImage& b) {
    int n = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) n += !(a.at(x, y) == b.at(x, y));
    return n;
}

}  // namespace

TEST(ImpactGlow, AGlowIsASizeInPixelsAroundItsPointAndHidesBehindAPart) {
    OffscreenContext context({.width = kGlowWidth, .height = kGlowHeight});
    RenderOptions options;
    options.overlay = false;
    Renderer renderer(context, options);
    // A dark grey wall facing the camera (its front face at y = -0.5), and a box in front of its
    // right side that hides what is behind it (larger than a glow at either distance).
    renderer.add_mesh(unit_box(Vec3::Zero(), 1.0), {.colour = {0.3f, 0.3f, 0.3f, 1.0f}, .lit = false});
    renderer.add_mesh(unit_box(Vec3(0.35, -1.0, 0.0), 0.5), {.colour = {0.5f, 0.2f, 0.2f, 1.0f}, .lit = false});
    const Vec3 open(-0.35, -0.5, 0.1), hidden(0.35, -0.5, 0.0);
    const ColourMap map = ColourMap::viridis();
    const float radius_px = 10.0f;
    for (double distance : {3.0, 6.0}) {
        const Camera camera = camera_at(distance);
        RgbaImage plain, glowing;
        renderer.render(camera, {}, plain);
        // The slowest colour of the map (dark purple): the core and rim must make even it visible.
        const std::vector<ImpactGlow> glows{{open, 0.01, radius_px, map.map(0.0, 0.0, 5.0)},
                                            {hidden, 0.01, radius_px, map.map(0.0, 0.0, 5.0)}};
        renderer.render(camera, {.glows = glows}, glowing);
        const auto at_open = camera.project_to_pixel(open, kGlowWidth, kGlowHeight);
        const auto at_hidden = camera.project_to_pixel(hidden, kGlowWidth, kGlowHeight);
        ASSERT_TRUE(at_open && at_hidden);
        // Its core is near white, far brighter than the wall (luminance 77).
        const Difference open_d = compare(glowing, plain, *at_open, radius_px + 1.0);
        EXPECT_GT(open_d.brightest, 220) << "at " << distance << " m";
        // The sprite covers pi r^2 pixels at either distance (the dark rim fades out at its edge).
        EXPECT_NEAR(open_d.changed, std::numbers::pi * radius_px * radius_px, 0.2 * std::numbers::pi * radius_px * radius_px)
            << "at " << distance << " m";
        EXPECT_EQ(compare(glowing, plain, *at_open, 3.0 * radius_px).changed, open_d.changed) << "nothing outside its radius";
        // The one behind the box in front does not show.
        EXPECT_EQ(compare(glowing, plain, *at_hidden, radius_px + 1.0).changed, 0) << "at " << distance << " m";
    }
}

// A run's recorder: one impact at the top of the rod at t = 2.5 ms, frames every simulated ms
// (no shot drawn: only the impact changes between frames near it).
TEST(ImpactGlow, AnImpactGlowsInTheNextFramesAndFadesAfter) {
    TempDir dir;
    const std::vector<std::string> overrides{"process.duration=0.02", "render.width=640",         "render.height=480",
                                             "render.fps=10",         "render.slow_motion=10 ms", "render.video=none"};
    const auto model = compile_model(parse_scene_file(std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml", overrides));
    Simulation sim(model);
    SimulationState state = sim.state();
    std::fill(state.shots.active.begin(), state.shots.active.end(), static_cast<unsigned char>(0));
    const int rod = model->component_index("rod");
    const Component& part = model->components[static_cast<std::size_t>(rod)];
    ImpactRecord impact;
    impact.time_s = 0.0025;
    impact.component = rod;
    impact.point_m = Vec3(0.0, 0.0, 0.025);  // the top of the rod (axis along y at z = 20 mm, radius 5 mm)
    impact.vn_in_m_per_s = 1.0;
    impact.v_in_m_per_s = Vec3(0.0, 0.0, -1.0);
    impact.v_out_m_per_s = Vec3(0.0, 0.0, 0.5);
    impact.shot_diameter_m = 0.002;
    {
        FrameRecorder recorder(*model, *model->description.render, dir.path.string(), state);
        for (int ms = 0; ms <= 14; ++ms) {
            state.time = SimTime{ms * 1e-3, 0.0};
            std::vector<ImpactRecord> impacts;
            if (ms == 3) impacts.push_back(impact);  // the step from 2 to 3 ms held it
            recorder.after_step(state, impacts, ms >= 3 ? 1 : 0);
        }
        recorder.flush();
    }
    // Where the impact projects, with the recorder's camera.
    const int w = 640, h = 480;
    OffscreenContext context({.width = w, .height = h});
    Renderer renderer(context, {.overlay = false});
    const ModelView view = add_model(renderer, *model);
    const Camera camera = scene_camera(*model->description.render, view, static_cast<double>(w) / h);
    const auto at = camera.project_to_pixel(part.kinematics.pose(SimTime{}).to_world(impact.point_m), w, h);
    ASSERT_TRUE(at.has_value());
    const double radius_px = std::max(3.0, kGlowRadiusPerHeight * h);  // 6 px
    auto frame = [&](int k) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%06d.png", k);
        return read_png((dir.path / "frames" / name).string());
    };
    const RgbaImage before = frame(2);  // t = 2 ms: the impact has not happened
    EXPECT_EQ(compare(frame(1), before, *at, 2.0 * radius_px).changed, 0) << "nothing moves near it before";
    // Frames 3 .. 10 (ages 0.5 .. 7.5 ms, the trail is 8 frames of 1 ms): bright, then fading.
    int last_changed = 1 << 30, last_brightest = 256;
    for (int k = 3; k < 3 + kTrailFrames; ++k) {
        const Difference d = compare(frame(k), before, *at, 2.0 * radius_px);
        EXPECT_GT(d.changed, 0) << "frame " << k;
        EXPECT_LE(d.changed, last_changed) << "frame " << k << ": it shrinks";
        EXPECT_LE(d.brightest, last_brightest) << "frame " << k << ": it fades";
        if (k == 3) {
            EXPECT_GT(d.brightest, 220) << "a white-hot core the frame after the impact";
            EXPECT_GT(d.changed, static_cast<int>(0.7 * std::numbers::pi * radius_px * radius_px));
        }
        last_changed = d.changed, last_brightest = d.brightest;
    }
    // Gone after the trail.
    for (int k = 3 + kTrailFrames; k <= 14; ++k) EXPECT_EQ(compare(frame(k), before, *at, 2.0 * radius_px).changed, 0) << "frame " << k;
}

TEST(ColourBarMark, AMarkLiesAcrossTheBarAtItsValueOrIsNotedAboveTheScale) {
    OffscreenContext context({.width = kGlowWidth, .height = kGlowHeight});
    RenderOptions options;
    options.background = {0.0f, 0.0f, 0.0f, 1.0f};
    Renderer renderer(context, options);
    const Camera camera = camera_at(4.0);
    ColourBar bar{ColourMap::viridis(), 0.0, 0.04, "coverage, %"};
    bar.label_scale = 100.0;
    bar.label_unit = " %";
    RgbaImage plain, marked, above;
    renderer.render(camera, {.colour_bar = &bar}, plain);
    // The bar's rows: from its top colour to its bottom colour.
    int top = kGlowHeight, bottom = -1;
    for (int y = 0; y < kGlowHeight; ++y)
        for (int x = kGlowWidth / 2; x < kGlowWidth; ++x) {
            const Rgba8 c = plain.at(x, y);
            if (std::abs(c.r - 0xFD) < 8 && std::abs(c.g - 0xE7) < 8 && std::abs(c.b - 0x25) < 8) top = std::min(top, y);
            if (std::abs(c.r - 0x44) < 8 && std::abs(c.g - 0x01) < 8 && std::abs(c.b - 0x54) < 8) bottom = std::max(bottom, y);
        }
    ASSERT_LT(top, bottom);
    bar.mark = 0.01;  // a quarter up the bar
    bar.mark_label = "target 1 %";
    renderer.render(camera, {.colour_bar = &bar}, marked);
    int white_rows_min = kGlowHeight, white_rows_max = -1, white = 0;
    for (int y = top; y <= bottom; ++y)
        for (int x = kGlowWidth / 2; x < kGlowWidth; ++x) {
            const Rgba8 c = marked.at(x, y);
            if (c == plain.at(x, y) || c.r < 250 || c.g < 250 || c.b < 250) continue;
            if (plain.at(x, y).b < 20 && plain.at(x, y).g < 20) continue;  // text over the black background, not the line
            ++white;
            white_rows_min = std::min(white_rows_min, y), white_rows_max = std::max(white_rows_max, y);
        }
    const double expected_y = bottom - 0.25 * (bottom - top);
    EXPECT_GT(white, 8) << "a white line across the bar";
    EXPECT_NEAR(0.5 * (white_rows_min + white_rows_max), expected_y, 2.5);
    EXPECT_GT(changed_pixels(marked, plain), white) << "and its label";
    // Above the scale: nothing across the bar, a note under it.
    bar.mark = 0.98;
    bar.mark_label = "target 98 %";
    renderer.render(camera, {.colour_bar = &bar}, above);
    int inside = 0, below = 0;
    for (int y = 0; y < kGlowHeight; ++y)
        for (int x = kGlowWidth / 2; x < kGlowWidth; ++x) {
            if (above.at(x, y) == plain.at(x, y)) continue;
            (y <= bottom + 1 ? inside : below) += 1;
        }
    EXPECT_EQ(inside, 0);
    EXPECT_GT(below, 40) << "the note's text";
}

TEST(CoverageMapScale, TheTopIsTheLargestCoverageRoundedUpToTwoDigits) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_DOUBLE_EQ(coverage_scale_top({0.0, 0.0317, nan, 0.01}), 0.032);
    EXPECT_DOUBLE_EQ(coverage_scale_top({0.00123}), 0.0013);
    EXPECT_DOUBLE_EQ(coverage_scale_top({0.5, 0.97}), 0.97);  // exactly two digits: kept
    EXPECT_DOUBLE_EQ(coverage_scale_top({0.996}), 1.0);
    EXPECT_DOUBLE_EQ(coverage_scale_top({0.0, nan}), 0.01);  // nothing covered: a 1 % scale
}
