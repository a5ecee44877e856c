// The animation of a run (scene `render` block or `run --render`): frames taken at fixed
// simulated-time intervals while simulating, written as PNG by a second thread (so the
// simulation waits only for the drawing), and assembled into an MP4 by ffmpeg when the run ends.
// A run without rendering never constructs one, nor loads this module: it pays nothing.
//
// Frame k shows the state at t_k = start + k * slow_motion / fps exactly: the step that passes
// t_k is followed by drawing its shot moved back along their flight to t_k (a shot that bounced
// within that step is off by at most one step's travel, R/4) and the components at their poses
// at t_k. Impacts on logged components glow for kTrailFrames frames (the frame after them at full
// strength, then fading and shrinking: a short trail of the last frames' impacts), each a sprite
// of kGlowRadiusPerHeight x the image height in pixels whatever the zoom, its body coloured by
// normal speed (render/glow_layer.h), depth-tested kGlowLiftRadii shot radii in front of the
// contact point (the shot that made it, still there, does not hide it; a tooth in front does).
// Frames are numbered by k, so a resumed run continues the sequence.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "app/render_module.h"
#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "model/model.h"

namespace peensim {

inline constexpr int kTrailFrames = 8;                // frames an impact stays visible, fading
inline constexpr double kGlowRadiusPerHeight = 0.03;  // glow radius / image height (22 px at 720 px)
inline constexpr double kGlowLiftRadii = 2.5;         // a glow is lifted toward the eye by this many shot radii

class FrameRecorder final : public FrameSink {
public:
    // dir: where frames/ and animation.mp4 go. now: the state's time (a resumed run starts late).
    FrameRecorder(const Model& model, const RenderDesc& desc, const std::string& dir, const SimulationState& now);
    ~FrameRecorder() override;
    FrameRecorder(const FrameRecorder&) = delete;
    FrameRecorder& operator=(const FrameRecorder&) = delete;

    // After every step (and once before the first): remembers the step's impacts and draws every
    // frame whose time the state has reached. logged_impacts: the run's total so far.
    void after_step(const SimulationState& state, std::span<const ImpactRecord> impacts, std::uint64_t logged_impacts) override;
    double next_frame_s() const override;

    // Waits for the frames still being written. Throws what the writing thread threw.
    void flush() override;

    // Assembles frames/frame_*.png into animation.mp4 (flush first). Returns a note for the user:
    // what was written, or why there is no video (ffmpeg missing, `video: none`, no frame).
    std::string finish_video() override;

    int frames_drawn() const override { return frames_drawn_; }     // by this process (not before a resume)
    double draw_seconds() const override { return draw_seconds_; }  // wall s spent drawing (not writing)

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    int frames_drawn_ = 0;
    double draw_seconds_ = 0.0;
};

}  // namespace peensim
