// A checkpoint is trusted only after it is checked. Users found that 8 of 12 single-bit flips
// resumed with exit 0 and different results, and that a time of NaN, past the duration or below
// zero and a NaN position were accepted. Now the file carries a checksum, and its contents are
// validated against the scene before a run resumes from it; every refusal is an input error
// (exit 2) naming the file. Settings that do not change the physics (the checkpoint interval,
// rendering) may change on resume.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "app/checkpoint/checkpoint.h"
#include "app/run/run_job.h"
#include "common/input_error.h"
#include "engine/simulation.h"
#include "support/files.h"
#include "support/run_in_process.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

TestSceneSpec small_spec() {
    TestSceneSpec spec = thrown_shot_scene(16, 0.05);
    return spec;
}

// A checkpoint of `scene`'s model at its start.
Checkpoint start_of(const Model& model) {
    Simulation sim(std::make_shared<const Model>(model));
    Checkpoint c;
    c.scene_hash = model.scene_hash;
    c.state = sim.state();
    return c;
}

std::string resume_error(const Checkpoint& c, const Model& model) {
    try {
        check_resumable("out/checkpoint.bin", c, model, 0);
    } catch (const InputError& e) {
        EXPECT_EQ(e.where().file, "out/checkpoint.bin");
        return e.what();
    }
    return "(accepted)";
}

TEST(CheckpointResumeChecks, EverySingleBitFlipIsRefused) {
    const TestScene scene(small_spec());
    const auto model = scene.compile();
    const fs::path path = fs::path(scene.make_subdirectory("flip")) / "checkpoint.bin";
    save_checkpoint(path.string(), start_of(*model));
    const std::string bytes = read_file(path);
    ASSERT_GT(bytes.size(), 100u);
    std::size_t flips = 0, refused = 0;
    for (std::size_t byte = 0; byte < bytes.size(); ++byte)
        for (int bit = 0; bit < 8; ++bit) {
            std::string damaged = bytes;
            damaged[byte] = static_cast<char>(damaged[byte] ^ (1 << bit));
            std::ofstream(path, std::ios::binary | std::ios::trunc) << damaged;
            ++flips;
            try {
                load_checkpoint(path.string());
            } catch (const InputError& e) {
                ++refused;
                EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos);
            }
        }
    EXPECT_EQ(refused, flips);
}

