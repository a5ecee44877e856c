// The rigid-sphere impulse laws of the CAD-based USP model (reference eq. 3, 4, 5):
// instantaneous binary collisions with velocity-dependent normal restitution,
// a constant tangential restitution, and Coulomb friction for sustained contact.
#pragma once

#include "contact/contact_law.h"

namespace peensim::contact {

// Eq. 3: equal masses, only the normal components change, momentum conserved exactly.
class ImpulseShotShotLaw final : public ShotShotLaw {
public:
    std::string_view name() const override { return "impulse"; }
    ShotShotResponse respond(const ShotShotInput& in, const PairCoefficients& k) const override;
};

// Eq. 5 (eq. 4 when the surface is still) for impacts; Coulomb friction for sustained contact.
class ImpulseSurfaceLaw final : public SurfaceLaw {
public:
    std::string_view name() const override { return "impulse"; }
    SurfaceContactResponse impact(const SurfaceContactInput& in, const PairCoefficients& k) const override;
    SurfaceContactResponse sustain(const SurfaceContactInput& in, const PairCoefficients& k) const override;
};

}  // namespace peensim::contact
