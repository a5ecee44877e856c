// How both stepping schemes describe a contact to a law (contact_law.h): velocities, the contact's
// identity and place in the component's own frame, and the law's state. One place, so the two
// schemes hand laws the same facts.
#pragma once

#include <span>

#include "contact/contact_law.h"
#include "engine/simulation_state.h"
#include "model/model.h"

namespace peensim {

// Where a shot touches a component. mesh_triangle: index into the component's mesh (the index
// of the per-triangle law state); pose: the component's pose at the contact.
struct ContactSite {
    int shot = -1;
    int component = -1;
    int mesh_triangle = -1;
    const Pose* pose = nullptr;
    Vec3 point_world = Vec3::Zero();  // m
    double time_s = 0.0;              // s, absolute simulated time
    double overlap_m = 0.0;           // m, depth of the shot in the surface (0 at an exact touch)
};

// A shot's size (its radius, mass and flight), and its radius (m).
inline const ShotSize& shot_size(const Model& model, const ShotArrays& shots, std::size_t i) {
    return model.shot_sizes[shots.size_class[i]];
}
inline double shot_radius(const Model& model, const ShotArrays& shots, std::size_t i) { return shot_size(model, shots, i).radius_m; }

// v_shot, v_surface: m/s, world; n: unit normal towards the shot; impact: the contact policy's
// verdict; pressing_accel (m/s2) and dt (s): for friction in sustained contact; contact_state: the
// contact's own state (sustained_contact_state or instant_contact_state below).
inline contact::SurfaceContactInput surface_input(const Model& model, const ShotArrays& shots, const ContactSite& site, const Vec3& v_shot,
                                                  const Vec3& v_surface, const Vec3& n, bool impact, double pressing_accel = 0.0,
                                                  double dt = 0.0, std::span<double> contact_state = {}) {
    contact::SurfaceContactInput in{v_shot, v_surface, n, pressing_accel, dt};
    in.contact_state = contact_state;
    in.shot = site.shot;
    in.component = site.component;
    in.triangle = site.mesh_triangle;
    in.point_local = site.pose != nullptr ? site.pose->to_component(site.point_world) : site.point_world;
    in.point_world = site.point_world;
    in.overlap_m = site.overlap_m;
    const ShotSize& size = shot_size(model, shots, static_cast<std::size_t>(site.shot));
    in.shot_radius_m = size.radius_m;
    in.shot_mass_kg = size.mass_kg;
    in.time_s = site.time_s;
    in.impact = impact;
    return in;
}

// The per-triangle state of a component's law (empty when its law keeps none).
inline std::span<double> law_state(SimulationState& state, std::size_t component) {
    return component < state.law_state.size() ? std::span<double>(state.law_state[component]) : std::span<double>();
}

// A fresh state for every component's law: state_per_triangle() zeros per mesh triangle.
inline std::vector<std::vector<double>> fresh_law_state(const Model& model) {
    std::vector<std::vector<double>> out(model.components.size());
    for (std::size_t c = 0; c < model.components.size(); ++c) {
        const Component& comp = model.components[c];
        const auto per = static_cast<std::size_t>(comp.law ? comp.law->state_per_triangle() : 0);
        out[c].assign(per * comp.mesh->triangle_count(), 0.0);
    }
    return out;
}

// Whether any component's law keeps state per contact (then the schemes keep ContactStates).
inline bool uses_contact_state(const Model& model) {
    for (const Component& c : model.components)
        if (c.law && c.law->state_per_contact() > 0) return true;
    return false;
}

// The state of shot's sustained contact with component c, found in resolution `stamp` (zeros if
// new; empty when c's law keeps none).
inline std::span<double> sustained_contact_state(SimulationState& state, const Model& model, int shot, std::size_t c, std::uint64_t stamp) {
    const int n = model.components[c].law->state_per_contact();
    return n > 0 ? state.contacts.touch(shot, static_cast<int>(c), static_cast<std::size_t>(n), stamp) : std::span<double>();
}

// An instantaneous contact's state (an impact, a ride in one piece): zeros, in `scratch`.
inline std::span<double> instant_contact_state(std::vector<double>& scratch, const Model& model, std::size_t c) {
    const auto n = static_cast<std::size_t>(model.components[c].law->state_per_contact());
    scratch.assign(n, 0.0);
    return scratch;
}

// The shot-shot law's input; mode: the contact policy's (contact_policy.h).
inline contact::ShotShotInput shot_shot_input(const Model& model, const ShotArrays& shots, int i, int j, const Vec3& vi, const Vec3& vj,
                                              const Vec3& n, contact::ShotShotMode mode, double distance_m, double time_s) {
    contact::ShotShotInput in{vi, vj, n, mode};
    in.shot_i = i;
    in.shot_j = j;
    const ShotSize& size_i = shot_size(model, shots, static_cast<std::size_t>(i));
    const ShotSize& size_j = shot_size(model, shots, static_cast<std::size_t>(j));
    in.overlap_m = std::max(0.0, size_i.radius_m + size_j.radius_m - distance_m);
    in.radius_i_m = size_i.radius_m;
    in.radius_j_m = size_j.radius_m;
    in.mass_i_kg = size_i.mass_kg;
    in.mass_j_kg = size_j.mass_kg;
    in.time_s = time_s;
    return in;
}

}  // namespace peensim