TEST(CheckpointResumeChecks, StatesThatCannotBeResumedAreRefused) {
    const TestScene scene(small_spec());
    const auto model = scene.compile();
    const Checkpoint good = start_of(*model);
    EXPECT_EQ(resume_error(good, *model), "(accepted)");
    const double nan = std::numeric_limits<double>::quiet_NaN();

    Checkpoint c = good;
    c.state.time = SimTime{nan, 0.0};
    EXPECT_NE(resume_error(c, *model).find("expected a time in [0, 0.05"), std::string::npos);
    c = good;
    c.state.time = SimTime{0.06, 0.0};  // past the duration
    EXPECT_NE(resume_error(c, *model).find("expected a time"), std::string::npos);
    c = good;
    c.state.time = SimTime{-1e-3, 0.0};
    EXPECT_NE(resume_error(c, *model).find("expected a time"), std::string::npos);
    c = good;
    c.state.shots.x[3] = nan;
    EXPECT_NE(resume_error(c, *model).find("shot 3: shots.x is not a number"), std::string::npos);
    c = good;
    c.state.shots.vz[5] = std::numeric_limits<double>::infinity();
    EXPECT_NE(resume_error(c, *model).find("shot 5"), std::string::npos);
    c = good;
    c.state.shots.z[2] = 10.0;  // 10 m up: outside the assembly
    EXPECT_NE(resume_error(c, *model).find("shot 2: active but outside the assembly"), std::string::npos);
    c = good;
    c.state.shots.active[2] = 0;  // a lost shot's last position does not matter
    c.state.shots.z[2] = 10.0;
    EXPECT_EQ(resume_error(c, *model), "(accepted)");
    c = good;
    c.state.shots.resize(15);
    EXPECT_NE(resume_error(c, *model).find("expected 16 shot, got 15"), std::string::npos);
    // A run until coverage as replicas (app/run/replica_rounds.h): its log's shift within the run,
    // the other replicas' counts one per summary entry (shot-shot, then each component).
    c = good;
    c.log_shift_s = 0.06;  // past the duration (0.05 s)
    EXPECT_NE(resume_error(c, *model).find("expected a log shift in [0, "), std::string::npos) << resume_error(c, *model);
    c.log_shift_s = nan;
    EXPECT_NE(resume_error(c, *model).find("log_shift_s"), std::string::npos) << resume_error(c, *model);
    c = good;
    c.log_shift_s = 0.01;
    c.replica_impacts.assign(model->components.size() + 1, 7);
    c.replica_slow_contacts.assign(model->components.size() + 1, 1);
    EXPECT_EQ(resume_error(c, *model), "(accepted)");
    c.replica_impacts.pop_back();
    EXPECT_NE(resume_error(c, *model).find("the other replicas' counts for the wrong number of components"), std::string::npos);
    // Every list's length and every number, by the field's name (app/checkpoint/field_checks.h).
    c = good;
    c.state.shots.wy.pop_back();
    EXPECT_NE(resume_error(c, *model).find("shots.wy: expected 16 values, one per shot slot, got 15"), std::string::npos);
    c = good;
    c.state.emitted_per_source.push_back(3);
    EXPECT_NE(resume_error(c, *model).find("emitted_per_source: expected 0 values, one per shot source, got 1"), std::string::npos);
    c = good;
    c.state.impacts_per_component.pop_back();
    EXPECT_NE(resume_error(c, *model).find("impacts_per_component: expected"), std::string::npos);
    c = good;
    c.state.lost.push_back({});
    c.state.lost.back().where_m.y() = nan;
    EXPECT_NE(resume_error(c, *model).find("lost[0].where_m: not a number"), std::string::npos);
    c = good;
    c.state.fastest_shot_m_per_s = std::numeric_limits<double>::infinity();
    EXPECT_NE(resume_error(c, *model).find("fastest_shot_m_per_s: not a number"), std::string::npos);
    c = good;
    c.wall_time_s = nan;
    EXPECT_NE(resume_error(c, *model).find("wall_time_s: not a number"), std::string::npos);
    c = good;
    c.scene_hash ^= 1;
    EXPECT_NE(resume_error(c, *model).find("the scene changed"), std::string::npos);
}

TEST(CheckpointResumeChecks, TheCheckpointIntervalMayChangeOnResumeTheShotCountMayNot) {
    const TestScene scene(small_spec());
    const std::string dir = scene.make_subdirectory("out");
    auto run = [&](bool resume, std::vector<std::string> overrides, std::optional<std::uint64_t> stop_after, std::string& err_text) {
        const InProcessResult r = run_in_process({scene.scene_path(), dir, resume, false, stop_after, std::move(overrides)});
        err_text = r.err;
        return r.code;
    };
    std::string err;
    ASSERT_EQ(run(false, {}, 50, err), kExitInterrupted) << err;
    EXPECT_EQ(run(true, {"shot.count=17"}, {}, err), kExitInputError);
    EXPECT_NE(err.find("the scene changed"), std::string::npos) << err;
    EXPECT_NE(err.find("(shot: the run had `count: "), std::string::npos) << err;  // what differs, named
    EXPECT_NE(err.find("now `count: 17`"), std::string::npos) << err;
    // The refused resume leaves the run's own resolved scene (it would say what differs next time).
    EXPECT_EQ(read_file(std::filesystem::path(dir) / "scene.resolved.yaml").find("count: 17"), std::string::npos);
    EXPECT_EQ(run(true, {"output.checkpoint_interval=5"}, {}, err), kExitOk) << err;
}

}  // namespace
}  // namespace peensim::testing
