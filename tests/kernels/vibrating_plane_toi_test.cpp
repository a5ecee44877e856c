// Exact shot-sonotrode times of impact: the still plate against the closed-form drop, the state at
// the start of the interval (touching and approaching, at rest and pulled in, separating right
// after a bounce, a shot that never really left, overlap), grazing double roots, long flights that
// must cost O(1), and thousands of random drops and launches against an independent reference in
// long double: a dense scan (2^20 samples) refined by a certified branch and bound (Taylor bounds,
// so no dip between samples escapes it) and bisection, also near t = 60 s where the phase w t is
// 7.5e6 rad.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "common/sim_time.h"
#include "kernels/vibrating_plane_toi.h"
#include "model/kinematics.h"

namespace peensim {
namespace {

constexpr double kPlaneG = 9.81;  // m/s^2
constexpr double kPlaneR = 1e-3;  // m, shot radius
constexpr double kA = 25e-6;      // m, sonotrode amplitude
constexpr double kF = 20e3;       // Hz
const Vec3 kPlaneGravity(0, 0, -kPlaneG);

using Real = long double;
constexpr Real kTwoPiL = 6.283185307179586476925286766559005768L;
const Real kNone = std::numeric_limits<Real>::quiet_NaN();

VibratingPlane sonotrode(double phase = 0.0) {
    VibratingPlane plane;
    plane.amplitude_m = kA;
    plane.frequency_hz = kF;
    plane.phase_rad = phase;
    return plane;
}

// The gap in long double, from the same double inputs the kernel sees: the reference truth.
struct Exact {
    Real D0 = 0, D1 = 0, D2 = 0;  // static gap D0 + D1 u + D2 u^2, u = t - t0
    Real t0 = 0;
    Real amp = 0, F = 0, phi = 0, w = 0;
    Real max_curvature = 0;  // bound on |h''|
    Real max_jerk = 0;       // bound on |h'''|

