// A perceptual colour map (value -> colour), for impact speeds, impact counts per triangle and
// the colour bar that explains them.
#pragma once

#include <span>

#include "render/colour.h"

namespace peensim::render {

// A piecewise-linear map through evenly spaced stops (stop 0 at fraction 0, the last at 1),
// interpolated in sRGB. Immutable; cheap to copy (it views a static table).
class ColourMap {
public:
    // Matplotlib's viridis (perceptually uniform, readable in grey and by colour-blind viewers),
    // sampled at 11 evenly spaced points. Between the samples viridis is close to a straight
    // line in sRGB, so 11 stops stay within about 2/255 of the full 256-entry table.
    static ColourMap viridis();

    // Colour at `fraction` of the range; fractions outside [0, 1] are clamped, NaN gives stop 0.
    Rgba at_fraction(double fraction) const;

    // Colour of `value` on the range [min, max] (clamped; NaN gives stop 0). A degenerate range
    // (max <= min) maps values >= max to the last stop and the others to the first.
    Rgba map(double value, double min, double max) const;
    Rgba8 map8(double value, double min, double max) const { return to_rgba8(map(value, min, max)); }

    std::span<const Rgba> stops() const { return stops_; }

private:
    explicit ColourMap(std::span<const Rgba> stops) : stops_(stops) {}
    std::span<const Rgba> stops_;
};

}  // namespace peensim::render
