#include "model/make_source.h"

#include "model/hopper_source.h"
#include "model/nozzle_source.h"

namespace peensim {

std::shared_ptr<const ShotSource> make_source(const SourceDesc& d, int index, double stop_s, std::uint64_t seed,
                                              const std::vector<double>& size_count_fraction) {
    const EmissionPlan plan{d.name, d.rate_per_s, d.start_s, stop_s, seed, index, size_count_fraction};
    switch (d.kind) {
        case SourceKind::hopper: return std::make_shared<const HopperSource>(HopperSpec{plan, d.opening->lo_m, d.opening->hi_m});
        case SourceKind::nozzle: break;
    }
    return std::make_shared<const NozzleSource>(
        NozzleSpec{plan, d.position_m, d.direction, d.exit_radius_m, d.speed_m_per_s, d.speed_spread, d.spread_rad});
}

}  // namespace peensim
