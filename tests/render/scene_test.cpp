// The renderer on tiny scenes (160x120, OSMesa): each test places something where the camera's
// projection says it must appear and checks the pixel there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/box_mesh.h"
#include "render/renderer.h"

namespace peensim::render {
namespace {

constexpr int kSceneW = 160, kSceneH = 120;
constexpr Rgba kBlack{0.0f, 0.0f, 0.0f, 1.0f};

// A camera at -y looking at the origin along +y, z up: a box's -y face looks straight at it.
Camera front_camera(double distance_m = 4.0) {
    Camera camera;
    camera.position_m = Vec3(0.0, -distance_m, 0.0);
    camera.look_at_m = Vec3::Zero();
    camera.fit_depth_range(Vec3(-2, -2, -2), Vec3(2, 2, 2));
    return camera;
}

TriangleMesh unit_box(const Vec3& centre = Vec3::Zero(), double size = 1.0) {
    BoxSpec spec;
    spec.size_m = Vec3::Constant(size);
    spec.center_m = centre;
    return box(spec);
}

// The walls of a closed cavity: a box with its normals turned inward (as the generated
// chambers have them).
TriangleMesh inward_box(double size) {
    TriangleMesh mesh = unit_box(Vec3::Zero(), size);
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    return mesh;
}

Rgba8 pixel_at(const RgbaImage& image, const Camera& camera, const Vec3& world) {
    const auto p = camera.project_to_pixel(world, image.width, image.height);
    EXPECT_TRUE(p.has_value());
    return image.at(static_cast<int>(p->x()), static_cast<int>(p->y()));
}

bool reddish(const Rgba8& c) { return c.r > 120 && c.g < 90 && c.b < 90; }
bool near(const Rgba8& a, const Rgba8& b, int tolerance = 2) {
    return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance && std::abs(a.b - b.b) <= tolerance;
}

class RenderScene : public ::testing::Test {
protected:
    RenderOptions no_text() {
        RenderOptions options;
        options.overlay = false;
        options.background = kBlack;
        return options;
    }
    OffscreenContext context{ContextOptions{kSceneW, kSceneH, 0}};
    RgbaImage image;
};

TEST_F(RenderScene, BoxFrameHasTheRequestedSizeAndShowsThePartColour) {
    Renderer renderer(context, no_text());
    renderer.add_mesh(unit_box(), {.colour = {0.2f, 0.8f, 0.3f, 1.0f}});
    const Camera camera = Camera::framing(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5), double(kSceneW) / kSceneH);
    renderer.render(camera, {}, image);

    ASSERT_EQ(image.width, kSceneW);
    ASSERT_EQ(image.height, kSceneH);
    ASSERT_EQ(image.pixels.size(), std::size_t{kSceneW} * kSceneH * 4);
    std::size_t lit = 0;
    for (int y = 0; y < kSceneH; ++y) {
        for (int x = 0; x < kSceneW; ++x) lit += image.at(x, y) == Rgba8{0, 0, 0, 255} ? 0 : 1;
    }
    EXPECT_GT(lit, std::size_t{kSceneW} * kSceneH / 10) << "the frame is (nearly) blank";
    EXPECT_LT(lit, std::size_t{kSceneW} * kSceneH) << "the box fills the whole frame: framing is off";

