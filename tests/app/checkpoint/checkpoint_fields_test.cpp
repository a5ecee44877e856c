// A checkpoint's fields are declared once (engine/saved_state.h, app/checkpoint/checkpoint_fields.h)
// and its writer, reader and checks follow from that list: every field round-trips, every list's
// length and every number is checked by name, an older file says what it lacks, and the counters
// are saved by name, so a renamed counter is refused rather than read into its neighbour.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "app/checkpoint/checkpoint.h"
#include "common/fnv_hash.h"
#include "common/input_error.h"
#include "engine/saved_state.h"
#include "engine/step_stats.h"
#include "support/files.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::read_file;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

// Every field away from its default, so that a field the list forgets reads back different.
Checkpoint everything_set() {
    Checkpoint c;
    c.scene_hash = 0xfeedull;
    SimulationState& s = c.state;
    s.shots.resize(2);
    for (auto* v : {&s.shots.x, &s.shots.y, &s.shots.z, &s.shots.vx, &s.shots.vy, &s.shots.vz, &s.shots.wx, &s.shots.wy, &s.shots.wz})
        *v = {0.25 + static_cast<double>(v - &s.shots.x), -1.5};
    s.shots.active = {1, 0};
    s.shots.in_flight = {0, 1};
    s.shots.size_class = {1, 0};
    s.time = SimTime{2.0, 1e-17};
    s.steps = 3, s.shot_steps = 4, s.shot_shot_impacts = 5, s.shot_shot_slow_contacts = 6;
    s.fastest_shot_m_per_s = 7.5;
    std::uint64_t k = 10;
    s.health.for_each([&](const char*, std::uint64_t& count) { count = k++; });
    s.impacts_per_component = {11, 12};
    s.slow_contacts_per_component = {13, 14};
    s.law_state = {{0.5, 0.25}, {}};
    s.contacts.restore(15, {{{1, 0}, {16, {0.125}}}});
    SoftContact soft;
    soft.shot = 0, soft.partner = 1, soft.component = -1, soft.law_state = {1e-6, 0, 0}, soft.normal = Vec3(0, 1, 0);
    soft.approach_m_per_s = 1.25, soft.start_time_s = 1.5, soft.mesh_triangle = 17, soft.start_point_m = Vec3(1, 2, 3);
    soft.start_velocity_m_per_s = Vec3(4, 5, 6), soft.start_tangential_m_per_s = 0.75;
    s.soft_contacts = {soft};
    LostShot lost{1, 0.5, Vec3(1, 1, 1), LossCause::leak, 0.25, Vec3(2, 2, 2), 0, Vec3(3, 3, 3), 1e-4, 1e-3};
    s.lost = {lost};
    s.first_search_fallback = {0.75, 1, 0, Vec3(4, 4, 4)};
    s.emitted_per_source = {18};
    s.collected_per_sink = {19, 20};
    s.shots_per_size = {21, 22};
    c.csv_bytes = 23, c.csv_rows = 24;
    SpeedHistogram h;
    h.add(2.0);
    c.normal_speeds = {h};
    c.wall_time_s = 25.0;
    return c;
}

std::string save(const Checkpoint& c, const fs::path& path) {
    save_checkpoint(path.string(), c);
    return read_file(path);
}

std::string load_error(const fs::path& path) {
    try {
        load_checkpoint(path.string());
    } catch (const InputError& e) {
        return e.what();
    }
    return "(loaded)";
}

// The bytes with their checksum made right again: damage the checksum cannot see.
std::string resealed(std::string bytes) {
    const std::size_t body = bytes.size() - sizeof(std::uint64_t);
    const std::uint64_t sum = fnv1a64(std::string_view(bytes).substr(0, body));
    bytes.replace(body, sizeof(sum), reinterpret_cast<const char*>(&sum), sizeof(sum));
    return bytes;
}

}  // namespace

TEST(CheckpointFields, EveryFieldRoundTrips) {
    TempDir dir;
    const Checkpoint c = everything_set();
    const std::string first = save(c, dir.path / "a.bin");
    const Checkpoint back = load_checkpoint((dir.path / "a.bin").string());
    // Written again from what was read: the same bytes, so every field the list names came back.
    EXPECT_EQ(save(back, dir.path / "b.bin"), first);
    // And the fields themselves (the list could name a field it never fills).
    EXPECT_EQ(back.state.shots.wz, c.state.shots.wz);
    EXPECT_EQ(back.state.shots.size_class, c.state.shots.size_class);
    EXPECT_EQ(back.state.health.search_fallbacks, c.state.health.search_fallbacks);
    EXPECT_EQ(back.state.health.shot_lost, 10u);
    EXPECT_EQ(back.state.lost[0].radius_m, 1e-3);
    EXPECT_EQ(back.state.lost[0].cause, LossCause::leak);
    EXPECT_EQ(back.state.soft_contacts[0].start_velocity_m_per_s, Vec3(4, 5, 6));
    EXPECT_EQ(back.state.soft_contacts[0].law_state, c.state.soft_contacts[0].law_state);
    EXPECT_EQ(back.state.first_search_fallback.position_m, Vec3(4, 4, 4));
    EXPECT_EQ(back.state.contacts.entries().at({1, 0}).values, std::vector<double>{0.125});
    EXPECT_EQ(back.state.contacts.resolutions(), 15u);
    EXPECT_EQ(back.state.law_state, c.state.law_state);
    EXPECT_EQ(back.state.time.lo, 1e-17);
    EXPECT_EQ(back.normal_speeds[0], c.normal_speeds[0]);
}

