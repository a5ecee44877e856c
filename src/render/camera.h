// Where the renderer looks from: a perspective camera in world coordinates (m), its matrices,
// an automatic framing of a bounding box, and the projection of world points to pixels.
#pragma once

#include <optional>
#include <span>

#include "common/vec.h"

namespace peensim::render {

using Mat4 = Eigen::Matrix4d;
using Vec2 = Eigen::Vector2d;

struct Camera {
    Vec3 position_m = Vec3(0.0, -1.0, 0.0);  // m, world
    Vec3 look_at_m = Vec3::Zero();           // m, world; the image centre
    Vec3 up = Vec3::UnitZ();                 // world direction shown upward (need not be unit)
    double vertical_fov_deg = 40.0;          // deg, full opening angle of the image height
    double near_m = 0.01;                    // m, nearest depth drawn (> 0)
    double far_m = 10.0;                     // m, farthest depth drawn (> near)

    // Front-above and a little from the side: the default view of framing(). World z is up,
    // the camera looks along +y, down by about 30 deg, turned about 20 deg toward +x.
    static Vec3 default_view_direction();

    // A camera looking along `view_direction` (toward the scene) at the centre of the box, far
    // enough that all 8 corners lie inside the central 90 % of the image of this `aspect`
    // (width / height); up is world +z (world +y when looking along z); near/far from the box.
    // Throws std::invalid_argument for a zero or non-finite direction, aspect <= 0, or a field
    // of view outside (0, 180) deg.
    static Camera framing(const Vec3& bounds_min_m, const Vec3& bounds_max_m, double aspect,
                          const Vec3& view_direction = default_view_direction(), double vertical_fov_deg = 40.0);

    // The same for a set of points (e.g. a mesh's vertices: a round chamber then fills the frame,
    // where its bounding box's corners would leave a margin). Throws std::invalid_argument for an
    // empty set and as framing() does.
    static Camera framing_points(std::span<const Vec3> points, double aspect, const Vec3& view_direction = default_view_direction(),
                                 double vertical_fov_deg = 40.0);

    // Sets near/far to enclose the box (with a 2 % margin of its diagonal) along the view axis.
    // A camera inside the box keeps a near plane of 1/1000 of the far one.
    void fit_depth_range(const Vec3& bounds_min_m, const Vec3& bounds_max_m);

    // World to camera (right-handed, the camera looks down its -z).
    Mat4 view_matrix() const;
    // Camera to clip space (OpenGL conventions: depth -1 at near, +1 at far).
    Mat4 projection_matrix(double aspect) const;

    // Pixel position of a world point in an image of width x height: x right, y down from the
    // top-left corner, pixel (i, j) covering [i, i+1) x [j, j+1). nullopt for a point at or
    // behind the camera plane. Points outside the image give coordinates outside [0, size).
    std::optional<Vec2> project_to_pixel(const Vec3& world_m, int width, int height) const;
};

}  // namespace peensim::render
