#include "contact/law_registry.h"

#include <array>
#include <stdexcept>

#include "contact/hertz_mindlin_law.h"
#include "contact/impact_history_law.h"
#include "contact/impulse_laws.h"
#include "contact/linear_spring_dashpot_law.h"

namespace peensim::contact {

namespace {

std::shared_ptr<const SurfaceLaw> make_impulse_surface(const ParameterValues& v, const SurfacePair&) {
    return std::make_shared<ImpulseSurfaceLaw>(impulse_coefficients(v));
}

std::shared_ptr<const ShotShotLaw> make_impulse_shot_shot(const ParameterValues& v, const ShotShotPair&) {
    return std::make_shared<ImpulseShotShotLaw>(impulse_coefficients(v));
}

std::shared_ptr<const SurfaceLaw> make_impact_history(const ParameterValues& v, const SurfacePair& pair) {
    const double influence_distance_m = v.scalar("influence_distance");
    if (influence_distance_m == 0.0 && !pair.yield_stress_pa)
        throw std::invalid_argument(
            "law 'impact-history' sizes its marks by the dent diameter (eq. 10), which needs the yield "
            "stress of material '" +
            pair.material + "': add materials." + pair.material + ".yield_stress, or give the pair an influence_distance");
    ImpactHistoryGeometry g;
    g.corners_m = pair.triangle_corners_m();
    g.shot_diameter_m = pair.shot_diameter_m;
    g.shot_density_kg_per_m3 = pair.shot_density_kg_per_m3;
    g.yield_stress_pa = pair.yield_stress_pa.value_or(0.0);
    return std::make_shared<ImpactHistoryLaw>(v.list("restitution_by_hits"), v.scalar("mu"), v.scalar("f"), influence_distance_m, g);
}

const std::array kCatalogue{
    LawEntry{"impulse",
             "Rigid-sphere impulses (reference eq. 2-5): restitution C0 below V0, C0 (V/V0)^-1/4 above; tangential "
             "restitution mu; Coulomb friction f in sustained contact.",
             impulse_parameters(), impulse_parameters().first(2), make_impulse_surface, make_impulse_shot_shot},
    LawEntry{"impact-history",
             "Impact-history restitution (reference section 4): each impact marks the triangles within one dent "
             "diameter (eq. 10) of its point, or within influence_distance; the next impact there rebounds with "
             "restitution_by_hits[marks], its tangential part as the impulse law's (mu, 0.71 by default: the 5/7 "
             "a gripping sphere keeps, as hertz-mindlin's rigid limit). For `shot-<material>` pairs whose material "
             "has a yield stress (or with influence_distance).",
             impact_history_parameters(),
             {},
             make_impact_history,
             nullptr},
    LawEntry{"hertz-mindlin",
             "Soft-sphere contact (reference section 4, as LIGGGHTS and EDEM): Hertz normal force, Mindlin "
             "tangential spring with Coulomb's cap f, both damped from the restitution e (e falls as (V/V0)^-1/4 "
             "above V0 = plastic_speed when it is > 0). Needs `youngs_modulus` and `poisson_ratio` of the shot's and the surface's "
             "materials. The soft scheme integrates it; the rigid schemes take its instantaneous limit (normal "
             "restitution e, the tangential impulse of a sphere that grips: 5/7 of the slip, or Coulomb-limited).",
             hertz_mindlin_parameters(), hertz_mindlin_parameters(), make_hertz_mindlin_surface, make_hertz_mindlin_shot_shot, true},
    LawEntry{"linear-spring-dashpot",
             "Soft-sphere contact with constant stiffnesses (LIGGGHTS's `model hooke` with `tangential history`, EDEM's "
             "linear spring): normal spring k_n from the materials' E and nu at characteristic_speed (the spring whose "
             "greatest overlap at that speed is Hertz's), tangential spring tangential_ratio k_n with Coulomb's cap f, "
             "dampers from the restitution e (the same e at every speed). Needs `youngs_modulus` and `poisson_ratio` of the "
             "shot's and the surface's materials. The soft scheme integrates it; the rigid schemes take its instantaneous "
             "limit (as hertz-mindlin's).",
             linear_spring_dashpot_parameters(), linear_spring_dashpot_parameters(), make_linear_spring_dashpot_surface,
             make_linear_spring_dashpot_shot_shot, true},
};

}  // namespace

std::span<const LawEntry> law_catalogue() { return kCatalogue; }

const LawEntry* find_law(std::string_view name) {
    for (const LawEntry& e : kCatalogue)
        if (e.name == name) return &e;
    return nullptr;
}

std::string soft_law_names_text() {
    std::string out;
    for (const LawEntry& e : kCatalogue)
        if (e.soft_sphere) out += (out.empty() ? "'" : ", '") + std::string(e.name) + "'";
    return out;
}

std::string law_names_text() {
    std::string out;
    for (const LawEntry& e : kCatalogue) out += (out.empty() ? "" : ", ") + std::string(e.name);
    return out;
}

}  // namespace peensim::contact
