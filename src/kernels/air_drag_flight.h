// Flight through air: gravity plus the drag of a smooth sphere, a = g - k(Re) |w| w with w = v - u(p)
// the shot's velocity relative to the air (u: still, or the nozzles' free jets, free_jet.h),
// k = 3 rho_air C_d / (8 rho_shot R) (drag force C_d rho_air |w| w pi R^2 / 2 over the shot's mass)
// and Re = rho_air |w| D / mu. C_d is the standard drag curve of a smooth sphere (Clift, Grace &
// Weber 1978, Table 5.2: piecewise fits in log10 Re, held at its Re = 3.38e5 value beyond, where
// the drag crisis begins), or a constant the scene gives.
//
// Drag matters for the fast jet of conventional peening and for small slow shot (reference sec. 5);
// for USP it is off by default. A flight is advanced by classical Runge-Kutta (4th order): at time
// stepping's steps (a quarter radius of travel) its error is far below a nanometre per step
// (tests/kernels/flight_models_test.cpp measures it against closed-form flights).
#pragma once

#include <memory>
#include <optional>

#include "kernels/flight_model.h"
#include "kernels/free_jet.h"

namespace peensim {

struct AirDrag {
    double air_density_kg_per_m3 = 1.205;          // kg/m3, air at 20 C
    double air_viscosity_pa_s = 1.822e-5;          // Pa s
    std::optional<double> drag_coefficient;        // -, constant C_d; empty: the standard drag curve C_d(Re)
    double shot_radius_m = 0.0;                    // m
    double shot_density_kg_per_m3 = 0.0;           // kg/m3
    std::shared_ptr<const AirVelocityField> wind;  // the air's motion; empty: still air
};

class AirDragFlight final : public FlightModel {
public:
    AirDragFlight(const Vec3& gravity_m_per_s2, const AirDrag& air);

    std::string_view name() const override { return "air drag"; }
    bool is_parabola() const override { return false; }
    Vec3 gravity() const override { return g_; }
    Vec3 acceleration(const Vec3& p, const Vec3& v) const override;
    void advance(Vec3& p, Vec3& v, double dt) const override;
    // Drag in still air only ever slows a shot: its speed grows by at most |g| per second. Moving
    // air (at most U m/s) speeds up only a shot slower than U along its own direction, and then
    // |w| <= 2 U: at most |g| + k(2U) (2U)^2.
    double speed_gain_bound() const override { return speed_gain_bound_; }

    // -, the drag coefficient at Reynolds number re (> 0).
    double drag_coefficient(double re) const;
    // -, the Reynolds number of a shot flying at speed (m/s) through this air.
    double reynolds(double speed_m_per_s) const { return speed_m_per_s * reynolds_per_speed_; }

private:
    Vec3 g_;
    AirDrag air_;
    double reynolds_per_speed_ = 0.0;  // s/m, rho_air D / mu
    double k_per_cd_ = 0.0;            // 1/m, 3 rho_air / (8 rho_shot R): k = C_d k_per_cd
    double speed_gain_bound_ = 0.0;    // m/s2
};

}  // namespace peensim
