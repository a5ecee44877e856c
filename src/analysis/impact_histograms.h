// Distributions of a set of impacts (a component, or one of its regions): normal impact speed,
// impact angle from the surface normal and dent diameter. Fixed bin widths, bins added as larger
// values arrive: a few kilobytes whatever the number of impacts.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace peensim {

inline constexpr double kSpeedBinWidth = 0.25;  // m/s
inline constexpr double kAngleBinWidth = 5.0;   // degrees
inline constexpr double kDentBinWidth = 10e-6;  // m

// Counts of values in [b w, (b + 1) w) for b = 0, 1, ...; negative or non-finite values are ignored.
struct Histogram {
    double width = 1.0;
    std::vector<std::uint64_t> bins;

    void add(double v) {
        if (!(v >= 0.0) || !std::isfinite(v)) return;
        const auto b = static_cast<std::size_t>(v / width);
        if (b >= bins.size()) bins.resize(b + 1, 0);
        ++bins[b];
    }
};

struct ImpactHistograms {
    Histogram normal_speed{kSpeedBinWidth, {}};  // m/s
    Histogram angle{kAngleBinWidth, {}};         // degrees from the normal
    Histogram dent{kDentBinWidth, {}};           // m (empty without a yield stress)

    // vn, vt: normal and tangential approach speeds (m/s); dent_m: dent diameter, or NaN for none.
    void add(double vn_m_per_s, double vt_m_per_s, double dent_m) {
        normal_speed.add(vn_m_per_s);
        angle.add(std::atan2(vt_m_per_s, vn_m_per_s) * 180.0 / M_PI);
        dent.add(dent_m);
    }
};

}  // namespace peensim
