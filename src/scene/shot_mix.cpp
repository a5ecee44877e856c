#include "scene/shot_mix.h"

#include <algorithm>
#include <cmath>

namespace peensim {

double sphere_mass_kg(double diameter_m, double density_kg_per_m3) { return density_kg_per_m3 * M_PI / 6.0 * std::pow(diameter_m, 3); }

std::vector<double> count_fractions(const ShotDesc& shot) {
    std::vector<double> share;
    share.reserve(shot.sizes.size());
    double sum = 0.0;
    for (const ShotSizeDesc& s : shot.sizes) {
        // By mass, w_k / D_k^3 (the density is common to the mix).
        share.push_back(shot.fractions_by_mass ? s.fraction / std::pow(s.diameter_m, 3) : s.fraction);
        sum += share.back();
    }
    for (double& f : share) f /= sum;
    return share;
}

double mean_shot_mass_kg(const ShotDesc& shot) {
    const std::vector<double> share = count_fractions(shot);
    double mass = 0.0;
    for (std::size_t k = 0; k < share.size(); ++k) mass += share[k] * sphere_mass_kg(shot.sizes[k].diameter_m, shot.density_kg_per_m3);
    return mass;
}

int size_for_draw(std::span<const double> count_fraction, double u) {
    double cumulative = 0.0;
    for (std::size_t k = 0; k + 1 < count_fraction.size(); ++k) {
        cumulative += count_fraction[k];
        if (u < cumulative) return static_cast<int>(k);
    }
    return static_cast<int>(count_fraction.size()) - 1;
}

double largest_diameter_m(const ShotDesc& shot) {
    double d = 0.0;
    for (const ShotSizeDesc& s : shot.sizes) d = std::max(d, s.diameter_m);
    return d;
}

double smallest_diameter_m(const ShotDesc& shot) {
    double d = shot.sizes.empty() ? 0.0 : shot.sizes.front().diameter_m;
    for (const ShotSizeDesc& s : shot.sizes) d = std::min(d, s.diameter_m);
    return d;
}

}  // namespace peensim
