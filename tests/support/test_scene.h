// Small generated scenes for the physics and engine tests: a box chamber open at the bottom whose
// opening is closed by a plate sonotrode (its top face at z = 0, centred on the z axis), an
// optional part (box, cylinder or thin plate; static or rotating), and every process setting as a
// plain value. TestScene writes the meshes (binary STL, mm) and scene.yaml into a fresh temporary
// directory, removed again when the TestScene goes out of scope; compile() returns the model.
//
// World frame: z up (gravity -z by default), the chamber's inner faces at x = +-size.x/2,
// y = +-size.y/2, z = size.z (the ceiling); the sonotrode's top face at z = 0 at rest.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "common/vec.h"
#include "engine/simulation_state.h"
#include "geometry/axis_frame.h"
#include "model/model.h"

namespace peensim::testing {

// Contact coefficients of one pair (reference eq. 2-5), as written into `contacts:`.
struct PairSpec {
    double C0 = 0.9;          // -, normal restitution below V0
    double V0_m_per_s = 0.5;  // m/s, onset of the plastic regime
    double mu = 0.71;         // -, tangential restitution (surface pairs only)
    double f = 0.1;           // -, Coulomb friction in sustained contact (surface pairs only)
};

// Soft-sphere contacts (law hertz-mindlin for every pair), as written into `materials:` and
// `contacts:` in place of the impulse pairs: every material, the shot's included, with these
// elastic constants; restitution e and Coulomb friction f per pair.
struct SoftSpec {
    double youngs_modulus_pa = 200e9;                                            // Pa, every material
    double poisson_ratio = 0.3;                                                  // -, every material
    double e_shot_shot = 0.9, e_sonotrode = 0.9, e_chamber = 0.9, e_part = 0.9;  // -
    double f_shot_shot = 0.1, f_sonotrode = 0.1, f_chamber = 0.1, f_part = 0.1;  // -
    double V0_m_per_s = 0.0;                                                     // m/s, every pair (0: e at every speed)
    double steps_per_contact = 20.0;                                             // -, accuracy.soft_steps_per_contact
    // The law of every pair: hertz-mindlin (V0 above), or linear-spring-dashpot with its stiffness
    // at this characteristic speed (m/s).
    bool linear = false;
    double characteristic_speed_m_per_s = 2.0;
};

enum class PartShape { box, cylinder, plate };

struct PartSpec {
    PartShape shape = PartShape::box;
    Vec3 size_m = Vec3(4e-3, 4e-3, 4e-3);   // m, box / plate edge lengths along x, y, z
    double radius_m = 2e-3;                 // m, cylinder radius
    double length_m = 10e-3;                // m, cylinder length along `axis`
    Axis axis = Axis::y;                    // cylinder axis (world axis)
    int segments = 64;                      // cylinder polygon sides
    Vec3 center_m = Vec3(0.0, 0.0, 10e-3);  // m, world centre of the part at t = 0
    // Rotation at constant speed about a world axis (none: a static part).
    std::optional<double> speed_rad_per_s;      // rad/s, signed, right-hand rule about axis_direction
    Vec3 axis_point_m = Vec3(0.0, 0.0, 10e-3);  // m, a point on the rotation axis
    Vec3 axis_direction = Vec3::UnitY();        // -, rotation axis direction
};

struct TestSceneSpec {
    // Chamber: inner size along x and y (m), and the ceiling height above the plate's top face (m).
    Vec3 chamber_size_m = Vec3(20e-3, 20e-3, 20e-3);
    bool chamber_missing_side_wall = false;                     // leave the +x wall out (an unclosed chamber)
    double plate_thickness_m = 5e-3;                            // m
    double plate_scale = 1.0;                                   // -, plate x/y size over the chamber's (< 1 leaves a gap)
    Eigen::Vector3i plate_divisions = Eigen::Vector3i::Ones();  // quads per edge on every plate face

