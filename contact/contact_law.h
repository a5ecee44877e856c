// Contact laws: pure values in, values out. No Bullet, no I/O, no globals, no bookkeeping.
// The engine measures the contact (normal, velocities relative to the moving surface, dt)
// and a law decides the rebound. Reference: shot-peening-model.md eq. 2-5.
#pragma once

#include "contact/contact_policy.h"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/vec.h"

namespace peensim::contact {

// Coefficients of one contact pair (reference tables 1 and 2).
struct PairCoefficients {
    double C0 = 0.9;          // -, normal restitution in the elastic regime, 0 < C0 <= 1
    double V0_m_per_s = 0.5;  // m/s, impact speed where the plastic regime starts, > 0
    double mu = 0.71;         // -, tangential restitution, 0 <= mu <= 1
    double f = 0.1;           // -, Coulomb friction coefficient in sustained contact, >= 0
};

// A shot touching a (possibly moving) surface. All vectors in one frame.
struct SurfaceContactInput {
    Vec3 v_shot;              // m/s, shot velocity just before the contact
    Vec3 v_surface;           // m/s, velocity of the surface material point at the contact
    Vec3 normal;              // unit, from the surface towards the shot centre
    double pressing_accel;    // m/s2, acceleration pressing the shot onto the surface (>= 0), for friction
    double dt;                // s, the step over which sustained-contact friction acts
};

struct SurfaceContactResponse {
    Vec3 v_shot;              // m/s, shot velocity after the contact
    double vn_in = 0.0;       // m/s, normal approach speed relative to the surface (>= 0)
    double vt_in = 0.0;       // m/s, tangential speed relative to the surface before
    double vn_out = 0.0;      // m/s, normal separation speed relative to the surface after (>= 0)
    bool approaching = false; // false: the pair was separating and nothing changed
};

// Two shots of equal mass in contact.
struct ShotShotInput {
    Vec3 v_i;                 // m/s
    Vec3 v_j;                 // m/s
    Vec3 normal;              // unit, from the centre of i to the centre of j
};

struct ShotShotResponse {
    Vec3 v_i;                 // m/s, after
    Vec3 v_j;                 // m/s, after
    double vn_in = 0.0;       // m/s, normal approach speed (>= 0)
    bool approaching = false;
};

// The impact line (contact::is_impact) and the other rules both schemes follow: contact_policy.h.

// A law for shot-surface contacts (static or moving mesh). Laws are immutable values.
class SurfaceLaw {
public:
    virtual ~SurfaceLaw() = default;
    virtual std::string_view name() const = 0;
    // An impact: the rebound. Leaves the velocity unchanged if the pair is separating.
    virtual SurfaceContactResponse impact(const SurfaceContactInput& in, const PairCoefficients& k) const = 0;
    // Sustained contact over dt: no normal approach remains; friction acts on the tangential part.
    virtual SurfaceContactResponse sustain(const SurfaceContactInput& in, const PairCoefficients& k) const = 0;
};

// A law for shot-shot contacts.
class ShotShotLaw {
public:
    virtual ~ShotShotLaw() = default;
    virtual std::string_view name() const = 0;
    virtual ShotShotResponse respond(const ShotShotInput& in, const PairCoefficients& k) const = 0;
};

}  // namespace peensim::contact
