// The small sections: process, accuracy, shot, output.
#include "scene/scene_sections.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/units.h"

namespace peensim {

ProcessDesc read_process(const Cursor& c) {
    ProcessDesc d;
    d.duration_s = read_quantity(c.child("duration"));
    d.gravity_m_per_s2 = read_vector(c.child("gravity"));
    d.seed = static_cast<std::uint64_t>(read_integer(c.child("seed")));
    d.until_coverage = read_optional_quantity(c.child("until_coverage"));
    if (c.child("until_coverage_of").present()) {
        if (!d.until_coverage) fail(c.child("until_coverage_of"), "until_coverage_of needs until_coverage (the target, e.g. 98 %)");
        d.until_coverage_of = read_names(c.child("until_coverage_of"));
    }
    d.where = location_of(c);
    return d;
}

AccuracyDesc read_accuracy(const Cursor& c) {
    AccuracyDesc d;
    d.travel_fraction = read_quantity(c.child("travel_fraction"));
    d.impact_speed_m_per_s = read_quantity(c.child("impact_speed"));
    const std::string scheme = read_choice(c.child("scheme"));
    if (scheme == "step") d.scheme = SteppingScheme::step;
    if (scheme == "event") d.scheme = SteppingScheme::event;
    if (scheme == "soft") d.scheme = SteppingScheme::soft;
    d.soft_steps_per_contact = read_quantity(c.child("soft_steps_per_contact"));
    d.scheme_given = c.child("scheme").present();
    d.where = location_of(c);
    return d;
}

namespace {

// One `diameter`, or a mix in `sizes` (diameters with fractions summing to 1).
void read_sizes(const Cursor& c, ShotDesc& d) {
    const Cursor diameter = c.child("diameter"), sizes = c.child("sizes");
    if (diameter.present() && sizes.present()) fail(sizes, "give either shot.diameter (one size) or shot.sizes (a mix), not both");
    if (!sizes.present()) {
        if (!diameter.present()) fail(c, "missing required key 'diameter' or 'sizes' (the shot's size)");
        if (c.child("fractions_by").present()) fail(c.child("fractions_by"), "'fractions_by' is only for a mix (shot.sizes)");
    }
    // One size: the schema's default (either reading of one size's share is the same).
    d.fractions_by_mass = read_choice(c.child("fractions_by")) == "mass";
    if (!sizes.present()) {
        d.sizes = {ShotSizeDesc{read_quantity(diameter), 1.0}};
        return;
    }
    d.sizes_given = true;
    if (sizes.size() == 0) fail(sizes, "expected at least one size (diameter and fraction)");
    if (sizes.size() > kMaxShotSizes)
        fail(sizes, "expected at most " + std::to_string(kMaxShotSizes) + " sizes, got " + std::to_string(sizes.size()));
    double sum = 0.0;
    for (std::size_t i = 0; i < sizes.size(); ++i) {
        const Cursor item = sizes.item(i);
        ShotSizeDesc s{read_quantity(item.child("diameter")), read_quantity(item.child("fraction"))};
        for (const ShotSizeDesc& before : d.sizes)
            if (before.diameter_m == s.diameter_m) fail(item.child("diameter"), "this diameter is already in the mix; give each size once");
        sum += s.fraction;
        d.sizes.push_back(s);
    }
    // Sieve data are rounded: the shares must sum to 1 within 0.5 % and are then scaled to it.
    if (!(std::abs(sum - 1.0) <= 5e-3)) fail(sizes, "expected the fractions to sum to 1 (within 0.005), got " + std::to_string(sum));
    for (ShotSizeDesc& s : d.sizes) s.fraction /= sum;
}

}  // namespace

ShotDesc read_shot(const Cursor& c, const std::vector<MaterialDesc>& materials) {
    ShotDesc d;
    d.count = static_cast<int>(read_integer(c.child("count")));
    read_sizes(c, d);

    const Cursor density = c.child("density");
    const Cursor material = c.child("material");
    if (density.present() && material.present()) fail(material, "give either shot.density or shot.material, not both");
    if (density.present()) {
        d.density_kg_per_m3 = read_quantity(density);
    } else if (material.present()) {
        d.material = read_text(material);
        const MaterialDesc* m = find_material(materials, d.material);
        if (m == nullptr)
            fail(material, "unknown material '" + d.material + "'; expected one of the materials: " + material_names(materials));
        if (!m->density_kg_per_m3)
            fail(material, "material '" + d.material + "' has no density; add materials." + d.material + ".density or give shot.density");
        d.density_kg_per_m3 = *m->density_kg_per_m3;
    } else {
        fail(density, "missing required key 'density' or 'material' (the shot needs a density)");
    }

    const Cursor velocity = c.child("initial_velocity");
    const Cursor speed = c.child("initial_speed");
    if (velocity.present() && speed.present()) fail(speed, "give either shot.initial_velocity or shot.initial_speed, not both");
    if (velocity.present()) {
        d.initial = InitialVelocityKind::vector;
        d.initial_velocity_m_per_s = read_vector(velocity);
        // The fastest shot anything throws (sources[].speed's limit, shot.initial_speed's).
        if (!(d.initial_velocity_m_per_s.norm() <= 1000.0))
            fail(velocity, "expected a velocity of at most 1000 m/s, got " + format_si(d.initial_velocity_m_per_s.norm()) + " m/s");
    } else if (speed.present()) {
        d.initial = InitialVelocityKind::random_upward;
        d.initial_speed_m_per_s = read_quantity(speed);
    }
    d.where = location_of(c);
    return d;
}

AirDesc read_air(const Cursor& c) {
    AirDesc d;
    d.drag = read_choice(c.child("drag")) == "sphere";
    d.density_kg_per_m3 = read_quantity(c.child("density"));
    d.viscosity_pa_s = read_quantity(c.child("viscosity"));
    if (c.child("drag_coefficient").present()) d.drag_coefficient = read_quantity(c.child("drag_coefficient"));
    const Cursor scatter = c.child("rebound_scatter");
    if (scatter.present()) {
        AirDesc::Scatter s;
        s.spread_rad = read_quantity(scatter.child("spread"));
        s.min_reynolds = read_quantity(scatter.child("min_reynolds"));
        s.min_speed_m_per_s = read_quantity(scatter.child("min_speed"));
        s.where = location_of(scatter);
        d.rebound_scatter = s;
    }
    d.where = location_of(c);
    return d;
}

constexpr double kMaxShotPositionSteps = 100000;  // files of the shot-position series

OutputDesc read_output(const Cursor& c, const std::vector<ComponentDesc>& components, double duration_s) {
    OutputDesc d;
    const Cursor log = c.child("log");
    if (log.present()) {
        d.logged_components = read_names(log);
        for (const std::string& name : d.logged_components) {
            const bool known = std::any_of(components.begin(), components.end(), [&](const ComponentDesc& k) { return k.name == name; });
            if (!known) {
                std::string names;
                for (const ComponentDesc& k : components) names += (names.empty() ? "" : ", ") + k.name;
                fail(log, "unknown component '" + name + "'; expected names of components: " + names);
            }
        }
    } else {
        for (const ComponentDesc& k : components)
            if (logged_by_default(k.role)) d.logged_components.push_back(k.name);
    }
    // An Almen strip is there to be measured: its impacts are logged whatever `log` says.
    for (const ComponentDesc& k : components)
        if (k.role == ComponentRole::almen &&
            std::find(d.logged_components.begin(), d.logged_components.end(), k.name) == d.logged_components.end())
            d.logged_components.push_back(k.name);
    d.directory = read_text(c.child("directory"));
    d.checkpoint_interval_s = read_quantity(c.child("checkpoint_interval"));
    d.shot_positions_s = read_optional_quantity(c.child("shot_positions"));
    // Work the series plans: a slip of the unit (5 us for 5 ms) would write millions of files.
    if (d.shot_positions_s && !(duration_s / *d.shot_positions_s <= kMaxShotPositionSteps))
        fail(c.child("shot_positions"), "the shot-position series plans " +
                                            std::to_string(static_cast<long long>(std::min(duration_s / *d.shot_positions_s, 1e18))) +
                                            " steps (process.duration / shot_positions); expected at most " +
                                            std::to_string(static_cast<long long>(kMaxShotPositionSteps)) + ": raise it");
    d.coverage_steps = static_cast<int>(read_integer(c.child("coverage_steps")));
    d.smoothing_radius_m = read_optional_quantity(c.child("smoothing_radius"));
    d.where = location_of(c);
    return d;
}

constexpr double kMaxRenderFrames = 100000;  // ~55 min of video at 30 fps

std::optional<RenderDesc> read_render(const Cursor& c) {
    if (!c.present()) return std::nullopt;
    RenderDesc d;
    d.width_px = static_cast<int>(read_integer(c.child("width")));
    d.height_px = static_cast<int>(read_integer(c.child("height")));
    d.fps = static_cast<int>(read_integer(c.child("fps")));
    d.slow_motion_s = read_quantity(c.child("slow_motion"));
    d.start_s = read_quantity(c.child("start"));
    d.duration_s = read_quantity(c.child("duration"));
    // Work a render block plans: a frame every slow_motion / fps of simulated time. A slip of the
    // unit (slow_motion: 1e-9) planned 3e8 frames and ran until the disk was full.
    const double frames = d.duration_s * d.fps / d.slow_motion_s;
    if (!(frames <= kMaxRenderFrames))
        fail(c.child("slow_motion"), "the render block plans " + std::to_string(static_cast<long long>(std::min(frames, 1e18))) +
                                         " frames (duration x fps / slow_motion); expected at most " +
                                         std::to_string(static_cast<long long>(kMaxRenderFrames)) +
                                         ": raise slow_motion or shorten render.duration");
    const Cursor camera = c.child("camera");
    if (camera.child("position").present()) d.camera_position_m = read_vector(camera.child("position"));
    if (camera.child("look_at").present()) d.camera_look_at_m = read_vector(camera.child("look_at"));
    if (const auto up = read_optional_direction(camera.child("up"))) d.camera_up = *up;
    d.fov_rad = read_quantity(camera.child("fov"));
    if (d.camera_position_m && d.camera_look_at_m && (*d.camera_position_m - *d.camera_look_at_m).norm() == 0.0)
        fail(camera.child("look_at"), "expected a point other than the camera position");
    d.speed_scale_m_per_s = read_quantity(c.child("speed_scale"));
    d.video = read_choice(c.child("video")) == "mp4";
    d.where = location_of(c);
    return d;
}

}  // namespace peensim
