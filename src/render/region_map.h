// Pictures of regions: `peensim render-regions` (every region of the logged components in its own
// colour, named where it faces the camera, with the facets no shot can reach in dark grey, so a
// region definition is checked by eye before or after a run), and the analysis' picture of one
// region (the slowest one, highlighted). Four views tiled, as the impact maps; a small highlighted
// area takes the last for its close-up (render/close_up.h).
#pragma once

#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "app/render_module.h"
#include "render/colour.h"

namespace peensim {

// The colour of region r in a region map: 12 distinct hues in turn (neighbouring sectors differ).
render::Rgba8 region_colour(std::size_t r);
inline constexpr render::Rgba8 kNoRegionColour{190, 190, 190, 255};  // in no region
inline constexpr render::Rgba8 kUnreachableColour{45, 45, 48, 255};  // out of the shot's reach
// An excluded region's colour: its own, dimmed toward grey.
render::Rgba8 excluded_colour(render::Rgba8 colour);

int render_regions_job(const RenderRegionsOptions& options, std::ostream& out, std::ostream& err);

void draw_region_highlight(const Model& model, std::size_t ci, std::span<const double> weight, std::span<const double> reach,
                           const std::string& label, const std::string& title, const std::string& png_path, int width_px, int height_px);

}  // namespace peensim
