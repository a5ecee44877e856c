// A scene file parsed into plain values: every quantity in SI, every default filled in,
// every field remembering where it came from (for error messages at compile time).
// This is the *description*; model/compile turns it into the immutable model the engine runs.
//
// Defaults and ranges have one source, the schema (scene/schema.cpp): the parser fills every key a
// scene leaves out from it. The initialisers below are therefore zero or empty; the few that are not
// are no scene default (a required key's placeholder, or a value a test builds in code), as their
// comments say. tests/scene/defaults_agree_test.cpp checks the parsed defaults against the schema.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/input_error.h"
#include "common/vec.h"

namespace peensim {

// almen: a virtual SAE Almen strip (J442: 76.2 x 19.0 mm), static, whose impacts are always logged
// and reported as an impact-energy dose and, once calibrated, an arc-height saturation curve.
enum class ComponentRole { sonotrode, chamber, part, fixture, almen };

// The word a scene file uses for a role.
inline const char* role_name(ComponentRole r) {
    switch (r) {
        case ComponentRole::sonotrode: return "sonotrode";
        case ComponentRole::chamber: return "chamber";
        case ComponentRole::part: return "part";
        case ComponentRole::fixture: return "fixture";
        case ComponentRole::almen: return "almen";
    }
    return "fixture";
}

// Components whose impacts are logged when the scene's output.log does not name them.
inline bool logged_by_default(ComponentRole r) { return r == ComponentRole::part || r == ComponentRole::almen; }

// Sinusoidal translation of a component along an axis: d(t) = A sin(2 pi F t + phase).
struct VibrationDesc {
    std::optional<Vec3> axis;   // unit vector, world frame; empty = the sonotrode's mean face normal
    double amplitude_m = 0.0;   // m, A0
    double frequency_hz = 0.0;  // Hz, F
    double phase_rad = 0.0;     // rad
    SourceLocation where;
};

// Constant-speed rotation of a component about a fixed world axis.
struct RotationDesc {
    Vec3 axis_point_m = Vec3::Zero();     // m, a point on the axis (world frame)
    Vec3 axis_direction = Vec3::UnitZ();  // unit vector (world frame), right-hand rule
    double speed_rad_per_s = 0.0;         // rad/s, omega (signed)
    SourceLocation where;
};

// A component's regions: named selections of its surface (component frame, m: the mesh frame after
// mesh_unit scaling), reported separately by the analysis. An entry holds one or more conditions, all
// of which a point must meet (their intersection): angular sectors, a box, a half-space, a distance
// to an axis or to a point (conditions on the point), a group of the mesh file, a facing direction
// (conditions on the triangle it lies on). src/analysis/regions.h does the selecting, by area.

// Angles about an axis: right-hand about axis_direction, 0 along `reference` projected normal to it.
struct AxisAngleFrame {
    Vec3 axis_point_m = Vec3::Zero();     // m, a point on the axis (component frame)
    Vec3 axis_direction = Vec3::UnitZ();  // unit vector (component frame)
    Vec3 reference = Vec3::UnitX();       // unit vector (component frame), not along the axis
};

struct SectorCondition {  // angles in [from, to)
    AxisAngleFrame frame;
    double from_rad = 0.0;  // rad, start (included)
    double to_rad = 0.0;    // rad, end (excluded), from < to <= from + 2 pi
};

struct SectorsCondition {  // `count` sectors of `width`, sector i centred at offset + i 2 pi / count
    AxisAngleFrame frame;
    int count = 0;            // >= 1
    double width_rad = 0.0;   // rad, (0, 2 pi]
    double offset_rad = 0.0;  // rad, centre angle of sector 0
    std::string name_prefix;  // sector i is the region name_prefix + i
};

struct BoxCondition {           // axis-aligned, faces included
    Vec3 min_m = Vec3::Zero();  // m, lowest corner
    Vec3 max_m = Vec3::Zero();  // m, highest corner
};

struct HalfSpaceCondition {       // the side of a plane its normal points to, the plane included
    Vec3 point_m = Vec3::Zero();  // m, a point on the plane
    Vec3 normal = Vec3::UnitZ();  // unit vector into the selected side
};

struct FacingCondition {             // triangles whose normal (by winding: outward on a closed part) is within `within` of `direction`
    Vec3 direction = Vec3::UnitZ();  // unit vector (component frame)
    double within_rad = 0.0;         // rad, (0, pi]
};

struct AxisDistanceCondition {            // points whose distance to an axis is in [min, max]
    Vec3 axis_point_m = Vec3::Zero();     // m, a point on the axis
    Vec3 axis_direction = Vec3::UnitZ();  // unit vector
    double min_m = 0.0;                   // m
    double max_m = 0.0;                   // m, > min (infinity: no upper bound)
};

struct PointDistanceCondition {   // points whose distance to `point` is in [min, max]
    Vec3 point_m = Vec3::Zero();  // m
    double min_m = 0.0;           // m
    double max_m = 0.0;           // m, > min (infinity: no upper bound)
};

struct RegionDesc {
    std::string name;  // the region (for `sectors`: the entry; its regions are <name_prefix><i>)
    std::optional<SectorCondition> sector;
    std::optional<SectorsCondition> sectors;
    std::optional<BoxCondition> box;
    std::optional<HalfSpaceCondition> half_space;
    std::optional<AxisDistanceCondition> distance_to_axis;
    std::optional<PointDistanceCondition> distance_to_point;
    std::optional<FacingCondition> facing;
    std::optional<std::string> group;  // a name of the mesh file's solids / sub-meshes
    // Not to be peened (masked) or out of the shot's reach: left out of coverage and uniformity.
    bool exclude = false;
    SourceLocation where;  // the region's entry in the file
};

// The names a region entry yields: its name, or for `sectors` name_prefix + 0 .. count - 1.
inline std::vector<std::string> region_names(const RegionDesc& r) {
    if (!r.sectors) return {r.name};
    std::vector<std::string> names;
    names.reserve(static_cast<std::size_t>(r.sectors->count));
    for (int i = 0; i < r.sectors->count; ++i) names.push_back(r.sectors->name_prefix + std::to_string(i));
    return names;
}

// The Almen strip's peened face and the calibration that turns its impact-energy dose E (J/m2) into
// an arc height h = a (1 - exp(-E / E_c)). The constants depend on strip type, shot and process and
// must come from a measured saturation curve; without them only the dose is reported.
// The predictive model's calibration (analysis/almen_model.h): the measured curve
// h = a (1 - exp(-(t / tau)^c)) and the exposure of the run that reproduced it.
struct AlmenCalibrationDesc {
    double saturation_arc_height_m = 0.0;  // m, a
    double time_constant_s = 0.0;          // s, tau
    double shape = 0.0;                    // -, c
    double dent_size_m = 0.0;              // m, the calibration run's dent-area-weighted mean dent diameter
    double covering_rate_per_s = 0.0;      // 1/s, the calibration run's dent area ratio per second
    std::string strip;                     // "A", "N", "C" or "" (not given)
};

struct AlmenDesc {
    Vec3 face_normal = Vec3::Zero();                  // unit vector, component frame: out of the peened face
    std::optional<double> saturation_arc_height_m;    // m, a
    std::optional<double> dose_constant_J_per_m2;     // J/m2, E_c
    std::optional<AlmenCalibrationDesc> calibration;  // the predictive model's; not with the two above
    SourceLocation where;
};

// How a STEP or IGES file's exact surfaces become triangles (geometry/cad_reader.h).
struct TessellationDesc {
    double chordal_m = 0.0;    // m, largest distance from a triangle to the exact surface
    double angular_rad = 0.0;  // rad, largest turn of the surface normal along a triangle edge
};

struct ComponentDesc {
    std::string name;
    ComponentRole role = ComponentRole::fixture;
    std::string mesh_path;                        // absolute or relative to the working directory (resolved by the parser)
    SourceLocation mesh_where;                    // the mesh field's (a file it names that cannot be read is an error there)
    double mesh_unit_m = 0.0;                     // m per mesh-file length unit (mm -> 1e-3); 1 for STEP/IGES (read in m)
    TessellationDesc tessellation;                // STEP/IGES files only (common/cad_file.h); the schema's defaults
    Vec3 translation_m = Vec3::Zero();            // m, placement of the component frame in the world
    Mat3 rotation = Mat3::Identity();             // component frame -> world (applied before translation)
    std::string material;                         // key into SceneDescription::materials
    std::optional<VibrationDesc> vibration;       // only for role sonotrode (required there)
    std::optional<RotationDesc> rotation_motion;  // only for role part; empty = static
    std::vector<RegionDesc> regions;              // named selections of triangles, for the impact analysis
    std::optional<AlmenDesc> almen;               // only for role almen (always present there)
    SourceLocation where;                         // the component's entry in the file
};

struct MaterialDesc {
    std::string name;
    std::optional<double> density_kg_per_m3;  // kg/m3
    std::optional<double> yield_stress_pa;    // Pa (used by the impact analysis, eq. 10)
    std::optional<double> youngs_modulus_pa;  // Pa, E (soft-sphere contacts, law hertz-mindlin)
    std::optional<double> poisson_ratio;      // -, nu (soft-sphere contacts)
    SourceLocation where;
};

// One parameter of a pair's contact law, resolved (written, taken from `default`, or the law's own).
struct LawParameterValue {
    std::string name;            // as the law declares it
    std::vector<double> values;  // SI; one value, or a table
    SourceLocation where;        // where it was written (the pair's or the default's), or the pair
};

// One contact pair (shot-shot, or shot against one material): its law (contact/law_registry.h)
// and every parameter that law declares, in the law's order.
struct ContactPairDesc {
    std::string key;  // "shot-shot", "shot-<material>" or "default"
    std::string law;  // a name of contact/law_registry.h
    std::vector<LawParameterValue> parameters;
    SourceLocation where;