    Exact(const Trajectory& path, double radius, const VibratingPlane& plane) {
        for (int k = 0; k < 3; ++k) {
            const Real n = plane.normal[k];
            D0 += n * (static_cast<Real>(path.p0[k]) - static_cast<Real>(plane.point_m[k]));
            D1 += n * static_cast<Real>(path.v0[k]);
            D2 += n * static_cast<Real>(path.g[k]) / 2;
            amp += n * static_cast<Real>(plane.axis[k]);
        }
        D0 -= radius;
        amp *= plane.amplitude_m;
        t0 = path.t0;
        F = plane.frequency_hz;
        phi = plane.phase_rad;
        w = kTwoPiL * F;
        max_curvature = 2 * std::fabs(D2) + std::fabs(amp) * w * w;
        max_jerk = std::fabs(amp) * w * w * w;
    }
    Real phase(Real t) const {
        Real cycles = F * t;
        cycles -= std::floor(cycles);
        return kTwoPiL * cycles + phi;
    }
    Real static_gap(Real t) const {
        const Real u = t - t0;
        return D0 + u * (D1 + u * D2);
    }
    Real static_rate(Real t) const { return D1 + 2 * (t - t0) * D2; }
    Real gap(Real t) const { return static_gap(t) - amp * std::sin(phase(t)); }
    Real rate(Real t) const { return static_rate(t) - amp * w * std::cos(phase(t)); }
    Real curvature(Real t) const { return 2 * D2 + amp * w * w * std::sin(phase(t)); }
    Real plate_speed(Real t) const { return amp * w * std::cos(phase(t)); }  // along the normal
};

// Earliest t in [a, b] with gap(t) <= 0, given gap(a) > 0 (none: NaN). Certified: an interval is
// dropped only when a lower bound of the gap on it is positive (first the plate cannot lower the
// static gap by more than |amp|; then h(a + s) >= h(a) + h'(a) s - max|h''| s^2 / 2), otherwise
// split, down to 1e-16 s, where the first sample at or below zero is refined by bisection.
Real certified_first_contact(const Exact& e, Real a, Real b) {
    const Real dt = b - a;
    const Real s0 = e.static_gap(a), s1 = e.static_rate(a);
    if (s0 + std::min<Real>(0, s1 * dt) + std::min<Real>(0, e.D2) * dt * dt > std::fabs(e.amp)) return kNone;
    const Real h = e.gap(a), dh = e.rate(a);
    if (std::min(h, h + dh * dt - e.max_curvature * dt * dt / 2) > 0) return kNone;
    if (dt <= 1e-16L) {
        if (e.gap(b) > 0) return kNone;
        Real lo = a, hi = b;  // gap(lo) > 0 >= gap(hi)
        for (int i = 0; i < 80 && hi - lo > 0; ++i) {
            const Real mid = (lo + hi) / 2;
            if (mid <= lo || mid >= hi) break;
            (e.gap(mid) > 0 ? lo : hi) = mid;
        }
        return hi;
    }
    constexpr int kSplit = 8;
    for (int j = 0; j < kSplit; ++j) {
        const Real c0 = a + dt * j / kSplit, c1 = j + 1 == kSplit ? b : a + dt * (j + 1) / kSplit;
        const Real r = certified_first_contact(e, c0, c1);
        if (!std::isnan(r)) return r;
    }
    return kNone;
}

// The reference: `samples` uniform samples over [a, b], each gap between them searched as above.
Real reference_contact(const Exact& e, Real a, Real b, long samples) {
    for (long i = 0; i < samples; ++i) {
        const Real c0 = a + (b - a) * i / samples, c1 = i + 1 == samples ? b : a + (b - a) * (i + 1) / samples;
        const Real r = certified_first_contact(e, c0, c1);
        if (!std::isnan(r)) return r;
    }
    return kNone;
}

// A time t1 > t such that the gap rises on (t, t1] and is positive at t1, for a shot that starts
// touching and separating: h'(t + s) >= h'(t) + h''(t) s - max|h'''| s^2 / 2, concave in s.
Real leave(const Exact& e, Real t) {
    const Real v = e.rate(t), c = e.curvature(t);
    Real s = 1e-6L;
    while (s > 1e-18L && !(v + c * s - e.max_jerk * s * s / 2 > 0 && e.gap(t + s) > 0)) s /= 2;
    return t + s;
}

Vec3 random_unit_near(std::mt19937_64& rng, const Vec3& axis, double max_angle) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Vec3 helper = std::fabs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 e1 = axis.cross(helper).normalized(), e2 = axis.cross(e1);
    const double cos_max = std::cos(max_angle);
    const double c = 1.0 - u(rng) * (1.0 - cos_max), s = std::sqrt(1.0 - c * c), az = 2.0 * M_PI * u(rng);
    return (c * axis + s * std::cos(az) * e1 + s * std::sin(az) * e2).normalized();
}

// A sonotrode of random tilt, axis, phase and (mostly 20 kHz, 25 um) vibration.
VibratingPlane random_plate(std::mt19937_64& rng, bool ceiling) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    VibratingPlane plane;
    plane.point_m = Vec3(0.03 * u(rng) - 0.015, 0.03 * u(rng) - 0.015, 0.01 * u(rng));
    plane.normal = random_unit_near(rng, ceiling ? Vec3(-Vec3::UnitZ()) : Vec3(Vec3::UnitZ()), 0.6);
    plane.axis = random_unit_near(rng, plane.normal, 0.3);
    plane.phase_rad = 2.0 * M_PI * u(rng) - M_PI;
    const double kind = u(rng);
    if (kind < 0.8) {
        plane.amplitude_m = kA;
        plane.frequency_hz = kF;
    } else if (kind < 0.9) {  // slow and large: knots, long pieces
        plane.amplitude_m = 1e-3;
        plane.frequency_hz = 50.0;
    } else {  // the plate never out-accelerates gravity: no knots at all
        plane.amplitude_m = 1e-3;
        plane.frequency_hz = 5.0;
    }
    return plane;
}

