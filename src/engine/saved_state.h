// The state a checkpoint saves, declared once: each field's name, the checkpoint format version
// that added it, what a list's length follows, and the value itself. The checkpoint's writer,
// reader and checks (app/checkpoint/) all walk this one list, so a field added here is saved,
// loaded, length-checked and (a floating value) checked finite without another line elsewhere; a
// field of SimulationState missing here is caught by `SavedState.EveryFieldIsDeclared`.
//
// A walker `f` offers (T a value: an arithmetic or enum type, or a Vec3):
//   f.value(name, T&, since)
//   f.array(name, std::vector<T>&, since, Extent)
//   f.records(name, std::vector<R>&, since, Extent, each)   each(R&, f) walks one record's fields
//   f.counters(name, C&, since)                            C::for_each(visit(name, count))
//   f.contact_states(name, ContactStates&, since)
// State may be const (the writer) or not (the reader).
#pragma once

#include "engine/simulation_state.h"

namespace peensim {

// What a list's length must equal.
enum class Extent : unsigned char {
    shots,              // one per shot slot (the length of shots.x)
    components,         // one per component of the scene
    logged_components,  // one per logged component
    sources,            // one per shot source
    sinks,              // one per shot sink
    shot_sizes,         // one per shot size of the mix
    free,               // any length (checked by what it means, in check_resumable)
};

// The format version: the latest `since` below (and in checkpoint_fields). 10 declared the fields
// once and saves the health counters by name; 11 added a run until coverage's replicas.
inline constexpr std::uint32_t kSavedStateVersion = 11;

template <class Shots, class Fields>
void shot_fields(Shots& s, Fields& f) {
    f.array("shots.x", s.x, 1, Extent::shots);
    f.array("shots.y", s.y, 1, Extent::shots);
    f.array("shots.z", s.z, 1, Extent::shots);
    f.array("shots.vx", s.vx, 1, Extent::shots);
    f.array("shots.vy", s.vy, 1, Extent::shots);
    f.array("shots.vz", s.vz, 1, Extent::shots);
    f.array("shots.wx", s.wx, 7, Extent::shots);
    f.array("shots.wy", s.wy, 7, Extent::shots);
    f.array("shots.wz", s.wz, 7, Extent::shots);
    f.array("shots.active", s.active, 1, Extent::shots);
    f.array("shots.in_flight", s.in_flight, 2, Extent::shots);
    f.array("shots.size_class", s.size_class, 8, Extent::shots);
}

template <class Lost, class Fields>
void lost_shot_fields(Lost& l, Fields& f) {
    f.value("shot", l.shot, 1);
    f.value("time_s", l.time_s, 1);
    f.value("position_m", l.position_m, 1);
    f.value("cause", l.cause, 1);
    f.value("from_time_s", l.from_time_s, 1);
    f.value("from_m", l.from_m, 1);
    f.value("component", l.component, 1);
    f.value("where_m", l.where_m, 1);
    f.value("clearance_m", l.clearance_m, 1);
    f.value("radius_m", l.radius_m, 8);
}

template <class Contact, class Fields>
void soft_contact_fields(Contact& k, Fields& f) {
    f.value("shot", k.shot, 7);
    f.value("partner", k.partner, 7);
    f.value("component", k.component, 7);
    f.value("law_state", k.law_state, 7);
    f.value("normal", k.normal, 7);
    f.value("approach_m_per_s", k.approach_m_per_s, 7);
    f.value("start_time_s", k.start_time_s, 7);
    f.value("mesh_triangle", k.mesh_triangle, 7);
    f.value("start_point_m", k.start_point_m, 7);
    f.value("start_velocity_m_per_s", k.start_velocity_m_per_s, 7);
    f.value("start_tangential_m_per_s", k.start_tangential_m_per_s, 7);
}

template <class State, class Fields>
void saved_state_fields(State& s, Fields& f) {
    f.value("time.hi", s.time.hi, 1);
    f.value("time.lo", s.time.lo, 1);
    f.value("steps", s.steps, 1);
    f.value("shot_steps", s.shot_steps, 1);
    f.value("shot_shot_impacts", s.shot_shot_impacts, 1);
    f.value("fastest_shot_m_per_s", s.fastest_shot_m_per_s, 1);
    f.counters("health", s.health, 10);
    f.array("impacts_per_component", s.impacts_per_component, 1, Extent::components);
    f.array("slow_contacts_per_component", s.slow_contacts_per_component, 2, Extent::components);
    f.value("shot_shot_slow_contacts", s.shot_shot_slow_contacts, 2);
    f.records("law_state", s.law_state, 4, Extent::components,
              [](auto& per_triangle, auto& g) { g.array("values", per_triangle, 4, Extent::free); });
    f.records("lost", s.lost, 1, Extent::free, [](auto& l, auto& g) { lost_shot_fields(l, g); });
    f.value("first_search_fallback.time_s", s.first_search_fallback.time_s, 9);
    f.value("first_search_fallback.shot", s.first_search_fallback.shot, 9);
    f.value("first_search_fallback.component", s.first_search_fallback.component, 9);
    f.value("first_search_fallback.position_m", s.first_search_fallback.position_m, 9);
    shot_fields(s.shots, f);
    f.array("emitted_per_source", s.emitted_per_source, 5, Extent::sources);
    f.array("collected_per_sink", s.collected_per_sink, 5, Extent::sinks);
    f.array("shots_per_size", s.shots_per_size, 8, Extent::shot_sizes);
    f.contact_states("contacts", s.contacts, 6);
    f.records("soft_contacts", s.soft_contacts, 7, Extent::free, [](auto& k, auto& g) { soft_contact_fields(k, g); });
}

}  // namespace peensim
