// The viridis colour map: its endpoints, clamping, interpolation and degenerate inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "render/colour_map.h"

namespace peensim::render {
namespace {

TEST(RenderColourMap, EndpointsAreViridisDarkPurpleAndYellow) {
    const ColourMap map = ColourMap::viridis();
    EXPECT_EQ(map.map8(2.0, 2.0, 7.0), (Rgba8{0x44, 0x01, 0x54, 255}));
    EXPECT_EQ(map.map8(7.0, 2.0, 7.0), (Rgba8{0xFD, 0xE7, 0x25, 255}));
    EXPECT_EQ(map.map8(4.5, 2.0, 7.0), (Rgba8{0x21, 0x90, 0x8C, 255}));  // the middle stop
}

TEST(RenderColourMap, ValuesOutsideTheRangeAreClamped) {
    const ColourMap map = ColourMap::viridis();
    EXPECT_EQ(map.map8(-100.0, 0.0, 1.0), map.map8(0.0, 0.0, 1.0));
    EXPECT_EQ(map.map8(100.0, 0.0, 1.0), map.map8(1.0, 0.0, 1.0));
    EXPECT_EQ(map.map8(std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0), map.map8(0.0, 0.0, 1.0));
}

TEST(RenderColourMap, InterpolatesLinearlyBetweenStops) {
    const ColourMap map = ColourMap::viridis();
    const Rgba a = map.at_fraction(0.5), b = map.at_fraction(0.6), mid = map.at_fraction(0.55);
    EXPECT_NEAR(mid.r, 0.5f * (a.r + b.r), 1e-6);
    EXPECT_NEAR(mid.g, 0.5f * (a.g + b.g), 1e-6);
    EXPECT_NEAR(mid.b, 0.5f * (a.b + b.b), 1e-6);
    // viridis gets lighter all the way: green rises monotonically.
    float last = -1.0f;
    for (int i = 0; i <= 100; ++i) {
        const float g = map.at_fraction(i / 100.0).g;
        EXPECT_GT(g, last);
        last = g;
    }
}

TEST(RenderColourMap, DegenerateRangeSplitsAtTheValue) {
    const ColourMap map = ColourMap::viridis();
    EXPECT_EQ(map.map8(3.0, 3.0, 3.0), map.map8(1.0, 0.0, 1.0));
    EXPECT_EQ(map.map8(2.0, 3.0, 3.0), map.map8(0.0, 0.0, 1.0));
}

}  // namespace
}  // namespace peensim::render
