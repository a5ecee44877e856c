// The `sources` and `sinks` sections: where shot enter and leave a run besides the initial load.
#include <cmath>
#include <set>

#include "common/cad_file.h"
#include "scene/scene_sections.h"

namespace peensim {

namespace {

std::string checked_name(const Cursor& c, std::set<std::string>& taken) {
    const std::string name = read_text(c);
    if (!is_valid_name(name)) fail(c, "invalid name '" + name + "'; names use only A-Z a-z 0-9 _ -");
    if (!taken.insert(name).second) fail(c, "duplicate name '" + name + "'; source and sink names must be unique");
    return name;
}

// Exactly one of the two keys.
void one_of(const Cursor& c, const char* a, const char* b) {
    const bool has_a = c.child(a).present(), has_b = c.child(b).present();
    if (has_a && has_b) fail(c.child(b), std::string("expected `") + a + "` or `" + b + "`, not both");
    if (!has_a && !has_b) fail(c, std::string("missing required key '") + a + "' (or '" + b + "')");
}

// position and direction, given or from the target: the exit `distance` from `target` along an axis
// at `angle_of_attack` to the surface (normal `target_normal`), leaning towards `azimuth`.
void read_placement(const Cursor& c, const Vec3& up, SourceDesc& d) {
    const bool by_target = c.child("target").present();
    if (by_target) {
        for (const char* key : {"position", "direction"})
            if (c.child(key).present()) fail(c.child(key), std::string("'") + key + "' and `target` both place the nozzle: expected one");
        if (!c.child("distance").present()) fail(c, "missing required key 'distance' (a nozzle placed by its target)");
        NozzleAim a;
        a.target_m = read_vector(c.child("target"));
        a.distance_m = read_quantity(c.child("distance"));
        a.angle_of_attack_rad = read_quantity(c.child("angle_of_attack"));
        a.target_normal = c.child("target_normal").present() ? *read_optional_direction(c.child("target_normal")) : up;
        a.azimuth_rad = read_quantity(c.child("azimuth"));
        // The lean's direction in the surface: world x projected on it (y when the normal is along x).
        const Vec3& n = a.target_normal;
        const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
        const Vec3 e1 = (helper - helper.dot(n) * n).normalized(), e2 = n.cross(e1);
        const Vec3 lean = std::cos(a.azimuth_rad) * e1 + std::sin(a.azimuth_rad) * e2;
        // From the nozzle towards the target: into the surface at the angle of attack.
        d.direction = (-std::sin(a.angle_of_attack_rad) * n + std::cos(a.angle_of_attack_rad) * lean).normalized();
        d.position_m = a.target_m - a.distance_m * d.direction;
        d.aim = a;
        return;
    }
    for (const char* key : {"distance", "angle_of_attack", "target_normal", "azimuth"})
        if (c.child(key).present()) fail(c.child(key), std::string("'") + key + "' places a nozzle by its `target`, which is missing");
    if (!c.child("position").present()) fail(c, "missing required key 'position' (or 'target')");
    if (!c.child("direction").present()) fail(c, "missing required key 'direction' (or 'target')");
    d.position_m = read_vector(c.child("position"));
    d.direction = *read_optional_direction(c.child("direction"));
}

// A nozzle's keys: where it is and where it aims, how fast and how wide it throws.
void read_nozzle(const Cursor& c, const Vec3& up, SourceDesc& d) {
    for (const char* key : {"opening_min", "opening_max"})
        if (c.child(key).present()) fail(c.child(key), std::string("'") + key + "' is only for kind hopper");
    read_placement(c, up, d);
    if (!c.child("speed").present()) fail(c, "missing required key 'speed' (a nozzle's mean exit speed)");
    d.speed_m_per_s = read_quantity(c.child("speed"));
    d.speed_spread = read_quantity(c.child("speed_spread"));
    if (c.child("air_speed").present()) d.air_speed_m_per_s = read_quantity(c.child("air_speed"));
    if (c.child("diameter").present() && c.child("exit_radius").present())
        fail(c.child("diameter"), "expected `diameter` or `exit_radius`, not both");
    d.exit_radius_m = c.child("diameter").present() ? 0.5 * read_quantity(c.child("diameter")) : read_quantity(c.child("exit_radius"));
    d.spread_rad = read_quantity(c.child("spread"));
}

// A hopper's keys: its opening, and none of a nozzle's.
void read_hopper(const Cursor& c, SourceDesc& d) {
    for (const char* key : {"position", "direction", "target", "distance", "angle_of_attack", "target_normal", "azimuth", "speed",
                            "speed_spread", "air_speed", "exit_radius", "diameter", "spread"})
        if (c.child(key).present())
            fail(c.child(key),
                 std::string("'") + key + "' is a nozzle's; a hopper drops its shot at rest from `opening_min` to `opening_max`");
    for (const char* key : {"opening_min", "opening_max"})
        if (!c.child(key).present()) fail(c, std::string("missing required key '") + key + "' (a hopper's opening)");
    HopperOpening o;
    o.lo_m = read_vector(c.child("opening_min"));
    o.hi_m = read_vector(c.child("opening_max"));
    if (!((o.hi_m.array() >= o.lo_m.array()).all())) fail(c.child("opening_max"), "expected opening_max >= opening_min in x, y and z");
    d.opening = o;
    d.speed_m_per_s = 0.0;
}

}  // namespace

void read_flow(const Cursor& sources, const Cursor& sinks, double duration_s, double shot_mass_kg, const Vec3& up,
               const std::filesystem::path& scene_dir, std::vector<SourceDesc>& out_sources, std::vector<SinkDesc>& out_sinks) {
    std::set<std::string> names;
    for (std::size_t i = 0; i < sources.size(); ++i) {
        const Cursor c = sources.item(i);
        SourceDesc d;
        d.name = checked_name(c.child("name"), names);
        d.kind = read_choice(c.child("kind")) == "hopper" ? SourceKind::hopper : SourceKind::nozzle;
        if (d.kind == SourceKind::hopper)
            read_hopper(c, d);
        else
            read_nozzle(c, up, d);
        one_of(c, "rate", "mass_flow");
        if (c.child("mass_flow").present()) {
            d.mass_flow_kg_per_s = read_quantity(c.child("mass_flow"));
            d.rate_per_s = *d.mass_flow_kg_per_s / shot_mass_kg;
            if (!(d.rate_per_s <= 1e8))
                fail(c.child("mass_flow"), "expected at most 1e8 shot per second, got " + format_si(d.rate_per_s) + " for this shot");
        } else {
            d.rate_per_s = read_quantity(c.child("rate"));
        }
        d.start_s = read_quantity(c.child("start"));
        d.stop_s = c.child("stop").present() ? read_quantity(c.child("stop")) : duration_s;
        if (!(d.stop_s > d.start_s)) fail(c.child("stop"), "expected a stop after the start (" + format_si(d.start_s) + " s)");
        d.where = location_of(c);
        out_sources.push_back(d);
    }
    for (std::size_t i = 0; i < sinks.size(); ++i) {
        const Cursor c = sinks.item(i);
        SinkDesc d;
        d.name = checked_name(c.child("name"), names);
        const std::string region = read_choice(c.child("region"));
        d.region = region == "outside" ? SinkRegion::outside : region == "mesh" ? SinkRegion::mesh : SinkRegion::box;
        for (const char* key : {"mesh", "mesh_unit", "translation"})
            if (d.region != SinkRegion::mesh && c.child(key).present())
                fail(c.child(key), std::string("'") + key + "' is only for region mesh");
        if (d.region == SinkRegion::mesh) {
            if (!c.child("mesh").present()) fail(c, "missing required key 'mesh' (a mesh sink needs its closed mesh)");
            d.mesh_path = resolve_mesh(c.child("mesh"), scene_dir);
            d.mesh_where = location_of(c.child("mesh"));
            if (is_cad_file(d.mesh_path) && c.child("mesh_unit").present())  // as for components (scene_components.cpp)
                fail(c.child("mesh_unit"), "mesh_unit does not apply to a STEP or IGES file: '" + d.mesh_path +
                                               "' states its own length unit, which is used; remove mesh_unit");
            d.mesh_unit_m = is_cad_file(d.mesh_path) ? 1.0 : parse_quantity("1 " + read_choice(c.child("mesh_unit")), Dimension::length);
            d.translation_m = read_vector(c.child("translation"));
        }
        if (d.region == SinkRegion::box) {
            if (!c.child("min").present()) fail(c.child("min"), "missing required key 'min' (a box sink needs its corners)");
            if (!c.child("max").present()) fail(c.child("max"), "missing required key 'max' (a box sink needs its corners)");
            d.min_m = read_vector(c.child("min"));
            d.max_m = read_vector(c.child("max"));
            if (!((d.max_m.array() > d.min_m.array()).all())) fail(c.child("max"), "expected max > min in x, y and z");
        } else {
            for (const char* key : {"min", "max"})
                if (c.child(key).present()) fail(c.child(key), std::string("'") + key + "' is only for region box");
        }
        d.where = location_of(c);
        out_sinks.push_back(d);
    }
}

}  // namespace peensim
