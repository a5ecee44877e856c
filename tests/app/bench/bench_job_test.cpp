// `peensim bench` on a tiny generated scene: the table has a row per scheme and a speed ratio,
// the same scheme twice gives the same statistics (difference 0, within noise), per-scheme
// overrides reach their run, the CSV has its columns, and bad scenes or schemes are clear input
// errors. Nothing here is timed: wall times only have to be there, not to have any value.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "app/bench/bench_job.h"
#include "app/run/run_job.h"
#include "common/input_error.h"
#include "support/temp_dir.h"
#include "support/test_scene.h"

namespace peensim {
namespace {

using testing::TempDir;
using testing::TestScene;
using testing::TestSceneSpec;

// 20 shot in a 20 mm chamber over a sonotrode vibrating at 25 um, 50 ms: a few thousand impacts
// in well under a second. Two logged components, so the "all logged" total is exercised too.
TestSceneSpec tiny_spec() {
    TestSceneSpec s;
    s.chamber_size_m = Vec3(20e-3, 20e-3, 20e-3);
    s.shot_count = 20;
    s.duration_s = 0.05;
    s.amplitude_m = 25e-6;
    s.log = {"sonotrode", "chamber"};
    return s;
}

using CsvRow = std::map<std::string, std::string>;

std::vector<std::string> split_csv_line(const std::string& line) {
    std::vector<std::string> fields;
    std::string field;
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
                field += '"', ++i;
            else if (c == '"')
                quoted = false;
            else
                field += c;
        } else if (c == '"')
            quoted = true;
        else if (c == ',')
            fields.push_back(field), field.clear();
        else
            field += c;
    }
    fields.push_back(field);
    return fields;
}

std::vector<std::string> csv_header(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    return split_csv_line(line);
}

std::vector<CsvRow> read_csv(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = split_csv_line(line);
    std::vector<CsvRow> rows;
    while (std::getline(in, line)) {
        const std::vector<std::string> fields = split_csv_line(line);
        EXPECT_EQ(fields.size(), header.size()) << line;
        CsvRow row;
        for (std::size_t k = 0; k < header.size() && k < fields.size(); ++k) row[header[k]] = fields[k];
        rows.push_back(std::move(row));
    }
    return rows;
}

const CsvRow* find_row(const std::vector<CsvRow>& rows, const std::string& label, const std::string& component) {
    for (const CsvRow& r : rows)
        if (r.at("scheme_label") == label && r.at("component") == component) return &r;
    return nullptr;
}

std::size_t count_lines_starting_with(const std::string& text, const std::string& prefix) {
    std::istringstream in(text);
    std::size_t n = 0;
    for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
    return n;
}