    // The values of a parameter; throws std::out_of_range if the law has no such parameter.
    const std::vector<double>& values(std::string_view name) const;
    double value(std::string_view name) const { return values(name).at(0); }
};

enum class InitialVelocityKind { rest, vector, random_upward };

// One size of a shot mix: its diameter and its share, by mass (a sieve analysis, SAE J444) or by
// count (ShotDesc::fractions_by_mass).
struct ShotSizeDesc {
    double diameter_m = 0.0;  // m
    double fraction = 1.0;    // -, the shares of a mix sum to 1
};

// The most sizes a mix may have (a shot's size is stored as one byte).
inline constexpr std::size_t kMaxShotSizes = 32;

struct ShotDesc {
    int count = 0;
    // The sizes: one (`shot.diameter`) or a mix (`shot.sizes`), in the file's order.
    std::vector<ShotSizeDesc> sizes;
    bool fractions_by_mass = false;  // the mix's fractions are shares of the mass (else of the count)
    bool sizes_given = false;        // the file wrote a mix (`shot.sizes`), not one `diameter`
    double density_kg_per_m3 = 0.0;  // kg/m3 (from `density`, or from `material`)
    std::string material;            // optional material name ("" if density given directly)
    InitialVelocityKind initial = InitialVelocityKind::rest;
    Vec3 initial_velocity_m_per_s = Vec3::Zero();  // m/s, for `vector`
    double initial_speed_m_per_s = 0.0;            // m/s, for `random_upward` (uniform on the upper hemisphere around the sonotrode axis)
    SourceLocation where;
};

struct ProcessDesc {
    double duration_s = 0.0;               // s (with until_coverage: the longest the run may go on)
    Vec3 gravity_m_per_s2 = Vec3::Zero();  // m/s2
    std::uint64_t seed = 0;
    // Run until coverage (as the analysis counts it) reaches this share (0..1] on every area named
    // in until_coverage_of ("part" or "part/region"; empty: every counted region of every logged
    // part with a yield stress, or a part's peened area where it has no regions). Empty: run for
    // `duration`.
    std::optional<double> until_coverage;
    std::vector<std::string> until_coverage_of;
    SourceLocation where;
};

// step: time stepping; event: event-driven, instantaneous rigid impacts; soft: event-driven flights
// with soft-sphere (Hertz-Mindlin) contacts integrated while they last.
enum class SteppingScheme { step, event, soft };
inline const char* scheme_name(SteppingScheme s) {
    switch (s) {
        case SteppingScheme::step: return "step";
        case SteppingScheme::event: return "event";
        case SteppingScheme::soft: return "soft";
    }
    return "event";
}

struct AccuracyDesc {
    double travel_fraction = 0.0;       // -, max travel per step / shot radius (eq. 7 uses 0.25)
    double impact_speed_m_per_s = 0.0;  // m/s, slower normal approaches are sustained contact, not impacts
    SteppingScheme scheme{};
    bool scheme_given = false;  // the file (or --set) chose the scheme; else the default for its flights
    // -, soft scheme: integration steps per Hertz contact time (the contact's duration at its
    // approach speed); the soft contacts' accuracy knob.
    double soft_steps_per_contact = 0.0;
    SourceLocation where;
};

// The still air the shot fly through. Without drag (the default, USP) flights are exact parabolas.
struct AirDesc {
    bool drag = false;
    double density_kg_per_m3 = 0.0;          // kg/m3
    double viscosity_pa_s = 0.0;             // Pa s
    std::optional<double> drag_coefficient;  // -, constant C_d; empty: Schiller-Naumann C_d(Re)
    // Rebound scatter (contact/rebound_scatter.h); empty: off.
    struct Scatter {
        double spread_rad = 0.0;         // rad
        double min_reynolds = 0.0;       // -
        double min_speed_m_per_s = 0.0;  // m/s
        SourceLocation where;
    };
    std::optional<Scatter> rebound_scatter;
    SourceLocation where;
};

// A source emitting shot during the run (model/shot_flow.h): a nozzle (model/nozzle_source.h) or a
// hopper (model/hopper_source.h).
// Where the jet aims, when the scene places a nozzle by its target (position and direction follow).
struct NozzleAim {
    Vec3 target_m = Vec3::Zero();        // m, world
    double distance_m = 0.0;             // m, exit to target along the axis
    double angle_of_attack_rad = 0.0;    // rad, axis to the target surface (pi/2: along its normal)
    Vec3 target_normal = Vec3::UnitZ();  // unit, world
    double azimuth_rad = 0.0;            // rad
};

enum class SourceKind { nozzle, hopper };

// A hopper's opening: the box its shot's centres start in (world frame).
struct HopperOpening {
    Vec3 lo_m = Vec3::Zero();  // m
    Vec3 hi_m = Vec3::Zero();  // m
};

struct SourceDesc {
    std::string name;
    SourceKind kind = SourceKind::nozzle;
    std::optional<HopperOpening> opening;  // a hopper's (and only a hopper's)
    // What follows down to rate is a nozzle's (a hopper's rate, mass flow, start and stop are its own too).
    Vec3 position_m = Vec3::Zero();            // m, world (given, or from `aim`)
    Vec3 direction = -Vec3::UnitZ();           // unit, world (given, or from `aim`)
    std::optional<NozzleAim> aim;              // the scene placed it by its target
    double speed_m_per_s = 0.0;                // m/s, mean exit speed v0
    double speed_spread = 0.0;                 // -, exit speeds uniform in v0 (1 +- speed_spread)
    std::optional<double> air_speed_m_per_s;   // m/s, the air jet's exit speed (kernels/free_jet.h); empty: none
    double rate_per_s = 0.0;                   // shot per second (given, or from mass_flow)
    std::optional<double> mass_flow_kg_per_s;  // kg/s, when the scene gives the flow as a mass
    double exit_radius_m = 0.0;                // m
    double spread_rad = 0.0;                   // rad, half-angle of the jet's cone
    double start_s = 0.0;                      // s
    double stop_s = 0.0;                       // s (the run's end unless given)
    SourceLocation where;
};

enum class SinkRegion { box, outside, mesh };

// Where shot are collected (model/shot_flow.h).
struct SinkDesc {
    std::string name;
    SinkRegion region = SinkRegion::box;
    Vec3 min_m = Vec3::Zero(), max_m = Vec3::Zero();  // m, world (box)
    std::string mesh_path;                            // mesh: a closed mesh, its file
    SourceLocation mesh_where;                        // mesh: the mesh field's
    double mesh_unit_m = 0.0;                         // mesh: metres per mesh unit
    Vec3 translation_m = Vec3::Zero();                // mesh: where its frame sits in the world
    SourceLocation where;
};

struct OutputDesc {
    std::vector<std::string> logged_components;  // names; default: every component with role part
    std::string directory;                       // "" = given on the command line
    double checkpoint_interval_s = 0.0;          // s of wall time between checkpoints (resume)
    std::optional<double> shot_positions_s;      // s of simulated time between steps of the shot series; empty: none
    int coverage_steps = 0;                      // steps of the analysis' coverage series after t = 0 (0: none)
    std::optional<double> smoothing_radius_m;    // m, the analysis' maps; empty: chosen by the analysis
    SourceLocation where;
};

// The off-screen animation recorded while simulating (scene `render:` block, or `run --render`).
// Frames are taken every slow_motion / fps simulated seconds from start for duration. A run
// without the block (`run --render`) takes default_render() (scene/schema_defaults.h), not RenderDesc{}.
struct RenderDesc {
    int width_px = 0;
    int height_px = 0;
    int fps = 0;                            // video frames per second
    double slow_motion_s = 0.0;             // s, simulated seconds per video second
    double start_s = 0.0;                   // s, simulated time of the first frame
    double duration_s = 0.0;                // s, simulated time recorded (cut at the run's end)
    std::optional<Vec3> camera_position_m;  // m, world; empty = automatic framing of the chamber
    std::optional<Vec3> camera_look_at_m;   // m, world; empty = the centre of the chamber
    Vec3 camera_up = Vec3::Zero();          // world direction shown upward
    double fov_rad = 0.0;                   // rad, vertical field of view
    double speed_scale_m_per_s = 0.0;       // m/s, top of the impact flashes' colour bar
    bool video = false;                     // assemble an MP4 from the frames (needs ffmpeg)
    SourceLocation where;
};

struct SceneDescription {
    std::string source_file;  // the scene file as given
    std::string name;         // free text, for reports
    ProcessDesc process;
    AccuracyDesc accuracy;
    ShotDesc shot;
    AirDesc air;
    std::vector<MaterialDesc> materials;
    std::vector<ContactPairDesc> contacts;  // includes a "default" entry (given or built in)
    std::vector<ComponentDesc> components;
    std::vector<SourceDesc> sources;
    std::vector<SinkDesc> sinks;
    OutputDesc output;
    std::optional<RenderDesc> render;  // present when the scene has a `render` block
    // Values to look at again (a plain number where units are given elsewhere): warnings, errors
    // with --strict.
    struct Warning {
        SourceLocation where;
        std::string field;
        std::string message;
    };
    std::vector<Warning> warnings;
};

// Whether a run logs `component`'s impacts: named by output.log, or by default (a part, a strip).
inline bool is_logged(const SceneDescription& scene, const ComponentDesc& component) {
    const std::vector<std::string>& named = scene.output.logged_components;
    if (named.empty()) return logged_by_default(component.role);
    for (const std::string& n : named)
        if (n == component.name) return true;
    return false;
}

}  // namespace peensim
