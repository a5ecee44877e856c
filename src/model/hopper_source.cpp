#include "model/hopper_source.h"

#include "common/random.h"
#include "model/emission_draw.h"
#include "model/shot_cavity.h"

namespace peensim {

std::optional<Emission> HopperSource::emission(std::uint64_t k, unsigned attempt) const {
    const std::optional<double> t = emission_time(spec_.plan, k);
    if (!t) return std::nullopt;
    Emission e;
    e.time_s = *t;
    Random rng(emission_stream(spec_.plan, k, attempt));
    for (int a = 0; a < 3; ++a) e.position_m[a] = spec_.opening_lo_m[a] + rng.uniform() * (spec_.opening_hi_m[a] - spec_.opening_lo_m[a]);
    e.velocity_m_per_s = Vec3::Zero();  // dropped: gravity does the rest
    e.size = emission_size(spec_.plan, k);
    return e;
}

SourceOutline HopperSource::outline() const {
    SourceOutline o = outline_of(spec_.plan, "hopper");
    o.fastest_speed_m_per_s = 0.0;
    o.start_lo_m = spec_.opening_lo_m;
    o.start_hi_m = spec_.opening_hi_m;
    o.start_place = "opening";
    o.start_keys = "opening_min and opening_max";
    o.how = "dropped at rest from the box " + mm_point(spec_.opening_lo_m) + " to " + mm_point(spec_.opening_hi_m);
    return o;
}

}  // namespace peensim
