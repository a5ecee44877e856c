// A hopper: shot drop out of an opening at a steady rate, at rest, and fall (a feed that tops up
// an ultrasonic chamber, a cabinet's gravity feed). The opening is a box (world frame); emission k
// leaves at start + k / rate from a point uniform over it, with no velocity, until `stop_s`. A
// shot that would overlap one already there is drawn again elsewhere in the box (ShotSource's
// `attempt`).
#pragma once

#include <string>
#include <vector>

#include "model/shot_flow.h"

namespace peensim {

struct HopperSpec {
    std::string name;
    Vec3 opening_lo_m = Vec3::Zero();  // m, world: the box shot centres start in (lo <= hi)
    Vec3 opening_hi_m = Vec3::Zero();
    double rate_per_s = 0.0;
    double start_s = 0.0;
    double stop_s = 0.0;
    std::uint64_t seed = 1;                   // the scene's seed (mixed with the source's index)
    int index = 0;                            // the source's place in the scene
    std::vector<double> size_count_fraction;  // -, per shot size (Model::size_count_fraction); empty for one size
};

class HopperSource final : public ShotSource {
public:
    explicit HopperSource(const HopperSpec& spec) : spec_(spec) {}
    const std::string& name() const override { return spec_.name; }
    std::optional<Emission> emission(std::uint64_t k, unsigned attempt = 0) const override;
    SourceOutline outline() const override;

private:
    HopperSpec spec_;
};

}  // namespace peensim