struct Tally {
    int impacts = 0, misses = 0;
    double worst = 0.0;  // s, largest |kernel - reference|
};

// One query against the reference; `from` is where the reference search starts (after leaving).
void check_against_reference(const Trajectory& path, const VibratingPlane& plane, double t_begin, double t_end, Real from, long samples,
                             Tally& tally, const char* what, int trial) {
    const Exact exact(path, kPlaneR, plane);
    const Real expected = reference_contact(exact, from, t_end, samples);
    PlaneContact contact;
    const ToiStatus status = vibrating_plane_toi(path, kPlaneR, plane, t_begin, t_end, contact);
    if (std::isnan(expected)) {
        EXPECT_EQ(status, ToiStatus::miss) << what << " trial " << trial << " t " << contact.time;
        ++tally.misses;
        return;
    }
    ASSERT_EQ(status, ToiStatus::impact) << what << " trial " << trial << " expected " << double(expected);
    const double error = static_cast<double>(static_cast<Real>(contact.time) - expected);
    tally.worst = std::max(tally.worst, std::fabs(error));
    EXPECT_LE(std::fabs(error), 1e-12) << what << " trial " << trial;
    ++tally.impacts;
    // What the contact law reads: the plane's velocity at the reported time, and the foot there.
    EXPECT_NEAR(plane.normal.dot(contact.plate_velocity), static_cast<double>(exact.plate_speed(contact.time)),
                1e-11 * (1.0 + plane.amplitude_m * plane.angular_frequency()))
        << what << " trial " << trial;
    EXPECT_NEAR((contact.point - (path.position(contact.time) - kPlaneR * plane.normal)).norm(), 0.0, 1e-12);
}

TEST(EventVibratingPlane, PhaseAgreesWithTheEngineKinematics) {
    // The kernel and the time-stepping engine must see the same plate: same cycle reduction.
    Kinematics k;
    k.kind = Kinematics::Kind::vibrating;
    k.amplitude_m = kA;
    k.frequency_hz = kF;
    k.phase_rad = 0.7;
    const VibratingPlane plane = sonotrode(0.7);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 61.0);
    for (int i = 0; i < 1000; ++i) {
        const double t = u(rng);
        EXPECT_EQ(plane.displacement(t), k.displacement(SimTime{t, 0.0})) << t;
        EXPECT_EQ(plane.velocity(t).z(), k.displacement_rate(SimTime{t, 0.0})) << t;
    }
}

TEST(EventVibratingPlane, StillPlateMatchesFreeFall) {
    // A = 0, and a plate that slides within its own plane (axis normal to n): the gap is the
    // static quadratic, so the contact is the closed-form drop time.
    for (int sliding = 0; sliding < 2; ++sliding) {
        VibratingPlane plane = sonotrode(0.3);
        plane.point_m = Vec3(0.002, -0.001, 0.004);
        if (sliding)
            plane.axis = Vec3::UnitX();
        else
            plane.amplitude_m = 0.0;
        for (double h : {1e-4, 0.02, 0.5}) {  // m, fall to contact
            const double t0 = 0.37;           // s
            const Trajectory path{Vec3(0.001, -0.002, 0.004 + h + kPlaneR), Vec3::Zero(), kPlaneGravity, t0};
            PlaneContact contact;
            ASSERT_EQ(vibrating_plane_toi(path, kPlaneR, plane, t0, t0 + 1.0, contact), ToiStatus::impact) << h;
            const double fall = std::sqrt(2.0 * h / kPlaneG);
            EXPECT_NEAR(contact.time - t0, fall, 1e-12 * fall) << h << " sliding " << sliding;
            EXPECT_NEAR((contact.point - Vec3(0.001, -0.002, 0.004)).norm(), 0.0, 1e-15);
            EXPECT_EQ(contact.normal, Vec3::UnitZ());
            if (sliding) {
                EXPECT_NEAR(contact.plate_velocity.x(), plane.velocity(contact.time).x(), 1e-15);
                EXPECT_GT(contact.plate_velocity.norm(), 0.0);
            }
            EXPECT_EQ(vibrating_plane_toi(path, kPlaneR, plane, t0, t0 + 0.999 * fall, contact), ToiStatus::miss);
        }
    }
}

