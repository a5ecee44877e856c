// report.html's 3D views (output/part_view_html.h) of the logged parts: each part's mesh (thinned
// for display beyond kViewMaxTriangles, geometry/vertex_clustering.h) with its per-triangle
// fields, and the library the page inlines (Debian's libjs-three), read from where Debian installs it.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/analysis/analysis_report.h"
#include "app/component_analysis.h"
#include "output/part_view_html.h"

namespace peensim {

// Triangles a view shows at most: a finer part is thinned for display (its fields are those of the
// triangles kept), so that report.html stays light (~55 bytes a triangle shown) and turns smoothly.
inline constexpr std::size_t kViewMaxTriangles = 200'000;

// The view of one part (window: what the analysis took, for the rates and the target).
PartView part_view_of(const ComponentAnalysis& c, const AnalysisWindow& window);

// The 3D views of the parts with a coverage map or smoothed maps, keyed by their report.md marker lines
// (part_view_marker), the first carrying the scripts; names the parts in context.views, or says in
// context.view_note why there are none. `library_dir`: where three.min.js and
// examples/js/controls/OrbitControls.js are (Debian's /usr/share/javascript/three).
std::map<std::string, std::string> report_views(const std::vector<ComponentAnalysis>& parts, const AnalysisWindow& window,
                                                const std::string& library_dir, ReportContext& context);

inline constexpr const char* kThreeJsDir = "/usr/share/javascript/three";

// Where the pages' three.js is: PEENSIM_THREE_JS if set, else Debian's (kThreeJsDir).
inline std::string three_js_library_dir() {
    const char* dir = std::getenv("PEENSIM_THREE_JS");
    return dir != nullptr ? dir : kThreeJsDir;
}

// The scripts a page of views needs (part_view_scripts), from library_dir; empty when its files
// are not there.
std::optional<std::string> view_scripts(const std::string& library_dir);

// The sentence a report gives for views it could not draw: what to install.
std::string no_view_library_note(const std::string& library_dir);

}  // namespace peensim