TEST(BenchJob, SameSchemeTwiceGivesIdenticalStatisticsAndATable) {
    const TestScene scene(tiny_spec());
    TempDir dir;
    BenchOptions o;
    o.scene_paths = {scene.scene_path()};
    o.schemes = {"step", "step"};
    o.csv_path = (dir.path / "bench.csv").string();
    std::ostringstream out, err;
    ASSERT_EQ(bench_job(o, out, err), kExitOk) << err.str();
    const std::string text = out.str();
    SCOPED_TRACE(text);

    // One table row per scheme and logged row (sonotrode, chamber, all logged).
    EXPECT_EQ(count_lines_starting_with(text, "step#1 "), 3u);
    EXPECT_EQ(count_lines_starting_with(text, "step#2 "), 3u);
    EXPECT_NE(text.find("step#2 against step#1: speed ratio "), std::string::npos);
    EXPECT_NE(text.find("all logged  impacts/s    +0.00 %"), std::string::npos);
    EXPECT_NE(text.find("all logged  mean vn      +0.00 %"), std::string::npos);
    EXPECT_EQ(text.find("DIFFERS"), std::string::npos);
    EXPECT_EQ(text.find("n/a"), std::string::npos);
    // The summary line of the scene.
    EXPECT_NE(text.find(scene.scene_path() + ": step#2 vs step#1 speed ratio "), std::string::npos);
    EXPECT_NE(text.find("all logged impacts/s +0.00 % (3 SE +-"), std::string::npos);
    EXPECT_NE(text.find("): within noise\n"), std::string::npos);

    const std::vector<std::string> header = csv_header(o.csv_path);
    for (const char* column : {"scene",
                               "scheme_label",
                               "scheme",
                               "compared_with",
                               "component",
                               "logged",
                               "duration_s",
                               "simulated_s",
                               "wall_s",
                               "wall_s_per_simulated_s",
                               "steps",
                               "impacts",
                               "impact_rate_per_s",
                               "impact_rate_se_per_s",
                               "mean_normal_speed_m_per_s",
                               "mean_normal_speed_se_m_per_s",
                               "shot_shot_impacts_per_s",
                               "serious_health",
                               "health_shot_lost",
                               "stage_mesh_queries_s",
                               "speed_ratio",
                               "impact_rate_difference_percent",
                               "impact_rate_bound_percent",
                               "mean_normal_speed_difference_percent",
                               "mean_normal_speed_bound_percent",
                               "verdict"})
        EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;

    const std::vector<CsvRow> rows = read_csv(o.csv_path);
    // Every component (sonotrode, chamber: logged) plus the total, for each scheme.
    ASSERT_EQ(rows.size(), 2u * 3u);
    for (const char* component : {"sonotrode", "chamber", "all logged"}) {
        SCOPED_TRACE(component);
        const CsvRow* a = find_row(rows, "step#1", component);
        const CsvRow* b = find_row(rows, "step#2", component);
        ASSERT_TRUE(a && b);
        EXPECT_EQ(a->at("scheme"), "step");
        EXPECT_EQ(a->at("logged"), "1");
        EXPECT_EQ(a->at("duration_s"), "0.05");
        EXPECT_GT(std::stoull(a->at("impacts")), 20u);
        EXPECT_GT(std::stod(a->at("impact_rate_se_per_s")), 0.0);
        EXPECT_GT(std::stod(a->at("mean_normal_speed_se_m_per_s")), 0.0);
        for (const char* same : {"steps", "impacts", "impact_rate_per_s", "impact_rate_se_per_s", "mean_normal_speed_m_per_s",
                                 "mean_normal_speed_se_m_per_s", "shot_shot_impacts_per_s", "serious_health"})
            EXPECT_EQ(a->at(same), b->at(same)) << same;
        // The reference row carries no comparison; the other is compared with it.
        EXPECT_EQ(a->at("compared_with"), "");
        EXPECT_EQ(a->at("verdict"), "");
        EXPECT_EQ(b->at("compared_with"), "step#1");
        EXPECT_EQ(std::stod(b->at("impact_rate_difference_percent")), 0.0);
        EXPECT_EQ(std::stod(b->at("mean_normal_speed_difference_percent")), 0.0);
        EXPECT_GT(std::stod(b->at("impact_rate_bound_percent")), 0.0);
        EXPECT_GT(std::stod(b->at("speed_ratio")), 0.0);
        EXPECT_EQ(b->at("verdict"), "within noise");
    }
    // The total is the sum of the logged components.
    EXPECT_EQ(std::stoull(find_row(rows, "step#1", "all logged")->at("impacts")),
              std::stoull(find_row(rows, "step#1", "sonotrode")->at("impacts")) +
                  std::stoull(find_row(rows, "step#1", "chamber")->at("impacts")));
}

TEST(BenchJob, PerSchemeOverridesReachTheirRunOnly) {
    const TestScene scene(tiny_spec());
    TempDir dir;
    BenchOptions o;
    o.scene_paths = {scene.scene_path()};
    o.schemes = {"step", "step:accuracy.travel_fraction=0.1"};
    o.duration = "20 ms";
    o.csv_path = (dir.path / "bench.csv").string();
    std::ostringstream out, err;
    ASSERT_EQ(bench_job(o, out, err), kExitOk) << err.str();
    SCOPED_TRACE(out.str());
    EXPECT_NE(out.str().find("step:accuracy.travel_fraction=0.1 against step: speed ratio "), std::string::npos);
    const std::vector<CsvRow> rows = read_csv(o.csv_path);
    const CsvRow* a = find_row(rows, "step", "all logged");
    const CsvRow* b = find_row(rows, "step:accuracy.travel_fraction=0.1", "all logged");
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->at("duration_s"), "0.02");  // --duration, with its unit
    // Eq. 7's step shrinks with the travel fraction (0.25 -> 0.1): more steps for the same time.
    EXPECT_GT(std::stod(b->at("steps")), 2.0 * std::stod(a->at("steps")));
    EXPECT_FALSE(b->at("verdict").empty());
}

