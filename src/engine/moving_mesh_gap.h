// The true gap between a shot and a rotating component within one time step, for finding when the
// shot first touched it. A turning mesh is not a plane moving with one velocity: within a step its
// facets turn (1.5 deg in a quarter-radius step at 1000 rpm on a 5 mm cylinder, half a facet of a
// 128-facet one), so the feature closest at the step end need not be the one first touched, and a
// gap that is quadratic in time only for a plane in translation has its root in the wrong place.
// Here the gap at a trial time is measured exactly: the shot's centre on its free-flight arc, taken
// into the component's frame at its closed-form pose at that very time, and its exact distance to
// the mesh from the BVH, minus R. The contact found at the touch time gives the normal, point and
// triangle actually touched.
#pragma once

#include <cstdint>

#include "common/sim_time.h"
#include "engine/step_stats.h"
#include "model/model.h"

namespace peensim {

// A shot's free flight within a step, known by its state at the step end (offset dt, s).
struct StepArc {
    Vec3 p_end;  // m, world, centre at the step end
    Vec3 v_end;  // m/s, world, velocity at the step end
    Vec3 g;      // m/s2, gravity
    double dt;   // s, the step

    Vec3 centre(double u) const {
        const double back = dt - u;
        return p_end - v_end * back + 0.5 * g * back * back;
    }
    Vec3 velocity(double u) const { return v_end - g * (dt - u); }
};

class MovingMeshGap {
public:
    // `u_from` (s): the earliest offset the gap is asked for (the shot's latest contact in the step).
    MovingMeshGap(const Component& component, const SimTime& step_start, const StepArc& arc, double radius_m, double u_from,
                  StepStats& stats);

    // Gap (m) at offset u (s) from the step start: distance from the shot's centre to the mesh, the
    // mesh in its pose at that time, minus R (< 0: overlap). Exact within the reach of a step's
    // relative travel; beyond it a lower bound (positive), which is all a root search needs there.
    double operator()(double u) const;

    // Longest time (s) between gap samples: the shot closes in on the surface by at most an eighth
    // of R in it (own speed plus the frame's turn at its distance from the axis), so only a graze
    // shallower than that can fall between two samples.
    double sample_interval() const { return sample_interval_s_; }

    struct Touch {
        Vec3 normal;        // unit, world, from the surface towards the shot centre
        Vec3 point;         // m, world, the closest point of the surface (the contact point)
        int mesh_triangle;  // index into the component's TriangleMesh
    };
    // The contact at offset u (a touch time the root search returned).
    Touch touch_at(double u) const;

private:
    const Component& component_;
    SimTime t0_;
    StepArc arc_;
    double radius_m_;
    double reach_m_;            // m, how far from the centre the exact distance is looked for
    double sample_interval_s_;  // s
    StepStats& stats_;
};

}  // namespace peensim
