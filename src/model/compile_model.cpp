// Scene description -> immutable model: load meshes, place them, build the collision
// structures, resolve materials and contact pairs, and check the assembly is closed.
#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "contact/rebound_scatter.h"
#include "geometry/mesh_checks.h"
#include "geometry/mesh_loader.h"
#include "kernels/air_drag_flight.h"
#include "model/component_mesh.h"
#include "model/enclosure.h"
#include "model/make_source.h"
#include "model/mesh_sink.h"
#include "model/model.h"
#include "scene/resolved_writer.h"
#include "scene/shot_mix.h"

namespace peensim {

namespace {

std::string component_leaf_field(std::size_t i, const std::string& leaf) { return "components[" + std::to_string(i) + "]." + leaf; }

// Mean outward normal of the triangles facing `up` (area weighted), in the mesh frame.
Vec3 mean_upward_normal(const TriangleMesh& mesh, const Vec3& up_in_mesh) {
    Vec3 sum = Vec3::Zero();
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 n2a = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
        if (n2a.norm() > 0.0 && n2a.normalized().dot(up_in_mesh) > 0.5) sum += n2a;
    }
    return sum.norm() > 0.0 ? Vec3(sum.normalized()) : up_in_mesh;
}

Kinematics build_kinematics(const ComponentDesc& desc, const TriangleMesh& mesh, const Vec3& up) {
    Kinematics k;
    k.rest = Pose{desc.rotation, desc.translation_m};
    if (desc.vibration) {
        const VibrationDesc& v = *desc.vibration;
        k.kind = Kinematics::Kind::vibrating;
        k.amplitude_m = v.amplitude_m;
        k.frequency_hz = v.frequency_hz;
        k.phase_rad = v.phase_rad;
        k.axis = v.axis ? v.axis->normalized() : Vec3(desc.rotation * mean_upward_normal(mesh, desc.rotation.transpose() * up));
    }
    if (desc.rotation_motion) {
        const RotationDesc& r = *desc.rotation_motion;
        k.kind = Kinematics::Kind::rotating;
        k.axis_point_m = r.axis_point_m;
        k.axis_direction = r.axis_direction.normalized();
        k.omega_rad_per_s = r.speed_rad_per_s;
    }
    return k;
}

void component_bounds(Component& c) {
    const Pose pose = c.kinematics.rest;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    double max_axis = 0.0, max_from_point = 0.0;
    for (const Vec3& v : c.mesh->vertices) {
        const Vec3 w = pose.to_world(v);
        lo = lo.cwiseMin(w);
        hi = hi.cwiseMax(w);
        const Vec3 r = w - c.kinematics.axis_point_m;
        max_axis = std::max(max_axis, (r - c.kinematics.axis_direction.dot(r) * c.kinematics.axis_direction).norm());
        max_from_point = std::max(max_from_point, r.norm());
    }
    if (c.kinematics.kind == Kinematics::Kind::rotating) {
        // The swept volume lies within a sphere about the axis point.
        lo = c.kinematics.axis_point_m - Vec3::Constant(max_from_point);
        hi = c.kinematics.axis_point_m + Vec3::Constant(max_from_point);
        c.max_axis_distance_m = max_axis;
    }
    if (c.kinematics.kind == Kinematics::Kind::vibrating) {
        const Vec3 swing = (c.kinematics.axis * c.kinematics.amplitude_m).cwiseAbs();
        lo -= swing;
        hi += swing;
    }
    c.world_lo = lo;
    c.world_hi = hi;
}

// Coordinates (m, world) beyond this belong to no peening assembly: a vertex at 3e38 (a damaged
// export) or a translation in the wrong unit. The collision grids sized from the bounds failed on
// them with "grid too large" and exit 1; this says where the far point comes from.
constexpr double kLargestCoordinate_m = 100.0;

void check_extent(const Component& c, const ComponentDesc& desc, std::size_t i) {
    const double farthest_m = std::max(c.world_lo.cwiseAbs().maxCoeff(), c.world_hi.cwiseAbs().maxCoeff());
    if (farthest_m <= kLargestCoordinate_m) return;  // (NaN cannot come from a loaded mesh)
    std::size_t far_vertex = 0;
    for (std::size_t v = 0; v < c.mesh->vertices.size(); ++v)
        if (c.mesh->vertices[v].cwiseAbs().maxCoeff() > c.mesh->vertices[far_vertex].cwiseAbs().maxCoeff()) far_vertex = v;
    const Vec3& far = c.mesh->vertices[far_vertex];  // m, component frame
    const bool in_mesh = far.cwiseAbs().maxCoeff() > kLargestCoordinate_m;
    std::ostringstream s;
    s.precision(4);
    s << "'" << c.name << "' reaches " << farthest_m << " m from the origin";
    if (in_mesh)
        s << " (vertex " << far_vertex + 1 << " of " << desc.mesh_path << " at (" << far.x() / desc.mesh_unit_m << ", "
          << far.y() / desc.mesh_unit_m << ", " << far.z() / desc.mesh_unit_m << ") file units, mesh_unit " << desc.mesh_unit_m << " m)";
    s << ": expected an assembly within " << kLargestCoordinate_m << " m of the origin; check "
      << (in_mesh ? "the file's vertices and mesh_unit" : "translation and the units it is given in");
    throw InputError(desc.where, component_leaf_field(i, in_mesh ? "mesh" : "translation"), s.str());
}

const ContactPairDesc& contact_for(const SceneDescription& scene, const std::string& key) {
    const ContactPairDesc* fallback = nullptr;
    for (const ContactPairDesc& c : scene.contacts) {
        if (c.key == key) return c;
        if (c.key == "default") fallback = &c;
    }
    if (!fallback) throw InputError({scene.source_file, 0, 0}, "contacts", "no entry for '" + key + "' and no default");
    return *fallback;
}

// The values of the parameters a law declares, by name, from the scene's resolved pair.
contact::ParameterValues parameter_values(const ContactPairDesc& pair, std::span<const contact::LawParameter> declared) {
    contact::ParameterValues v;
    for (const contact::LawParameter& p : declared) v.parameters.push_back({p.name, pair.values(p.name)});
    return v;
}

// E and nu of a material, where the scene gives both.
std::optional<contact::ElasticMaterial> elastic_of(const SceneDescription& scene, const std::string& material) {
    for (const MaterialDesc& m : scene.materials)
        if (m.name == material && m.youngs_modulus_pa && m.poisson_ratio)
            return contact::ElasticMaterial{*m.youngs_modulus_pa, *m.poisson_ratio};
    return std::nullopt;
}

std::shared_ptr<const contact::ShotShotLaw> shot_shot_law_of(const ContactPairDesc& pair, const SceneDescription& scene) {
    const contact::LawEntry* law = contact::find_law(pair.law);
    if (law == nullptr || law->make_shot_shot == nullptr)
        throw InputError(pair.where, "contacts." + pair.key + ".law", "'" + pair.law + "' is not a shot-shot law");
    contact::ShotShotPair what;
    what.shot_diameter_m = largest_diameter_m(scene.shot);
    what.shot_density_kg_per_m3 = scene.shot.density_kg_per_m3;
    what.shot_elastic = elastic_of(scene, scene.shot.material);
    what.shot_material = scene.shot.material;
    try {
        return law->make_shot_shot(parameter_values(pair, law->shot_shot_parameters), what);
    } catch (const std::invalid_argument& e) {
        throw InputError(pair.where, "contacts." + pair.key + ".law", std::string(e.what()) + " (shot-shot)");
    }
}

// The soft scheme integrates every contact with the pair's soft-sphere law: each pair must have one.
void require_soft_laws(const Model& model, const SceneDescription& scene) {
    const auto refuse = [&](const std::string& key) {
        const ContactPairDesc& pair = contact_for(scene, key);
        throw InputError(pair.where, "contacts." + pair.key + ".law",
                         "the soft scheme (accuracy.scheme: soft) integrates soft-sphere contacts; expected a soft-sphere law (" +
                             contact::soft_law_names_text() + ") for " + key +
                             " (write it in the `default` pair to set it for every pair), found '" + pair.law + "'");
    };
    if (model.shot_shot_law->soft() == nullptr) refuse("shot-shot");
    for (const Component& c : model.components)
        if (c.law->soft() == nullptr) refuse("shot-" + c.material);
}

std::shared_ptr<const contact::SurfaceLaw> surface_law_of(const ContactPairDesc& pair, const SceneDescription& scene, const Component& c) {
    const contact::LawEntry* law = contact::find_law(pair.law);
    if (law == nullptr) throw InputError(pair.where, "contacts." + pair.key + ".law", "unknown law '" + pair.law + "'");
    contact::SurfacePair what;
    const TriangleMesh& mesh = *c.mesh;
    what.triangle_corners_m = [&mesh] {
        std::vector<Vec3> corners;
        corners.reserve(3 * mesh.triangle_count());
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
            for (int k = 0; k < 3; ++k) corners.push_back(mesh.corner(t, k));
        return corners;
    };
    what.shot_diameter_m = largest_diameter_m(scene.shot);
    what.shot_density_kg_per_m3 = scene.shot.density_kg_per_m3;
    what.material = c.material;
    for (const MaterialDesc& m : scene.materials)
        if (m.name == c.material) what.yield_stress_pa = m.yield_stress_pa;
    what.surface_elastic = elastic_of(scene, c.material);
    what.shot_elastic = elastic_of(scene, scene.shot.material);
    what.shot_material = scene.shot.material;
    try {
        return law->make_surface(parameter_values(pair, law->surface_parameters), what);
    } catch (const std::invalid_argument& e) {
        throw InputError(pair.where, "contacts." + pair.key + ".law", std::string(e.what()) + " (component '" + c.name + "')");
    }
}

// The air's motion: the nozzles' jets (sources[].air_speed), or none (still air).
std::shared_ptr<const AirVelocityField> air_field_of(const SceneDescription& scene) {
    std::vector<FreeJet> jets;
    for (const SourceDesc& s : scene.sources) {
        if (!s.air_speed_m_per_s) continue;
        FreeJet jet;
        jet.exit_m = s.position_m;
        jet.axis = s.direction;
        jet.exit_diameter_m = 2.0 * s.exit_radius_m;
        jet.exit_speed_m_per_s = *s.air_speed_m_per_s;
        jets.push_back(jet);
    }
    if (jets.empty()) return nullptr;
    return std::make_shared<const AirVelocityField>(std::move(jets));
}

contact::ReboundScatter rebound_scatter_of(const SceneDescription& scene) {
    const AirDesc::Scatter& s = *scene.air.rebound_scatter;
    if (scene.accuracy.scheme == SteppingScheme::soft)
        throw InputError(s.where, "air.rebound_scatter",
                         "the soft scheme integrates contact forces, which rebound scatter cannot turn; expected accuracy.scheme "
                         "event or step with rebound scatter");
    contact::ReboundScatter r;
    r.spread_rad = s.spread_rad;
    r.min_reynolds = s.min_reynolds;
    r.min_speed_m_per_s = s.min_speed_m_per_s;
    r.air_density_kg_per_m3 = scene.air.density_kg_per_m3;
    r.air_viscosity_pa_s = scene.air.viscosity_pa_s;
    r.seed = scene.process.seed;
    if (std::shared_ptr<const AirVelocityField> field = air_field_of(scene))
        r.air_velocity = [field](const Vec3& p) { return field->at(p); };
    return r;
}

void add_sources(Model& model, const SceneDescription& scene) {
    const std::vector<double> shares = model.has_size_mix() ? model.size_count_fraction : std::vector<double>{};
    for (std::size_t k = 0; k < scene.sources.size(); ++k) {
        const SourceDesc& s = scene.sources[k];
        model.sources.push_back(
            make_source(s, static_cast<int>(k), std::min(s.stop_s, scene.process.duration_s), scene.process.seed, shares));
    }
}

// After the world's bounds: a sink `outside` is the world box.
void add_sinks(Model& model, const SceneDescription& scene) {
    for (std::size_t k = 0; k < scene.sinks.size(); ++k) {
        const SinkDesc& s = scene.sinks[k];
        if (s.region == SinkRegion::mesh) {
            TriangleMesh mesh;
            try {
                mesh = load_mesh(s.mesh_path, s.mesh_unit_m);
            } catch (const InputError& e) {
                throw InputError(s.mesh_where, "sinks[" + std::to_string(k) + "].mesh", e.problem_at_its_place());
            }
            for (Vec3& v : mesh.vertices) v += s.translation_m;
            try {
                model.sinks.push_back(std::make_shared<const MeshSink>(s.name, std::make_shared<const TriangleMesh>(std::move(mesh))));
            } catch (const std::invalid_argument& e) {
                throw InputError(s.mesh_where, "sinks[" + std::to_string(k) + "].mesh", std::string(e.what()) + " (" + s.mesh_path + ")");
            }
        } else if (s.region == SinkRegion::box)
            model.sinks.push_back(std::make_shared<const BoxSink>(s.name, s.min_m, s.max_m, BoxSink::Side::inside));
        else
            model.sinks.push_back(std::make_shared<const BoxSink>(s.name, model.world_lo, model.world_hi, BoxSink::Side::outside));
    }
}

std::shared_ptr<const FlightModel> flight_model_of(const SceneDescription& scene, double shot_radius_m) {
    const Vec3 g = scene.process.gravity_m_per_s2;
    // An air jet moves the air; drag is what makes the shot feel it in flight (rebound scatter
    // reads it at an impact too), and the jet needs its exit.
    for (std::size_t k = 0; k < scene.sources.size(); ++k) {
        const SourceDesc& s = scene.sources[k];
        if (!s.air_speed_m_per_s) continue;
        const std::string field = "sources[" + std::to_string(k) + "].air_speed";
        if (!scene.air.drag && !scene.air.rebound_scatter)
            throw InputError(
                s.where, field,
                "an air jet acts on the shot through drag (or rebound scatter), both off; expected air.drag: sphere with air_speed");
        if (!(s.exit_radius_m > 0.0))
            throw InputError(s.where, field, "an air jet needs the nozzle's exit; expected `diameter` or `exit_radius` > 0 with air_speed");
    }
    if (!scene.air.drag) return std::make_shared<const ParabolaFlight>(g);
    AirDrag air;
    air.air_density_kg_per_m3 = scene.air.density_kg_per_m3;
    air.air_viscosity_pa_s = scene.air.viscosity_pa_s;
    air.drag_coefficient = scene.air.drag_coefficient;
    air.shot_radius_m = shot_radius_m;
    air.shot_density_kg_per_m3 = scene.shot.density_kg_per_m3;
    air.wind = air_field_of(scene);
    return std::make_shared<const AirDragFlight>(g, air);
}

// The shot's sizes: radius, mass, count share and flight of each.
void add_shot_sizes(Model& model, const SceneDescription& scene) {
    const std::vector<double> share = count_fractions(scene.shot);
    model.min_shot_radius_m = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < scene.shot.sizes.size(); ++k) {
        ShotSize size;
        size.radius_m = 0.5 * scene.shot.sizes[k].diameter_m;
        size.mass_kg = scene.shot.density_kg_per_m3 * (4.0 / 3.0) * M_PI * std::pow(size.radius_m, 3);
        size.count_fraction = share[k];
        size.flight = flight_model_of(scene, size.radius_m);
        model.flight_speed_gain_bound_m_per_s2 = std::max(model.flight_speed_gain_bound_m_per_s2, size.flight->speed_gain_bound());
        model.min_shot_radius_m = std::min(model.min_shot_radius_m, size.radius_m);
        model.max_shot_radius_m = std::max(model.max_shot_radius_m, size.radius_m);
        model.size_count_fraction.push_back(share[k]);
        model.shot_sizes.push_back(std::move(size));
    }
    model.flight = model.shot_sizes.front().flight;
    if (model.has_size_mix() && scene.accuracy.scheme == SteppingScheme::soft)
        throw InputError(scene.shot.where, "shot.sizes",
                         "the soft scheme's Hertz-Mindlin pairs are built for one shot size; expected shot.diameter (one size) with "
                         "accuracy.scheme: soft, or the event or step scheme for a mix");
}

}  // namespace

