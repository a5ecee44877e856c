// What `peensim new` chooses around a user's part: where the part goes, the sonotrode, the
// chamber, the shot, the process. Numbers only (the YAML and the meshes are written elsewhere),
// so that every choice is a rule a test can check.
//
// The rules are USP practice as the shipped gear case (scenes/gear.yaml) applies it, scaled to the
// part: the sonotrode is wider than the part's footprint so that the shot rise under all of it;
// the chamber's lower section hugs the sonotrode with a gap narrower than a quarter shot (no
// shot escapes below), its upper section leaves the part a clearance to the wall; the part's
// lowest point (or its swept solid's) stands off the sonotrode; the shot cover a share of the
// sonotrode's face.
#pragma once

#include <optional>
#include <string>

#include "geometry/axis_frame.h"
#include "geometry/part_envelope.h"

namespace peensim {

// The part's material: a name for the scene, its density and yield stress (the dents, eq. 10),
// and the restitution and friction of shot on it (the shipped scenes' coefficients, Table 2 of the
// CAD-based USP study, for the alloy family).
struct PartMaterial {
    std::string option;  // what --material takes: steel, aluminium, titanium
    std::string name;    // the scene's material name
    double density_g_cm3 = 0.0;
    double yield_stress_mpa = 0.0;
    std::string yield_note;  // where the yield stress comes from
    double C0 = 0.0, V0_m_s = 0.0, mu = 0.0, f = 0.0;
};
// nullptr for an unknown option.
const PartMaterial* find_part_material(const std::string& option);
std::string part_material_options();  // "steel, aluminium, titanium"

struct NewSceneRequest {
    std::optional<Axis> turning_axis;  // the part turns about this axis of its own, through its centre
    double rpm = 0.0;                  // rev/min, > 0 when turning
    double shot_diameter_m = 2e-3;     // m
};

struct SceneDesign {
    PartEnvelope envelope;    // in the part's own frame (m)
    Vec3 translation_m;       // m, where the part's frame goes in the world
    Vec3 axis_point_m;        // m, world: the turning axis passes here (the part's centre)
    double standoff_m = 0.0;  // m, sonotrode face (z = 0) to the envelope's lowest point
    double sonotrode_radius_m = 0.0;
    double sonotrode_thickness_m = 0.0;
    double sonotrode_margin_m = 0.0;  // m, sonotrode radius beyond the part's footprint
    double gap_m = 0.0;               // m, between the sonotrode's rim and the chamber's lower wall
    double lower_radius_m = 0.0, upper_radius_m = 0.0;
    double bottom_z_m = 0.0, step_z_m = 0.0, lid_z_m = 0.0;
    double wall_clearance_m = 0.0;  // m, part footprint to the upper wall (at least)
    double lid_clearance_m = 0.0;   // m, envelope top to the lid
    double shot_fill = 0.0;         // -, the shot's cross-sections over the sonotrode's face
    int shot_count = 0;
    double amplitude_m = 0.0, frequency_hz = 0.0;
    double duration_s = 0.0;
    int turns = 0;  // whole turns in the duration (0: not turning)
};

SceneDesign design_scene(const PartEnvelope& envelope, const NewSceneRequest& request);

}  // namespace peensim
