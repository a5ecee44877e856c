// Regions of a component: named selections of its surface (sector, sectors, box, half_space,
// distance_to_axis, distance_to_point, facing, group; several in one entry select their
// intersection). The schema checks the keys; this checks what it cannot: at least one condition,
// one angular one at most, axes not zero, references not along the axis, from < to, box corners in
// order, distances in order, names unique.
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "scene/scene_sections.h"

namespace peensim {
namespace {

constexpr double kSceneFullTurnRad = 2.0 * std::numbers::pi;  // rad
// A reference direction closer to the axis than this (sine of the angle, -) leaves angle 0
// undefined to within round-off.
constexpr double min_reference_sine = 1e-9;
// "360 deg" converted to rad may exceed 2 pi by a rounding (rad).
constexpr double full_turn_slack_rad = 1e-12;

constexpr std::string_view condition_keys[] = {"sector",           "sectors",           "box",    "half_space",
                                               "distance_to_axis", "distance_to_point", "facing", "group"};

Vec3 read_direction(const Cursor& c) { return *read_optional_direction(c); }

AxisAngleFrame read_frame(const Cursor& c) {
    AxisAngleFrame f;
    f.axis_point_m = read_vector(c.child("axis_point"));
    f.axis_direction = read_direction(c.child("axis_direction"));
    f.reference = read_direction(c.child("reference"));
    if (!(f.reference.cross(f.axis_direction).norm() > min_reference_sine))
        fail(c.child("reference"), "expected a reference direction not along the axis (angle 0 is measured from it)");
    return f;
}

SectorCondition read_sector(const Cursor& c) {
    SectorCondition s{read_frame(c), read_quantity(c.child("from")), read_quantity(c.child("to"))};
    if (!(s.from_rad < s.to_rad)) fail(c.child("to"), "expected an angle greater than `from`");
    if (!(s.to_rad - s.from_rad <= kSceneFullTurnRad + full_turn_slack_rad)) fail(c.child("to"), "expected at most 360 deg from `from`");
    return s;
}

SectorsCondition read_sectors(const Cursor& c, const std::string& entry_name) {
    SectorsCondition s;
    s.frame = read_frame(c);
    s.count = static_cast<int>(read_integer(c.child("count")));
    s.width_rad = read_quantity(c.child("width"));
    if (!(s.width_rad <= kSceneFullTurnRad + full_turn_slack_rad)) fail(c.child("width"), "expected a width of at most 360 deg");
    s.offset_rad = read_quantity(c.child("offset"));
    const Cursor prefix = c.child("name_prefix");
    s.name_prefix = prefix.present() ? read_text(prefix) : entry_name + "-";
    if (!is_valid_name(s.name_prefix + "0"))
        fail(prefix.present() ? prefix : c, "invalid name prefix '" + s.name_prefix + "'; names use only A-Z a-z 0-9 _ -");
    return s;
}

BoxCondition read_box(const Cursor& c) {
    BoxCondition b{read_vector(c.child("min")), read_vector(c.child("max"))};
    if (!(b.min_m.array() <= b.max_m.array()).all()) fail(c.child("max"), "expected a corner >= min in x, y and z");
    return b;
}

// min and max of a distance condition: max > min >= 0; no max = no upper bound.
std::pair<double, double> read_distance_range(const Cursor& c) {
    const double min = read_quantity(c.child("min"));
    const std::optional<double> max = read_optional_quantity(c.child("max"));
    if (max && !(*max > min)) fail(c.child("max"), "expected a distance greater than `min`");
    if (!max && !(min > 0.0)) fail(c, "expected `max`, or a `min` above 0 (the condition would hold everywhere)");
    return {min, max.value_or(std::numeric_limits<double>::infinity())};
}

RegionDesc read_region(const Cursor& c) {
    RegionDesc r;
    r.name = read_text(c.child("name"));
    if (!is_valid_name(r.name)) fail(c.child("name"), "invalid name '" + r.name + "'; names use only A-Z a-z 0-9 _ -");
    r.where = location_of(c);
    int conditions = 0;
    for (std::string_view k : condition_keys) conditions += c.child(k).present() ? 1 : 0;
    if (conditions == 0)
        fail(c,
             "expected at least one of sector, sectors, box, half_space, distance_to_axis, distance_to_point, facing, group "
             "(several select where all of them hold)");
    if (c.child("sector").present() && c.child("sectors").present())
        fail(c.child("sectors"), "expected `sector` or `sectors`, not both (one angular condition per region)");
    if (const Cursor x = c.child("sector"); x.present()) r.sector = read_sector(x);
    if (const Cursor x = c.child("sectors"); x.present()) r.sectors = read_sectors(x, r.name);
    if (const Cursor x = c.child("box"); x.present()) r.box = read_box(x);
    if (const Cursor h = c.child("half_space"); h.present())
        r.half_space = HalfSpaceCondition{read_vector(h.child("point")), read_direction(h.child("normal"))};
    if (const Cursor a = c.child("distance_to_axis"); a.present()) {
        const auto [min, max] = read_distance_range(a);
        r.distance_to_axis = AxisDistanceCondition{read_vector(a.child("axis_point")), read_direction(a.child("axis_direction")), min, max};
    }
    if (const Cursor p = c.child("distance_to_point"); p.present()) {
        const auto [min, max] = read_distance_range(p);
        r.distance_to_point = PointDistanceCondition{read_vector(p.child("point")), min, max};
    }
    if (const Cursor f = c.child("facing"); f.present()) {
        r.facing = FacingCondition{read_direction(f.child("direction")), read_quantity(f.child("within"))};
        if (!(r.facing->within_rad <= 0.5 * kSceneFullTurnRad + full_turn_slack_rad)) fail(f.child("within"), "expected at most 180 deg");
    }
    if (const Cursor g = c.child("group"); g.present()) r.group = read_text(g);
    r.exclude = read_choice(c.child("exclude")) == "true";
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
