// The coverage geometry a sweep's runs share: each logged part's sample classes (a reach probe per
// probe cell: a distance query to every component) and the area out of reach depend on the
// assembly at t = 0 and the shot alone, and most sweeps vary neither (a speed, an amplitude, a
// seed, the duration). The first run of such an assembly computes them and keeps them in the
// sweep's cache folder; the others read them back (on the shipped gear about a sixth of a run's
// processor time, docs/design.md "Setup and analysis").
//
// Keyed by what the computation reads, not by the scene's text: every component's triangles and
// groups, its pose at t = 0, its solidity and axis; gravity; the sonotrode; the part, its regions
// as the resolved scene writes them, its yield stress; the shot's sizes and density; and the
// peensim binary itself (a rebuilt one may compute otherwise). Any difference in any of them is
// another file. A file that is not whole (a run killed while writing it, a full disk) fails its
// checksum and is computed again and replaced: the cache is never trusted beyond its bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "analysis/regions.h"
#include "analysis/sample_classes.h"
#include "analysis/unreachable_area.h"
#include "model/model.h"

namespace peensim {

// The key of component ci's coverage geometry in `model` (its yield stress yield_pa, Pa).
std::uint64_t coverage_geometry_key(const Model& model, std::size_t ci, double yield_pa);

// <dir>/coverage-<key as 16 hex digits>.bin
std::string coverage_geometry_file(const std::string& dir, std::uint64_t key);

// Reads the entry for `key` into classes and unreachable: false when there is none, or it is not
// whole or not of this part (`why` then says so; empty for no file).
bool load_coverage_geometry(const std::string& dir, std::uint64_t key, const TriangleMesh& mesh, const RegionSet& regions,
                            SampleClasses& classes, UnreachableFindings& unreachable, std::string& why);

// While it lives, this process alone computes the entry for `key` among those that take the same
// lock (flock on <dir>/coverage-<key>.lock, released by the kernel if the process dies): a sweep's
// runs that start together wait for the first to keep it instead of each computing it. Waits in
// steps of 20 ms, calling `waiting` between them (which may throw to give up: a run that is
// stopped), for at most patience_s: a run stuck holding it (or far slower) is not waited for
// longer, and this one computes the entry itself. A folder where the lock cannot be made is no
// reason to wait: then it holds nothing.
inline constexpr double kCoverageGeometryPatience_s = 300.0;
class CoverageGeometryLock {
public:
    CoverageGeometryLock(const std::string& dir, std::uint64_t key, const std::function<void()>& waiting,
                         double patience_s = kCoverageGeometryPatience_s);
    ~CoverageGeometryLock();
    CoverageGeometryLock(const CoverageGeometryLock&) = delete;
    CoverageGeometryLock& operator=(const CoverageGeometryLock&) = delete;

    double waited_s() const { return waited_s_; }  // s, for another run's lock
    bool gave_up() const { return gave_up_; }      // waited patience_s, and holds nothing

private:
    int fd_ = -1;
    double waited_s_ = 0.0;
    bool gave_up_ = false;
};

// At most this many bytes of entries in a folder (1 GiB): a study that varies the shot's size gives
// each run an entry of its own (22 MB on a 500k-triangle gear), which nothing reads again.
inline constexpr std::uintmax_t kCoverageGeometryCacheBytes = std::uintmax_t{1} << 30;

// Keeps the entry for `key` (written under a name of this process's, then renamed: runs that store
// the same entry at once leave one whole file), then removes the oldest other entries while the
// folder's entries hold more than cap_bytes (read or written longest ago first). Throws std::runtime_error if it cannot be written.
void store_coverage_geometry(const std::string& dir, std::uint64_t key, const SampleClasses& classes,
                             const UnreachableFindings& unreachable, std::uintmax_t cap_bytes = kCoverageGeometryCacheBytes);

}  // namespace peensim