    int shot_count = 1;
    double shot_diameter_m = 2e-3;  // m
    // A mix instead (shot.sizes, fractions by count): (diameter m, count fraction) per size.
    std::vector<std::pair<double, double>> shot_sizes;
    double shot_density_kg_per_m3 = 7800.0;        // kg/m3
    std::optional<Vec3> initial_velocity_m_per_s;  // m/s, every shot (shot.initial_velocity)
    std::optional<double> initial_speed_m_per_s;   // m/s, random upward directions (shot.initial_speed)

    double amplitude_m = 0.0;                       // m, sonotrode A0 (0: a still sonotrode)
    double frequency_hz = 20e3;                     // Hz
    double phase_rad = 0.0;                         // rad
    Vec3 gravity_m_per_s2 = Vec3(0.0, 0.0, -9.81);  // m/s2
    double duration_s = 0.1;                        // s
    std::uint64_t seed = 1;
    double travel_fraction = 0.25;  // -, eq. 7 travel per step over R
    std::string scheme = "step";    // accuracy.scheme: "step" (time stepping), "event" (event-driven) or "soft"
    std::optional<SoftSpec> soft;   // hertz-mindlin for every pair (the soft scheme needs it) instead of the PairSpecs below

    PairSpec shot_shot{0.9, 0.5, 0.71, 0.1};  // mu, f unused for shot-shot
    PairSpec sonotrode{0.9, 0.5, 0.71, 0.1};  // shot against the sonotrode (material titanium)
    PairSpec chamber{0.9, 0.5, 0.71, 0.1};    // shot against the chamber (material steel)
    PairSpec part_pair{0.6, 0.3, 0.71, 0.1};  // shot against the part (material copper)

    std::optional<PartSpec> part;  // component named "part"
    // Components whose impacts are logged ("sonotrode", "chamber", "part"); empty: the default
    // (the part, if any).
    std::vector<std::string> log;
};

// The scene text for `spec`, with mesh files sonotrode.stl, chamber.stl and part.stl relative to
// the scene file's directory.
std::string scene_yaml(const TestSceneSpec& spec);

class TestScene {
public:
    // Writes the meshes and scene.yaml into a new directory under the system temporary directory.
    explicit TestScene(const TestSceneSpec& spec);
    ~TestScene();
    TestScene(const TestScene&) = delete;
    TestScene& operator=(const TestScene&) = delete;

    const TestSceneSpec& spec() const { return spec_; }
    const std::string& directory() const { return directory_; }
    const std::string& scene_path() const { return scene_path_; }
    const std::string& yaml() const { return yaml_; }

    // parse_scene_text + compile_model (throws InputError like they do).
    std::shared_ptr<const Model> compile(const std::vector<std::string>& overrides = {}) const;

    // A fresh empty directory inside this scene's directory (for run outputs).
    std::string make_subdirectory(const std::string& name) const;

private:
    TestSceneSpec spec_;
    std::string directory_;
    std::string scene_path_;
    std::string yaml_;
};

// Puts shot i at position_m (m, world) with velocity_m_per_s (m/s, world), moving the shot the
// placement put there, and raises the speed the next step's size is computed from (eq. 7).
void set_shot(SimulationState& state, std::size_t i, const Vec3& position_m, const Vec3& velocity_m_per_s);

// `shot_count` shot of 2 mm thrown up at 1 m/s in random directions from the plate (A0 25 um), no
// part: the smallest busy run (outputs, checkpoints, resumes).
TestSceneSpec thrown_shot_scene(int shot_count, double duration_s);

// A 10 x 6 x 2 mm plate part centred 10 mm above the sonotrode, turning at omega (rad/s) about +y
// through its centre (at 1000 rpm its rim moves at 0.53 m/s and sweeps down to 4.9 mm).
PartSpec turning_plate_part(double omega_rad_per_s);

// 64 shot of 2 mm thrown up at 1 m/s in random directions from the plate (A0 25 um) onto a static
// rod (r 3 mm, 16 mm along y, axis 8 mm up): a small, busy scene for determinism and run tests.
TestSceneSpec small_rod_scene(const std::string& scheme, double duration_s);

}  // namespace peensim::testing
