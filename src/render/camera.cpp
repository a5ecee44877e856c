#include "render/camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace peensim::render {

namespace {

constexpr double kFramingFill = 0.9;      // -, part of the image the framed box may span
constexpr double kDepthMargin = 0.02;     // -, of the box diagonal, added before near and after far
constexpr double kNearOverFarMin = 1e-3;  // -, floor of near / far (depth buffer resolution)

double radians(double deg) { return deg * std::numbers::pi / 180.0; }

std::array<Vec3, 8> corners(const Vec3& lo, const Vec3& hi) {
    std::array<Vec3, 8> c;
    for (int i = 0; i < 8; ++i) {
        c[static_cast<std::size_t>(i)] = Vec3(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    }
    return c;
}

}  // namespace

Vec3 Camera::default_view_direction() { return Vec3(0.35, 1.0, -0.6).normalized(); }

Camera Camera::framing(const Vec3& bounds_min_m, const Vec3& bounds_max_m, double aspect, const Vec3& view_direction,
                       double vertical_fov_deg) {
    const auto box = corners(bounds_min_m, bounds_max_m);
    return framing_points(box, aspect, view_direction, vertical_fov_deg);
}

Camera Camera::framing_points(std::span<const Vec3> points, double aspect, const Vec3& view_direction, double vertical_fov_deg) {
    if (!(view_direction.norm() > 0.0) || !view_direction.allFinite()) {
        throw std::invalid_argument("render: camera view direction must be a finite non-zero vector");
    }
    if (!(aspect > 0.0) || !(vertical_fov_deg > 0.0 && vertical_fov_deg < 180.0)) {
        throw std::invalid_argument("render: camera framing needs aspect > 0 and 0 < field of view < 180 deg");
    }
    if (points.empty()) throw std::invalid_argument("render: camera framing needs at least one point");
    Vec3 lo = points.front(), hi = points.front();
    for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const Vec3 d = view_direction.normalized();
    const Vec3 up = std::abs(d.z()) > 0.99 ? Vec3::UnitY() : Vec3::UnitZ();
    const Vec3 right = d.cross(up).normalized();
    const Vec3 true_up = right.cross(d);
    const Vec3 centre = 0.5 * (lo + hi);
    const double tan_v = std::tan(0.5 * radians(vertical_fov_deg)) * kFramingFill;
    const double tan_h = tan_v * aspect;

    // A point at (x, y, z) in the camera basis, seen from distance D behind the centre, is
    // inside the frame when |x| <= (z + D) tan_h and |y| <= (z + D) tan_v.
    double distance = 0.0;
    for (const Vec3& point : points) {
        const Vec3 q = point - centre;
        const double z = q.dot(d);
        distance = std::max({distance, std::abs(q.dot(right)) / tan_h - z, std::abs(q.dot(true_up)) / tan_v - z});
    }
    if (distance == 0.0) distance = 1e-3;  // one point: view it from about 1 mm

    Camera camera;
    camera.position_m = centre - distance * d;
    camera.look_at_m = centre;
    camera.up = up;
    camera.vertical_fov_deg = vertical_fov_deg;
    camera.fit_depth_range(lo, hi);
    return camera;
}

void Camera::fit_depth_range(const Vec3& bounds_min_m, const Vec3& bounds_max_m) {
    const Vec3 d = (look_at_m - position_m).normalized();
    const double margin = std::max(kDepthMargin * (bounds_max_m - bounds_min_m).norm(), 1e-6);
    double z_min = std::numeric_limits<double>::infinity();
    double z_max = -std::numeric_limits<double>::infinity();
    for (const Vec3& corner : corners(bounds_min_m, bounds_max_m)) {
        const double z = (corner - position_m).dot(d);
        z_min = std::min(z_min, z);
        z_max = std::max(z_max, z);
    }
    far_m = std::max(z_max + margin, 2.0 * margin);
    near_m = std::max(z_min - margin, far_m * kNearOverFarMin);
}

Mat4 Camera::view_matrix() const {
    const Vec3 f = (look_at_m - position_m).normalized();
    const Vec3 s = f.cross(up).normalized();
    const Vec3 u = s.cross(f);
    Mat4 m = Mat4::Identity();
    m.block<1, 3>(0, 0) = s.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -s.dot(position_m);
    m(1, 3) = -u.dot(position_m);
    m(2, 3) = f.dot(position_m);
    return m;
}

Mat4 Camera::projection_matrix(double aspect) const {
    const double t = 1.0 / std::tan(0.5 * radians(vertical_fov_deg));
    Mat4 m = Mat4::Zero();
    m(0, 0) = t / aspect;
    m(1, 1) = t;
    m(2, 2) = -(far_m + near_m) / (far_m - near_m);
    m(2, 3) = -2.0 * far_m * near_m / (far_m - near_m);
    m(3, 2) = -1.0;
    return m;
}

std::optional<Vec2> Camera::project_to_pixel(const Vec3& world_m, int width, int height) const {
    const Eigen::Vector4d clip =
        projection_matrix(static_cast<double>(width) / static_cast<double>(height)) * view_matrix() * world_m.homogeneous();
    if (clip.w() <= 0.0) return std::nullopt;
    const double x = clip.x() / clip.w();
    const double y = clip.y() / clip.w();
    return Vec2(0.5 * (x + 1.0) * width, 0.5 * (1.0 - y) * height);
}

}  // namespace peensim::render
