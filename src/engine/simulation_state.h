// The mutable state of a run: only what changes (STYLE practice 2). Shot data are stored as
// structure of arrays, the layout the per-step loops stream through.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/sim_time.h"
#include "common/vec.h"
#include "engine/contact_states.h"
#include "engine/soft_contact.h"

namespace peensim {

struct ShotArrays {
    std::vector<double> x, y, z;            // m, centre, world
    std::vector<double> vx, vy, vz;         // m/s, world
    std::vector<double> wx, wy, wz;         // rad/s, angular velocity, world (changed only by soft-sphere contacts)
    std::vector<unsigned char> active;      // 0 once a shot is lost (left the chamber, non-finite state)
    std::vector<unsigned char> size_class;  // index into Model::shot_sizes (0 for a scene of one size)
    // 1 while a shot is in free flight: since an impact sent it off, or since a step (time
    // stepping) in which it touched nothing. 0 once it is in sustained contact, and at the start
    // (placed shot have not flown). A sustained contact that finds it 1 ends a flight more slowly
    // than the impact speed: counted once as a slow contact, then not again while the shot rests.
    std::vector<unsigned char> in_flight;

    std::size_t size() const { return x.size(); }
    void resize(std::size_t n) {
        for (auto* v : {&x, &y, &z, &vx, &vy, &vz, &wx, &wy, &wz}) v->assign(n, 0.0);
        active.assign(n, 1);
        size_class.assign(n, 0);
        in_flight.assign(n, 0);
    }
    // Room for n shot (n >= size()): the new slots inactive, at the origin, at rest.
    void grow(std::size_t n) {
        for (auto* v : {&x, &y, &z, &vx, &vy, &vz, &wx, &wy, &wz}) v->resize(n, 0.0);
        active.resize(n, 0);
        size_class.resize(n, 0);
        in_flight.resize(n, 0);
    }
    Vec3 position(std::size_t i) const { return {x[i], y[i], z[i]}; }
    Vec3 velocity(std::size_t i) const { return {vx[i], vy[i], vz[i]}; }
    Vec3 spin(std::size_t i) const { return {wx[i], wy[i], wz[i]}; }
    void set_position(std::size_t i, const Vec3& p) { x[i] = p.x(), y[i] = p.y(), z[i] = p.z(); }
    void set_velocity(std::size_t i, const Vec3& v) { vx[i] = v.x(), vy[i] = v.y(), vz[i] = v.z(); }
    void set_spin(std::size_t i, const Vec3& w) { wx[i] = w.x(), wy[i] = w.y(), wz[i] = w.z(); }
};

// Numerical trouble is counted, never fatal (STYLE practice 11); `--strict` fails a run on any.
struct HealthCounters {
    std::uint64_t shot_lost = 0;                 // shot that left the chamber (a leaky mesh)
    std::uint64_t non_finite = 0;                // shot removed because their state became NaN/inf
    std::uint64_t mesh_overlap_corrections = 0;  // overlaps with a mesh removed by moving the shot (no energy added)
    std::uint64_t shot_overlap_corrections = 0;  // shot-shot overlaps removed the same way
    std::uint64_t deep_penetrations = 0;         // a shot found deeper than R/2 inside a surface
    std::uint64_t unresolved_contacts = 0;       // contact passes exhausted within one step
    std::uint64_t engine_errors = 0;             // lost shot that crossed a surface (not through an opening)
    // Flights whose exact contact search made no headway (kMaxResumedSearches searches in a row ran
    // out of iterations near a moving surface) and went on in sustained-contact substeps instead:
    // the net under "time always advances" (SimulationState::first_search_fallback says where).
    std::uint64_t search_fallbacks = 0;

