// The ParaView files that name other files: a time series (.pvd, "Collection": one data file per
// time step) and a multiblock (.vtm: one named data file per block). File names are relative to
// the collection file's directory, so a run directory can be moved. Both are written atomically
// (`path.tmp` renamed over `path`): a reader sees the previous list or the new one.
#pragma once

#include <span>
#include <string>

#include "output/atomic_file.h"

namespace peensim {

struct TimeStepFile {
    double time_s = 0.0;  // s
    std::string file;     // relative to the .pvd's directory
};

// Throws std::runtime_error (path + errno text) when the file cannot be written.
void write_pvd(const std::string& path, std::span<const TimeStepFile> steps, Durability durability = Durability::power_cut);

struct NamedBlock {
    std::string name;  // shown in ParaView's block list
    std::string file;  // relative to the .vtm's directory
};

void write_vtm(const std::string& path, std::span<const NamedBlock> blocks);

}  // namespace peensim
