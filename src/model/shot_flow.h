// Where shot enter and leave a run besides the initial load: sources emit shot during the run (a
// conventional peening nozzle, model/nozzle_source.h; a hopper dropping shot, model/hopper_source.h),
// sinks take them out (an outlet, a hopper's mouth: collected, not lost). Both are part of the
// compiled model and pluggable: the schemes, the checks and the reports see only these interfaces
// (model/make_source.h is the one place that knows every kind of source).
//
// A source's emissions are numbered; emission k's time, centre and velocity are a function of the
// source, the scene's seed and k alone (counter-based random numbers), so a run resumed from a
// checkpoint (which keeps how many each source has emitted) emits exactly the same shot.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
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

// A directed stream of shot (a nozzle's jet): what the conventional-peening figures need.
struct SourceJet {
    Vec3 exit_m = Vec3::Zero();  // m, world, the centre its shot leave
    Vec3 axis = -Vec3::UnitZ();  // unit, world
    double speed_m_per_s = 0.0;  // m/s, the mean exit speed v0
};

// What every kind of source tells the checks and the reports (check, summary, analysis, ParaView),
// so that none of them needs to know the kind.
struct SourceOutline {
    std::string kind;                                           // the scene's `sources[].kind`: nozzle, hopper
    double rate_per_s = 0.0;                                    // shot per second while it emits
    double start_s = 0.0, stop_s = 0.0;                         // s, absolute: emissions in [start, stop)
    double fastest_speed_m_per_s = 0.0;                         // m/s, the fastest shot it starts
    Vec3 start_lo_m = Vec3::Zero(), start_hi_m = Vec3::Zero();  // m, world: the box its shot's centres start in
    std::optional<SourceJet> jet;                               // a directed stream; none for a source that drops its shot
    std::string start_place;                                    // its kind's word for where its shot start: "exit", "opening"
    std::string start_keys;                                     // the scene keys that place it: "position, or target and distance"
    std::string how;                                            // "at 100 m/s from its exit at (0, 0, 50) mm": for `check`
};

class ShotSource {
public:
    virtual ~ShotSource() = default;
    virtual const std::string& name() const = 0;
    // Emission k (0, 1, ...), or none: the source has stopped before it. `attempt` > 0 draws the
    // same emission again elsewhere (same time; another point, direction and speed), for when the
    // first draw would overlap a shot already there.
    virtual std::optional<Emission> emission(std::uint64_t k, unsigned attempt = 0) const = 0;
    virtual SourceOutline outline() const = 0;
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

// m/s, the fastest shot any of `sources` starts (0 without sources).
inline double fastest_start_speed_m_per_s(const std::vector<std::shared_ptr<const ShotSource>>& sources) {
    double fastest = 0.0;
    for (const auto& s : sources) fastest = std::max(fastest, s->outline().fastest_speed_m_per_s);
    return fastest;
}

// The dimensionless flow rate of a jet, eps = r_m D / (v0 m_shot) = rate D / v0 (r_m the mass
// flow, kg/s; D the shot diameter, m): the conventional-peening study's measure of how crowded the
// jet is (0.667 for 5.5 kg/min of 0.58 mm shot at 100 m/s, 3.154 for 13 kg/min at 50 m/s). For a
// mix D is the mean diameter of the shot emitted (weighted by count): shot per diameter travelled.
inline double jet_flow_rate_eps(double rate_per_s, const SourceJet& jet, double shot_diameter_m) {
    return rate_per_s * shot_diameter_m / jet.speed_m_per_s;
}

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
