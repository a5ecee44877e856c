#include "app/new_scene/scene_design.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace peensim {

namespace {

// The rules (see the header). Each floor is the shipped gear case's value; each shot multiple
// keeps the rule sensible for large shot (3 mm shot want more room than 0.3 mm shot).
constexpr double kStandoffFloorM = 20e-3;        // m: the gear case's lowest tooth tip stands 20 mm off
constexpr double kStandoffShots = 10.0;          // shot diameters
constexpr double kSonotrodeMarginFloorM = 5e-3;  // m: the gear case's disk is 7 mm wider than the gear's footprint
constexpr double kSonotrodeMarginShots = 2.5;    // shot diameters
constexpr double kGapFloorM = 0.1e-3;            // m: the gear case's rim gap
constexpr double kGapShareOfShot = 0.25;         // a gap below a quarter shot lets no shot through
constexpr double kWallClearanceFloorM = 15e-3;   // m: the gear case's gear is 18 mm from its upper wall
constexpr double kWallClearanceShots = 7.5;      // shot diameters
constexpr double kStepAboveLowerM = 5e-3;        // m: the upper section at least this much wider
constexpr double kLidClearanceFloorM = 15e-3;    // m: the gear case's lid is 11 mm above its top tip
constexpr double kLidClearanceShots = 7.5;       // shot diameters
constexpr double kSonotrodeThicknessM = 10e-3;   // m: the gear case's disk
constexpr double kShotFill = 0.15;               // the gear case: 140 x 2 mm on a 29.9 mm disk, 15.7 %
constexpr double kAmplitudeM = 25e-6;            // m: the gear case's (USP uses 20-80 um)
constexpr double kFrequencyHz = 20e3;            // Hz: USP sonotrodes' usual frequency
constexpr double kFirstRunS = 5.0;               // s: the gear case's run, enough for a forecast

const std::array<PartMaterial, 3> kPartMaterials{{
    {"steel", "part-steel", 7.85, 900.0, "a quenched and tempered gear steel (42CrMo4: about 900 MPa)", 0.95, 2.0, 0.8, 0.1},
    {"aluminium", "part-aluminium-2000", 2.78, 345.0, "a 2000-series aluminium, as the shipped gear", 0.95, 0.5, 0.8, 0.1},
    {"titanium", "part-TA6V", 4.43, 880.0, "annealed Ti-6Al-4V (TA6V)", 0.9, 1.5, 0.9, 0.1},
}};

}  // namespace

const PartMaterial* find_part_material(const std::string& option) {
    for (const PartMaterial& m : kPartMaterials)
        if (m.option == option) return &m;
    return nullptr;
}

std::string part_material_options() {
    std::string s;
    for (const PartMaterial& m : kPartMaterials) s += (s.empty() ? "" : ", ") + m.option;
    return s;
}

SceneDesign design_scene(const PartEnvelope& envelope, const NewSceneRequest& request) {
    const double d = request.shot_diameter_m;
    SceneDesign s;
    s.envelope = envelope;
    s.standoff_m = std::max(kStandoffFloorM, kStandoffShots * d);
    // Centred over the sonotrode's axis (world z through the origin), its lowest point standoff up.
    s.translation_m = Vec3(-envelope.centre_m.x(), -envelope.centre_m.y(), s.standoff_m - envelope.lo_m.z());
    s.axis_point_m = envelope.centre_m + s.translation_m;

    s.sonotrode_margin_m = std::max(kSonotrodeMarginFloorM, kSonotrodeMarginShots * d);
    s.sonotrode_radius_m = envelope.footprint_radius_m + s.sonotrode_margin_m;
    s.sonotrode_thickness_m = kSonotrodeThicknessM;
    s.gap_m = std::min(kGapFloorM, kGapShareOfShot * d);
    s.lower_radius_m = s.sonotrode_radius_m + s.gap_m;
    s.wall_clearance_m = std::max(kWallClearanceFloorM, kWallClearanceShots * d);
    s.upper_radius_m = std::max(envelope.footprint_radius_m + s.wall_clearance_m, s.lower_radius_m + kStepAboveLowerM);
    s.bottom_z_m = -s.sonotrode_thickness_m;
    s.step_z_m = 0.5 * s.standoff_m;  // the section change below the part
    s.lid_clearance_m = std::max(kLidClearanceFloorM, kLidClearanceShots * d);
    s.lid_z_m = s.standoff_m + (envelope.hi_m.z() - envelope.lo_m.z()) + s.lid_clearance_m;

    s.shot_fill = kShotFill;
    const double face_m2 = std::numbers::pi * s.sonotrode_radius_m * s.sonotrode_radius_m;
    const double shot_m2 = std::numbers::pi * 0.25 * d * d;
    s.shot_count = std::max(1, static_cast<int>(std::lround(kShotFill * face_m2 / shot_m2)));
    s.amplitude_m = kAmplitudeM;
    s.frequency_hz = kFrequencyHz;
    s.duration_s = kFirstRunS;
    if (request.turning_axis && request.rpm > 0.0) {
        // Whole turns (the analysis of a turning part counts whole turns): the fewest covering 5 s.
        const double turn_s = 60.0 / request.rpm;
        s.turns = std::max(1, static_cast<int>(std::ceil(kFirstRunS / turn_s - 1e-9)));
        // Rounded up to the millisecond: a duration written short of the last turn (16/3 s as
        // 5.33333333) would lose that turn to the analysis; one a little past it loses nothing.
        s.duration_s = std::ceil(s.turns * turn_s * 1e3 - 1e-6) / 1e3;
    }
    return s;
}

}  // namespace peensim
