// The coverage geometry a sweep's runs share (coverage_geometry_cache.h): read back it is the one
// computed, to the byte; its key changes with everything the computation reads and with nothing a
// sweep usually varies; a damaged entry is computed again and replaced, never trusted.
#include "app/analysis/coverage_geometry_cache.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/analysis/coverage_geometry.h"
#include "scene/scene_parser.h"
#include "support/files.h"
#include "support/temp_dir.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;
using testing::read_file;
using testing::TempDir;

const std::string kGear = std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml";
constexpr std::size_t kGearPart = 3;  // scenes/gear.yaml: sonotrode, chamber, axle, gear

std::shared_ptr<const Model> gear_with(const std::vector<std::string>& overrides = {}) {
    return compile_model(parse_scene_file(kGear, overrides));
}

// Every figure of a part's classes and findings, as bytes.
std::string bytes_of(const PartCoverageGeometry& part) {
    ByteWriter w;
    part.classes.write_bytes(w);
    w.put(part.unreachable.shot_diameter_m);
    w.put(part.unreachable.whole);
    w.put_vector(part.unreachable.regions);
    w.put_vector(part.unreachable.triangle_share);
    return w.bytes();
}

std::string note_of(const std::shared_ptr<const Model>& model, const std::string& dir, std::string* bytes = nullptr) {
    CoverageGeometry geometry(model, nullptr, 0, {}, dir);
    const PartCoverageGeometry* part = geometry.part(kGearPart);
    if (part == nullptr) return "no part";
    if (bytes != nullptr) *bytes = bytes_of(*part);
    return part->cache_note;
}

// A run does not wait for ever on a run stuck holding the lock: past its patience it goes on.
TEST(CoverageGeometryCache, ALockHeldPastThePatienceIsGivenUp) {
    TempDir dir;
    const CoverageGeometryLock held(dir.path.string(), 7, [] {});
    EXPECT_FALSE(held.gave_up());
    EXPECT_EQ(held.waited_s(), 0.0);
    const CoverageGeometryLock waiting(
        dir.path.string(), 7, [] {}, 0.1);
    EXPECT_TRUE(waiting.gave_up());
    EXPECT_GE(waiting.waited_s(), 0.1);
    const CoverageGeometryLock other_key(
        dir.path.string(), 8, [] {}, 0.1);  // another entry's lock is free
    EXPECT_FALSE(other_key.gave_up());
}

// Overwrites the file at `path` with `bytes`.
void write_bytes_to(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes; }

