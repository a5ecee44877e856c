// A shot mix in numbers: the share of the count each size has, the mean mass of one shot, and
// which size a random draw picks. Sieve analyses (SAE J444) and DEM tools give a mix by mass; the
// engine draws shot one at a time, so it needs shares of the count: a mass share w_k of shot of
// mass m_k is a count share proportional to w_k / m_k.
#pragma once

#include <span>
#include <vector>

#include "scene/scene_description.h"

namespace peensim {

// kg, one sphere of diameter d (m) and density rho (kg/m3).
double sphere_mass_kg(double diameter_m, double density_kg_per_m3);

// -, the share of the shot count of each of shot.sizes (summing to 1).
std::vector<double> count_fractions(const ShotDesc& shot);

// kg, the mean mass of one shot of the mix (what a mass flow divides by to give shot per second).
double mean_shot_mass_kg(const ShotDesc& shot);

// The size a uniform draw u in [0, 1) picks, given the count shares (the first size whose
// cumulative share exceeds u; the last for u rounding past the sum).
int size_for_draw(std::span<const double> count_fraction, double u);

// m, the largest and the smallest diameter of the mix.
double largest_diameter_m(const ShotDesc& shot);
double smallest_diameter_m(const ShotDesc& shot);

}  // namespace peensim
