// Labels never overlap (render/label_layout.h): twenty names on one spot (a crowded region map),
// names near the text block, near the frame's edge; a free label stays where it was put.
#include <gtest/gtest.h>

#include "render/label_layout.h"

namespace peensim::render {
namespace {

// A monospace stand-in for the font: 8 px a character, 14 px ascender, 18 px lines.
const LabelMetrics kMetrics{[](const std::string& t) { return 8.0f * static_cast<float>(t.size()); }, 14.0f, 18.0f};

void expect_no_overlap(const std::vector<Label>& placed, const std::vector<LabelBox>& taken, int w, int h) {
    for (std::size_t i = 0; i < placed.size(); ++i) {
        const LabelBox b = label_box(placed[i], kMetrics);
        EXPECT_GE(b.left, 0.0f);
        EXPECT_GE(b.top, 0.0f);
        EXPECT_LE(b.right, static_cast<float>(w));
        EXPECT_LE(b.bottom, static_cast<float>(h));
        for (const LabelBox& t : taken) EXPECT_FALSE(b.overlaps(t)) << placed[i].text << " over the text block";
        for (std::size_t j = i + 1; j < placed.size(); ++j)
            EXPECT_FALSE(b.overlaps(label_box(placed[j], kMetrics))) << placed[i].text << " over " << placed[j].text;
    }
}

TEST(LabelLayout, AFreeLabelStaysWhereItWasPut) {
    const std::vector<Label> one{{400.0f, 300.0f, "tooth-3", {}}};
    const std::vector<Label> placed = lay_out_labels(one, kMetrics, 800, 600);
    ASSERT_EQ(placed.size(), 1u);
    EXPECT_EQ(placed[0].x_px, 400.0f);
    EXPECT_EQ(placed[0].y_px, 300.0f);
}

TEST(LabelLayout, CrowdedLabelsMoveApartOrAreLeftOutButNeverOverlap) {
    std::vector<Label> crowd;
    for (int i = 0; i < 20; ++i) crowd.push_back({400.0f + 3.0f * i, 300.0f + 2.0f * i, "tooth-" + std::to_string(i), {}});
    const std::vector<LabelBox> text_block{{0.0f, 0.0f, 300.0f, 80.0f}};
    const std::vector<Label> placed = lay_out_labels(crowd, kMetrics, 800, 600, text_block);
    expect_no_overlap(placed, text_block, 800, 600);
    // Nine heights up and down and three columns hold far more than one: most are kept.
    EXPECT_GE(placed.size(), 10u);
    EXPECT_EQ(placed.front().text, "tooth-0");  // the first keeps its place
    EXPECT_EQ(placed.front().x_px, 400.0f);

    // Under the text block and at the frame's edges.
    const std::vector<Label> edges{{20.0f, 20.0f, "end-plus-y", {}}, {795.0f, 300.0f, "sector-3", {}}, {400.0f, 599.0f, "bore", {}}};
    const std::vector<Label> kept = lay_out_labels(edges, kMetrics, 800, 600, text_block);
    expect_no_overlap(kept, text_block, 800, 600);
}

}  // namespace
}  // namespace peensim::render
