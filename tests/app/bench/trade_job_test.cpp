// `peensim trade` on a tiny generated soft scene: a row per knob (the reference first, without an
// error against itself), every figure with its standard error, the rigid verdict line, the CSV with
// a row per knob and its columns, and a scene whose contacts are not hertz-mindlin refused with the
// law it lacks (exit 2). Nothing here is timed.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/bench/trade_job.h"
#include "app/run/run_job.h"
#include "support/files.h"
#include "support/temp_dir.h"
#include "support/test_scene.h"

namespace peensim::testing {
namespace {

TestSceneSpec tiny_soft() {
    TestSceneSpec s = small_rod_scene("soft", 0.04);
    s.soft = SoftSpec{};
    s.shot_count = 24;
    s.log = {"part"};
    return s;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

TEST(TradeJob, ARowPerKnobAgainstTheReferenceAndACsv) {
    const TestScene scene(tiny_soft());
    TempDir dir;
    TradeOptions o;
    o.scene_path = scene.scene_path();
    o.csv_path = (dir.path / "trade.csv").string();
    o.reference_steps = 40.0;
    std::ostringstream out, err;
    ASSERT_EQ(trade_job(o, out, err), kExitOk) << err.str();
    const std::string text = out.str();
    std::cout << text;
    for (const char* knob : {"soft, 40 steps/contact (reference)", "soft, 20 steps/contact", "soft, 10 steps/contact",
                             "soft, 20 steps, E x 0.1", "soft, 20 steps, E x 0.01", "rigid, event-driven", "rigid, time step R x 0.25",
                             "rigid, time step R x 0.1", "rigid, time step R x 0.05"})
        EXPECT_NE(text.find(knob), std::string::npos) << knob;
    EXPECT_EQ(text.find("soft, 80 steps"), std::string::npos);  // nothing finer than the reference
    EXPECT_NE(text.find("the rigid, instantaneous impact against the soft reference: impact rate"), std::string::npos);
    // The reference's row has no error against itself; the others do.
    for (const std::string& l : lines_of(text)) {
        if (l.rfind("soft, 40 steps/contact (reference)", 0) == 0) {
            EXPECT_EQ(l.find("SE)"), std::string::npos) << l;
        }
        if (l.rfind("rigid, event-driven", 0) == 0) {
            EXPECT_NE(l.find("SE)"), std::string::npos) << l;
        }
    }
    const std::vector<std::string> csv = lines_of(read_file(o.csv_path));
    ASSERT_EQ(csv.size(), 1u + 9u);
    EXPECT_EQ(csv[0].rfind("knob,scheme,wall_s,rate_per_s,rate_per_s_se,rate_per_s_error_pct,rate_per_s_error_se,mean_vn_mps", 0), 0u);
    EXPECT_NE(csv[0].find("coverage_pct_error_se,serious"), std::string::npos);
    EXPECT_EQ(csv[1].rfind("\"soft, 40 steps/contact (reference)\",soft,", 0), 0u);
}

TEST(TradeJob, AScenesContactsMustBeHertzMindlin) {
    TestSceneSpec spec = tiny_soft();
    spec.scheme = "event";
    spec.soft.reset();  // impulse laws
    const TestScene scene(spec);
    TradeOptions o;
    o.scene_path = scene.scene_path();
    std::ostringstream out, err;
    EXPECT_EQ(trade_job(o, out, err), kExitInputError);
    EXPECT_NE(err.str().find("expected a soft-sphere law ('hertz-mindlin', 'linear-spring-dashpot')"), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("scene.yaml"), std::string::npos) << err.str();
}

}  // namespace
}  // namespace peensim::testing
