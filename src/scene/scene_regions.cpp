// Regions of a component: named selections of its triangles (sector, sectors, box, half-space,
// group). The schema checks the keys; this checks what it cannot: one kind per region, axes not
// zero, references not along the axis, from < to, box corners in order, names unique.
#include <cmath>
#include <numbers>
#include <set>

#include "scene/scene_sections.h"

namespace peensim {
namespace {

constexpr double full_turn_rad = 2.0 * std::numbers::pi;  // rad
// A reference direction closer to the axis than this (sine of the angle, -) leaves angle 0
// undefined to within round-off.
constexpr double min_reference_sine = 1e-9;
// "360 deg" converted to rad may exceed 2 pi by a rounding (rad).
constexpr double full_turn_slack_rad = 1e-12;

constexpr std::string_view region_kinds[] = {"sector", "sectors", "box", "half_space", "group"};

Vec3 read_direction(const Cursor& c) { return *read_optional_direction(c); }

Vec3 read_reference(const Cursor& c, const Vec3& axis) {
    const Vec3 ref = read_direction(c);
    if (!(ref.cross(axis).norm() > min_reference_sine))
        fail(c, "expected a reference direction not along the axis (angle 0 is measured from it)");
    return ref;
}

void read_sector(const Cursor& c, RegionDesc& r) {
    r.kind = RegionKind::sector;
    r.axis_point_m = read_vector(c.child("axis_point"));
    r.axis_direction = read_direction(c.child("axis_direction"));
    r.reference = read_reference(c.child("reference"), r.axis_direction);
    r.from_rad = read_quantity(c.child("from"));
    r.to_rad = read_quantity(c.child("to"));
    if (!(r.from_rad < r.to_rad)) fail(c.child("to"), "expected an angle greater than `from`");
    if (!(r.to_rad - r.from_rad <= full_turn_rad + full_turn_slack_rad)) fail(c.child("to"), "expected at most 360 deg from `from`");
}

void read_sectors(const Cursor& c, RegionDesc& r) {
    r.kind = RegionKind::sectors;
    r.axis_point_m = read_vector(c.child("axis_point"));
    r.axis_direction = read_direction(c.child("axis_direction"));
    r.reference = read_reference(c.child("reference"), r.axis_direction);
    r.count = static_cast<int>(read_integer(c.child("count")));
    r.width_rad = read_quantity(c.child("width"));
    if (!(r.width_rad <= full_turn_rad + full_turn_slack_rad)) fail(c.child("width"), "expected a width of at most 360 deg");
    r.offset_rad = read_quantity(c.child("offset"));
    const Cursor prefix = c.child("name_prefix");
    r.name_prefix = prefix.present() ? read_text(prefix) : r.name + "-";
    if (!is_valid_name(r.name_prefix + "0"))
        fail(prefix.present() ? prefix : c, "invalid name prefix '" + r.name_prefix + "'; names use only A-Z a-z 0-9 _ -");
}

void read_box(const Cursor& c, RegionDesc& r) {
    r.kind = RegionKind::box;
    r.box_min_m = read_vector(c.child("min"));
    r.box_max_m = read_vector(c.child("max"));
    if (!(r.box_min_m.array() <= r.box_max_m.array()).all()) fail(c.child("max"), "expected a corner >= min in x, y and z");
}

RegionDesc read_region(const Cursor& c) {
    RegionDesc r;
    r.name = read_text(c.child("name"));
    if (!is_valid_name(r.name)) fail(c.child("name"), "invalid name '" + r.name + "'; names use only A-Z a-z 0-9 _ -");
    r.where = location_of(c);
    int kinds = 0;
    for (std::string_view k : region_kinds) kinds += c.child(k).present() ? 1 : 0;
    if (kinds != 1) fail(c, "expected exactly one of sector, sectors, box, half_space, group, got " + std::to_string(kinds));
    if (c.child("sector").present()) read_sector(c.child("sector"), r);
    if (c.child("sectors").present()) read_sectors(c.child("sectors"), r);
    if (c.child("box").present()) read_box(c.child("box"), r);
    if (const Cursor h = c.child("half_space"); h.present()) {
        r.kind = RegionKind::half_space;
        r.plane_point_m = read_vector(h.child("point"));
        r.plane_normal = read_direction(h.child("normal"));
    }
    if (const Cursor g = c.child("group"); g.present()) {
        r.kind = RegionKind::group;
        r.group = read_text(g);
    }
    return r;
}

}  // namespace

std::vector<RegionDesc> read_regions(const Cursor& c) {
    std::vector<RegionDesc> out;
    std::set<std::string> names;  // every region name so far (sectors expanded)
    for (std::size_t i = 0; i < c.size(); ++i) {
        const Cursor item = c.item(i);
        RegionDesc r = read_region(item);
        for (const std::string& n : region_names(r))
            if (!names.insert(n).second)
                fail(item.child("name"), "duplicate region name '" + n + "' on this component; region names must be unique");
        out.push_back(std::move(r));
    }
    return out;
}

}  // namespace peensim
