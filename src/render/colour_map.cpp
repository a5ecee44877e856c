#include "render/colour_map.h"

#include <array>
#include <cmath>

namespace peensim::render {

namespace {

constexpr Rgba hex(unsigned rgb) {
    return {static_cast<float>((rgb >> 16) & 0xffu) / 255.0f, static_cast<float>((rgb >> 8) & 0xffu) / 255.0f,
            static_cast<float>(rgb & 0xffu) / 255.0f, 1.0f};
}

// viridis at fractions 0, 0.1, ..., 1.
constexpr std::array<Rgba, 11> kViridis = {hex(0x440154), hex(0x482576), hex(0x414487), hex(0x35608D), hex(0x2A788E), hex(0x21908C),
                                           hex(0x22A884), hex(0x43BF71), hex(0x7AD151), hex(0xBBDF27), hex(0xFDE725)};

}  // namespace

ColourMap ColourMap::viridis() { return ColourMap(kViridis); }

Rgba ColourMap::at_fraction(double fraction) const {
    if (!(fraction > 0.0)) return stops_.front();  // also NaN
    if (fraction >= 1.0) return stops_.back();
    const double x = fraction * static_cast<double>(stops_.size() - 1);
    const std::size_t i = static_cast<std::size_t>(x);
    const float w = static_cast<float>(x - static_cast<double>(i));
    const Rgba& a = stops_[i];
    const Rgba& b = stops_[i + 1];
    return {a.r + w * (b.r - a.r), a.g + w * (b.g - a.g), a.b + w * (b.b - a.b), 1.0f};
}

Rgba ColourMap::map(double value, double min, double max) const {
    if (!(max > min)) return value >= max ? stops_.back() : stops_.front();
    return at_fraction((value - min) / (max - min));
}

}  // namespace peensim::render
