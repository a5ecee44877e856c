// The one place contact laws are registered: their scene names, the parameters each declares for
// the pairs it serves, and how each is built for a pair. A scene selects a law per pair
// (`contacts.<pair>.law`); the engine only sees the built laws (contact_law.h).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_law.h"
#include "contact/law_parameters.h"

namespace peensim::contact {

// What a surface law may be built from besides its parameter values: the pair it serves.
struct SurfacePair {
    // Three corners per mesh triangle of the component, its own frame (m); built only for a law
    // that asks (the impulse law does not: a scene pays only for what it uses).
    std::function<std::vector<Vec3>()> triangle_corners_m;
    // m, the shot's diameter; for a mix its largest (each contact hands the law its own shot's
    // radius and mass: SurfaceContactInput).
    double shot_diameter_m = 0.0;
    double shot_density_kg_per_m3 = 0.0;    // kg/m3
    std::optional<double> yield_stress_pa;  // Pa, of the component's material, if the scene gives it
    std::string material;                   // the component's material (for messages)
    // E and nu of the component's and the shot's materials, where the scene gives both.
    std::optional<ElasticMaterial> surface_elastic;
    std::optional<ElasticMaterial> shot_elastic;
    std::string shot_material;  // the shot's material ("" if the scene gives only a density; for messages)
};

// What a shot-shot law may be built from besides its parameter values.
struct ShotShotPair {
    double shot_diameter_m = 0.0;         // m (for a mix its largest, as SurfacePair)
    double shot_density_kg_per_m3 = 0.0;  // kg/m3
    std::optional<ElasticMaterial> shot_elastic;
    std::string shot_material;
};

struct LawEntry {
    std::string_view name;
    std::string_view doc;
    std::span<const LawParameter> surface_parameters;    // for `shot-<material>` pairs
    std::span<const LawParameter> shot_shot_parameters;  // for `shot-shot`; empty: not a shot-shot law
    // Throw std::invalid_argument saying what the pair lacks (the caller adds the scene location).
    std::shared_ptr<const SurfaceLaw> (*make_surface)(const ParameterValues&, const SurfacePair&);
    std::shared_ptr<const ShotShotLaw> (*make_shot_shot)(const ParameterValues&, const ShotShotPair&);  // nullptr when not a shot-shot law
    bool soft_sphere = false;  // its laws offer soft() for every pair: the soft scheme can run it
};

// Every law, the default ("impulse") first.
std::span<const LawEntry> law_catalogue();

// The entry of a law name, or nullptr.
const LawEntry* find_law(std::string_view name);

// "impulse, impact-history, hertz-mindlin, linear-spring-dashpot".
std::string law_names_text();
// "'hertz-mindlin', 'linear-spring-dashpot'": the laws the soft scheme can run.
std::string soft_law_names_text();

}  // namespace peensim::contact
