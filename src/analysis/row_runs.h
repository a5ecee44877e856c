// A row of coverage samples (first + i step, i = 0 .. count - 1) cut into runs that lie in one
// cube of a grid (side 1 / inverse_side, corner at origin): binning a row run by run, with the
// crossings found in closed form, instead of sample by sample. The smoothing (surface_smoothing.h)
// and the coverage forecast (coverage_forecast.h) bin the coverage map's samples this way.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "common/vec.h"

namespace peensim {

// Calls f(i, run) for each run of samples i .. i + run - 1 in one cube, in order.
template <class F>
void for_each_cube_run(const Vec3& first, const Vec3& step, std::int64_t count, const Vec3& origin, double inverse_side, F&& f) {
    const Vec3 q0 = (first - origin) * inverse_side;  // cubes
    const Vec3 dq = step * inverse_side;              // cubes per sample
    for (std::int64_t i = 0; i < count;) {
        std::int64_t run = count - i;
        for (int k = 0; k < 3; ++k) {
            if (dq[k] == 0.0) continue;
            const double q = q0[k] + static_cast<double>(i) * dq[k];
            const double boundary = dq[k] > 0.0 ? std::floor(q) + 1.0 : std::floor(q);
            // The first sample past the boundary (at least the next one).
            const double steps = std::ceil((boundary - q) / dq[k]);
            run = std::min(run, std::max<std::int64_t>(1, static_cast<std::int64_t>(std::min(steps, 1e15))));
        }
        f(i, run);
        i += run;
    }
}

}  // namespace peensim
