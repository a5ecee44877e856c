// A sweep's variants side by side in one 3D view (output/part_view_html.h), for sweep/report.html:
// the compared part of each variant, left to right in the variants' order, on one colour bar per
// field. Per triangle, the mean over the variant's analysed runs (its seeds) of their
// <part>_triangles.csv: coverage, impact density and mean normal speed (both smoothed), and the
// region. Each variant's mesh is its own run's (a variant may change the part).
#pragma once

#include <map>
#include <string>

#include "app/sweep/sweep_plan.h"

namespace peensim {

// The line of sweep/report.md that sweep/report.html replaces by the view.
inline constexpr const char* kSweepViewMarker = "<!-- 3D view: variants -->";

// The view's block keyed by kSweepViewMarker (with the page's scripts), or no block and `note`
// saying why (no variant analysed, or no library in library_dir). target: the coverage target
// (0..1], marked on the coverage's colour bar.
std::map<std::string, std::string> sweep_views(const SweepPlan& plan, const std::string& component, double target,
                                               const std::string& library_dir, std::string& note);

}  // namespace peensim
