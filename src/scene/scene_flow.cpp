// The `sources` and `sinks` sections: where shot enter and leave a run besides the initial load.
#include <set>

#include "scene/scene_sections.h"

namespace peensim {

namespace {

std::string checked_name(const Cursor& c, std::set<std::string>& taken) {
    const std::string name = read_text(c);
    if (!is_valid_name(name)) fail(c, "invalid name '" + name + "'; names use only A-Z a-z 0-9 _ -");
    if (!taken.insert(name).second) fail(c, "duplicate name '" + name + "'; source and sink names must be unique");
    return name;
}

}  // namespace

void read_flow(const Cursor& sources, const Cursor& sinks, double duration_s, std::vector<SourceDesc>& out_sources,
               std::vector<SinkDesc>& out_sinks) {
    std::set<std::string> names;
    for (std::size_t i = 0; i < sources.size(); ++i) {
        const Cursor c = sources.item(i);
        SourceDesc d;
        d.name = checked_name(c.child("name"), names);
        d.position_m = read_vector(c.child("position"));
        d.direction = *read_optional_direction(c.child("direction"));
        d.speed_m_per_s = read_quantity(c.child("speed"));
        d.rate_per_s = read_quantity(c.child("rate"));
        d.exit_radius_m = read_quantity(c.child("exit_radius"));
        d.spread_rad = read_quantity(c.child("spread"));
        d.start_s = read_quantity(c.child("start"));
        d.stop_s = c.child("stop").present() ? read_quantity(c.child("stop")) : duration_s;
        if (!(d.stop_s > d.start_s)) fail(c.child("stop"), "expected a stop after the start (" + format_si(d.start_s) + " s)");
        d.where = location_of(c);
        out_sources.push_back(d);
    }
    for (std::size_t i = 0; i < sinks.size(); ++i) {
        const Cursor c = sinks.item(i);
        SinkDesc d;
        d.name = checked_name(c.child("name"), names);
        d.region = read_choice(c.child("region")) == "outside" ? SinkRegion::outside : SinkRegion::box;
        if (d.region == SinkRegion::box) {
            if (!c.child("min").present()) fail(c.child("min"), "missing required key 'min' (a box sink needs its corners)");
            if (!c.child("max").present()) fail(c.child("max"), "missing required key 'max' (a box sink needs its corners)");
            d.min_m = read_vector(c.child("min"));
            d.max_m = read_vector(c.child("max"));
            if (!((d.max_m.array() > d.min_m.array()).all())) fail(c.child("max"), "expected max > min in x, y and z");
        } else {
            for (const char* key : {"min", "max"})
                if (c.child(key).present()) fail(c.child(key), std::string("'") + key + "' is only for region box");
        }
        d.where = location_of(c);
        out_sinks.push_back(d);
    }
}

}  // namespace peensim
