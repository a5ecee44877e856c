// A hopper: shot drop out of an opening at a steady rate, at rest, and fall (a feed that tops up
// an ultrasonic chamber, a cabinet's gravity feed). The opening is a box (world frame); emission k
// leaves from a point uniform over it, with no velocity, as its plan says when
// (model/emission_draw.h). A shot that would overlap one already there is drawn again elsewhere in
// the box (ShotSource's `attempt`).
#pragma once

#include "model/emission_draw.h"
#include "model/shot_flow.h"

namespace peensim {

struct HopperSpec {
    EmissionPlan plan;
    Vec3 opening_lo_m = Vec3::Zero();  // m, world: the box shot centres start in (lo <= hi)
    Vec3 opening_hi_m = Vec3::Zero();
};

class HopperSource final : public ShotSource {
public:
    explicit HopperSource(const HopperSpec& spec) : spec_(spec) {}
    const std::string& name() const override { return spec_.plan.name; }
    std::optional<Emission> emission(std::uint64_t k, unsigned attempt = 0) const override;
    SourceOutline outline() const override;

private:
    HopperSpec spec_;
};

}  // namespace peensim
