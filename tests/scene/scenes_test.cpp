// Every shipped scene (scenes/*.yaml) is exercised: it parses, compiles, places its shot (what
// `peensim check` does) and runs 200 steps without numerical trouble.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "engine/simulation.h"
#include "model/model.h"
#include "model/shot_placement.h"
#include "scene/scene_parser.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> shipped_scenes() {
    std::vector<std::string> out;
    for (const auto& entry : fs::directory_iterator(fs::path(PEENSIM_SOURCE_DIR) / "scenes"))
        if (entry.path().extension() == ".yaml") out.push_back(entry.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

TEST(ShippedScenes, ThereAreScenesToTest) {
    const std::vector<std::string> scenes = shipped_scenes();
    EXPECT_GE(scenes.size(), 2u);
    EXPECT_NE(std::find(scenes.begin(), scenes.end(), "rod.yaml"), scenes.end());
    EXPECT_NE(std::find(scenes.begin(), scenes.end(), "gear.yaml"), scenes.end());
}

class ShippedScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScene, ParsesCompilesPlacesAndRuns200StepsHealthy) {
    const std::string path = (fs::path(PEENSIM_SOURCE_DIR) / "scenes" / GetParam()).string();
    const SceneDescription scene = parse_scene_file(path);
    const auto model = compile_model(scene);
    ASSERT_TRUE(model->sonotrode >= 0 || !model->sources.empty());  // shot placed on it, or emitted
    const InitialShots shots = place_shots(*model);
    ASSERT_EQ(static_cast<int>(shots.positions.size()), model->shot_count);
    ASSERT_EQ(shots.velocities.size(), shots.positions.size());

    Simulation sim(model);
    std::vector<ImpactRecord> impacts;
    std::size_t logged = 0;
    // By hand: exactly 200 units of work of each scene's scheme; RunLoop stops only at restart points (the event schemes': 0.1 s).
    for (int k = 0; k < 200 && !sim.finished(); ++k) {
        sim.step(impacts);
        logged += impacts.size();
        impacts.clear();
    }
    const SimulationState& st = sim.state();
    std::cout << "[ scenes   ] " << GetParam() << ": " << model->shot_count << " shot in " << shots.layers << " layer(s), " << st.steps
              << " steps to t = " << st.time.seconds() << " s, " << logged << " logged impacts\n";
    EXPECT_EQ(st.steps, 200u);
    EXPECT_GT(st.time.seconds(), 0.0);
    st.health.for_each([&](const char* name, std::uint64_t value) {
        if (std::string(name) == "mesh_overlap_corrections" || std::string(name) == "shot_overlap_corrections") return;
        EXPECT_EQ(value, 0u) << name;
    });
    // Every shot placed or emitted is still in the run, or was collected by a sink (none is lost).
    std::uint64_t active = 0, collected = 0, emitted = 0;
    for (std::size_t i = 0; i < st.shots.size(); ++i) active += st.shots.active[i];
    for (std::uint64_t c : st.collected_per_sink) collected += c;
    for (std::uint64_t e : st.emitted_per_source) emitted += e;
    EXPECT_EQ(active + collected, static_cast<std::uint64_t>(model->shot_count) + emitted) << "shot unaccounted for";
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, ::testing::ValuesIn(shipped_scenes()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             std::string name = fs::path(info.param).stem().string();
                             std::replace_if(
                                 name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
                             return name;
                         });

}  // namespace
}  // namespace peensim
