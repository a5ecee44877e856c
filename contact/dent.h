// Dent left by one shot on the part: Johnson's sphere-on-plane estimate (reference eq. 10).
// Valid for normal impact speeds below ~100 m/s (fully plastic, no rate effects).
#pragma once

#include <cmath>
#include <stdexcept>

namespace peensim {

// Dent diameter (m): phi = D * (8 rho V^2 / (9 sigma_y))^(1/4).
//   shot_diameter_m          D, shot diameter (m)
//   shot_density_kg_per_m3   rho, shot density (kg/m^3)
//   normal_speed_m_per_s     V, normal approach speed (m/s); its sign is ignored (a speed)
//   yield_stress_pa          sigma_y, yield stress of the part's material (Pa)
// Throws std::invalid_argument for a non-positive diameter, density or yield stress: those are
// programming errors upstream (the scene checks its values), not something to round away.
inline double dent_diameter(double shot_diameter_m, double shot_density_kg_per_m3, double normal_speed_m_per_s, double yield_stress_pa) {
    if (!(shot_diameter_m > 0.0) || !(shot_density_kg_per_m3 > 0.0) || !(yield_stress_pa > 0.0))
        throw std::invalid_argument("dent_diameter: diameter, density and yield stress must be positive");
    const double v2 = normal_speed_m_per_s * normal_speed_m_per_s;  // m^2/s^2
    return shot_diameter_m * std::sqrt(std::sqrt(8.0 * shot_density_kg_per_m3 * v2 / (9.0 * yield_stress_pa)));
}

}  // namespace peensim
