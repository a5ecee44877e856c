// The one place that knows every scheme (engine/stepper.h).
#include "engine/event/event_stepping.h"
#include "engine/soft/soft_stepping.h"
#include "engine/stepper.h"
#include "engine/time_stepping.h"

namespace peensim {

std::unique_ptr<Stepper> make_stepper(const std::shared_ptr<const Model>& model) {
    switch (model->scheme) {
        case SteppingScheme::step: return std::make_unique<TimeStepping>(model);
        case SteppingScheme::event: return std::make_unique<EventStepping>(model);
        case SteppingScheme::soft: return std::make_unique<SoftStepping>(model);
    }
    return std::make_unique<TimeStepping>(model);
}

}  // namespace peensim
