#include "contact/law_registry.h"

#include <stdexcept>

#include "contact/impulse_laws.h"

namespace peensim::contact {

std::vector<std::string> law_names() { return {"impulse"}; }

LawSet make_laws(std::string_view name) {
    if (name == "impulse")
        return {std::make_shared<ImpulseShotShotLaw>(), std::make_shared<ImpulseSurfaceLaw>()};
    throw std::invalid_argument("unknown contact law '" + std::string(name) + "' (known: impulse)");
}

}  // namespace peensim::contact
