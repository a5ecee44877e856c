// `peensim render-impacts OUTDIR`: stills of every logged component coloured by a per-triangle
// field of the run's analysis (impacts per mm2 per s, mean normal speed, coverage), each from
// four viewpoints tiled in one PNG with its colour bar: OUTDIR/analysis/<component>_map_<field>.png.
// The fields are the analysis' smoothed ones (`*_smoothed` columns: the same map whatever the
// tessellation), and every picture states their smoothing radius. The colour bar spans 0 to the
// value 98 % of the area stays under (higher values take the top colour); coverage's spans 0 to
// its maximum, in per cent, with the target coverage marked on it (or noted above the scale).
#pragma once

#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "app/render_module.h"
#include "common/vec.h"
#include "render/renderer.h"

namespace peensim {

// A field of <component>_triangles.csv that can be mapped.
struct MapField {
    std::string name;    // on the command line and in the file name: impacts, speed, coverage
    std::string column;  // in <component>_triangles.csv
    std::string title;   // on the colour bar
};
std::span<const MapField> map_fields();

// The four viewpoints of a map (view directions, world frame): front-above, back-above, from
// below (where the sonotrode is) and from the side.
struct MapView {
    std::string name;
    Vec3 direction;  // the camera looks along it
};
std::span<const MapView> map_views();

// The top of the coverage map's scale: the largest finite value (a fraction) rounded up to two
// significant digits, at most 1; 0.01 when nothing is covered.
double coverage_scale_top(const std::vector<double>& values);

// Per-triangle colours of `values` on [0, max]: NaN (no data, e.g. a mean speed without impacts)
// in neutral grey.
std::vector<render::Rgba8> field_colours(std::span<const double> values, double max);

int render_impacts_job(const RenderImpactsOptions& options, std::ostream& out, std::ostream& err);

}  // namespace peensim
