// The rendering module (src/render/, built as libpeensim_render.so) is loaded only when a run
// renders or `render-impacts` is asked for: OSMesa brings LLVM, ~50 MB of memory the moment it is
// linked, which a run without pictures must not pay. This header is all the rest of peensim sees
// of it; it names no OpenGL type.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/impact_record.h"
#include "engine/simulation_state.h"
#include "model/assembly_checks.h"
#include "model/model.h"

namespace peensim {

// The animation of a run (render/frame_recorder.h has the details).
class FrameSink {
public:
    virtual ~FrameSink() = default;
    // After every step (and once before the first): draws the frames whose time has come.
    virtual void after_step(const SimulationState& state, std::span<const ImpactRecord> impacts, std::uint64_t logged_impacts) = 0;
    // The simulated time (s) of the next frame to draw (infinity: none left); the run pauses the
    // event-driven scheme there, so that the frame shows the state of that very moment.
    virtual double next_frame_s() const = 0;
    virtual void flush() = 0;                // waits for the frames being written
    virtual std::string finish_video() = 0;  // the MP4, and a note for the user
    virtual int frames_drawn() const = 0;
    virtual double draw_seconds() const = 0;  // wall s spent drawing
};

struct RenderImpactsOptions {
    std::string output_dir;
    std::vector<std::string> fields;  // impacts, speed, coverage; empty = all
    int width_px = 1600;              // whole image (2 x 2 views)
    int height_px = 1200;
    // The coverage marked on the coverage map's colour bar (0..1, `--target`); empty: the run's
    // analysis's target (analysis/figures.json), else 98 %.
    std::optional<double> coverage_target;
};

// `peensim render-regions`: the regions of the logged components, each in its own colour.
struct RenderRegionsOptions {
    std::string input;                   // a run directory, or a scene file
    std::vector<std::string> overrides;  // --set, for a scene file
    std::string output_dir;              // "" = the run's analysis/, or the current directory for a scene file
    int width_px = 1600;                 // whole image (2 x 2 views)
    int height_px = 1200;
};

// What the module exports (one C symbol returns it: peensim_render_module).
struct RenderModule {
    std::unique_ptr<FrameSink> (*make_recorder)(const Model& model, const RenderDesc& desc, const std::string& dir,
                                                const SimulationState& now);
    int (*render_impacts)(const RenderImpactsOptions& options, std::ostream& out, std::ostream& err);
    // `check --render`: the assembly at t = 0 with the placed shot, into a PNG (throws on failure).
    // `issues`: those naming a point (at_m) are marked there, numbered as the picture lists them.
    void (*draw_assembly)(const Model& model, const SimulationState& start, const std::vector<AssemblyIssue>& issues,
                          const std::string& png_path, int width_px, int height_px);
    int (*render_regions)(const RenderRegionsOptions& options, std::ostream& out, std::ostream& err);
    // The analysis' picture of one region of component `ci`: the triangles with weight[t] >= 0.5
    // highlighted and named `label`, the rest in grey, darkened by the share no shot reaches (reach);
    // 2 x 2 views with `title` (throws on failure).
    void (*draw_region_highlight)(const Model& model, std::size_t ci, std::span<const double> weight, std::span<const double> reach,
                                  const std::string& label, const std::string& title, const std::string& png_path, int width_px,
                                  int height_px);
};

// Loads the module on first use: $PEENSIM_RENDER_MODULE, else libpeensim_render.so next to the
// executable or one directory up (the tests' place in the build tree), else the library path.
// Throws std::runtime_error saying where it looked when it is not found.
const RenderModule& render_module();

}  // namespace peensim
