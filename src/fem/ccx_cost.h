// What a deck of `peensim export-fem` will cost CalculiX (ccx 2.20, one thread, the SPOOLES direct
// solver of the Debian package): wall time and peak memory, from the deck's size (its nodes) and
// the increments its dynamic steps plan (explicit: each step's duration over the stable increment;
// implicit: over its largest increment, and ccx cuts back several times more where contact begins),
// with constants of their own for each (the fitted constants absorb ccx's own factors). The constants
// were fitted to ccx runs measured on the project's 2-core machine (docs/user-guide.md, "FEM hand-off": the
// runs, the fit and its error on a deck it was not fitted to). Pure computation: no I/O.
#pragma once

#include "fem/fem_deck.h"

namespace peensim {

struct CcxCostEstimate {
    double nodes = 0.0;               // -, the deck's nodes (block and shot)
    double planned_increments = 0.0;  // -, sum over the dynamic steps of duration / largest increment
    double seconds = 0.0;             // s, wall time on one core
    double bytes = 0.0;               // B, peak resident memory
};

CcxCostEstimate estimate_ccx_cost(const FemDeck& deck);

// The explicit steps' increment (s): the shortest element edge over the dilatational wave speed
// sqrt(E (1 - nu) / (rho (1 + nu) (1 - 2 nu))), block and shot; ccx's own (Courant) is a fixed
// fraction of it, which the fitted constants absorb.
double stable_increment(const FemDeck& deck);

// Beyond these the deck is impractical on a workstation core: export-fem warns (and still writes it).
constexpr double kCcxPracticalSeconds = 3600.0;  // s
constexpr double kCcxPracticalBytes = 8e9;       // B

}  // namespace peensim
