// Where a flying shot first meets a surface: the event-driven scheme's wall prediction, a const
// function of the model, the scheme's clock and a flight (model and collision in, a WallEvent
// out). Static meshes by MeshCollider::first_hit (a time-ordered swept-sphere walk of the BVH),
// the sonotrode's face by its exact vibrating plane (vibrating_plane_toi), moving meshes (a
// rotating part, the sonotrode's sides) by conservative advancement on exact distances.
#pragma once

#include <memory>
#include <vector>

#include "common/sim_time.h"
#include "engine/event/sonotrode_face.h"
#include "engine/event/wall_event.h"
#include "engine/step_stats.h"
#include "kernels/trajectory.h"
#include "model/model.h"

namespace peensim {

class WallPredictor {
public:
    explicit WallPredictor(std::shared_ptr<const Model> model);

    // The scheme's clock restarts at `epoch` (absolute): every time passed in or out is seconds
    // since it (the face's phase is rebased to it).
    void set_epoch(const SimTime& epoch);

    // The first event of the flight `path` (rebased at t) of a shot of radius R (m) with a surface, searched over
    // [t_search, window_end]: a contact (kind contact; overlapping if the shot is already in a
    // surface at t_search), leaving the world box (kind leave), or nothing found (kind none) at
    // the window's end or where a moving-mesh search ran out of iterations (the search goes on
    // from there). Counts its work in `stats`.
    WallEvent first_event(const Trajectory& path, double R, double t, double t_search, double window_end, StepStats& stats) const;

    // The first time after t the centre leaves the world box (t if it is outside already).
    double leave_time(const Trajectory& path, double t) const;

    // If the centre p (world) of a shot of radius R (m) lies behind the face of w.mesh_triangle of
    // solid component c at time t, moves p out to touch that face and sets w's point, normal and
    // surface motion: true.
    bool put_out_of_solid(std::size_t c, double R, double t, WallEvent& w, Vec3& p) const;

    // Each vibrating sonotrode's face (its exact vibrating plane): face(c) for component c, which
    // has_face(c).
    bool has_face(std::size_t c) const { return face_of_[c] >= 0; }
    const SonotrodeFace& face(std::size_t c) const { return faces_[static_cast<std::size_t>(face_of_[c])]; }
    // The mesh file's facet of a triangle of component c's mesh (impact records).
    int source_facet(std::size_t c, int mesh_triangle) const { return facets_[c][static_cast<std::size_t>(mesh_triangle)]; }
    double surface_speed(std::size_t c) const { return surface_speed_[c]; }  // m/s, fastest surface point of c
    double moving_part_speed() const { return moving_part_speed_; }          // m/s, of any moving part but the sonotrodes

private:
    // Moving-mesh contact by conservative advancement, with a per-call iteration budget.
    struct AdvancementResult {
        bool found = false;
        bool exhausted = false;       // out of iterations: nothing found up to searched_until
        double searched_until = 0.0;  // s
    };

    bool static_contact(int c, const Trajectory& path, double R, double t, double t_end, WallEvent& out, StepStats& stats) const;
    bool face_contact(int c, const Trajectory& path, double R, double t, double t_end, WallEvent& out, StepStats& stats) const;
    // Unit, world: the direction component c's face looks into the chamber (see the .cpp).
    static Vec3 face_direction(const Model& m, std::size_t c);
    AdvancementResult advance_to_contact(int c, const MeshCollider& collider, const std::vector<int>& facets, double surface_speed,
                                         const Trajectory& path, double R, double t, double t_end, WallEvent& out) const;
    // The search found nothing up to t and must go on from there: the event becomes a window end at t
    // if that comes before what `w` holds.
    static void resume_search_at(WallEvent& w, double t, int component, StepStats& stats);
    const TriangleMesh& collider_mesh(int c, const MeshCollider& collider) const;  // the mesh `collider` was built over
    // s, >= u: component `comp` (a turning part) cannot touch the shot before this time, from a
    // sweep of its path in the part's frame (turning_frame_path.h) from u, its radius grown by at
    // most `allowance` (m: less than the shot's clearance at u, or the sweep gains nothing); past
    // t_end if it cannot before then. u for any other kind of motion.
    double clear_until(const Component& comp, const MeshCollider& collider, const Trajectory& path, double R, double u, double t_end,
                       double allowance) const;

    std::shared_ptr<const Model> model_;
    SimTime epoch_;
    std::vector<int> face_of_;                // per component: index into faces_, -1: none
    std::vector<SonotrodeFace> faces_;        // one per vibrating sonotrode
    std::vector<double> face_phase_at_zero_;  // rad, per face: its phase at t = 0
    std::vector<std::vector<int>> facets_;    // per component: source facet per mesh triangle
    std::vector<double> surface_speed_;       // m/s, per component: fastest surface point
    double moving_part_speed_ = 0.0;          // m/s
};

}  // namespace peensim