// A shot placed on the plate at t, at gap `offset`, with a velocity relative to it along the normal.
Trajectory on_the_plate(const VibratingPlane& plane, double t, double relative_speed, double offset = 0.0) {
    const Vec3 sideways(0.003, -0.002, 0.0);
    const Vec3 centre = plane.point_m + plane.displacement(t) * plane.axis + (kPlaneR + offset) * plane.normal +
                        (sideways - plane.normal.dot(sideways) * plane.normal);
    return {centre, plane.velocity(t) + relative_speed * plane.normal, kPlaneGravity, t};
}

// The phase offset that gives the plate phase theta at time t.
double phase_for(double theta, double t) { return theta - 2.0 * M_PI * SimTime{t, 0.0}.cycle_fraction(kF); }

TEST(EventVibratingPlane, TouchingAndApproachingIsAnImpactNow) {
    const double t = 0.4123;
    for (double phase : {0.0, 1.0, 2.0, 4.0, 5.5}) {
        const VibratingPlane plane = sonotrode(phase);
        PlaneContact contact;
        // Approaching, at a gap of 0 and of +-half the start band.
        for (double offset : {0.0, 0.5e-12, -0.5e-12}) {
            ASSERT_EQ(vibrating_plane_toi(on_the_plate(plane, t, -0.1, offset), kPlaneR, plane, t, t + 0.01, contact), ToiStatus::impact);
            EXPECT_EQ(contact.time, t);
            EXPECT_NEAR((contact.plate_velocity - plane.velocity(t)).norm(), 0.0, 1e-15);
        }
        // Overlapping beyond the band.
        ASSERT_EQ(vibrating_plane_toi(on_the_plate(plane, t, 0.5, -1e-9), kPlaneR, plane, t, t + 0.01, contact), ToiStatus::overlapping);
        EXPECT_EQ(contact.time, t);
    }
}

TEST(EventVibratingPlane, AtRestOnThePlateIsAnImpactOnlyWhenPulledIn) {
    // Relative speed zero: an impact now if the plate accelerates into the shot faster than
    // gravity pulls it (h'' < 0), else the shot floats off and the plate catches it up later.
    const double t = 0.25;
    int now = 0, later = 0;
    for (double phase = 0.05; phase < 2.0 * M_PI; phase += 0.5) {
        const VibratingPlane plane = sonotrode(phase_for(phase, t));  // phase `phase` at t
        const Trajectory path = on_the_plate(plane, t, 0.0);
        const Exact exact(path, kPlaneR, plane);
        PlaneContact contact;
        const ToiStatus status = vibrating_plane_toi(path, kPlaneR, plane, t, t + 1.0, contact);
        if (exact.curvature(t) < 0) {
            EXPECT_EQ(status, ToiStatus::impact) << phase;
            EXPECT_EQ(contact.time, t) << phase;
            ++now;
        } else {
            // Floating off with the plate's velocity: caught up within the period when the plate
            // moves down, else a flight of up to 0.64 s.
            const Real expected = reference_contact(exact, leave(exact, t), t + 1.0, 1024);
            if (std::isnan(expected)) {
                EXPECT_EQ(status, ToiStatus::miss) << phase;
                continue;
            }
            ASSERT_EQ(status, ToiStatus::impact) << phase;
            EXPECT_GT(contact.time, t + 1e-6) << phase;
            EXPECT_NEAR(contact.time, static_cast<double>(expected), 1e-12) << phase;
            ++later;
        }
    }
    EXPECT_GE(now, 5);
    EXPECT_GE(later, 5);
    // On a still plate gravity alone pulls the resting shot in: an impact now (the engine's rest
    // state, not this query, has to stop such a shot from bouncing forever).
    VibratingPlane still = sonotrode();
    still.amplitude_m = 0.0;
    PlaneContact contact;
    EXPECT_EQ(vibrating_plane_toi(on_the_plate(still, t, 0.0), kPlaneR, still, t, t + 1.0, contact), ToiStatus::impact);
    EXPECT_EQ(contact.time, t);
}

