// report.html's interactive 3D view of a logged part: its triangles coloured by a field the reader
// chooses (coverage, impact density, mean normal speed, the region's time to the target, the
// region), a colour bar with the target marked, and what a click on the part finds there. The
// page stays one file that opens offline: three.js and its OrbitControls (Debian's libjs-three) are
// inlined once per page, each part's mesh and fields as base64 typed arrays in a JSON block.
// Pure text building: no file I/O (the caller reads the library's files).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace peensim {

// One colouring of the part: a value per triangle shown (NaN: none).
struct PartViewField {
    std::string name;   // machine name (the triangles CSV's column it comes from)
    std::string label;  // what the reader sees, unit included
    std::string unit;   // printed after a value ("" for none)
    std::vector<float> values;
    double lo = 0.0, hi = 1.0;     // the colour bar's ends, in the field's unit
    std::optional<double> target;  // marked on the colour bar
    int digits = 3;                // decimals of a value read by a click
    bool categorical = false;      // a region index (-1: none), coloured by category
    bool clipped = false;          // values above hi exist (drawn in the top colour; the bar says >=)
    std::string grey;              // what a grey triangle means ("": no value)
};

// A field's colour bar from its finite values: lo their least (0 when from_zero), hi their 99th
// percentile (one hot triangle would wash the rest out; clipped says when some lie above).
// Returns false when no value is finite: the field has nothing to show.
bool set_colour_range(PartViewField& field, bool from_zero);

struct PartViewRegion {
    std::string name;
    std::string forecast;  // its time to the target, as the report gives it ("" for none)
};

struct PartView {
    std::string name;
    std::vector<float> positions_mm;     // mm, x y z per vertex (component frame)
    std::vector<std::uint32_t> indices;  // 3 per triangle shown
    std::vector<std::uint32_t> source;   // per triangle shown: the part's triangle
    std::vector<PartViewField> fields;
    std::vector<PartViewRegion> regions;
    // Several copies of the part side by side (a sweep's variants, left to right): their names, and
    // per triangle shown the copy it belongs to. Empty: one part.
    std::vector<std::string> instances;
    std::vector<std::uint32_t> instance;
    std::vector<float> offsets_mm;  // mm, per copy: its shift along x
    std::size_t shown = 0;          // the field drawn first
    std::string note;               // under the view: what it shows (e.g. "3,120 of 500,480 triangles")
};

// The scripts every view of a page needs, once, before the first view: the library's sources as
// given (three.min.js, then OrbitControls.js) and the viewer's own code.
std::string part_view_scripts(const std::string& three_js, const std::string& orbit_controls_js);

// One part's view: a canvas, the field chooser, the colour bar and the info line.
std::string part_view_html(const PartView& view);

}  // namespace peensim