TEST(BenchJob, ReplicasAreOneOfTheSchemesComparedWithinNoise) {
    // The rod, 4 s, as one trajectory and as 2 replicas (run --replicas): the replicas' rows count
    // the windows' impacts (about the same rate), and bench's own batch-means comparison finds them
    // within noise.
    TempDir dir;
    BenchOptions o;
    o.scene_paths = {std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml"};
    o.schemes = {"event", "event:replicas=2"};
    o.duration = "4";
    o.csv_path = (dir.path / "bench.csv").string();
    std::ostringstream out, err;
    ASSERT_EQ(bench_job(o, out, err), kExitOk) << err.str();
    SCOPED_TRACE(out.str() + err.str());
    EXPECT_EQ(err.str().find("went on as one replica"), std::string::npos);
    EXPECT_NE(out.str().find("event:replicas=2 against event: speed ratio "), std::string::npos);
    const std::vector<CsvRow> rows = read_csv(o.csv_path);
    const CsvRow* a = find_row(rows, "event", "rod");
    const CsvRow* b = find_row(rows, "event:replicas=2", "rod");
    ASSERT_TRUE(a && b);
    EXPECT_NEAR(std::stod(b->at("impacts")) / std::stod(a->at("impacts")), 1.0, 0.05);
    EXPECT_EQ(b->at("verdict"), "within noise");
}

TEST(BenchJob, BadSceneIsAClearInputError) {
    std::ostringstream out, err;
    BenchOptions o;
    o.scene_paths = {"/nonexistent/peensim/scene.yaml"};
    o.schemes = {"step", "step"};
    EXPECT_EQ(bench_job(o, out, err), kExitInputError);
    EXPECT_NE(err.str().find("/nonexistent/peensim/scene.yaml"), std::string::npos) << err.str();
    EXPECT_EQ(out.str(), "");

    // A bad --set names the field, before anything runs.
    const TestScene scene(tiny_spec());
    std::ostringstream out2, err2;
    o.scene_paths = {scene.scene_path()};
    o.overrides = {"shot.diameter=-2 mm"};
    EXPECT_EQ(bench_job(o, out2, err2), kExitInputError);
    EXPECT_NE(err2.str().find("shot.diameter"), std::string::npos) << err2.str();
}

TEST(BenchJob, BadSchemesAreInputErrors) {
    const TestScene scene(tiny_spec());
    for (const std::vector<std::string>& schemes : std::vector<std::vector<std::string>>{{"step"},
                                                                                         {"step", "leapfrog"},
                                                                                         {"step", "step:travel_fraction"},
                                                                                         {"event", "event:replicas=0"},
                                                                                         {"event", "event:replicas=two"}}) {
        std::ostringstream out, err;
        BenchOptions o;
        o.scene_paths = {scene.scene_path()};
        o.schemes = schemes;
        EXPECT_EQ(bench_job(o, out, err), kExitInputError) << schemes.back();
        EXPECT_NE(err.str().find("--schemes"), std::string::npos) << err.str();
    }
}

TEST(BenchJob, FindsTheShippedScenesNextToTheBinary) {
    // The binary is <build>/peensim and the scenes <repo>/scenes: found through <exe dir>/..
    // only when the build directory is inside the repository (as build/ is).
    const std::string binary = PEENSIM_BINARY;
    const std::string source = PEENSIM_SOURCE_DIR;
    if (binary.rfind(source + "/", 0) == 0) {
        const std::vector<std::string> scenes = shipped_scenes(binary);
        EXPECT_NE(std::find(scenes.begin(), scenes.end(), source + "/scenes/gear.yaml"), scenes.end());
        EXPECT_NE(std::find(scenes.begin(), scenes.end(), source + "/scenes/rod.yaml"), scenes.end());
        EXPECT_TRUE(std::is_sorted(scenes.begin(), scenes.end()));
    }
    const std::vector<std::string> dirs = shipped_scene_search_dirs("/nonexistent/peensim/build/peensim");
    ASSERT_GE(dirs.size(), 2u);
    EXPECT_EQ(dirs[0], "/nonexistent/peensim/build/scenes");
    EXPECT_EQ(dirs[1], "/nonexistent/peensim/scenes");
    if (dirs.size() == 2) {  // no compiled-in source directory to fall back on: a clear error naming where it looked
        try {
            shipped_scenes("/nonexistent/peensim/build/peensim");
            ADD_FAILURE() << "expected an InputError";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("/nonexistent/peensim/build/scenes, /nonexistent/peensim/scenes"), std::string::npos)
                << e.what();
        }
    }
}