// A field added to a saved struct and not to the list: these sizes change, and this test says
// where to declare it (engine/saved_state.h) before it passes again. The health counters' list
// must hold every counter: its size is the counters' and nothing else.
TEST(CheckpointFields, EveryFieldIsDeclared) {
    std::size_t counters = 0;
    HealthCounters{}.for_each([&](const char*, std::uint64_t) { ++counters; });
    EXPECT_EQ(sizeof(HealthCounters), counters * sizeof(std::uint64_t)) << "a health counter missing from HealthCounters::each";
    EXPECT_EQ(sizeof(LostShot), 128u) << "a LostShot field added? declare it in lost_shot_fields (engine/saved_state.h)";
    EXPECT_EQ(sizeof(SoftContact), 144u) << "a SoftContact field added? declare it in soft_contact_fields";
    EXPECT_EQ(sizeof(SearchFallback), 40u) << "a SearchFallback field added? declare it in saved_state_fields";
    EXPECT_EQ(sizeof(ShotArrays), 12 * sizeof(std::vector<double>)) << "a shot array added? declare it in shot_fields";
    EXPECT_EQ(sizeof(SimulationState), 696u) << "a SimulationState field added? declare it in saved_state_fields";
}

TEST(CheckpointFields, NamesAreUniqueAndTheVersionIsTheLatestField) {
    std::set<std::string> seen;
    std::uint32_t latest = 0;
    for (const FieldName& f : checkpoint_field_names()) {
        EXPECT_TRUE(seen.insert(f.name).second) << f.name;
        EXPECT_GE(f.since, 1u) << f.name;
        latest = std::max(latest, f.since);
    }
    EXPECT_EQ(latest, kSavedStateVersion);
    for (const char* name : {"time.hi", "shots.size_class", "health.search_fallbacks", "lost[].radius_m", "soft_contacts[].law_state",
                             "law_state[].values", "normal_speeds[].histogram", "contacts", "wall_time_s"})
        EXPECT_TRUE(seen.count(name)) << name;
}

TEST(CheckpointFields, AnOlderFileSaysWhatItLacks) {
    TempDir dir;
    std::string bytes = save(everything_set(), dir.path / "c.bin");
    // Format 9 began "PEENCKP9".
    std::ofstream(dir.path / "v9.bin", std::ios::binary) << "PEENCKP9" << bytes.substr(8);
    const std::string e = load_error(dir.path / "v9.bin");
    EXPECT_NE(e.find("checkpoint format 9, this one reads " + std::to_string(kSavedStateVersion)), std::string::npos) << e;
    EXPECT_NE(e.find("added since: health.shot_lost"), std::string::npos) << e;
    EXPECT_NE(e.find("run without --resume"), std::string::npos) << e;
    // A newer file: its version, no list.
    const std::uint32_t newer = kSavedStateVersion + 1;
    bytes.replace(8, sizeof(newer), reinterpret_cast<const char*>(&newer), sizeof(newer));
    std::ofstream(dir.path / "new.bin", std::ios::binary) << resealed(bytes);
    EXPECT_NE(load_error(dir.path / "new.bin").find("checkpoint format " + std::to_string(newer) + ", this one reads"), std::string::npos);
}

TEST(CheckpointFields, ACounterIsReadByItsNameNotItsPlace) {
    TempDir dir;
    std::string bytes = save(everything_set(), dir.path / "d.bin");
    const std::size_t at = bytes.find("deep_penetrations");
    ASSERT_NE(at, std::string::npos);
    bytes[at + 1] = 'i';  // "diep_penetrations": a counter this version does not have
    std::ofstream(dir.path / "renamed.bin", std::ios::binary) << resealed(bytes);
    const std::string e = load_error(dir.path / "renamed.bin");
    EXPECT_NE(e.find("an unknown health counter 'diep_penetrations'"), std::string::npos) << e;
    EXPECT_NE(e.find((dir.path / "renamed.bin").string()), std::string::npos) << e;
}

TEST(CheckpointFields, StepStatsAddsEveryCounterInItsList) {
    StepStats a;
    std::set<std::string> names;
    std::uint64_t k = 1;
    a.for_each_counter([&](const char* name, std::uint64_t& v) {
        names.insert(name);
        v = k++;
    });
    EXPECT_EQ(names.size(), StepStats::kCounters);
    a[Stage::mesh_queries] = 0.5;
    StepStats b = a;
    b += a;
    k = 1;
    b.for_each_counter([&](const char* name, std::uint64_t v) { EXPECT_EQ(v, 2 * k++) << name; });
    EXPECT_EQ(b[Stage::mesh_queries], 1.0);
}
