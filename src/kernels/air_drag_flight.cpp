#include "kernels/air_drag_flight.h"

#include <cmath>

namespace peensim {

namespace {
// Schiller-Naumann's fit holds up to this Reynolds number; above it the drag coefficient of a
// sphere stays near Newton's value until the drag crisis (Re ~ 3e5, far above any shot's).
constexpr double kNewtonRegimeReynolds = 1000.0;
constexpr double kNewtonDragCoefficient = 0.44;
}  // namespace

AirDragFlight::AirDragFlight(const Vec3& gravity_m_per_s2, const AirDrag& air) : g_(gravity_m_per_s2), air_(air) {
    reynolds_per_speed_ = air.air_density_kg_per_m3 * 2.0 * air.shot_radius_m / air.air_viscosity_pa_s;
    k_per_cd_ = 3.0 * air.air_density_kg_per_m3 / (8.0 * air.shot_density_kg_per_m3 * air.shot_radius_m);
    speed_gain_bound_ = g_.norm();
    if (air_.wind && air_.wind->max_speed() > 0.0) {
        // C_d(Re) |w|^2 grows with |w| (Schiller-Naumann's 24/Re (1 + 0.15 Re^0.687) |w|^2 does).
        const double w = 2.0 * air_.wind->max_speed();
        speed_gain_bound_ += k_per_cd_ * drag_coefficient(reynolds(w)) * w * w;
    }
}

double AirDragFlight::drag_coefficient(double re) const {
    if (air_.drag_coefficient) return *air_.drag_coefficient;
    if (re > kNewtonRegimeReynolds) return kNewtonDragCoefficient;
    return 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687));
}

Vec3 AirDragFlight::acceleration(const Vec3& p, const Vec3& v) const {
    const Vec3 w = air_.wind ? Vec3(v - air_.wind->at(p)) : v;
    const double speed = w.norm();
    if (!(speed > 0.0)) return g_;
    return g_ - (k_per_cd_ * drag_coefficient(reynolds(speed)) * speed) * w;
}

void AirDragFlight::advance(Vec3& p, Vec3& v, double dt) const {
    // Classical Runge-Kutta on (p' = v, v' = a(p, v)).
    const Vec3 a1 = acceleration(p, v);
    const Vec3 v2 = v + (0.5 * dt) * a1, p2 = p + (0.5 * dt) * v;
    const Vec3 a2 = acceleration(p2, v2);
    const Vec3 v3 = v + (0.5 * dt) * a2, p3 = p + (0.5 * dt) * v2;
    const Vec3 a3 = acceleration(p3, v3);
    const Vec3 v4 = v + dt * a3, p4 = p + dt * v3;
    const Vec3 a4 = acceleration(p4, v4);
    p += (dt / 6.0) * (v + 2.0 * v2 + 2.0 * v3 + v4);
    v += (dt / 6.0) * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
}

}  // namespace peensim