TEST(BenchJob, CommandLine) {
    const TestScene scene(tiny_spec());
    TempDir dir;
    const std::string log = (dir.path / "log.txt").string();
    const auto run = [&](const std::string& args) {
        const int status = std::system(("'" + std::string(PEENSIM_BINARY) + "' bench " + args + " > '" + log + "' 2>&1").c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    const auto output = [&] {
        std::ifstream in(log);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    };
    // --schemes before the scene takes one value (it must not swallow the scene path).
    ASSERT_EQ(run("--schemes step,step '" + scene.scene_path() + "' --duration 0.01 --csv '" + (dir.path / "b.csv").string() + "'"), 0)
        << output();
    EXPECT_NE(output().find("step#2 against step#1: speed ratio"), std::string::npos) << output();
    EXPECT_EQ(read_csv((dir.path / "b.csv").string()).size(), 6u);
    EXPECT_EQ(run("/nonexistent/peensim/scene.yaml --schemes step,step"), kExitInputError) << output();
    EXPECT_NE(output().find("error: "), std::string::npos) << output();
}

TEST(BenchJobStats, BatchMeansOfAKnownSeries) {
    // 1 s in 10 batches of 0.1 s: 10 impacts at 1 m/s in the even batches, 20 at 2 m/s in the odd.
    BatchedImpactStats s(1.0);
    for (int k = 0; k < kBenchBatches; ++k) {
        const int n = k % 2 ? 20 : 10;
        for (int i = 0; i < n; ++i) s.add(0.1 * k + 0.1 * (i + 0.5) / n, k % 2 ? 2.0 : 1.0);
    }
    EXPECT_EQ(s.count(), 150u);
    EXPECT_DOUBLE_EQ(s.rate_per_s(), 150.0);
    // Batch rates 100 and 200 per s: sample sd 50 sqrt(10/9), over sqrt(10).
    EXPECT_NEAR(s.rate_se_per_s(), 50.0 / 3.0, 1e-12);
    EXPECT_NEAR(s.mean_speed_m_per_s(), 5.0 / 3.0, 1e-15);
    // Ratio estimator: S_k - m n_k = -+20/3 in every batch: sqrt(10/9 x 10 x 400/9) / 150 = 4/27.
    EXPECT_NEAR(s.mean_speed_se_m_per_s(), 4.0 / 27.0, 1e-15);

    // A steady series has no spread.
    BatchedImpactStats steady(0.5);
    for (int i = 0; i < 100; ++i) steady.add(0.5 * (i + 0.5) / 100.0, 3.0);
    EXPECT_DOUBLE_EQ(steady.rate_per_s(), 200.0);
    EXPECT_NEAR(steady.rate_se_per_s(), 0.0, 1e-12);
    EXPECT_NEAR(steady.mean_speed_se_m_per_s(), 0.0, 1e-15);
    // An impact at the very end belongs to the last batch: rates 200 (x9) and 220, mean 202,
    // SE sqrt((9 x 4 + 324) / 90) = 2.
    steady.add(0.5, 3.0);
    EXPECT_DOUBLE_EQ(steady.rate_per_s(), 202.0);
    EXPECT_NEAR(steady.rate_se_per_s(), 2.0, 1e-12);

    // Merging is adding the impacts to one set.
    BatchedImpactStats merged(1.0);
    merged.merge(s);
    merged.merge(s);
    EXPECT_EQ(merged.count(), 300u);
    EXPECT_NEAR(merged.rate_se_per_s(), 2.0 * 50.0 / 3.0, 1e-12);
    EXPECT_NEAR(merged.mean_speed_se_m_per_s(), 4.0 / 27.0, 1e-15);

    const BatchedImpactStats empty(1.0);
    EXPECT_EQ(empty.rate_per_s(), 0.0);
    EXPECT_TRUE(std::isnan(empty.mean_speed_m_per_s()));
    EXPECT_TRUE(std::isnan(empty.mean_speed_se_m_per_s()));
}

TEST(BenchJobStats, DifferenceAndItsThreeSigmaBound) {
    const BenchDifference small = bench_difference(100.0, 1.0, 103.0, 1.0);
    EXPECT_NEAR(small.percent, 3.0, 1e-12);
    EXPECT_NEAR(small.bound_percent, 3.0 * std::sqrt(2.0), 1e-12);
    EXPECT_TRUE(small.within_noise);
    const BenchDifference large = bench_difference(100.0, 1.0, 95.0, 1.0);
    EXPECT_NEAR(large.percent, -5.0, 1e-12);
    EXPECT_FALSE(large.within_noise);
    const BenchDifference none = bench_difference(std::nan(""), std::nan(""), 1.0, 0.1);
    EXPECT_TRUE(std::isnan(none.percent));
    EXPECT_TRUE(none.within_noise);
    EXPECT_EQ(bench_difference(2.0, 0.0, 2.0, 0.0).percent, 0.0);
    EXPECT_TRUE(bench_difference(2.0, 0.0, 2.0, 0.0).within_noise);
}

}  // namespace
}  // namespace peensim
