// Where the words placed in a frame go so that no two overlap, nor cover the text block at the top
// left: each label keeps its spot when it is free, else takes the nearest free one among shifts
// up and down by up to kLabelShifts line heights (then the same shifts half a width left and
// right); a label that finds none is left out (the region maps draw four views, so a region
// crowded out of one is named in another). Plain geometry, no GL, so a test can check it.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "render/scene_types.h"

namespace peensim::render {

inline constexpr int kLabelShifts = 4;

struct LabelBox {
    float left = 0, top = 0, right = 0, bottom = 0;  // px
    bool overlaps(const LabelBox& o) const { return left < o.right && o.left < right && top < o.bottom && o.top < bottom; }
};

struct LabelMetrics {
    std::function<float(const std::string&)> text_width;  // px
    float ascender = 0;                                   // px, baseline to the top of tall glyphs
    float line_height = 0;                                // px, baseline to baseline
};

// The box a label's text covers (with a pixel of room about it), its centre at x, baseline at y.
LabelBox label_box(const Label& label, const LabelMetrics& m);

// taken: boxes already covered (the text block). The labels in their order, moved or left out.
std::vector<Label> lay_out_labels(std::span<const Label> labels, const LabelMetrics& metrics, int width_px, int height_px,
                                  std::vector<LabelBox> taken = {});

}  // namespace peensim::render
