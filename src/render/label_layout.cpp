#include "render/label_layout.h"

#include <algorithm>
#include <cmath>

namespace peensim::render {

namespace {
constexpr float kRoomPx = 1.0f;  // px kept free about each label (its shadow is 1 px down and right)
}

LabelBox label_box(const Label& label, const LabelMetrics& m) {
    const float w = m.text_width(label.text);
    const float descent = m.line_height - m.ascender;
    return {label.x_px - 0.5f * w - kRoomPx, label.y_px - m.ascender - kRoomPx, label.x_px + 0.5f * w + kRoomPx + 1.0f,
            label.y_px + std::max(descent, 0.0f) + kRoomPx + 1.0f};
}

std::vector<Label> lay_out_labels(std::span<const Label> labels, const LabelMetrics& metrics, int width_px, int height_px,
                                  std::vector<LabelBox> taken) {
    std::vector<Label> placed;
    const LabelBox frame{0.0f, 0.0f, static_cast<float>(width_px), static_cast<float>(height_px)};
    const auto inside = [&](const LabelBox& b) {
        return b.left >= frame.left && b.top >= frame.top && b.right <= frame.right && b.bottom <= frame.bottom;
    };
    const auto free = [&](const LabelBox& b) {
        return inside(b) && std::none_of(taken.begin(), taken.end(), [&](const LabelBox& t) { return t.overlaps(b); });
    };
    for (const Label& label : labels) {
        const float half_width = 0.5f * metrics.text_width(label.text);
        // Candidates nearest first: in place, then k line heights down and up, then half a width aside.
        bool done = false;
        for (int side = 0; side < 3 && !done; ++side) {
            const float dx = side == 0 ? 0.0f : (side == 1 ? -half_width : half_width);
            for (int k = 0; k <= kLabelShifts && !done; ++k)
                for (int sign : {1, -1}) {
                    if (k == 0 && sign < 0) continue;
                    Label moved = label;
                    moved.x_px += dx;
                    moved.y_px += static_cast<float>(sign * k) * metrics.line_height;
                    const LabelBox box = label_box(moved, metrics);
                    if (!free(box)) continue;
                    taken.push_back(box);
                    placed.push_back(std::move(moved));
                    done = true;
                    break;
                }
        }
    }
    return placed;
}

}  // namespace peensim::render
