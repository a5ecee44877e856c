// Maps scene names of contact laws to law instances, so that later laws (soft-sphere
// Hertz-Mindlin, impact-history restitution) plug in without touching the engine.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_law.h"

namespace peensim::contact {

struct LawSet {
    std::shared_ptr<const ShotShotLaw> shot_shot;
    std::shared_ptr<const SurfaceLaw> surface;
};

// Names a scene may use; the first is the default.
std::vector<std::string> law_names();

// Throws std::invalid_argument for an unknown name (the caller adds the scene location).
LawSet make_laws(std::string_view name);

}  // namespace peensim::contact
