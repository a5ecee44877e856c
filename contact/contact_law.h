// Contact laws: pure values in, values out. No Bullet, no I/O, no globals, no bookkeeping.
// The engine measures the contact (normal, velocities relative to the moving surface, dt)
// and a law decides the rebound. Reference: shot-peening-model.md eq. 2-5.
#pragma once

#include "contact/contact_policy.h"

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/vec.h"
#include "contact/hertz_mindlin.h"
#include "contact/soft_pair.h"

namespace peensim::contact {

// A shot touching a (possibly moving) surface. All vectors in one frame (world).
struct SurfaceContactInput {
    Vec3 v_shot;                  // m/s, shot velocity just before the contact
    Vec3 v_surface;               // m/s, velocity of the surface material point at the contact
    Vec3 normal;                  // unit, from the surface towards the shot centre
    double pressing_accel = 0.0;  // m/s2, acceleration pressing the shot onto the surface (>= 0), for friction
    double dt = 0.0;              // s, the time over which sustained-contact friction acts
    // The contact's identity, for laws that keep state or look at geometry (the engine fills all).
    int shot = -1;                    // index of the shot
    int component = -1;               // index of the component touched
    int triangle = -1;                // index of the mesh triangle touched (indexes the per-triangle state)
    Vec3 point_local = Vec3::Zero();  // m, contact point in the component's own frame
    Vec3 point_world = Vec3::Zero();  // m, the same point in the world (where the air's velocity is known)
    double overlap_m = 0.0;           // m, how far the shot is into the surface (0 at an exact touch)
    double shot_radius_m = 0.0;       // m
    double shot_mass_kg = 0.0;        // kg
    double time_s = 0.0;              // s, simulated time of the contact
    // The contact policy's verdict (contact_policy.h): an impact (counted and logged) or a slower
    // contact the scheme resolves as a rebound. A law with a memory of hits counts only impacts.
    bool impact = false;
    // This contact's own state (state_per_contact() doubles; zeros when the contact starts), kept
    // while the contact lasts; empty for a law that keeps none.
    std::span<double> contact_state{};
};

struct SurfaceContactResponse {
    Vec3 v_shot;               // m/s, shot velocity after the contact
    double vn_in = 0.0;        // m/s, normal approach speed relative to the surface (>= 0)
    double vt_in = 0.0;        // m/s, tangential speed relative to the surface before
    double vn_out = 0.0;       // m/s, normal separation speed relative to the surface after (>= 0)
    bool approaching = false;  // false: the pair was separating and nothing changed
};

// Two shots in contact (of one size, or two sizes of a mix).
struct ShotShotInput {
    Vec3 v_i;     // m/s
    Vec3 v_j;     // m/s
    Vec3 normal;  // unit, from the centre of i to the centre of j
    ShotShotMode mode = ShotShotMode::law;
    // The partner is held (a pile's substeps move one shot at a time, its neighbours held like
    // walls): only i's velocity changes, as against an infinite mass.
    bool j_held = false;
    int shot_i = -1, shot_j = -1;               // indices of the two shot
    double overlap_m = 0.0;                     // m, R_i + R_j - distance between the centres (0 at an exact touch)
    double radius_i_m = 0.0, radius_j_m = 0.0;  // m
    double mass_i_kg = 0.0, mass_j_kg = 0.0;    // kg (0 for both: equal masses)
    double time_s = 0.0;                        // s
};

// How a shot-shot impulse changes the two velocities: shot i's by share i of the change of their
// relative velocity, j's by share j, m_j / (m_i + m_j) and m_i / (m_i + m_j) (a half each for equal
// masses, or when the masses are not given); against a held partner i takes all of it.
struct ImpulseShares {
    double i = 0.5, j = 0.5;
};
inline ImpulseShares impulse_shares(const ShotShotInput& in) {
    ImpulseShares s;
    if (in.mass_i_kg > 0.0 && in.mass_j_kg > 0.0 && in.mass_i_kg != in.mass_j_kg) {
        s.i = in.mass_j_kg / (in.mass_i_kg + in.mass_j_kg);
        s.j = in.mass_i_kg / (in.mass_i_kg + in.mass_j_kg);
    }
    if (in.j_held) s.i = 1.0;
    return s;
}

struct ShotShotResponse {
    Vec3 v_i;            // m/s, after
    Vec3 v_j;            // m/s, after
    double vn_in = 0.0;  // m/s, normal approach speed (>= 0)
    bool approaching = false;
};

// The impact line (contact::is_impact) and the other rules both schemes follow: contact_policy.h.

// What the soft-sphere scheme asks of a pair's law (a law that offers it: `hertz-mindlin`,
// `linear-spring-dashpot`): the constants of a contact that starts approaching at approach_speed
// (m/s, >= 0), its family saying which forces follow from them (soft_pair.h). A velocity-dependent
// restitution fixes the contact's damping from its approach speed.
// What such a contact remembers while it lasts is the law's per-contact state (SoftContactState:
// the tangential spring), which the soft pool keeps with the contact and never reads.
class SoftLaw {
public:
    virtual ~SoftLaw() = default;
    virtual SoftPair contact(double approach_speed_m_per_s) const = 0;
};

// A law for shot-surface contacts (static or moving mesh), built for one pair (its parameters
// bound) and immutable: what it must remember it keeps in the state the engine stores for it (in
// the simulation state and the checkpoint), never in itself: per mesh triangle, across contacts
// (a memory of hits), and per contact, while one lasts (a tangential spring, a contact's age).
class SurfaceLaw {
public:
    virtual ~SurfaceLaw() = default;
    virtual std::string_view name() const = 0;
    // Doubles of state per mesh triangle of the component (0: none, and the scene stores nothing).
    virtual int state_per_triangle() const { return 0; }
    // Doubles of state per contact (0: none). A contact lasts while the shot stays in sustained
    // contact with the component (engine/contact_states.h); an impact in the rigid schemes is a
    // contact of its own, handed zeros.
    virtual int state_per_contact() const { return 0; }
    // A rebound: the shot's velocity after the contact. Leaves it unchanged if the pair is separating.
    // triangle_state: the component's whole state (state_per_triangle() doubles per triangle).
    virtual SurfaceContactResponse impact(const SurfaceContactInput& in, std::span<double> triangle_state) const = 0;
    // Sustained contact over in.dt (resting, sliding, riding): no normal approach remains; friction
    // acts on the tangential part.
    virtual SurfaceContactResponse sustain(const SurfaceContactInput& in, std::span<double> triangle_state) const = 0;
    // One line on what the state holds now, for the run's summary ("" when the law keeps none).
    virtual std::string describe_state(std::span<const double> /*triangle_state*/) const { return ""; }
    // The soft-sphere form of this law, or nullptr (the soft scheme needs it for every pair).
    virtual const SoftLaw* soft() const { return nullptr; }
};

// A law for shot-shot contacts, built with its parameters bound. (Per-contact state for shot-shot
// laws, such as Hertz-Mindlin's tangential spring, comes with the soft-sphere scheme: in the rigid
// schemes a resting pile's shot-shot contacts are not handed to the law while they last, only
// their approaches are.)
class ShotShotLaw {
public:
    virtual ~ShotShotLaw() = default;
    virtual std::string_view name() const = 0;
    virtual ShotShotResponse respond(const ShotShotInput& in) const = 0;
    // The soft-sphere form of this law, or nullptr (the soft scheme needs it for every pair).
    virtual const SoftLaw* soft() const { return nullptr; }
};

}  // namespace peensim::contact
