// The contact coefficients of the event-driven prototype of the reference notes
// (shared/reference/event-driven-notes.md: C = 0.9 at every speed, mu = 1), as `--set` overrides of
// scenes/rod.yaml, for the tests that compare the rod scene with that code's figures.
#pragma once

#include <string>
#include <vector>

namespace peensim::testing {

inline const std::vector<std::string> kPrototypeCoefficients = {
    "contacts.shot-shot={C0: 0.9, V0: 1000 m/s}",
    "contacts.shot-titanium={C0: 0.9, V0: 1000 m/s, mu: 1, f: 0.1}",
    "contacts.shot-copper={C0: 0.9, V0: 1000 m/s, mu: 1, f: 0.1}",
    "contacts.shot-steel={C0: 0.9, V0: 1000 m/s, mu: 1, f: 0.1}",
};

}  // namespace peensim::testing
