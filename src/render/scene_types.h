// What a frame shows, as plain values: mesh styles, sets of spheres (shot), impact markers and
// the colour bar. The Renderer draws them; the caller owns the data.
#pragma once

#include <limits>
#include <span>
#include <string>

#include "common/vec.h"
#include "render/camera.h"
#include "render/colour.h"
#include "render/colour_map.h"

namespace peensim::render {

// Which side of a mesh's triangles is dropped. A triangle's front is the side its normal points
// to (counter-clockwise corners, see TriangleMesh). For a closed chamber seen from outside,
// dropping the walls that face away from the inside cuts the near walls away and leaves the
// far inner walls: `back` for a chamber whose normals face the cavity (the generated ones),
// `front` for a closed solid with outward normals used as a chamber.
enum class Cull { none, back, front };

struct MeshStyle {
    Rgba colour{0.72f, 0.74f, 0.78f, 1.0f};  // alpha < 1: transparent, blended over what is behind
    Cull cull = Cull::none;
    bool lit = true;  // false: flat colours (an impact map that must match its colour bar exactly)
    bool visible = true;
};

// Rigid transform of a mesh: world_from_mesh (rotation and translation, m).
inline Mat4 make_pose(const Mat3& rotation, const Vec3& translation_m) {
    Mat4 m = Mat4::Identity();
    m.block<3, 3>(0, 0) = rotation;
    m.block<3, 1>(0, 3) = translation_m;
    return m;
}

// Spheres of one radius and colour, centres as three coordinate arrays (the simulator's shot
// layout, no copy needed). All spans have the same size; `active`, if not empty, hides the
// spheres whose entry is 0.
struct SphereSet {
    std::span<const double> x_m{}, y_m{}, z_m{};  // m, world centres
    std::span<const unsigned char> active{};
    double radius_m = 0.0;  // m, every sphere's, unless radii_m is given
    Rgba colour{0.85f, 0.86f, 0.9f, 1.0f};
    std::span<const double> radii_m{};  // m, per sphere (a shot mix); empty: radius_m for all
};

// A flash where an impact happened: a small sphere centred on the contact point (half of it
// sticks out of the wall, so it reads as a disc on the surface). The caller fades it over a
// few frames by lowering colour.a; alpha 0 draws nothing.
struct ImpactMarker {
    Vec3 point_m = Vec3::Zero();  // m, world
    double radius_m = 0.0;        // m
    Rgba colour;                  // typically ColourMap::map(normal speed, ...)
};

// A word of text at a pixel of the frame (e.g. a region's name over its projected centre), in its
// own colour over a dark shadow.
struct Label {
    float x_px = 0.0f;  // px from the left edge: the text's centre
    float y_px = 0.0f;  // px from the top edge: its baseline
    std::string text;   // ASCII
    Rgba8 colour{255, 255, 255, 255};
};

// An impact drawn as a glow of a fixed size in pixels (render/glow_layer.h): the recorder's way to
// make impacts visible in a chamber-wide view. The caller fades it by lowering colour.a.
struct ImpactGlow {
    Vec3 point_m = Vec3::Zero();  // m, world: the contact point
    double lift_m = 0.0;          // m, moved toward the eye for the depth test (its own surface must not hide it)
    float radius_px = 0.0f;       // px, the sprite's radius in the image
    Rgba colour;                  // its body's colour (typically ColourMap::map(normal speed, ...)); a fades it
};

// A vertical colour bar at the right edge of the frame: `title` above, `max` at the top end,
// `min` at the bottom end (labels printed with 3 significant digits).
struct ColourBar {
    ColourMap map = ColourMap::viridis();
    double min = 0.0;
    double max = 1.0;
    std::string title{};       // e.g. "normal speed (m/s)"; ASCII (other characters print as '?')
    double label_scale = 1.0;  // the labels show value x this (100: a fraction in per cent)
    std::string label_unit{};  // after each label's number (" %")
    // A value marked across the bar with mark_label beside it (a coverage target); NaN: none. A
    // mark above max is written under the bar as "<mark_label>: above the scale".
    double mark = std::numeric_limits<double>::quiet_NaN();
    std::string mark_label{};
};

}  // namespace peensim::render
