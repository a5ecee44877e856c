// The `linear-spring-dashpot` contact law for a pair: the soft-sphere contact LIGGGHTS calls
// `model hooke` (with `tangential history`) and EDEM "linear spring": a normal spring of constant
// stiffness k_n with a damper, a tangential spring k_t with a damper, Coulomb's cap f. The
// stiffness comes from the materials the way LIGGGHTS's does, at a characteristic speed v_c (the
// linear spring whose greatest overlap at v_c equals Hertz's):
//   k_n = 16/15 sqrt(R*) E* (15 m* v_c^2 / (16 sqrt(R*) E*))^(1/5),   k_t = ratio k_n,
// the dampers from the restitution e: c_n = c_t = 2 zeta sqrt(k_n m*), zeta = -ln e / sqrt(ln^2 e +
// pi^2) (LIGGGHTS's gamma_t = gamma_n). A normal impact then rebounds at e exactly at every speed
// and lasts pi / omega_d, omega_d = sqrt(k_n / m* - (c_n / 2 m*)^2), the closed forms the tests
// hold the soft scheme to. The rigid schemes take its instantaneous limit, as hertz-mindlin's.
#pragma once

#include <memory>
#include <span>

#include "contact/contact_law.h"
#include "contact/hertz_mindlin.h"
#include "contact/hertz_mindlin_law.h"
#include "contact/law_parameters.h"
#include "contact/law_registry.h"
#include "contact/soft_pair.h"

namespace peensim::contact {

// The pair's constants: E*, R*, m* as Hertz's (hertz_pair), then k_n, k_t and beta.
SoftPair linear_spring_dashpot_pair(const ElasticMaterial& a, const ElasticMaterial& b, double radius_a_m, double radius_b_m,
                                    double mass_a_kg, double mass_b_kg, double restitution, double friction,
                                    double characteristic_speed_m_per_s, double tangential_ratio);

// The family's forces (soft_pair.h dispatches to them).
double linear_normal_damping(const SoftPair& p);  // N s/m, c_n (>= 0)
double linear_normal_force(const SoftPair& p, double delta_m, double delta_rate_m_per_s);
Vec3 linear_tangential_force(const SoftPair& p, double normal_force_n, const Vec3& v_t, const Vec3& slip_m, Vec3& spring_m);
double linear_elastic_energy(const SoftPair& p, double delta_m);  // J, k_n delta^2 / 2
double linear_contact_duration(const SoftPair& p);                // s, pi / omega_d (every speed)

class LinearSpringDashpotSurfaceLaw final : public SurfaceLaw, public SoftLaw {
public:
    LinearSpringDashpotSurfaceLaw(const SoftPair& pair, const HertzMindlinCoefficients& rigid) : pair_(pair), rigid_(rigid) {}
    std::string_view name() const override { return "linear-spring-dashpot"; }
    SurfaceContactResponse impact(const SurfaceContactInput& in, std::span<double>) const override;
    SurfaceContactResponse sustain(const SurfaceContactInput& in, std::span<double>) const override;
    const SoftLaw* soft() const override { return this; }
    SoftPair contact(double /*approach_speed_m_per_s*/) const override { return pair_; }

private:
    SoftPair pair_;
    HertzMindlinCoefficients rigid_;  // e and f of the rigid limit (no plastic speed)
};

class LinearSpringDashpotShotShotLaw final : public ShotShotLaw, public SoftLaw {
public:
    LinearSpringDashpotShotShotLaw(const SoftPair& pair, const HertzMindlinCoefficients& rigid) : pair_(pair), rigid_(rigid) {}
    std::string_view name() const override { return "linear-spring-dashpot"; }
    ShotShotResponse respond(const ShotShotInput& in) const override;
    const SoftLaw* soft() const override { return this; }
    SoftPair contact(double /*approach_speed_m_per_s*/) const override { return pair_; }

private:
    SoftPair pair_;
    HertzMindlinCoefficients rigid_;
};

std::span<const LawParameter> linear_spring_dashpot_parameters();
// Factories for the law registry; throw std::invalid_argument naming the elastic constants a pair lacks.
std::shared_ptr<const SurfaceLaw> make_linear_spring_dashpot_surface(const ParameterValues& v, const SurfacePair& pair);
std::shared_ptr<const ShotShotLaw> make_linear_spring_dashpot_shot_shot(const ParameterValues& v, const ShotShotPair& pair);

}  // namespace peensim::contact
