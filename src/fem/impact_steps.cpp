#include "fem/impact_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace peensim {

std::vector<std::vector<int>> group_impacts(const std::vector<PatchImpact>& impacts, const GroupingRule& rule) {
    std::vector<std::vector<int>> groups;
    for (std::size_t i = 0; i < impacts.size(); ++i) {
        const PatchImpact& a = impacts[i];
        bool fits = !groups.empty() && a.time_s - impacts[static_cast<std::size_t>(groups.back().front())].time_s <= rule.window_s;
        if (fits)
            for (int j : groups.back()) {
                const PatchImpact& b = impacts[static_cast<std::size_t>(j)];
                const double apart = rule.separation_dent_diameters * std::max(a.dent_diameter_m, b.dent_diameter_m);
                if ((a.point_m - b.point_m).norm() <= apart) {
                    fits = false;
                    break;
                }
            }
        if (fits)
            groups.back().push_back(static_cast<int>(i));
        else
            groups.push_back({static_cast<int>(i)});
    }
    return groups;
}

double hertz_contact_time(double radius_m, double mass_kg, double effective_modulus_pa, double normal_speed_m_per_s) {
    return 2.87 * std::pow(mass_kg * mass_kg / (radius_m * effective_modulus_pa * effective_modulus_pa * normal_speed_m_per_s), 0.2);
}

void plan_steps(FemDeck& deck, const std::vector<PatchImpact>& impacts, const std::vector<std::vector<int>>& groups, double shot_radius_m,
                const StepTiming& timing) {
    const double mass = deck.shot.density_kg_per_m3 * 4.0 / 3.0 * M_PI * std::pow(shot_radius_m, 3);
    const double e_star = 1.0 / ((1.0 - deck.target.poisson_ratio * deck.target.poisson_ratio) / deck.target.youngs_modulus_pa +
                                 (1.0 - deck.shot.poisson_ratio * deck.shot.poisson_ratio) / deck.shot.youngs_modulus_pa);
    const double gap = timing.gap_radii * shot_radius_m;
    deck.shots.clear();
    deck.steps.clear();
    double step_start = 0.0;  // s, model time
    for (std::size_t g = 0; g < groups.size(); ++g) {
        FemStep step;
        double longest = 0.0, shortest_contact = std::numeric_limits<double>::infinity();
        for (int i : groups[g]) {
            const PatchImpact& im = impacts[static_cast<std::size_t>(i)];
            const double vn = -im.velocity_m_per_s.z();
            if (!(vn > 0.0)) throw std::invalid_argument("plan_steps: impact " + std::to_string(i + 1) + " does not approach the surface");
            const double speed = im.velocity_m_per_s.norm();
            const double t_contact = hertz_contact_time(shot_radius_m, mass, e_star, vn);
            longest = std::max(longest, gap / vn + timing.contact_times * t_contact);
            shortest_contact = std::min(shortest_contact, t_contact);
            // Touching at the impact point: centre one radius above it. Back along the velocity by
            // the gap's flight and by the time until the step starts.
            const Vec3 touch = im.point_m + Vec3(0.0, 0.0, shot_radius_m);
            const Vec3 dir = im.velocity_m_per_s / speed;
            const double back = gap / (-dir.z()) + speed * step_start;
            step.shots.push_back(static_cast<int>(deck.shots.size()));
            deck.shots.push_back({touch - back * dir, im.velocity_m_per_s, static_cast<int>(g), i});
        }
        step.duration_s = longest;
        step.max_increment_s = shortest_contact / timing.increments_per_contact;
        step.initial_increment_s = 0.5 * step.max_increment_s;
        deck.steps.push_back(step);
        step_start += longest;
    }
}

}  // namespace peensim
