// `peensim trade SCENE`: the speed/accuracy trade, knob by knob. Runs the scene (its contacts
// `hertz-mindlin`, so that every scheme runs the same material data) with each accuracy knob --
// the rigid event-driven scheme (instantaneous impacts: the law's limit), time stepping at several
// travel fractions, the soft scheme at several integration resolutions and at reduced stiffness --
// against a converged reference (the soft scheme at the finest resolution), and prints for the
// logged part the impact rate, the mean and p90 normal speed and the coverage after the run, each
// with its standard error, the error against the reference (in % and in combined standard errors)
// and the wall time; optionally a CSV and a gnuplot picture of error against wall time.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace peensim {

struct TradeOptions {
    std::string scene_path;
    std::vector<std::string> overrides;  // --set path=value, for every knob
    std::string duration;                // --duration: process.duration ("" = the scene's)
    std::string settle;                  // --settle: time left out of rates and speeds, >= 0 ("" = a tenth of the run)
    double reference_steps = 80.0;       // --reference-steps: the reference's soft steps per contact
    int seeds = 1;                       // --seeds: runs per knob (seeds process.seed, +1, ...), their figures averaged
    std::string csv_path;                // --csv: every figure; "" = none
    std::string plot_path;               // --plot: PNG of error against wall time (gnuplot); "" = none
};

// Returns kExitOk, kExitInputError (a bad scene or option, or a scene whose contacts are not all
// `hertz-mindlin`), or kExitRuntimeError.
int trade_job(const TradeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace peensim
