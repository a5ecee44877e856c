#include "contact/impact_history_law.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "contact/dent.h"
#include "contact/impulse_laws.h"

namespace peensim::contact {

namespace {

const std::array<LawParameter, 4> kImpactHistoryParameters{
    LawParameter{"restitution_by_hits", Dimension::dimensionless, "", open_closed(0, 1), true,
                 "Normal restitution of an impact on a spot hit 0, 1, 2, ... times before (a table; the last "
                 "value holds for every later hit). Law `impact-history` only."},
    impulse_parameters()[2],  // mu
    impulse_parameters()[3],  // f
    LawParameter{"influence_distance", Dimension::length, "0", at_least(0), false,
                 "An impact marks the triangles within this distance of its point (the DEM-FEM study: one shot diameter); "
                 "0: the impact's own dent diameter (eq. 10). Law `impact-history` only."},
};

}  // namespace

std::span<const LawParameter> impact_history_parameters() { return kImpactHistoryParameters; }

ImpactHistoryLaw::ImpactHistoryLaw(std::vector<double> restitution_by_hits, double mu, double f, double influence_distance_m,
                                   const ImpactHistoryGeometry& g)
    : restitution_by_hits_(std::move(restitution_by_hits)),
      mu_(mu),
      f_(f),
      influence_distance_m_(influence_distance_m),
      shot_density_kg_per_m3_(g.shot_density_kg_per_m3),
      yield_stress_pa_(g.yield_stress_pa),
      // Dents (and the study's reach, one shot diameter) are of the order of the shot diameter (the
      // mix's largest): a cell that size keeps the scan to a few cells.
      facets_(g.corners_m, influence_distance_m > 0.0 ? std::max(influence_distance_m, g.shot_diameter_m) : g.shot_diameter_m) {
    if (restitution_by_hits_.empty()) throw std::invalid_argument("impact-history: an empty restitution table");
}

double ImpactHistoryLaw::restitution_after(double hits) const {
    const auto last = static_cast<double>(restitution_by_hits_.size() - 1);
    return restitution_by_hits_[static_cast<std::size_t>(std::min(std::max(hits, 0.0), last))];
}

SurfaceContactResponse ImpactHistoryLaw::impact(const SurfaceContactInput& in, std::span<double> marks) const {
    const auto t = static_cast<std::size_t>(in.triangle);
    const double C = restitution_after(t < marks.size() ? marks[t] : 0.0);
    const SurfaceContactResponse r = impulse_surface_rebound(in, C, mu_);
    if (in.impact && r.approaching && !marks.empty()) {
        // The impact work-hardens the surface within one dent diameter of its centre (eq. 10, this
        // shot's own size), or within the scene's fixed reach (the study's: one shot diameter).
        const double reach = influence_distance_m_ > 0.0
                                 ? influence_distance_m_
                                 : dent_diameter(2.0 * in.shot_radius_m, shot_density_kg_per_m3_, r.vn_in, yield_stress_pa_);
        facets_.for_each_within(in.point_local, reach, [&](std::size_t k) { marks[k] += 1.0; });
    }
    return r;
}

std::string ImpactHistoryLaw::describe_state(std::span<const double> marks) const {
    std::size_t hit = 0;
    double most = 0.0, fewest = std::numeric_limits<double>::infinity();
    for (double m : marks) {
        hit += m > 0.0;
        most = std::max(most, m);
        fewest = std::min(fewest, m);
    }
    if (marks.empty()) return "";
    char text[200];
    std::snprintf(text, sizeof text, "%zu of %zu triangles hit, up to %.0f times (next restitution there %.3g-%.3g)", hit, marks.size(),
                  most, restitution_after(fewest), restitution_after(most));
    return text;
}

SurfaceContactResponse ImpactHistoryLaw::sustain(const SurfaceContactInput& in, std::span<double>) const {
    return impulse_surface_sustain(in, f_);
}

}  // namespace peensim::contact
