// `peensim almen-fit CURVE.csv`: a measured Almen saturation curve fitted per SAE J443 practice
// (analysis/saturation_fit.h: the 2P and 3P exponential forms, the saturation point where doubling
// the exposure raises the arc height by 10 %), with the intensity in mm, inches and thou, the
// saturation time in the curve's unit, J443's conditions checked (warnings), and which fit to use.
// With --calibrate RUNDIR it also prints the predictive model's calibration (analysis/almen_model.h)
// on the run that reproduced the measurement, for the scene's `almen.calibration`.
#pragma once

#include <iosfwd>
#include <string>

namespace peensim {

struct AlmenFitOptions {
    std::string curve_path;     // the measured curve (CSV: header, then exposure, arc height)
    std::string time_unit;      // --time-unit: s, min, h, passes, cycles ("" = from the header)
    std::string height_unit;    // --height-unit: mm, um, in, thou ("" = from the header)
    std::string strip;          // --strip: A, N or C ("" = not given)
    std::string form;           // --form: 2P or 3P ("" = the recommended one)
    std::string json_path;      // --json: also write the figures as JSON here
    std::string plot_path;      // --plot: draw the points and fits to this PNG (gnuplot)
    std::string calibrate_run;  // --calibrate: the run directory that reproduced the measurement
    std::string component;      // --component: the strip in that run ("" = its only Almen strip)
};

// Returns kExitOk, or kExitInputError (a bad file or option, a curve without a saturation point,
// a run without the strip's dent figures).
int almen_fit_job(const AlmenFitOptions& options, std::ostream& out, std::ostream& err);

}  // namespace peensim