int Model::component_index(const std::string& name) const {
    for (std::size_t i = 0; i < components.size(); ++i)
        if (components[i].name == name) return static_cast<int>(i);
    return -1;
}

std::shared_ptr<const Model> compile_model(const SceneDescription& scene) {
    auto model = std::make_shared<Model>();
    model->description = scene;
    model->resolved_scene_yaml = resolved_scene_yaml(scene);
    model->scene_hash = scene_hash(scene);
    model->shot_count = scene.shot.count;
    model->gravity_m_per_s2 = scene.process.gravity_m_per_s2;
    add_shot_sizes(*model, scene);
    model->duration_s = scene.process.duration_s;
    model->seed = scene.process.seed;
    model->scheme = scene.accuracy.scheme;
    model->travel_fraction = scene.accuracy.travel_fraction;
    model->impact_speed_m_per_s = scene.accuracy.impact_speed_m_per_s;
    model->soft_steps_per_contact = scene.accuracy.soft_steps_per_contact;
    model->shot_shot_law = shot_shot_law_of(contact_for(scene, "shot-shot"), scene);

    const double R = model->max_shot_radius_m;
    const Vec3 up = model->gravity_m_per_s2.norm() > 0.0 ? Vec3(-model->gravity_m_per_s2.normalized()) : Vec3::UnitZ();
    const std::vector<std::string>& logged = scene.output.logged_components;

    // Each mesh's collider (Bullet's BVH: ~0.5 s for 500 k triangles) is built on a thread of its
    // own while the loop checks that mesh and loads the next (at most a core's worth at once);
    // joined before anything asks for one.
    std::vector<std::future<std::shared_ptr<const MeshCollider>>> colliders;
    std::size_t joined = 0;
    const std::size_t at_once = std::max(1u, std::thread::hardware_concurrency());
    for (std::size_t i = 0; i < scene.components.size(); ++i) {
        const ComponentDesc& desc = scene.components[i];
        for (; colliders.size() - joined >= at_once; ++joined) model->components[joined].collider = colliders[joined].get();
        Component c;
        c.name = desc.name;
        c.role = desc.role;
        c.material = desc.material;
        try {
            c.mesh = std::make_shared<const TriangleMesh>(load_component_mesh(desc));
        } catch (const InputError& e) {
            throw InputError(desc.mesh_where, component_leaf_field(i, "mesh"), e.problem_at_its_place());
        }
        colliders.push_back(std::async(std::launch::async, [mesh = c.mesh] { return std::make_shared<const MeshCollider>(*mesh); }));
        c.kinematics = build_kinematics(desc, *c.mesh, up);
        const ContactPairDesc& pair = contact_for(scene, "shot-" + desc.material);
        c.law = surface_law_of(pair, scene, c);
        if (scene.air.rebound_scatter) c.law = contact::with_rebound_scatter(c.law, rebound_scatter_of(scene));
        c.coefficients_source = pair.key;
        c.logged = logged.empty() ? logged_by_default(desc.role) : std::find(logged.begin(), logged.end(), desc.name) != logged.end();
        component_bounds(c);
        check_extent(c, desc, i);
        c.edges = edge_report(*c.mesh);
        if (desc.role == ComponentRole::part || desc.role == ComponentRole::fixture || desc.role == ComponentRole::almen)
            c.solid = c.edges.boundary_edges == 0 && c.edges.non_manifold_edges == 0 && c.edges.misoriented_edges == 0 &&
                      enclosed_volume(*c.mesh) > 0.0;
        // The first sonotrode is the one the shot are placed on.
        if (desc.role == ComponentRole::sonotrode && model->sonotrode < 0) model->sonotrode = static_cast<int>(i);
        model->components.push_back(std::move(c));
    }
    for (; joined < colliders.size(); ++joined) model->components[joined].collider = colliders[joined].get();

    model->world_lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    model->world_hi = -model->world_lo;
    for (const Component& c : model->components) {
        model->world_lo = model->world_lo.cwiseMin(c.world_lo);
        model->world_hi = model->world_hi.cwiseMax(c.world_hi);
        model->peak_surface_speed_m_per_s =
            std::max(model->peak_surface_speed_m_per_s, c.kinematics.peak_surface_speed(c.max_axis_distance_m));
    }
    add_sources(*model, scene);
    for (const auto& source : model->sources) {  // where a source's shot start lies inside the bounds
        const SourceOutline o = source->outline();
        model->world_lo = model->world_lo.cwiseMin(o.start_lo_m);
        model->world_hi = model->world_hi.cwiseMax(o.start_hi_m);
    }
    // A shot beyond the assembly's bounds by more than a diameter has certainly left it.
    model->world_lo -= Vec3::Constant(4.0 * R);
    model->world_hi += Vec3::Constant(4.0 * R);
    add_sinks(*model, scene);
    if (model->scheme == SteppingScheme::soft) require_soft_laws(*model, scene);
    return model;
}

}  // namespace peensim
