// What a time-of-impact query found, shared by the shot-triangle, shot-shot and shot-mesh kernels,
// and the one tolerance that decides how the state at the start of the interval is read.
#pragma once

namespace peensim {

enum class ToiStatus : unsigned char {
    miss,         // no approaching contact in the interval
    impact,       // the earliest approaching (or grazing) contact
    overlapping,  // already interpenetrating at the start: not a new impact, an error to resolve
};

// At the start of an interval, a gap within +-kStartTouchFraction times the contact distance (R
// for a triangle, R1 + R2 for a pair) is a touch, decided by the approach sign (an impact now, or
// nothing until a later return), and a gap below that is an overlap. The engine leaves a bounce
// with a gap of about an ulp (the prototype measured |gap| <= 1.4e-15 m), far below this band
// (1e-12 m for R = 1 mm), which is itself far below any physical overlap.
constexpr double kStartTouchFraction = 1e-9;

}  // namespace peensim
