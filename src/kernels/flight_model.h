// How a shot flies between contacts. The default is the exact parabola under gravity (eq. 1): the
// event scheme's closed-form kernels (trajectory.h, the times of impact) hold only for it, and
// time stepping advances it in closed form. Another model (air drag) plugs in here: time stepping
// advances any model through this interface and bounds a step's travel by speed_gain_bound(); a
// model that is not the parabola runs with time stepping (the scene's scheme falls back to it).
#pragma once

#include <string_view>

#include "common/vec.h"

namespace peensim {

class FlightModel {
public:
    virtual ~FlightModel() = default;
    virtual std::string_view name() const = 0;
    // Every flight is Trajectory's exact parabola under gravity(): the event scheme may run.
    virtual bool is_parabola() const = 0;
    virtual Vec3 gravity() const = 0;  // m/s2
    // m/s2, acceleration of a shot in free flight at centre p (m) and velocity v (m/s).
    virtual Vec3 acceleration(const Vec3& p, const Vec3& v) const = 0;
    // Free flight of dt (s) from centre p (m) and velocity v (m/s); both updated.
    virtual void advance(Vec3& p, Vec3& v, double dt) const = 0;
    // m/s2, the most a shot's speed can grow per second of free flight, whatever its velocity: so
    // over [0, t] its speed is at most |v0| + b t and its centre stays within |v0| t + b t^2 / 2 of
    // where it started (the bounds time stepping sizes steps and skips distance queries by).
    virtual double speed_gain_bound() const = 0;
};

// The exact parabola under gravity: eq. 1 of the model.
class ParabolaFlight final : public FlightModel {
public:
    explicit ParabolaFlight(const Vec3& gravity_m_per_s2) : g_(gravity_m_per_s2) {}
    std::string_view name() const override { return "parabola"; }
    bool is_parabola() const override { return true; }
    Vec3 gravity() const override { return g_; }
    Vec3 acceleration(const Vec3& /*p*/, const Vec3& /*v*/) const override { return g_; }
    void advance(Vec3& p, Vec3& v, double dt) const override {
        p += v * dt + (0.5 * dt * dt) * g_;
        v += g_ * dt;
    }
    double speed_gain_bound() const override { return g_.norm(); }

private:
    Vec3 g_;
};

}  // namespace peensim
