// The shot-position series for ParaView (scene `output.shot_positions`), written while the run goes:
//
//   DIR/paraview/shots.pvd                  the time series (open this one)
//   DIR/paraview/shots/shots_<k>.vtp        step k, at t_k = k * interval (k = 0, 1, ... up to the run's end)
//
// Each step holds one point per shot in the run (world frame, m) with the point arrays `shot`
// (Int64: its index, impacts.csv's `shot`), `v_mps` (velocity, 3 components, world frame),
// `speed_mps` and `shot_diameter_m`, and the field data `time_s` and, per moving component,
// `<name>_displacement_m` (a sonotrode's displacement along its axis) or `<name>_angle_rad` (a
// turning part's angle about its axis since t = 0, in [0, 2 pi)).
//
// Step k shows the state at exactly t_k: it asks the run to stop there (pause_at_s), which the
// event-driven schemes do without changing the run; time stepping passes t_k within its step, and
// the shot are moved back along their flight to t_k as the animation's frames are (a shot that
// bounced within that step is off by at most the step's travel, R/4).
//
// Reliability: each step file is written to `.tmp` and renamed (complete or absent; not fsynced:
// like animation frames, an fsync each would cost more than the step). The .pvd lists only steps
// already written and is rewritten atomically at most once a second of wall time, when the run is
// interrupted and when it ends. A resumed run starts at the first step after its checkpoint's
// time (steps are numbered by their time), rewriting any the interrupted session wrote after that
// checkpoint with the same bytes, so it ends with the files of an uninterrupted run. Memory: one
// step's file buffer; nothing accumulates.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/run_loop.h"
#include "model/model.h"

namespace peensim {

inline constexpr const char* kShotSeriesFileName = "shots.pvd";
inline constexpr double kPvdRewriteInterval_s = 1.0;  // s of wall time between rewrites of the .pvd

class ShotSeriesRecorder final : public RunListener {
public:
    // Writes the steps the state `now` has reached that are not before it (a fresh run: step 0; a
    // resumed run: a step at exactly its checkpoint's time), then the .pvd.
    ShotSeriesRecorder(const Model& model, const std::string& run_dir, double interval_s, const SimulationState& now);

    double pause_at_s() const override;
    void after_step(const Simulation& sim, const std::vector<ImpactRecord>& impacts) override;

    // Rewrites the .pvd with every step written so far (an interrupted run's last word).
    void flush();
    // Writes any step left at the run's end and the .pvd; returns a note for the user.
    std::string finish(const SimulationState& state);

    std::int64_t steps_written() const { return next_; }     // steps 0 .. steps_written() - 1 exist
    double write_seconds() const { return write_seconds_; }  // wall s spent writing steps and .pvd (this session)

private:
    double step_time(std::int64_t k) const { return static_cast<double>(k) * interval_s_; }
    void write_due(const SimulationState& state, double tolerance_s);
    void write_step(const SimulationState& state, std::int64_t k);

    const Model& model_;
    std::string dir_;          // DIR/paraview
    double interval_s_;        // s of simulated time between steps
    std::int64_t last_;        // the last step (its time is within the run)
    std::int64_t next_;        // the next step to write
    std::vector<int> moving_;  // indices of the components that move
    std::chrono::steady_clock::time_point pvd_written_;
    double write_seconds_ = 0.0;  // s of wall time
};

}  // namespace peensim
