// The `hertz-mindlin` contact law for a pair: soft-sphere constants for the soft scheme (Hertz's
// normal force, Mindlin's tangential spring capped by Coulomb, damping from the restitution e),
// and their instantaneous limit for the rigid schemes, so that one scene runs with every scheme
// and the schemes can be compared on the same material data (`peensim trade`).
//
// The rigid limit of an impact: the normal relative velocity reverses and scales by e(V); the
// tangential impulse is what a grip gives a solid sphere without spin (the slip at the contact
// point stopped: 5/7 of the tangential velocity kept), or, when Coulomb's limit f (1 + e) |v_n|
// is smaller, that limit. The spin this gives is not kept by the rigid schemes (they have none).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "contact/contact_law.h"
#include "contact/hertz_mindlin.h"
#include "contact/law_parameters.h"
#include "contact/law_registry.h"

namespace peensim::contact {

struct HertzMindlinCoefficients {
    double e = 0.9;           // -, coefficient of restitution (rebound over approach speed), (0, 1]
    double f = 0.1;           // -, Coulomb friction
    double V0_m_per_s = 0.0;  // m/s, `plastic_speed`: e falls as (V/V0)^-1/4 above V0 (eq. 2); 0: constant e
    // e at a normal approach speed v (m/s).
    double restitution(double v_m_per_s) const;
};

// The factor the rigid limit keeps of a tangential slip speed vt (m/s) at a normal approach speed
// vn (m/s) with restitution e: 5/7 (gripped), or 1 - f (1 + e) vn / vt (sliding), whichever is larger.
double rigid_tangential_keep(double vt_m_per_s, double vn_m_per_s, double e, double f);

// The rigid limit of a soft law with restitution k.restitution(V) and friction k.f (see above):
// a surface impact, sustained contact, and a shot-shot contact. Every soft law's rigid form.
SurfaceContactResponse rigid_limit_impact(const SurfaceContactInput& in, const HertzMindlinCoefficients& k);
SurfaceContactResponse rigid_limit_sustain(const SurfaceContactInput& in, const HertzMindlinCoefficients& k);
ShotShotResponse rigid_limit_respond(const ShotShotInput& in, const HertzMindlinCoefficients& k);

class HertzMindlinSurfaceLaw final : public SurfaceLaw, public SoftLaw {
public:
    // shot: the shot's material and its radius (m) and mass (kg); surface: the component's (a wall:
    // infinite radius and mass).
    HertzMindlinSurfaceLaw(const HertzMindlinCoefficients& k, const ElasticMaterial& shot, const ElasticMaterial& surface,
                           double shot_radius_m, double shot_mass_kg);
    std::string_view name() const override { return "hertz-mindlin"; }
    SurfaceContactResponse impact(const SurfaceContactInput& in, std::span<double>) const override;
    SurfaceContactResponse sustain(const SurfaceContactInput& in, std::span<double>) const override;
    const SoftLaw* soft() const override { return this; }
    SoftPair contact(double approach_speed_m_per_s) const override;

private:
    HertzMindlinCoefficients k_;
    SoftPair elastic_;  // beta 0: set per contact
};

class HertzMindlinShotShotLaw final : public ShotShotLaw, public SoftLaw {
public:
    HertzMindlinShotShotLaw(const HertzMindlinCoefficients& k, const ElasticMaterial& shot, double shot_radius_m, double shot_mass_kg);
    std::string_view name() const override { return "hertz-mindlin"; }
    ShotShotResponse respond(const ShotShotInput& in) const override;
    const SoftLaw* soft() const override { return this; }
    SoftPair contact(double approach_speed_m_per_s) const override;

private:
    HertzMindlinCoefficients k_;
    SoftPair elastic_;
};

// kg, a sphere's mass from its diameter (m) and density (kg/m3).
double sphere_mass(double diameter_m, double density_kg_per_m3);
// The elastic constants a soft law (named `law`) needs, or std::invalid_argument saying where to
// give them: the shot's material's, the surface's.
const ElasticMaterial& shot_elastic_for(std::string_view law, const std::optional<ElasticMaterial>& shot, const std::string& shot_material);
const ElasticMaterial& surface_elastic_for(std::string_view law, const SurfacePair& pair);

std::span<const LawParameter> hertz_mindlin_parameters();
// Factories for the law registry; throw std::invalid_argument naming the elastic constants a pair lacks.
std::shared_ptr<const SurfaceLaw> make_hertz_mindlin_surface(const ParameterValues& v, const SurfacePair& pair);
std::shared_ptr<const ShotShotLaw> make_hertz_mindlin_shot_shot(const ParameterValues& v, const ShotShotPair& pair);

}  // namespace peensim::contact
