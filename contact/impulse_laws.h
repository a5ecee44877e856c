// The rigid-sphere impulse laws of the CAD-based USP model (reference eq. 3, 4, 5):
// instantaneous binary collisions with velocity-dependent normal restitution,
// a constant tangential restitution, and Coulomb friction for sustained contact.
#pragma once

#include "contact/contact_law.h"
#include "contact/law_parameters.h"

namespace peensim::contact {

// The parameters of the impulse laws for one pair (reference tables 1 and 2).
struct PairCoefficients {
    double C0 = 0.9;          // -, normal restitution in the elastic regime, 0 < C0 <= 1
    double V0_m_per_s = 0.5;  // m/s, impact speed where the plastic regime starts, > 0
    double mu = 0.71;         // -, tangential restitution, 0 <= mu <= 1
    double f = 0.1;           // -, Coulomb friction coefficient in sustained contact, >= 0
};

// The laws as functions of their coefficients (the classes below bind them to a pair; the
// impact-history law reuses them with its own restitution).
// Eq. 3: equal masses, only the normal components change, momentum conserved exactly.
ShotShotResponse impulse_shot_shot(const ShotShotInput& in, const PairCoefficients& k);
// Eq. 5 (eq. 4 when the surface is still), with the normal restitution C (-) given.
SurfaceContactResponse impulse_surface_rebound(const SurfaceContactInput& in, double C, double mu);
// Eq. 5 with C from eq. 2.
SurfaceContactResponse impulse_surface_impact(const SurfaceContactInput& in, const PairCoefficients& k);
// Coulomb friction for sustained contact.
SurfaceContactResponse impulse_surface_sustain(const SurfaceContactInput& in, double f);

// The parameters both impulse laws declare (shot-shot uses C0 and V0).
std::span<const LawParameter> impulse_parameters();
PairCoefficients impulse_coefficients(const ParameterValues& values);

class ImpulseShotShotLaw final : public ShotShotLaw {
public:
    explicit ImpulseShotShotLaw(const PairCoefficients& k = {}) : k_(k) {}
    std::string_view name() const override { return "impulse"; }
    ShotShotResponse respond(const ShotShotInput& in) const override { return impulse_shot_shot(in, k_); }

private:
    PairCoefficients k_;
};

class ImpulseSurfaceLaw final : public SurfaceLaw {
public:
    explicit ImpulseSurfaceLaw(const PairCoefficients& k = {}) : k_(k) {}
    std::string_view name() const override { return "impulse"; }
    SurfaceContactResponse impact(const SurfaceContactInput& in, std::span<double>) const override {
        return impulse_surface_impact(in, k_);
    }
    SurfaceContactResponse sustain(const SurfaceContactInput& in, std::span<double>) const override {
        return impulse_surface_sustain(in, k_.f);
    }

private:
    PairCoefficients k_;
};

}  // namespace peensim::contact