    const Rgba8 centre = pixel_at(image, camera, Vec3::Zero());
    EXPECT_GT(centre.g, centre.r + 60) << int(centre.r) << "," << int(centre.g) << "," << int(centre.b);
    EXPECT_GT(centre.g, centre.b + 60);
    EXPECT_EQ(centre.a, 255);
    // A face square to the headlight shows its own colour: (0.2, 0.8, 0.3) * (ambient + diffuse).
    renderer.render(front_camera(), {}, image);
    EXPECT_TRUE(near(pixel_at(image, front_camera(), Vec3::Zero()), Rgba8{51, 204, 77, 255}, 3));
}

TEST_F(RenderScene, PoseMovesTheMesh) {
    Renderer renderer(context, no_text());
    const MeshId id = renderer.add_mesh(unit_box(Vec3::Zero(), 0.5), {.colour = {1.0f, 0.0f, 0.0f, 1.0f}});
    const Camera camera = front_camera();
    renderer.set_pose(id, make_pose(Mat3::Identity(), Vec3(1.0, 0.0, 0.0)));
    renderer.render(camera, {}, image);
    EXPECT_EQ(pixel_at(image, camera, Vec3::Zero()), (Rgba8{0, 0, 0, 255}));
    EXPECT_TRUE(reddish(pixel_at(image, camera, Vec3(1.0, 0.0, 0.0))));
}

TEST_F(RenderScene, SphereAppearsWhereItsCentreProjectsWithItsSize) {
    Renderer renderer(context, no_text());
    const Camera camera = front_camera();
    const std::vector<double> x = {0.4}, y = {0.2}, z = {-0.3};
    const double radius = 0.15;
    const SphereSet set{x, y, z, {}, radius, {0.9f, 0.1f, 0.1f, 1.0f}};
    renderer.render(camera, {.spheres = {&set, 1}}, image);

    const Vec3 centre(x[0], y[0], z[0]);
    const Vec2 c = *camera.project_to_pixel(centre, kSceneW, kSceneH);
    EXPECT_TRUE(reddish(image.at(int(c.x()), int(c.y()))));
    // Its width on the row through the centre is the projected diameter (to a pixel or two).
    const int row = static_cast<int>(c.y());
    int first = kSceneW, last = -1;
    for (int px = 0; px < kSceneW; ++px) {
        if (image.at(px, row).r > 40) first = std::min(first, px), last = std::max(last, px);
    }
    const double edge_x = camera.project_to_pixel(centre + Vec3(radius, 0.0, 0.0), kSceneW, kSceneH)->x();
    const double expected_diameter = 2.0 * (edge_x - c.x());
    EXPECT_NEAR(last - first + 1, expected_diameter, 2.5);
    EXPECT_EQ(image.at(int(c.x()), int(c.y() - expected_diameter)), (Rgba8{0, 0, 0, 255}));
}

TEST_F(RenderScene, SpheresHideAndAreHiddenByDepth) {
    Renderer renderer(context, no_text());
    renderer.add_mesh(unit_box(), {.colour = {0.1f, 0.1f, 1.0f, 1.0f}});
    const Camera camera = front_camera();
    // One sphere half sunk into the -y face (visible), one inside the box (hidden), one
    // inactive (skipped) in front of the box.
    const std::vector<double> x = {-0.25, 0.25, 0.0}, y = {-0.5, 0.0, -1.0}, z = {0.2, 0.2, -0.25};
    const std::vector<unsigned char> active = {1, 1, 0};
    const SphereSet set{x, y, z, active, 0.1, {1.0f, 0.0f, 0.0f, 1.0f}};
    renderer.render(camera, {.spheres = {&set, 1}}, image);
    EXPECT_TRUE(reddish(pixel_at(image, camera, Vec3(-0.25, -0.5, 0.2))));
    const Rgba8 hidden = pixel_at(image, camera, Vec3(0.25, 0.0, 0.2));
    EXPECT_GT(hidden.b, 200);
    EXPECT_LT(hidden.r, 50);
    EXPECT_LT(pixel_at(image, camera, Vec3(0.0, -1.0, -0.25)).r, 50);
}

TEST_F(RenderScene, PerTriangleColourLandsOnThatTriangle) {
    Renderer renderer(context, no_text());
    const TriangleMesh mesh = unit_box();
    const MeshId id = renderer.add_mesh(mesh, {.colour = {0.5f, 0.5f, 0.5f, 1.0f}, .lit = false});
    std::vector<std::size_t> front;  // the two triangles of the -y face, which faces the camera
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (mesh.group_names[static_cast<std::size_t>(mesh.group_of_triangle[t])] == "-y") front.push_back(t);
    }
    ASSERT_EQ(front.size(), 2u);
    std::vector<Rgba8> colours(mesh.triangle_count(), Rgba8{0, 0, 255, 255});
    colours[front[0]] = Rgba8{255, 0, 0, 255};
    colours[front[1]] = Rgba8{10, 200, 30, 255};
    renderer.set_triangle_colours(id, colours);
    const Camera camera = front_camera();
    renderer.render(camera, {}, image);
    auto centroid = [&](std::size_t t) { return (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0; };
    EXPECT_EQ(pixel_at(image, camera, centroid(front[0])), (Rgba8{255, 0, 0, 255}));
    EXPECT_EQ(pixel_at(image, camera, centroid(front[1])), (Rgba8{10, 200, 30, 255}));

    renderer.set_triangle_colours(id, {});  // back to the style colour
    renderer.render(camera, {}, image);
    EXPECT_EQ(pixel_at(image, camera, centroid(front[0])), (Rgba8{128, 128, 128, 255}));
    EXPECT_THROW(renderer.set_triangle_colours(id, std::vector<Rgba8>(3)), std::invalid_argument);
}

TEST_F(RenderScene, CutAwayChamberShowsThePartInside) {
    Renderer renderer(context, no_text());
    const MeshId chamber = renderer.add_mesh(inward_box(2.0), {.colour = {0.6f, 0.6f, 0.6f, 1.0f}, .cull = Cull::none});
    renderer.add_mesh(unit_box(Vec3::Zero(), 0.5), {.colour = {1.0f, 0.0f, 0.0f, 1.0f}});
    const Camera camera = front_camera(5.0);
    renderer.render(camera, {}, image);
    const Rgba8 closed = pixel_at(image, camera, Vec3::Zero());
    EXPECT_FALSE(reddish(closed)) << "without the cut-away the near wall hides the part";

    renderer.set_style(chamber, {.colour = {0.6f, 0.6f, 0.6f, 1.0f}, .cull = Cull::back});
    renderer.render(camera, {}, image);
    EXPECT_TRUE(reddish(pixel_at(image, camera, Vec3::Zero())));
    // Beside the part the far inner wall shows (not the background).
    const Rgba8 wall = pixel_at(image, camera, Vec3(0.7, 0.0, 0.7));
    EXPECT_GT(wall.r, 40);
    EXPECT_NEAR(wall.r, wall.g, 2);

    // Culling the other side is for outward-facing chambers: here it leaves the near wall.
    renderer.set_style(chamber, {.colour = {0.6f, 0.6f, 0.6f, 1.0f}, .cull = Cull::front});
    renderer.render(camera, {}, image);
    EXPECT_FALSE(reddish(pixel_at(image, camera, Vec3::Zero())));
}

TEST_F(RenderScene, TransparentChamberBlendsOverThePart) {
    Renderer renderer(context, no_text());
    renderer.add_mesh(inward_box(2.0), {.colour = {0.0f, 0.0f, 1.0f, 0.3f}});
    renderer.add_mesh(unit_box(Vec3::Zero(), 0.5), {.colour = {1.0f, 0.0f, 0.0f, 1.0f}, .lit = false});
    const Camera camera = front_camera(5.0);
    renderer.render(camera, {}, image);
    const Rgba8 c = pixel_at(image, camera, Vec3::Zero());
    EXPECT_GT(c.r, 100) << "the part shows through";
    EXPECT_LT(c.r, 240) << "the part is dimmed by the walls in front";
    EXPECT_GT(c.b, 40) << "the wall colour is mixed in";
    EXPECT_EQ(c.a, 255) << "the frame stays opaque";
}

TEST_F(RenderScene, ImpactMarkersBlendByTheirAlpha) {
    Renderer renderer(context, no_text());
    renderer.add_mesh(unit_box(), {.colour = {0.0f, 0.0f, 0.0f, 1.0f}, .lit = false});
    const Camera camera = front_camera();
    const ColourMap map = ColourMap::viridis();
    const Vec3 full(-0.25, -0.5, 0.0), half(0.25, -0.5, 0.0), gone(0.0, -0.5, 0.3);
    const std::vector<ImpactMarker> markers = {
        {full, 0.08, map.map(5.0, 0.0, 5.0)}, {half, 0.08, {1.0f, 1.0f, 1.0f, 0.5f}}, {gone, 0.08, {1.0f, 1.0f, 1.0f, 0.0f}}};
    renderer.render(camera, {.markers = markers}, image);
    const Rgba8 yellow = pixel_at(image, camera, full);  // top of viridis, lit ~flat at the centre
    EXPECT_TRUE(near(yellow, map.map8(5.0, 0.0, 5.0), 3)) << int(yellow.r) << "," << int(yellow.g) << "," << int(yellow.b);
    const Rgba8 grey = pixel_at(image, camera, half);
    EXPECT_NEAR(grey.r, 128, 3);
    EXPECT_EQ(pixel_at(image, camera, gone), (Rgba8{0, 0, 0, 255}));
}

TEST_F(RenderScene, MultisamplingSmoothsEdges) {
    auto count_partial = [&](OffscreenContext& ctx) {
        Renderer renderer(ctx, no_text());
        renderer.add_mesh(unit_box(), {.colour = {1.0f, 0.0f, 0.0f, 1.0f}, .lit = false});
        Camera camera = front_camera();
        camera.up = Vec3(0.3, 0.0, 1.0);  // a tilted box: its edges cross pixels at an angle
        renderer.render(camera, {}, image);
        EXPECT_EQ(pixel_at(image, camera, Vec3::Zero()), (Rgba8{255, 0, 0, 255}));
        int partial = 0;
        for (int y = 0; y < ctx.height(); ++y) {
            for (int x = 0; x < ctx.width(); ++x) partial += image.at(x, y).r > 0 && image.at(x, y).r < 255;
        }
        return partial;
    };
    EXPECT_EQ(count_partial(context), 0);
    OffscreenContext smooth(ContextOptions{kSceneW, kSceneH, 4});
    EXPECT_GT(count_partial(smooth), 20);
}

TEST_F(RenderScene, TextAndColourBarDrawOnlyInTheirCorners) {
    RenderOptions options;
    options.background = kBlack;
    Renderer renderer(context, options);
    const Camera camera = front_camera();
    RgbaImage plain;
    renderer.render(camera, {}, plain);

    const std::vector<std::string> lines = {"t = 1.234 s", "impacts: 5678"};
    const ColourBar bar{ColourMap::viridis(), 0.0, 3.5, "normal speed (m/s)"};
    renderer.render(camera, {.text = lines, .colour_bar = &bar}, image);
    int text_pixels = 0, changed_elsewhere = 0, bar_min = 0, bar_max = 0;
    for (int y = 0; y < kSceneH; ++y) {
        for (int x = 0; x < kSceneW; ++x) {
            const Rgba8 c = image.at(x, y);
            if (c == plain.at(x, y)) continue;
            if (x < kSceneW / 2 && y < kSceneH / 2) {
                text_pixels += c.r > 200 && c.g > 200 && c.b > 200;
            } else if (x < kSceneW / 2) {
                ++changed_elsewhere;
            }
            bar_min += near(c, Rgba8{0x44, 0x01, 0x54, 255}, 6);
            bar_max += near(c, Rgba8{0xFD, 0xE7, 0x25, 255}, 6);
        }
    }
    EXPECT_GT(text_pixels, 30) << "white text at the top left";
    EXPECT_EQ(changed_elsewhere, 0) << "the overlay touches the bottom-left quarter";
    EXPECT_GT(bar_min, 3) << "the colour bar's bottom (min) colour";
    EXPECT_GT(bar_max, 3) << "the colour bar's top (max) colour";
}

TEST_F(RenderScene, OverlayErrorsArePlain) {
    Renderer renderer(context, no_text());
    const std::vector<std::string> lines = {"t = 0 s"};
    EXPECT_THROW(renderer.render(front_camera(), {.text = lines}, image), std::logic_error);

    RenderOptions missing;
    missing.font_path = "/no/such/font.ttf";
    try {
        Renderer broken(context, missing);
        FAIL() << "expected std::runtime_error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/no/such/font.ttf"), std::string::npos) << e.what();
    }
}

TEST(RenderContext, RejectsImpossibleSizes) {
    EXPECT_THROW(OffscreenContext(ContextOptions{0, 10, 0}), std::invalid_argument);
    EXPECT_THROW(OffscreenContext(ContextOptions{10, 10, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace peensim::render