TEST(CoverageGeometryCache, ReadBackItIsTheComputedGeometryToTheByte) {
    TempDir dir;
    const std::string cache = (dir.path / "cache").string();
    const std::shared_ptr<const Model> model = gear_with();
    std::string computed, kept, reused;
    EXPECT_EQ(note_of(model, "", &computed), "");
    EXPECT_EQ(note_of(model, cache, &kept).rfind("kept in " + cache + "/coverage-", 0), 0u);
    EXPECT_EQ(note_of(model, cache, &reused).rfind("reused from " + cache + "/coverage-", 0), 0u);
    EXPECT_GT(computed.size(), 100'000u);
    EXPECT_EQ(kept, computed);
    EXPECT_EQ(reused, computed);
    // One entry, of the part (the chamber and the sonotrode are not logged), and its lock; no
    // temporary left.
    std::vector<std::string> files;
    for (const fs::directory_entry& e : fs::directory_iterator(cache)) files.push_back(e.path().filename().string());
    std::sort(files.begin(), files.end());
    const std::string entry = fs::path(coverage_geometry_file(cache, coverage_geometry_key(*model, kGearPart, 345e6))).stem().string();
    EXPECT_EQ(files, (std::vector<std::string>{entry + ".bin", entry + ".lock"}));
}

TEST(CoverageGeometryCache, TheKeyFollowsWhatTheGeometryReadsAndNothingASweepUsuallyVaries) {
    const std::uint64_t base = coverage_geometry_key(*gear_with(), kGearPart, 345e6);
    EXPECT_EQ(base, coverage_geometry_key(*gear_with(), kGearPart, 345e6));  // the same inputs, the same key
    // What the coverage geometry does not read: the same key.
    for (const char* same : {"process.seed=7", "process.duration=60 s", "shot.count=60", "components[sonotrode].vibration.amplitude=40 um",
                             "contacts.shot-aluminium-2000.C0=0.6", "output.smoothing_radius=2 mm"})
        EXPECT_EQ(coverage_geometry_key(*gear_with({same}), kGearPart, 345e6), base) << same;
    // What it reads: another key each.
    for (const char* other : {"shot.diameter=1.5 mm", "materials.steel.density=7.9 g/cm3", "components[gear].translation=[0, 0, 42.1 mm]",
                              "components[axle].translation=[0, 0.1 mm, 42 mm]", "process.gravity=[0, -9.81, 0]",
                              "components[gear].regions[1].distance_to_axis.max=5.2 mm"})
        EXPECT_NE(coverage_geometry_key(*gear_with({other}), kGearPart, 345e6), base) << other;
    // The part's yield stress (the dents' size, so the map's resolution).
    EXPECT_NE(coverage_geometry_key(*gear_with(), kGearPart, 300e6), base);
}

// A sweep's runs that start together: one computes the entry, the others wait for it and read it
// (flock conflicts between two opens of the lock file in one process as between two processes).
TEST(CoverageGeometryCache, RunsStartedTogetherComputeItOnceTheOthersReadIt) {
    TempDir dir;
    const std::string cache = (dir.path / "cache").string();
    const std::shared_ptr<const Model> model = gear_with();
    std::vector<std::unique_ptr<CoverageGeometry>> runs;
    for (int k = 0; k < 3; ++k)
        runs.push_back(std::make_unique<CoverageGeometry>(model, nullptr, 1, std::vector<std::optional<RegionSet>>{}, cache));
    int kept = 0, reused = 0;
    std::string first;
    for (const auto& run : runs) {
        const PartCoverageGeometry* part = run->part(kGearPart);
        ASSERT_NE(part, nullptr);
        kept += part->cache_note.rfind("kept in ", 0) == 0 ? 1 : 0;
        reused += part->cache_note.rfind("reused from ", 0) == 0 ? 1 : 0;
        if (first.empty()) first = bytes_of(*part);
        EXPECT_EQ(bytes_of(*part), first);
    }
    EXPECT_EQ(kept, 1);
    EXPECT_EQ(reused, 2);
    // A run stopped while it waits for another's entry stops waiting.
    const std::shared_ptr<const Model> moved = gear_with({"components[gear].translation=[0, 0, 42.2 mm]"});
    const std::uint64_t key = coverage_geometry_key(*moved, kGearPart, 345e6);
    const CoverageGeometryLock held(cache, key, [] {});
    { CoverageGeometry waiting(moved, nullptr, 1, {}, cache); }  // destroyed while it waits: returns
    EXPECT_FALSE(fs::exists(coverage_geometry_file(cache, key)));
}

// A folder holds at most a cap of entries: past it the oldest go, never the one just kept.
TEST(CoverageGeometryCache, AFolderPastItsCapDropsItsOldestEntries) {
    TempDir dir;
    const std::string cache = (dir.path / "cache").string();
    const std::shared_ptr<const Model> model = gear_with();
    CoverageGeometry computed(model, nullptr, 0);
    const PartCoverageGeometry& part = *computed.part(kGearPart);
    const std::uintmax_t entry = [&] {
        store_coverage_geometry(cache, 1, part.classes, part.unreachable);
        return fs::file_size(coverage_geometry_file(cache, 1));
    }();
    // Entries 2 and 3 older than 1, written in that order; room for two.
    for (std::uint64_t key : {2, 3}) {
        store_coverage_geometry(cache, key, part.classes, part.unreachable);
        fs::last_write_time(coverage_geometry_file(cache, key),
                            fs::last_write_time(coverage_geometry_file(cache, 1)) - std::chrono::hours(4 - static_cast<int>(key)));
    }
    // Entry 1 made the oldest, entry 2 read since: of 1, 2 and 3, 1 and 3 were read or written
    // longest ago.
    fs::last_write_time(coverage_geometry_file(cache, 1), fs::last_write_time(coverage_geometry_file(cache, 1)) - std::chrono::hours(8));
    SampleClasses classes;
    UnreachableFindings unreachable;
    std::string why;
    ASSERT_TRUE(load_coverage_geometry(cache, 2, *model->components[kGearPart].mesh, part.regions, classes, unreachable, why)) << why;
    store_coverage_geometry(cache, 4, part.classes, part.unreachable, 2 * entry);
    EXPECT_FALSE(fs::exists(coverage_geometry_file(cache, 1)));
    EXPECT_FALSE(fs::exists(coverage_geometry_file(cache, 3)));
    EXPECT_TRUE(fs::exists(coverage_geometry_file(cache, 2)));
    EXPECT_TRUE(fs::exists(coverage_geometry_file(cache, 4)));
    // A cap below one entry keeps the one just written alone; a temporary an hour old (a run
    // killed while writing) goes too, a fresh one (a run writing now) stays.
    const std::string stale = coverage_geometry_file(cache, 9) + ".123", fresh = coverage_geometry_file(cache, 9) + ".456";
    write_bytes_to(stale, "x");
    write_bytes_to(fresh, "x");
    fs::last_write_time(stale, fs::last_write_time(stale) - std::chrono::hours(2));
    store_coverage_geometry(cache, 5, part.classes, part.unreachable, 1);
    EXPECT_FALSE(fs::exists(coverage_geometry_file(cache, 2)));
    EXPECT_FALSE(fs::exists(coverage_geometry_file(cache, 4)));
    EXPECT_TRUE(fs::exists(coverage_geometry_file(cache, 5)));
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(fresh));
}

