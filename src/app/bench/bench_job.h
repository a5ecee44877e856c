// `peensim bench`: runs two (or more) stepping schemes side by side on the same scenes in one
// process, without writing impact files, and prints how much faster one is and whether their
// impact statistics agree within statistical noise (issue 5: `event` against `step`).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace peensim {

struct BenchOptions {
    std::vector<std::string> scene_paths;  // empty: every *.yaml of the shipped scenes/ directory
    std::vector<std::string> overrides;    // --set path=value, applied to every scene and scheme
    std::string duration;                  // --duration: process.duration of every scene ("0.5", "500 ms"); "" = each scene's own
    // --schemes: two or more, each `step`, `event`, or either followed by its own overrides
    // (`step:accuracy.travel_fraction=0.1`, ':'-separated); every scheme is compared with the first.
    std::vector<std::string> schemes{"step", "event"};
    std::string csv_path;         // --csv: also write every figure there; "" = no CSV
    std::string executable_path;  // where the shipped scenes are looked for from; "" = /proc/self/exe
};

// Runs every scene with every scheme and prints a table per scene, the comparisons and a summary
// line per scene to `out`. Returns kExitOk when every run finished (differences are reported, not
// failures), kExitInputError for a bad scene, option or missing scenes directory, kExitRuntimeError
// otherwise (a scheme that throws, a CSV that cannot be written).
int bench_job(const BenchOptions& options, std::ostream& out, std::ostream& err);

// Directories searched for the shipped scenes, in order: <exe dir>/scenes, <exe dir>/../scenes
// (the binary is build/peensim), and <PEENSIM_SOURCE_DIR>/scenes when the build defines it.
std::vector<std::string> shipped_scene_search_dirs(const std::string& executable_path);

// The *.yaml files of the first search directory that has any, sorted by name. Throws InputError
// naming every directory it looked in when none has.
std::vector<std::string> shipped_scenes(const std::string& executable_path);

// Number of equal time batches a run is split into for the batch-means standard errors.
inline constexpr int kBenchBatches = 10;

// Impact count and normal-speed statistics of one component (or several together) over a run of
// `duration_s`, with standard errors by batch means: impacts are strongly correlated in time
// (the same few shot bounce between the same surfaces, the sonotrode phase repeats), so the
// naive sqrt(N) and sigma/sqrt(N) errors would be far too small; the spread between
// kBenchBatches consecutive time batches is an honest estimate as long as a batch is much longer
// than the correlation time (a batch of a 1 s run is 0.1 s, thousands of sonotrode periods and
// many flights). The start-up transient (shot resting on the sonotrode at t = 0) stays in the
// first batch and widens the errors rather than hiding.
class BatchedImpactStats {
public:
    explicit BatchedImpactStats(double duration_s = 1.0);

    void add(double time_s, double vn_m_per_s);   // s from the start of the run, m/s normal approach speed
    void merge(const BatchedImpactStats& other);  // same duration

    std::uint64_t count() const { return count_; }
    double rate_per_s() const;             // 1/s, impacts per simulated second
    double rate_se_per_s() const;          // 1/s, standard error of the rate (batch means)
    double mean_speed_m_per_s() const;     // m/s, mean normal speed; NaN without impacts
    double mean_speed_se_m_per_s() const;  // m/s, its standard error (ratio estimator over batches); NaN without impacts

private:
    double duration_s_;
    std::uint64_t count_ = 0;
    double speed_sum_ = 0.0;  // m/s, summed normal speeds
    std::uint64_t batch_count_[kBenchBatches]{};
    double batch_speed_sum_[kBenchBatches]{};  // m/s
};

// The relative difference of b from a and whether it is within noise: |b - a| <= 3 sqrt(se_a^2 + se_b^2).
struct BenchDifference {
    double percent = 0.0;        // %, 100 (b - a) / a; NaN when a is 0 or either value is NaN
    double bound_percent = 0.0;  // %, 100 x 3 combined standard errors / a
    bool within_noise = true;    // also true when there is nothing to compare (NaN)
};
BenchDifference bench_difference(double a, double se_a, double b, double se_b);

}  // namespace peensim
