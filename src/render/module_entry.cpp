// The entry point of libpeensim_render.so (see app/render_module.h): the frame recorder and the
// impact maps, the region maps and the assembly picture, handed to a peensim that loaded this module on demand.
#include "app/render_module.h"
#include "render/assembly_picture.h"
#include "render/frame_recorder.h"
#include "render/region_map.h"
#include "render/render_impacts_job.h"

namespace {

std::unique_ptr<peensim::FrameSink> make_recorder(const peensim::Model& model, const peensim::RenderDesc& desc, const std::string& dir,
                                                  const peensim::SimulationState& now) {
    return std::make_unique<peensim::FrameRecorder>(model, desc, dir, now);
}

const peensim::RenderModule kModule{&make_recorder, &peensim::render_impacts_job, &peensim::draw_assembly_picture,
                                    &peensim::render_regions_job, &peensim::draw_region_highlight};

}  // namespace

extern "C" __attribute__((visibility("default"))) const peensim::RenderModule* peensim_render_module() { return &kModule; }
