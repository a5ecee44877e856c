// A view close to a small highlighted area of a part (the analysis' picture of the slowest region
// and of the area out of reach put it in place of their last fixed view): the four fixed views
// frame the whole part, where an area of a few square millimetres (a root fillet, a spot out of
// reach) is a few pixels. Seen from outside along the area's mean facing, framing it and a margin
// around it.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/vec.h"
#include "model/model.h"

namespace peensim {

struct CloseUp {
    std::vector<Vec3> points_m;  // world: the corners of the area's bounds grown by the margin
    Vec3 direction;              // world, unit: the view's (into the area)
    std::string name;            // "close-up of <label>"
};

// An area larger than this share of the part's extent (its bounds' diagonal over the part's)
// shows in the fixed views; one that faces every way (its area-weighted mean normal shorter than
// kCloseUpFacing: a ring, a whole part) has no side to look from.
inline constexpr double kCloseUpExtent = 0.35;
inline constexpr double kCloseUpFacing = 0.3;
// The margin: a quarter of the area's extent on every side, at least a fortieth of the part's.
inline constexpr double kCloseUpMargin = 0.25;

// The close-up of the part's triangles weighted by `weight` (their share of the area, one per
// triangle), at the part's pose at time zero; nothing for no area, a large one, or one that faces
// every way.
std::optional<CloseUp> close_up_of(const Component& part, std::span<const double> weight, const std::string& label);

}  // namespace peensim
