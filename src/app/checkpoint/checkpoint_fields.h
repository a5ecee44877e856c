// A checkpoint's fields, declared once: the run's own (the scene it belongs to, how far the impact
// log got, the running statistics) around the simulation state's (engine/saved_state.h). The
// writer, the reader, the checks and the list of names all walk this.
#pragma once

#include "app/checkpoint/checkpoint.h"
#include "engine/saved_state.h"

namespace peensim {

template <class C, class Fields>  // C: Checkpoint or const Checkpoint
void checkpoint_fields(C& c, Fields& f) {
    f.value("scene_hash", c.scene_hash, 1);
    saved_state_fields(c.state, f);
    f.value("csv_bytes", c.csv_bytes, 1);
    f.value("csv_rows", c.csv_rows, 1);
    f.records("normal_speeds", c.normal_speeds, 1, Extent::logged_components, [](auto& h, auto& g) { g.value("histogram", h, 1); });
    f.value("wall_time_s", c.wall_time_s, 1);
    f.value("log_shift_s", c.log_shift_s, 11);
    f.array("replica_impacts", c.replica_impacts, 11, Extent::free);
    f.array("replica_slow_contacts", c.replica_slow_contacts, 11, Extent::free);
}

}  // namespace peensim
