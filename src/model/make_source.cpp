#include "model/make_source.h"

#include "model/hopper_source.h"
#include "model/nozzle_source.h"

namespace peensim {

std::shared_ptr<const ShotSource> make_source(const SourceDesc& d, int index, double stop_s, std::uint64_t seed,
                                              const std::vector<double>& size_count_fraction) {
    switch (d.kind) {
        case SourceKind::hopper: {
            HopperSpec spec;
            spec.name = d.name;
            spec.opening_lo_m = d.opening->lo_m;
            spec.opening_hi_m = d.opening->hi_m;
            spec.rate_per_s = d.rate_per_s;
            spec.start_s = d.start_s;
            spec.stop_s = stop_s;
            spec.seed = seed;
            spec.index = index;
            spec.size_count_fraction = size_count_fraction;
            return std::make_shared<const HopperSource>(spec);
        }
        case SourceKind::nozzle: break;
    }
    NozzleSpec spec;
    spec.name = d.name;
    spec.position_m = d.position_m;
    spec.direction = d.direction;
    spec.exit_radius_m = d.exit_radius_m;
    spec.speed_m_per_s = d.speed_m_per_s;
    spec.speed_spread = d.speed_spread;
    spec.spread_rad = d.spread_rad;
    spec.rate_per_s = d.rate_per_s;
    spec.start_s = d.start_s;
    spec.stop_s = stop_s;
    spec.seed = seed;
    spec.index = index;
    spec.size_count_fraction = size_count_fraction;
    return std::make_shared<const NozzleSource>(spec);
}

}  // namespace peensim
