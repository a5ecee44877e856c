// The compiled model: immutable, checked, everything resolved (meshes loaded in their own
// frames, Bullet BVHs built, the contact law of each pair built with its parameters, SI). What only one stepping
// scheme needs (time stepping's distance gates) that scheme builds.
// The engine reads it; only the simulation state changes during a run.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "collision/mesh_collider.h"
#include "contact/contact_law.h"
#include "contact/law_registry.h"
#include "geometry/mesh_checks.h"
#include "geometry/triangle_mesh.h"
#include "kernels/flight_model.h"
#include "model/kinematics.h"
#include "model/shot_flow.h"
#include "scene/scene_description.h"

namespace peensim {

struct Component {
    std::string name;
    ComponentRole role = ComponentRole::fixture;
    std::string material;
    std::shared_ptr<const TriangleMesh> mesh;      // component frame, m
    std::shared_ptr<const MeshCollider> collider;  // Bullet BVH over `mesh`
    Kinematics kinematics;
    // Shot against this component's material: the pair's law, its parameters bound (law_registry.h).
    std::shared_ptr<const contact::SurfaceLaw> law;
    std::string coefficients_source;   // the scene's pair: "shot-<material>" or "default"
    bool logged = false;               // impacts written to impacts.csv
    double max_axis_distance_m = 0.0;  // m, largest distance of a vertex from the rotation axis
    Vec3 world_lo, world_hi;           // m, bounds at t = 0 (rotating: swept about the axis)
    // A solid the shot stay out of (part, fixture, Almen strip) whose mesh is closed, consistently
    // wound, normals outward: a centre on the inner side of its nearest facet is inside the solid,
    // and is put back out through that facet, never pushed further in.
    bool solid = false;
    // Its mesh's edges, counted once when the model is compiled (the assembly checks ask again; a
    // 500k-triangle part's count is a sort of 1.5 M words).
    EdgeReport edges;
};

// One size of the shot (a scene gives one, or a mix: shot.sizes). A shot's size is its index
// into Model::shot_sizes (ShotArrays::size_class).
struct ShotSize {
    double radius_m = 0.0;        // m, R = D / 2
    double mass_kg = 0.0;         // kg
    double count_fraction = 1.0;  // -, this size's share of the shot count
    // How shot of this size fly (drag depends on the size); all sizes fly the same kind of flight.
    std::shared_ptr<const FlightModel> flight;
};

struct Model {
    SceneDescription description;
    std::string resolved_scene_yaml;
    std::uint64_t scene_hash = 0;

    std::vector<Component> components;
    int sonotrode = -1;  // index into components; -1: none (a scene fed by sources only)

    int shot_count = 0;  // placed on the sonotrode at the start; sources may add more during the run
    // The shot's sizes, in the scene's order; one for a scene of one size. Geometry is per shot
    // (its size's radius); the smallest radius scales the schemes' tolerances and step lengths,
    // the largest their search reaches.
    std::vector<ShotSize> shot_sizes;
    std::vector<double> size_count_fraction;                    // -, shot_sizes' count_fraction in one array (size_for_draw)
    double min_shot_radius_m = 0.0;                             // m
    double max_shot_radius_m = 0.0;                             // m
    std::shared_ptr<const contact::ShotShotLaw> shot_shot_law;  // the `shot-shot` pair's law, bound

    Vec3 gravity_m_per_s2 = Vec3::Zero();  // m/s2
    // How shot fly between contacts (the exact parabola under gravity unless the scene's air drags);
    // never null: the first size's flight (each size has its own, ShotSize::flight, of the same
    // kind). The event scheme runs only parabolas (the scene parser chose time stepping else).
    std::shared_ptr<const FlightModel> flight;
    // m/s2, the largest speed_gain_bound() of the sizes' flights.
    double flight_speed_gain_bound_m_per_s2 = 0.0;
    // The run's settings, copied from the description by compile_model (their defaults are the
    // schema's, filled in by the parser; none is re-defaulted here).
    double duration_s = 0.0;  // s
    std::uint64_t seed = 0;
    SteppingScheme scheme{};              // the scheme that runs it (accuracy.scheme)
    double travel_fraction = 0.0;         // -, eq. 7 travel per step / R
    double soft_steps_per_contact = 0.0;  // -, soft scheme: integration steps per Hertz contact time
    // m/s, the one line between impacts and sustained contact, for both schemes: a normal approach
    // (relative to the surface's material, or between two shot) at least this fast is an impact;
    // slower is sustained contact (approach removed, friction, no rebound, not logged).
    double impact_speed_m_per_s = 0.0;
    double peak_surface_speed_m_per_s = 0.0;  // m/s, fastest moving surface (sonotrode or part rim)

    Vec3 world_lo, world_hi;  // m, a shot outside this box has left the chamber

    // Where shot enter and leave besides the initial load (model/shot_flow.h), in the scene's order.
    std::vector<std::shared_ptr<const ShotSource>> sources;
    std::vector<std::shared_ptr<const ShotSink>> sinks;

    bool has_size_mix() const { return shot_sizes.size() > 1; }
    const Component& sonotrode_component() const { return components[static_cast<std::size_t>(sonotrode)]; }
    // Index of a component by name, or -1.
    int component_index(const std::string& name) const;
};

// Checks a scene description and builds the model. Throws InputError naming the scene line.
std::shared_ptr<const Model> compile_model(const SceneDescription& scene);

}  // namespace peensim
