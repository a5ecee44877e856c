// The one place that knows every kind of shot source: a scene's `sources[]` entry into its
// ShotSource. Everything after it (the schemes, the checks, the summary, the analysis, ParaView)
// sees only the ShotSource interface and its outline.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "model/shot_flow.h"
#include "scene/scene_description.h"

namespace peensim {

// `index`: the source's place in the scene; `stop_s`: its stop, capped at the run's end; `seed`
// the scene's; `size_count_fraction` the mix's count shares (empty for one size).
std::shared_ptr<const ShotSource> make_source(const SourceDesc& d, int index, double stop_s, std::uint64_t seed,
                                              const std::vector<double>& size_count_fraction);

}  // namespace peensim
