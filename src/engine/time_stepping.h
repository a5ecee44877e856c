// Time stepping (the CAD-based USP model's scheme, reference sec. 2): each step every shot flies
// exactly under gravity (eq. 1) for a step chosen by eq. 7; contacts are then detected and each is
// taken back to its exact moment of first touch, where the contact law decides the rebound.
//
// Stages of one step, in order (each timed into StepStats):
//   advance_kinematics  component poses at the step end, in closed form
//   integrate_shots     exact ballistic flight
//   mesh_queries        per shot and component: distance gate, Bullet BVH, closest feature
//   contact_laws        touch time (quadratic, or sampled for the vibrating sonotrode), eq. 4/5
//   shot_broadphase     candidate shot-shot pairs (Bullet btDbvtBroadphase)
//   shot_shot_contacts  exact touch time of each overlapping pair, eq. 3 there
//   (mesh_queries and contact_laws again for the shot a shot-shot contact kicked)
//   check_health        lost and non-finite shot, fastest speed for the next step
// Walls come first so that no shot ends a step inside a surface.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "collision/sharp_distance.h"
#include "collision/shot_pair_finder.h"
#include "engine/stepper.h"
#include "model/model.h"

namespace peensim {

class TimeStepping final : public Stepper {
public:
    explicit TimeStepping(std::shared_ptr<const Model> model);

    std::string_view name() const override { return "step"; }
    // Steps are short (at most a quarter radius of travel): pause_at_s is not needed and ignored, so
    // that recording an animation cannot change a run.
    void advance(SimulationState& state, double t_end_s, double pause_at_s, std::vector<ImpactRecord>& impacts) override;
    const StepStats& stats() const override { return stats_; }
    // A shot moved by hand may be anywhere: the skip counters (which assume bounded travel per
    // step) and distance memos are dropped.
    void state_changed() override;
    void shots_added(SimulationState& state, const std::vector<int>& shots) override;

    // Eq. 7 generalised to a travel fraction: the step in which the fastest thing (speed v, m/s)
    // travels at most fraction * R under gravity g (m/s2).
    static double step_for(double v_max, double gravity, double travel_m);
    // The step (s) this scheme takes when the fastest thing moves at v_max (m/s): eq. 7 at the
    // model's travel fraction, and never so long that gravity adds more than a tenth of the impact
    // speed in it (otherwise a shot resting on a support that drops away for one step would land
    // on it again fast enough to count as an impact, and how many bounces of a slowing shot are
    // followed would depend on the step).
    static double time_step(const Model& model, double v_max);

private:
    struct Contact {
        double gap;         // m, distance from the shot surface to the closest feature (< 0: overlap)
        Vec3 normal;        // unit, world, from the surface towards the shot centre
        Vec3 point;         // m, world, closest point on the surface at the step end
        int triangle;       // facet index in the component's mesh file
        int mesh_triangle;  // index into the component's TriangleMesh
    };

