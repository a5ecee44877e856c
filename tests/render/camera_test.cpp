// Camera matrices, automatic framing and the world-to-pixel projection (no OpenGL needed).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "render/camera.h"

namespace peensim::render {
namespace {

constexpr int kW = 160, kH = 120;

std::array<Vec3, 8> box_corners(const Vec3& lo, const Vec3& hi) {
    std::array<Vec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[static_cast<std::size_t>(i)] = Vec3(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    return c;
}

TEST(RenderCamera, LookAtPointProjectsToTheImageCentre) {
    Camera camera;
    camera.position_m = Vec3(0.3, -0.5, 0.2);
    camera.look_at_m = Vec3(0.01, 0.02, 0.03);
    const auto pixel = camera.project_to_pixel(camera.look_at_m, kW, kH);
    ASSERT_TRUE(pixel.has_value());
    EXPECT_NEAR(pixel->x(), kW / 2.0, 1e-9);
    EXPECT_NEAR(pixel->y(), kH / 2.0, 1e-9);
}

TEST(RenderCamera, ImageAxesPointRightAndDown) {
    Camera camera;  // at -y, looking along +y, z up: world +x is image right, world +z is image up
    camera.position_m = Vec3(0.0, -1.0, 0.0);
    camera.look_at_m = Vec3::Zero();
    const Vec2 right = *camera.project_to_pixel(Vec3(0.1, 0.0, 0.0), kW, kH);
    const Vec2 up = *camera.project_to_pixel(Vec3(0.0, 0.0, 0.1), kW, kH);
    EXPECT_GT(right.x(), kW / 2.0);
    EXPECT_NEAR(right.y(), kH / 2.0, 1e-9);
    EXPECT_LT(up.y(), kH / 2.0);
    // 0.1 m at 1 m with a 40 deg vertical field: tan(atan(0.1)) / tan(20 deg) of the half height.
    EXPECT_NEAR(kH / 2.0 - up.y(), 0.1 / std::tan(20.0 * std::numbers::pi / 180.0) * kH / 2.0, 1e-9);
}

TEST(RenderCamera, PointsBehindTheCameraDoNotProject) {
    Camera camera;
    camera.position_m = Vec3(0.0, -1.0, 0.0);
    camera.look_at_m = Vec3::Zero();
    EXPECT_FALSE(camera.project_to_pixel(Vec3(0.0, -2.0, 0.0), kW, kH).has_value());
}

TEST(RenderCamera, FramingShowsTheWholeBoxAndFillsTheFrame) {
    const Vec3 lo(-0.03, -0.03, 0.0), hi(0.03, 0.03, 0.075);  // the gear chamber's size
    for (const Vec3& direction : {Camera::default_view_direction(), Vec3(1.0, 0.0, 0.0), Vec3(0.0, 0.0, -1.0)}) {
        const Camera camera = Camera::framing(lo, hi, static_cast<double>(kW) / kH, direction);
        double x_min = kW, x_max = 0.0, y_min = kH, y_max = 0.0;
        for (const Vec3& corner : box_corners(lo, hi)) {
            const auto p = camera.project_to_pixel(corner, kW, kH);
            ASSERT_TRUE(p.has_value());
            x_min = std::min(x_min, p->x()), x_max = std::max(x_max, p->x());
            y_min = std::min(y_min, p->y()), y_max = std::max(y_max, p->y());
            const double depth = (corner - camera.position_m).dot((camera.look_at_m - camera.position_m).normalized());
            EXPECT_GT(depth, camera.near_m);
            EXPECT_LT(depth, camera.far_m);
        }
        // Inside the central 90 % (plus rounding), and touching it on at least one side.
        EXPECT_GE(x_min, 0.05 * kW - 1e-6);
        EXPECT_LE(x_max, 0.95 * kW + 1e-6);
        EXPECT_GE(y_min, 0.05 * kH - 1e-6);
        EXPECT_LE(y_max, 0.95 * kH + 1e-6);
        const bool tight = x_min < 0.05 * kW + 1.0 || x_max > 0.95 * kW - 1.0 || y_min < 0.05 * kH + 1.0 || y_max > 0.95 * kH - 1.0;
        EXPECT_TRUE(tight) << "framing leaves the box small: x " << x_min << ".." << x_max << ", y " << y_min << ".." << y_max;
        EXPECT_GT(camera.near_m, 0.0);
    }
}

TEST(RenderCamera, FramingPointsFitsARoundChamberTighterThanItsBox) {
    // Rings of a cylinder (r 30 mm, z 0..75 mm): framed by its points it fills the central 90 %
    // and appears larger than when framed by its bounding box (whose corners stick out).
    std::vector<Vec3> points;
    for (int i = 0; i < 64; ++i)
        for (double z : {0.0, 0.075}) points.emplace_back(0.03 * std::cos(i * M_PI / 32), 0.03 * std::sin(i * M_PI / 32), z);
    const Camera by_points = Camera::framing_points(points, static_cast<double>(kW) / kH);
    const Camera by_box = Camera::framing(Vec3(-0.03, -0.03, 0.0), Vec3(0.03, 0.03, 0.075), static_cast<double>(kW) / kH);
    double y_min = kH, y_max = 0.0, x_min = kW, x_max = 0.0;
    for (const Vec3& p : points) {
        const auto q = by_points.project_to_pixel(p, kW, kH);
        ASSERT_TRUE(q.has_value());
        EXPECT_GE(q->x(), 0.05 * kW - 1e-6);
        EXPECT_LE(q->x(), 0.95 * kW + 1e-6);
        EXPECT_GE(q->y(), 0.05 * kH - 1e-6);
        EXPECT_LE(q->y(), 0.95 * kH + 1e-6);
        y_min = std::min(y_min, q->y()), y_max = std::max(y_max, q->y());
        x_min = std::min(x_min, q->x()), x_max = std::max(x_max, q->x());
    }
    EXPECT_TRUE(y_min < 0.05 * kH + 1.0 || y_max > 0.95 * kH - 1.0 || x_min < 0.05 * kW + 1.0 || x_max > 0.95 * kW - 1.0);
    EXPECT_LT((by_points.position_m - by_points.look_at_m).norm(), (by_box.position_m - by_box.look_at_m).norm());
    EXPECT_THROW(Camera::framing_points({}, 1.0), std::invalid_argument);
}

TEST(RenderCamera, FramingRejectsADegenerateView) {
    EXPECT_THROW(Camera::framing(Vec3::Zero(), Vec3::Ones(), 1.0, Vec3::Zero()), std::invalid_argument);
    EXPECT_THROW(Camera::framing(Vec3::Zero(), Vec3::Ones(), 0.0), std::invalid_argument);
}

TEST(RenderCamera, DefaultViewIsFromFrontAndAbove) {
    const Vec3 d = Camera::default_view_direction();
    EXPECT_GT(d.y(), 0.0);  // the camera stands at -y, looking toward +y
    EXPECT_LT(d.z(), 0.0);  // looking down
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
}

TEST(RenderCamera, DepthRangeEnclosesTheBoxFromInsideToo) {
    Camera camera;
    camera.position_m = Vec3::Zero();  // inside the box
    camera.look_at_m = Vec3(0.0, 1.0, 0.0);
    camera.fit_depth_range(Vec3(-1, -1, -1), Vec3(1, 1, 1));
    EXPECT_GT(camera.near_m, 0.0);
    EXPECT_GT(camera.far_m, 1.0);  // depth is along the view axis: the far face is at y = 1
    EXPECT_LT(camera.near_m, 0.01);
}

}  // namespace
}  // namespace peensim::render
