// A run's output directory belongs to one run at a time, and holds one run's outputs.
// Users found two runs started into the same directory mixing their rows in one impacts.csv
// (a malformed row, time going backwards) with a summary of one and a scene of the other, and a
// fresh run killed early leaving the previous run's summary.json (finished: true) and analysis/
// beside its own scene. A run now holds an exclusive lock on the directory for its whole life
// (flock on DIR/.peensim.lock, released by the kernel however the process ends), and a fresh run
// (not --resume) first removes the outputs a previous run left there (only the files and
// folders peensim writes; anything else in the directory is left alone).
#pragma once

#include <string>
#include <vector>

namespace peensim {

class RunDirectoryLock {
public:
    // Takes the lock or throws InputError naming the holder (its pid and when it started).
    explicit RunDirectoryLock(const std::string& dir);
    ~RunDirectoryLock();
    RunDirectoryLock(const RunDirectoryLock&) = delete;
    RunDirectoryLock& operator=(const RunDirectoryLock&) = delete;

private:
    int fd_ = -1;
};

inline constexpr const char* kRunLockFileName = ".peensim.lock";
// The analysis is written into analysis.partial/ and replaces analysis/ when it is complete, so
// that analysis/ holds one analysis's files, whole: none of an earlier analysis left beside
// them (a picture it drew and this one does not), none half written.
inline constexpr const char* kAnalysisDirName = "analysis";
inline constexpr const char* kAnalysisPartialDirName = "analysis.partial";

// The outputs a run writes into its directory (files and folders).
const std::vector<std::string>& run_output_names();

// Removes every output of a previous run from `dir`; returns the names removed.
std::vector<std::string> clear_previous_outputs(const std::string& dir);

}  // namespace peensim