TEST(EventVibratingPlane, NoRedetectionRightAfterABounce) {
    // Leaving the plate at the start (gap ~0, separating): the next return, not t_begin.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Tally tally;
    for (int trial = 0; trial < 1000; ++trial) {
        const VibratingPlane plane = random_plate(rng, false);
        const double t = 2.0 * u(rng);
        const double offset = (u(rng) - 0.5) * 1e-12;  // within the start band
        Trajectory path = on_the_plate(plane, t, 0.05 + 3.0 * u(rng), offset);
        const Vec3 sideways(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        path.v0 += sideways - plane.normal.dot(sideways) * plane.normal;
        const Exact exact(path, kPlaneR, plane);
        ASSERT_GT(exact.rate(t), 0);
        check_against_reference(path, plane, t, t + 1.5, leave(exact, t), 4096, tally, "launch", trial);
    }
    EXPECT_GT(tally.impacts, 900);
    std::printf("[ launches ] %d impacts, %d misses, worst |t - reference| %.3g s\n", tally.impacts, tally.misses, tally.worst);
}

TEST(EventVibratingPlane, AShotThatNeverReallyLeftIsAnImpactNotAMiss) {
    // Separating at 1e-9 m/s from 0.5 pm inside the plate while the plate accelerates up at ~2e5
    // m/s^2: the gap peaks ~5e-15 s later still negative. Reporting nothing would let the shot
    // sink through the plate; the query reports the moment it starts closing again.
    const double t = 0.3;
    const double phase = -M_PI / 6.0;  // sin = -1/2: plate acceleration +A w^2 / 2
    const VibratingPlane plane = sonotrode(phase_for(phase, t));
    const Trajectory path = on_the_plate(plane, t, 1e-9, -0.5e-12);
    PlaneContact contact;
    ASSERT_EQ(vibrating_plane_toi(path, kPlaneR, plane, t, t + 0.01, contact), ToiStatus::impact);
    EXPECT_GE(contact.time, t);
    EXPECT_LE(contact.time, t + 1e-13);
    EXPECT_GT(plane.normal.dot(contact.plate_acceleration), 1e5);
}

// The tangent case: the shot moves with the plate at t_star (same position less R, same velocity)
// where the plate decelerates faster than gravity, so h has a double root (h = h' = 0, h'' > 0).
struct Graze {
    VibratingPlane plane;
    Trajectory path;
    double t_star;
};
Graze graze_at(double theta_star, double t_star, double lift) {
    Graze c;
    c.plane = sonotrode(phase_for(theta_star, t_star));
    c.t_star = t_star;
    c.path = on_the_plate(c.plane, t_star, 0.0, lift);
    return c;
}

TEST(EventVibratingPlane, FindsAGrazingDoubleRoot) {
    const double period = 1.0 / kF;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        // The plate moving down and decelerating faster than gravity (sin(theta) > g / (A w^2)),
        // steeply enough that the shot, on the tangent, was above the plate for the 20 periods
        // before; up to 0.02 period after, the plate is still on the concave arc below the tangent.
        const double theta = M_PI / 2.0 + 0.1 + (M_PI / 2.0 - 0.4) * u(rng);
        const double t_star = 0.1 + u(rng);
        const Graze exact = graze_at(theta, t_star, 0.0);
        const double t_begin = t_star - 20.5 * period, t_end = t_star + 0.02 * period;
        PlaneContact contact;
        ASSERT_EQ(vibrating_plane_toi(exact.path, kPlaneR, exact.plane, t_begin, t_end, contact), ToiStatus::impact) << theta;
        // A double root is ill-conditioned: the ~1e-19 m rounding of the constructed gap moves it
        // by sqrt(2e-19 / h''), below 1e-12 s.
        EXPECT_NEAR(contact.time, t_star, 2e-12) << theta;
        const Exact e_exact(exact.path, kPlaneR, exact.plane);
        EXPECT_TRUE(std::isnan(certified_first_contact(e_exact, t_begin, t_star - 1e-9))) << theta;
        // 0.1 nm higher it is a near miss; 0.1 nm lower, two roots 2 sqrt(2e-10 / h'') ~ 50 ns
        // apart, which 32 samples a period (1.6 us) would step over.
        const Graze above = graze_at(theta, t_star, 1e-10);
        EXPECT_EQ(vibrating_plane_toi(above.path, kPlaneR, above.plane, t_begin, t_end, contact), ToiStatus::miss) << theta;
        EXPECT_TRUE(std::isnan(certified_first_contact(Exact(above.path, kPlaneR, above.plane), t_begin, t_end)));
        const Graze below = graze_at(theta, t_star, -1e-10);
        ASSERT_EQ(vibrating_plane_toi(below.path, kPlaneR, below.plane, t_begin, t_end, contact), ToiStatus::impact);
        const Exact e(below.path, kPlaneR, below.plane);
        const double curvature = static_cast<double>(e.curvature(t_star));
        // ~ t_star - sqrt(2e-10 / h''), to the few per cent the jerk A w^3 moves it.
        EXPECT_NEAR(contact.time, t_star - std::sqrt(2e-10 / curvature), 0.1 * std::sqrt(2e-10 / curvature));
        EXPECT_NEAR(contact.time, static_cast<double>(certified_first_contact(e, t_begin, t_end)), 1e-12);
    }
}

