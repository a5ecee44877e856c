// A checkpoint reads back exactly what was saved, and a damaged one (cut short, another file,
// trailing bytes, another version, a corrupt histogram) is refused with a message naming the file,
// never loaded half-right.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/checkpoint/checkpoint.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

Checkpoint sample() {
    Checkpoint c;
    c.scene_hash = 0x1234567890abcdefull;
    c.state.shots.resize(3);
    c.state.shots.set_position(1, Vec3(1.0 / 3.0, -2e-3, 0.5));
    c.state.shots.set_velocity(2, Vec3(0.1, 0.2, -0.3));
    c.state.shots.active[0] = 0;
    c.state.time.advance(0.125);
    c.state.time.advance(1e-17);
    c.state.steps = 42;
    c.state.impacts_per_component = {5, 0, 7};
    c.state.slow_contacts_per_component = {2, 0, 1};
    c.state.shot_shot_slow_contacts = 4;
    c.state.shots.in_flight[1] = 1;
    c.state.health.mesh_overlap_corrections = 3;
    c.state.lost.push_back({0, 0.01, Vec3(0.1, 0.2, 0.3)});
    c.csv_bytes = 1000;
    c.csv_rows = 12;
    SpeedHistogram h;
    h.add(1.5);
    h.add(2.5);
    c.normal_speeds = {h};
    c.wall_time_s = 3.5;
    return c;
}

std::string checkpoint_load_error(const fs::path& path) {
    try {
        load_checkpoint(path.string());
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(loaded)";
}

}  // namespace

TEST(Checkpoint, ReadsBackWhatWasSaved) {
    TempDir dir;
    const fs::path path = dir.path / "checkpoint.bin";
    const Checkpoint c = sample();
    save_checkpoint(path.string(), c);
    const Checkpoint r = load_checkpoint(path.string());
    EXPECT_EQ(r.scene_hash, c.scene_hash);
    EXPECT_EQ(r.state.time.hi, c.state.time.hi);
    EXPECT_EQ(r.state.time.lo, c.state.time.lo);
    EXPECT_EQ(r.state.steps, 42u);
    EXPECT_EQ(r.state.shots.x, c.state.shots.x);
    EXPECT_EQ(r.state.shots.vz, c.state.shots.vz);
    EXPECT_EQ(r.state.shots.active, c.state.shots.active);
    EXPECT_EQ(r.state.impacts_per_component, c.state.impacts_per_component);
    EXPECT_EQ(r.state.slow_contacts_per_component, c.state.slow_contacts_per_component);
    EXPECT_EQ(r.state.shot_shot_slow_contacts, 4u);
    EXPECT_EQ(r.state.shots.in_flight, c.state.shots.in_flight);
    EXPECT_EQ(r.state.health.mesh_overlap_corrections, 3u);
    ASSERT_EQ(r.state.lost.size(), 1u);
    EXPECT_EQ(r.state.lost[0].position_m, Vec3(0.1, 0.2, 0.3));
    EXPECT_EQ(r.csv_bytes, 1000u);
    ASSERT_EQ(r.normal_speeds.size(), 1u);
    EXPECT_EQ(r.normal_speeds[0].count(), 2u);
    EXPECT_EQ(r.normal_speeds[0].serialize(), c.normal_speeds[0].serialize());
    EXPECT_EQ(r.wall_time_s, 3.5);
}

TEST(Checkpoint, DamagedFilesAreRefusedWithTheirName) {
    TempDir dir;
    const fs::path good = dir.path / "checkpoint.bin";
    save_checkpoint(good.string(), sample());
    std::string bytes;
    {
        std::ifstream in(good, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    auto write = [&](const std::string& name, const std::string& content) {
        const fs::path p = dir.path / name;
        std::ofstream(p, std::ios::binary) << content;
        return p;
    };
    // Cut at every length: always a clear refusal, never a crash or a half-loaded state.
    for (std::size_t n = 0; n < bytes.size(); n += 7) {
        const fs::path p = write("cut.bin", bytes.substr(0, n));
        const std::string e = checkpoint_load_error(p);
        EXPECT_NE(e.find(p.string()), std::string::npos) << n << ": " << e;
        EXPECT_TRUE(e.find("truncated") != std::string::npos || e.find("not a peensim checkpoint") != std::string::npos ||
                    e.find("damaged") != std::string::npos)
            << n << ": " << e;
    }
    EXPECT_NE(checkpoint_load_error(write("other.bin", "PK\x03\x04 a zip file")).find("not a peensim checkpoint"), std::string::npos);
    EXPECT_NE(checkpoint_load_error(write("long.bin", bytes + "x")).find("damaged"), std::string::npos);
    std::string other_version = bytes;
    other_version[7] = '2';
    EXPECT_NE(checkpoint_load_error(write("v2.bin", other_version)).find("written by another version of peensim (checkpoint format 2"),
              std::string::npos);
    EXPECT_NE(checkpoint_load_error(dir.path / "missing.bin").find("no checkpoint to resume from"), std::string::npos);
    // A corrupt histogram inside: its own message.
    EXPECT_THROW(SpeedHistogram::deserialize("PSHIST01garbage"), std::runtime_error);
}