TEST(CoverageGeometryCache, ADamagedEntryIsComputedAgainAndReplacedNeverTrusted) {
    TempDir dir;
    const std::string cache = (dir.path / "cache").string();
    const std::shared_ptr<const Model> model = gear_with();
    std::string computed, again;
    ASSERT_EQ(note_of(model, cache, &computed).rfind("kept in ", 0), 0u);
    const std::string path = coverage_geometry_file(cache, coverage_geometry_key(*model, kGearPart, 345e6));
    const std::string whole = read_file(path);
    // Cut short (a run killed while writing, a full disk), one byte flipped in the middle, and
    // another file's bytes under its name: each is computed again, the same, and kept whole.
    std::string flipped = whole;
    flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
    for (const std::string& damaged : {whole.substr(0, whole.size() / 2), flipped, std::string("not a cache entry")}) {
        write_bytes_to(path, damaged);
        const std::string note = note_of(model, cache, &again);
        EXPECT_EQ(note.rfind("computed again (" + path + ": ", 0), 0u) << note;
        EXPECT_NE(note.find("; kept in " + path), std::string::npos) << note;
        EXPECT_EQ(again, computed);
        EXPECT_EQ(read_file(path), whole);
    }
    EXPECT_EQ(note_of(model, cache, &again).rfind("reused from ", 0), 0u);
    EXPECT_EQ(again, computed);
    // A FIFO under the entry's name (which a read would block on) and a folder (which a read
    // would throw on) are not read: computed, the FIFO replaced, the folder left and said so.
    fs::remove(path);
    ASSERT_EQ(::mkfifo(path.c_str(), 0644), 0);
    const std::string fifo_note = note_of(model, cache, &again);
    EXPECT_EQ(fifo_note.rfind("computed again (" + path + ": not a regular file); kept in ", 0), 0u) << fifo_note;
    EXPECT_EQ(read_file(path), whole);
    fs::remove(path);
    fs::create_directory(path);
    const std::string folder_note = note_of(model, cache, &again);
    EXPECT_EQ(folder_note.rfind("computed again (" + path + ": not a regular file); not kept: ", 0), 0u) << folder_note;
    EXPECT_EQ(again, computed);
    fs::remove(path);
    for (const fs::directory_entry& e : fs::directory_iterator(cache))  // its temporary removed
        EXPECT_EQ(e.path().string().find(".bin."), std::string::npos) << e.path();
    // A folder it cannot write to: computed, and said so, the run going on.
    const std::string blocked = (dir.path / "a-file").string();
    write_bytes_to(blocked, "x");
    const std::string note = note_of(model, blocked, &again);
    EXPECT_EQ(note.rfind("not kept: ", 0), 0u) << note;
    EXPECT_EQ(again, computed);
}

}  // namespace
}  // namespace peensim
