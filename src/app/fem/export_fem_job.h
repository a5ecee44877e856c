// `peensim export-fem RUNDIR -o OUTDIR`: hands the impacts of a patch of a logged part to a
// finite-element model. Writes OUTDIR/<name>.inp, an Abaqus-format input deck (CalculiX reads it:
// `ccx -i <name>`), in SI units: the block of the part's material under a circular patch (C3D8I
// bricks by default, fine near the impacts, elastic-plastic), one elastic steel ball per impact
// placed just above its point with its logged velocity, penalty contact, one implicit dynamic step
// per group of impacts far enough apart (src/fem/impact_steps.h) and a static relaxation step (the
// residual state); OUTDIR/impacts.csv (which impact went into which step) and OUTDIR/README.md
// (what the deck holds and how to run it). Before writing, it prints the element count and the
// CalculiX time and memory the cost model (fem/ccx_cost.h) expects, with a warning when impractical.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

namespace peensim {

struct ExportFemOptions {
    std::string run_dir;             // the run's output directory ("" only with --single)
    std::string output_dir;          // -o: where the deck goes
    std::string name = "patch";      // --name: the deck's file name without .inp (ccx's job name; output/output_names.h)
    std::string component;           // --component: the logged part ("" = the only one)
    std::string center;              // --center x,y,z: the patch centre, component frame (lengths with units)
    std::string radius;              // --radius: the patch radius ("" = max(3 R, 2 dent diameters))
    std::string region;              // --region: a region of the component (centre and impacts from it)
    std::optional<int> max_impacts;  // --impacts N (>= 1): the first N impacts of the patch (none: all)
    std::string single;              // --single x,y,z,vx,vy,vz: one synthetic impact instead of the run's
    std::string shot_diameter;       // --shot-diameter: the shot without a run directory; a mix run: whose impacts
    std::string yield_stress;        // --yield-stress: the target's (default: its material's, else steel's)
    std::string hardening;           // --hardening: slope of yield stress against plastic strain (default 0)
    std::string element_size;  // --element-size: fine elements' edge ("" = the patch's 10th-percentile dent, at least half its median, /
                               // elements_per_dent)
    double elements_per_dent = 6.0;     // --elements-per-dent
    int shot_divisions = 8;             // --shot-divisions: cells along the shot mesh's cube edge (even)
    std::string element = "C3D8I";      // --element: the block's brick, C3D8I | C3D8R | C3D8 (fem/fem_deck.h)
    std::string dynamics = "explicit";  // --dynamics: the impacts' steps, explicit | implicit (fem/fem_deck.h)
    bool quarter = false;               // --quarter: quarter model (one normal impact at the centre)
    std::string group_window = "1 ms";  // --group-window: a step spans at most this much of the run's time
    double contact_times = 2.5;         // --contact-times: a step lasts this many Hertz contact times
};

// Returns kExitOk, kExitInputError (bad option, run directory, centre, no impact in the patch) or
// kExitRuntimeError (I/O).
int export_fem_job(const ExportFemOptions& options, std::ostream& out, std::ostream& err);

}  // namespace peensim
