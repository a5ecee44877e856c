// A nozzle (conventional peening): shot leave a disc of radius `exit_radius_m` centred on
// `position_m`, facing `direction`, at speeds uniform in `speed` (1 +- `speed_spread`), in
// directions uniform over the cone of half-angle `spread_rad` about `direction`, at points uniform
// over the disc, as its plan says when (model/emission_draw.h).
#pragma once

#include "model/emission_draw.h"
#include "model/shot_flow.h"

namespace peensim {

struct NozzleSpec {
    EmissionPlan plan;
    Vec3 position_m = Vec3::Zero();
    Vec3 direction = -Vec3::UnitZ();  // unit
    double exit_radius_m = 0.0;
    double speed_m_per_s = 0.0;  // m/s, the mean exit speed v0
    double speed_spread = 0.0;   // -, exit speeds uniform in v0 (1 +- speed_spread)
    double spread_rad = 0.0;
};

class NozzleSource final : public ShotSource {
public:
    explicit NozzleSource(const NozzleSpec& spec);
    const std::string& name() const override { return spec_.plan.name; }
    std::optional<Emission> emission(std::uint64_t k, unsigned attempt = 0) const override;
    SourceOutline outline() const override;
    const NozzleSpec& spec() const { return spec_; }

private:
    NozzleSpec spec_;
    Vec3 e1_, e2_;  // unit, completing `direction` to a right-handed frame
};

}  // namespace peensim