TEST(EventVibratingPlane, LongFlightAboveTheBandCostsNothing) {
    // Thrown up at 2.5 m/s from 1 mm above the band: 0.51 s (10^4 periods) of flight. Before the
    // return the query is a miss without examining a single piece; the return is found exactly
    // with a handful of pieces.
    const VibratingPlane plane = sonotrode(0.4);
    const double t0 = 1.25;
    const Trajectory path{Vec3(0.001, 0.002, kPlaneR + kA + 1e-3), Vec3(0.1, 0.0, 2.5), kPlaneGravity, t0};
    PlaneContact contact;
    PlaneToiWork work;
    EXPECT_EQ(vibrating_plane_toi(path, kPlaneR, plane, t0, t0 + 0.5, contact, &work), ToiStatus::miss);
    EXPECT_EQ(work.windows, 0);
    EXPECT_EQ(work.pieces, 0);

    work = PlaneToiWork{};
    ASSERT_EQ(vibrating_plane_toi(path, kPlaneR, plane, t0, t0 + 1.0, contact, &work), ToiStatus::impact);
    EXPECT_GT(contact.time - t0, 0.5);
    EXPECT_LE(work.windows, 1);
    EXPECT_LE(work.pieces, 6);
    const Exact exact(path, kPlaneR, plane);
    EXPECT_NEAR(contact.time, static_cast<double>(reference_contact(exact, t0, t0 + 1.0, 1 << 20)), 1e-12);
}

