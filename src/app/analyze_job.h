// `peensim analyze OUTDIR` (also run at the end of `peensim run` unless --no-analyze): streams a
// run's impact log once and writes, into OUTDIR/analysis/, per logged component: per-triangle
// fields (CSV), coverage (SAE J2277, dents from eq. 10) vs time with its Avrami fit, histograms of
// normal speed, impact angle and dent diameter, and report.md putting the numbers on one page.
#pragma once

#include <iosfwd>
#include <string>

namespace peensim {

int analyze_job(const std::string& output_dir, std::ostream& out, std::ostream& err);

// The same, with errors thrown (InputError for a bad scene, std::runtime_error for a directory
// that is not a run's) instead of reported: for a caller with exceptions of its own (Python).
void analyze_run(const std::string& output_dir, std::ostream& out, std::ostream& err);

}  // namespace peensim
