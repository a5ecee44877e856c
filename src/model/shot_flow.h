// Where shot enter and leave a run besides the initial load: sources emit shot during the run
// (a conventional peening nozzle), sinks take them out (an outlet, a hopper: collected, not lost).
// Both are part of the compiled model and pluggable: the schemes see only these interfaces.
//
// A source's emissions are numbered; emission k's time, centre and velocity are a function of the
// source, the scene's seed and k alone (counter-based random numbers), so a run resumed from a
// checkpoint (which keeps how many each source has emitted) emits exactly the same shot.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/vec.h"
#include "kernels/trajectory.h"

namespace peensim {

struct Emission {
    double time_s = 0.0;                   // s, absolute
    Vec3 position_m = Vec3::Zero();        // m, world, the shot's centre then
    Vec3 velocity_m_per_s = Vec3::Zero();  // m/s, world
    int size = 0;                          // index into Model::shot_sizes
};

class ShotSource {
public:
    virtual ~ShotSource() = default;
    virtual const std::string& name() const = 0;
    // Emission k (0, 1, ...), or none: the source has stopped before it. `attempt` > 0 draws the
    // same emission again elsewhere (same time; another point, direction and speed), for when the
    // first draw would overlap a shot already there.
    virtual std::optional<Emission> emission(std::uint64_t k, unsigned attempt = 0) const = 0;
};

class ShotSink {
public:
    virtual ~ShotSink() = default;
    virtual const std::string& name() const = 0;
    // The centre p (m, world) is in the sink: the shot is collected.
    virtual bool contains(const Vec3& p) const = 0;
    // The first time in [ta, tb] (s, the path's clock) the centre on `path` is in the sink, or none.
    virtual std::optional<double> first_entry(const Trajectory& path, double ta, double tb) const = 0;
};

// A nozzle: shot leave a disc of radius `exit_radius_m` centred on `position_m`, facing
// `direction`, at speeds uniform in `speed` (1 +- `speed_spread`), in directions uniform over the
// cone of half-angle `spread_rad` about `direction`, at points uniform over the disc; `rate_per_s`
// shot per second from `start_s` until `stop_s` (s, absolute), emission k at start + k / rate.
struct NozzleSpec {
    std::string name;
    Vec3 position_m = Vec3::Zero();
    Vec3 direction = -Vec3::UnitZ();  // unit
    double exit_radius_m = 0.0;
    double speed_m_per_s = 0.0;  // m/s, the mean exit speed v0
    double speed_spread = 0.0;   // -, exit speeds uniform in v0 (1 +- speed_spread)
    double spread_rad = 0.0;
    double rate_per_s = 0.0;
    double start_s = 0.0;
    double stop_s = 0.0;
    std::uint64_t seed = 1;  // the scene's seed (mixed with the source's index)
    int index = 0;           // the source's place in the scene
    // -, the count share of each shot size (Model::size_count_fraction); empty for one size.
    std::vector<double> size_count_fraction;
};

class NozzleSource final : public ShotSource {
public:
    explicit NozzleSource(const NozzleSpec& spec);
    const std::string& name() const override { return spec_.name; }
    std::optional<Emission> emission(std::uint64_t k, unsigned attempt = 0) const override;
    const NozzleSpec& spec() const { return spec_; }

private:
    // The seed of emission k's draw `attempt`: the scene's seed, the source and k mixed (Random's
    // SplitMix64 seeding spreads neighbouring seeds), the attempt above bit 40 (k never gets there).
    std::uint64_t emission_stream(std::uint64_t k, unsigned attempt) const;
    static constexpr unsigned kSizeStream = 255;  // the size's own stream: never a redraw's attempt (at most 32)
    NozzleSpec spec_;
    Vec3 e1_, e2_;  // unit, completing `direction` to a right-handed frame
};

// The dimensionless flow rate of a nozzle, eps = r_m D / (v0 m_shot) = rate D / v0 (r_m the mass
// flow, kg/s; D the shot diameter, m): the conventional-peening study's measure of how crowded the
// jet is (0.667 for 5.5 kg/min of 0.58 mm shot at 100 m/s, 3.154 for 13 kg/min at 50 m/s). For a
// mix D is the mean diameter of the shot emitted (weighted by count): shot per diameter travelled.
inline double nozzle_flow_rate_eps(const NozzleSpec& n, double shot_diameter_m) { return n.rate_per_s * shot_diameter_m / n.speed_m_per_s; }

// An axis-aligned box (world frame). Side inside: a shot whose centre enters it is collected (an
// outlet, a hopper's opening). Side outside: a shot whose centre leaves it is (the chamber's
// bounds, for an open setup, a nozzle over a part in a cabinet not modelled: a shot flying away is
// collected, not lost).
class BoxSink final : public ShotSink {
public:
    enum class Side { inside, outside };
    BoxSink(std::string name, const Vec3& lo_m, const Vec3& hi_m, Side side) : name_(std::move(name)), lo_(lo_m), hi_(hi_m), side_(side) {}
    const std::string& name() const override { return name_; }
    bool contains(const Vec3& p) const override;
    std::optional<double> first_entry(const Trajectory& path, double ta, double tb) const override;

private:
    std::string name_;
    Vec3 lo_, hi_;  // m
    Side side_;
};

}  // namespace peensim