TEST(EventVibratingPlane, ContactAfterThousandsOfPeriodsFromInsideTheBand) {
    // Launched from the plate (the band's first window is crossed on the way up), a return after
    // 2v/g ~ 0.3 s = 6000 periods: two windows, few pieces, exact.
    const double t = 3.7;
    const VibratingPlane plane = sonotrode(1.1);
    const Trajectory path = on_the_plate(plane, t, 1.5);
    PlaneContact contact;
    PlaneToiWork work;
    ASSERT_EQ(vibrating_plane_toi(path, kPlaneR, plane, t, t + 1.0, contact, &work), ToiStatus::impact);
    EXPECT_GT(contact.time - t, 0.25);
    EXPECT_EQ(work.windows, 2);
    EXPECT_LE(work.pieces, 12);
    const Exact exact(path, kPlaneR, plane);
    EXPECT_NEAR(contact.time, static_cast<double>(reference_contact(exact, leave(exact, t), t + 1.0, 1 << 20)), 1e-12);
}

// Random drops: a shot above a random plate, thrown anywhere from 2 m/s down to 1 m/s up.
void random_drops(std::uint64_t seed, int trials, double t_min, double t_span, long dense_trials, const char* what) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Tally tally;
    for (int trial = 0; trial < trials; ++trial) {
        const bool ceiling = u(rng) < 0.1;  // a plate above, the shot thrown up at it
        const VibratingPlane plane = random_plate(rng, ceiling);
        const double t_begin = t_min + t_span * u(rng);
        const double band = std::fabs(plane.amplitude_m * plane.normal.dot(plane.axis));
        const double height = band + 1e-6 + 5e-3 * u(rng) * u(rng);  // m, static gap at t_begin
        const Vec3 foot = plane.point_m + Vec3(0.01 * u(rng) - 0.005, 0.01 * u(rng) - 0.005, 0.0);
        Vec3 v(u(rng) - 0.5, u(rng) - 0.5, ceiling ? 0.3 + 1.7 * u(rng) : 1.0 - 3.0 * u(rng));
        const Vec3 centre = foot + (kPlaneR + height - plane.normal.dot(foot - plane.point_m)) * plane.normal;
        const Trajectory path{centre, v, kPlaneGravity, t_begin};
        const double t_end = t_begin + (u(rng) < 0.1 ? 0.02 : 0.8) * u(rng);
        check_against_reference(path, plane, t_begin, t_end, t_begin, trial < dense_trials ? (1L << 20) : 64, tally, what, trial);
    }
    EXPECT_GT(tally.impacts, trials / 2);
    std::printf("[ %s ] %d impacts, %d misses, worst |t - reference| %.3g s\n", what, tally.impacts, tally.misses, tally.worst);
}

TEST(EventVibratingPlane, RandomDropsMatchTheDenseReference) { random_drops(1, 3000, 0.0, 2.0, 200, "drops"); }

TEST(EventVibratingPlane, PhaseStaysAccurateNearSixtySeconds) {
    // w t ~ 7.5e6 rad: the kernel's times and plate velocities agree with the long double
    // reference (whose phase error is ~4e-13 rad); a phase from the plain product w t would be
    // off by ~1e-9 rad, 3e-9 m/s of plate velocity, far beyond the 1e-11 relative check.
    random_drops(7, 500, 59.5, 1.0, 50, "t ~ 60 s");
}

TEST(EventVibratingPlane, EmptyOrReversedIntervalIsAMiss) {
    const VibratingPlane plane = sonotrode();
    const Trajectory path{Vec3(0, 0, kPlaneR + 1e-3), Vec3::Zero(), kPlaneGravity, 0.0};
    PlaneContact contact;
    EXPECT_EQ(vibrating_plane_toi(path, kPlaneR, plane, 0.1, 0.05, contact), ToiStatus::miss);
    EXPECT_EQ(vibrating_plane_toi(path, kPlaneR, plane, 0.0, 0.0, contact), ToiStatus::miss);
    EXPECT_GT(vibrating_plane_gap(path, kPlaneR, plane, 0.0), 0.0);
}

}  // namespace
}  // namespace peensim