    void integrate(SimulationState& state, double dt);
    void clear_step_marks();  // per-step marks (latest touch, kicks) back to "none"
    // The acceleration of shot i's arc within a step (gravity; with air drag its size's flight model's at p and v).
    Vec3 arc_acceleration(const ShotArrays& s, std::size_t i, const Vec3& p, const Vec3& v) const;
    // Sets shot i to where the flight model takes it in dt (s) from centre p and velocity v.
    void fly(ShotArrays& s, std::size_t i, const Vec3& p, const Vec3& v, double dt) const;
    void resolve_shot_pairs(SimulationState& state, double dt);
    // only_kicked: just the shot whose flight a shot-shot contact changed in this step.
    void resolve_mesh_contacts(SimulationState& state, double dt, std::vector<ImpactRecord>& impacts, bool only_kicked);
    // Returns true if an impact happened (the shot's trajectory changed within the step).
    bool handle_component(SimulationState& state, std::size_t shot, std::size_t component, double dt, std::vector<ImpactRecord>& impacts);
    // The first touch (s into the step, at or after u_lo) of the shot of radius R (m) ending the
    // step at p1 with velocity v1 on its arc of acceleration g (m/s2) on the vibrating surface
    // whose contact at the step end is `contact`.
    std::optional<double> vibrating_touch(const Kinematics& kin, const Contact& contact, const Vec3& p1, const Vec3& v1, const Vec3& g,
                                          double R, double dt, double u_lo, bool leaving) const;
    // A shot that starts riding the vibrating plate at u (s into the step) with velocity v_after
    // and centre `centre` (the plate in pose_touch then): launched where the plate pulls away faster than gravity, if that comes
    // before the step end (its state at the step end set accordingly; true), else false.
    bool launch_within_step(SimulationState& state, std::size_t shot, std::size_t component, const Vec3& n, const Vec3& centre,
                            const Vec3& v_after, double u, const Pose& pose_touch, double dt);
    // The contact of a shot of radius R (m) with a component, if the surface is within query_radius of its centre.
    bool closest_contact(std::size_t component, std::size_t shot, double R, const Vec3& p_world, const Vec3& v_world, double query_radius,
                         Contact& out);
    void sustain_contact(SimulationState& state, std::size_t shot, std::size_t component, const Contact& contact, const Vec3& v1,
                         const Vec3& p1, double dt);
    // The shot is now in sustained contact: true if that ends a free flight (its in_flight flag was
    // set: the caller counts one slow contact), false while it goes on resting, rolling or sliding.
    bool ends_a_flight(SimulationState& state, std::size_t shot);
    // After a step: a shot that touched nothing in it is in free flight.
    void note_free_flights(SimulationState& state);
    void check_health(SimulationState& state);
    // Shot i is in a sink at the step end: taken out and counted there (true).
    bool collected(SimulationState& state, std::size_t i) const;
    // Per-shot tables for n shot (a source emitted, or an edit added shot).
    void fit_shots(std::size_t n);
    // A kicked shot may move further than the per-step bound: check it against every component again.
    void forget_clearances(std::size_t shot);

    std::shared_ptr<const Model> model_;
    ShotPairFinder pairs_;
    bool parabola_ = true;                 // flights are exact parabolas (closed form, no call through the flight model)
    bool contact_state_ = false;           // a law keeps state per contact (ContactStates)
    std::uint64_t stamp_ = 0;              // this step's resolution of the sustained contacts
    std::vector<double> contact_scratch_;  // an instantaneous contact's state (zeros)
    StepStats stats_;
    // Per step:
    SimTime t0_;                                 // step start
    std::vector<Pose> pose_end_;                 // per component, at the step end
    std::vector<double> last_touch_;             // per shot: offset (s) of its latest contact in this step
    std::vector<int> last_touch_component_;      // per shot: component of that contact (-1: a shot or none)
    std::vector<unsigned char> kicked_by_shot_;  // per shot: a shot-shot contact changed its flight this step
    std::vector<unsigned char> touched_;         // per shot: any contact (impact or sustained) this step
    std::vector<std::pair<int, int>> touching_;  // overlapping shot pairs of this step, reused
    std::uint64_t step_ = 0;                     // index of the current step
    // Per component and shot: the first step at which the shot could touch the component again
    // (the distance gate's clearance divided by the most a shot can close in per step), at
    // [component * n_shots_ + shot]: n_shots_ is the tables' stride, at least the shot count.
    std::size_t n_shots_ = 0;
    std::vector<std::uint64_t> skip_until_;
    double max_relative_travel_ = 0.0;  // m per step
    // Per component: a voxel gate of distance lower bounds (built here: only time stepping uses it)
    // and bounds sharper than the gate's.
    std::vector<std::unique_ptr<const DistanceGate>> gates_;
    std::vector<SharpDistance> sharp_;
    std::vector<double> max_query_radius_;  // m, per component
    // Per component and shot: where (component frame, m) the shot's exact distance (m) to the
    // component was last measured, and that distance (0 = none: always query).
    struct DistanceMemo {
        Vec3 where = Vec3::Zero();
        double distance = 0.0;
    };
    std::vector<DistanceMemo> memo_;
    double memo_margin_ = 0.0;  // m
};

}  // namespace peensim