    // Every counter, by name: the one list the summary, the benchmark and the checkpoint follow.
    template <class Visit>
    void for_each(Visit&& visit) const {
        each(*this, visit);
    }
    template <class Visit>
    void for_each(Visit&& visit) {
        each(*this, visit);
    }
    // Counters that mean a wrong result (the others are routine corrections).
    std::uint64_t serious() const { return shot_lost + non_finite + deep_penetrations + unresolved_contacts + engine_errors; }

private:
    template <class Self, class Visit>
    static void each(Self& self, Visit& visit) {
        visit("shot_lost", self.shot_lost);
        visit("non_finite", self.non_finite);
        visit("mesh_overlap_corrections", self.mesh_overlap_corrections);
        visit("shot_overlap_corrections", self.shot_overlap_corrections);
        visit("deep_penetrations", self.deep_penetrations);
        visit("unresolved_contacts", self.unresolved_contacts);
        visit("engine_errors", self.engine_errors);
        visit("search_fallbacks", self.search_fallbacks);
    }
};

// Why a shot was lost (engine/loss_diagnosis.h): through an opening of the assembly (a setup
// error), or through a surface the scheme failed to see (an engine error). Time stepping's losses
// are not diagnosed (its last step alone proves nothing).
enum class LossCause : unsigned char { not_diagnosed, leak, engine_error };

// Where and when a shot left the assembly, and why.
struct LostShot {
    int shot = 0;
    double time_s = 0.0;             // s
    Vec3 position_m = Vec3::Zero();  // m, world, where it left the world box
    LossCause cause = LossCause::not_diagnosed;
    double from_time_s = 0.0;     // s, its last event (the flight that carried it out started there)
    Vec3 from_m = Vec3::Zero();   // m, world, its centre then
    int component = -1;           // engine error: the component it crossed; leak: the nearest at the opening
    Vec3 where_m = Vec3::Zero();  // m, world, engine error: the point crossed; leak: where the centre left the chamber's bounds
    double clearance_m = 0.0;     // m, leak: centre to the nearest surface there (the opening is at least 2 R wide)
    double radius_m = 0.0;        // m, the shot's radius R (diagnosed losses)
};

// The first search fallback of a run (HealthCounters::search_fallbacks): where and why.
struct SearchFallback {
    double time_s = -1.0;  // s; negative: none yet
    int shot = -1;
    int component = -1;              // the moving component whose search ran out
    Vec3 position_m = Vec3::Zero();  // m, world, the shot's centre then
};

struct SimulationState {
    ShotArrays shots;
    SimTime time;
    std::uint64_t steps = 0;
    std::uint64_t shot_steps = 0;  // active shot advanced, summed over steps
    std::uint64_t shot_shot_impacts = 0;
    std::vector<std::uint64_t> impacts_per_component;  // every impact, logged or not
    // Flights that ended in sustained contact, approaching slower than the model's impact speed
    // (not impacts, not logged): per component, and between two shot.
    std::vector<std::uint64_t> slow_contacts_per_component;
    std::uint64_t shot_shot_slow_contacts = 0;
    double fastest_shot_m_per_s = 0.0;  // m/s, after the last step (feeds eq. 7)
    // What the contact laws remember between contacts (contact_law.h): per component, its law's
    // state_per_triangle() doubles per mesh triangle; empty for a law that keeps none.
    std::vector<std::vector<double>> law_state;
    // What the surface laws remember per contact while it lasts (empty unless a law asks).
    ContactStates contacts;
    // The soft scheme's contacts in progress at the state's time (engine/soft/soft_pool.h), ordered
    // by (shot, partner, component); empty for the rigid schemes.
    std::vector<SoftContact> soft_contacts;
    HealthCounters health;
    std::vector<LostShot> lost;  // one entry per lost shot (bounded by the shot count)
    SearchFallback first_search_fallback;
    // Shot sources and sinks (model/shot_flow.h), in the model's order: how many each source has
    // emitted (the number of its next emission) and each sink collected. An emitted shot takes
    // the lowest inactive slot of `shots` (one collected or lost), else a new one at the end.
    std::vector<std::uint64_t> emitted_per_source;
    std::vector<std::uint64_t> collected_per_sink;
    // Shot placed or emitted so far of each size (Model::shot_sizes' order): what the mix came out as.
    std::vector<std::uint64_t> shots_per_size;
};

}  // namespace peensim
