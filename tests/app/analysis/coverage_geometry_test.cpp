// The coverage geometry a run computes on a thread of its own while it steps is the one an analysis
// computes for itself afterwards, sample for sample; a run that ends early stops it.
#include "app/analysis/coverage_geometry.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "model/model.h"
#include "scene/scene_parser.h"

namespace peensim {
namespace {

std::shared_ptr<const Model> shipped_gear() {
    return compile_model(parse_scene_file(std::string(PEENSIM_SOURCE_DIR) + "/scenes/gear.yaml"));
}

TEST(CoverageGeometry, OnItsOwnThreadItEqualsTheOneComputedWhenAsked) {
    const std::shared_ptr<const Model> model = shipped_gear();
    CoverageGeometry ahead(model, nullptr, 2);
    CoverageGeometry asked(model, nullptr, 0);
    std::size_t parts = 0;
    for (std::size_t ci = 0; ci < model->components.size(); ++ci) {
        const PartCoverageGeometry* a = ahead.part(ci);
        const PartCoverageGeometry* b = asked.part(ci);
        ASSERT_EQ(a == nullptr, b == nullptr) << model->components[ci].name;
        if (a == nullptr) continue;
        ++parts;
        ASSERT_EQ(a->map->sample_count(), b->map->sample_count());
        EXPECT_GT(a->map->sample_count(), 1'000'000);
        EXPECT_EQ(a->classes.size(), b->classes.size());
        EXPECT_EQ(a->classes.peened_area_m2(), b->classes.peened_area_m2());
        EXPECT_EQ(a->classes.reachable_area_m2(), b->classes.reachable_area_m2());
        for (std::size_t r = 0; r < a->classes.region_count(); ++r)
            EXPECT_EQ(a->classes.region_peened_area_m2(r), b->classes.region_peened_area_m2(r)) << "region " << r;
        for (std::size_t t = 0; t < a->map->triangle_count(); ++t) {
            ASSERT_EQ(a->classes.triangle_class(t), b->classes.triangle_class(t)) << "triangle " << t;
            ASSERT_EQ(a->classes.reachable_samples(t), b->classes.reachable_samples(t)) << "triangle " << t;
        }
        EXPECT_EQ(a->unreachable.whole.area_m2, b->unreachable.whole.area_m2);
        EXPECT_GT(a->unreachable.whole.area_m2, 0.0);  // the gear's bore, which its axle fills
        EXPECT_EQ(a->unreachable.triangle_share, b->unreachable.triangle_share);
        // A coverage counted from it starts at no dent.
        const std::unique_ptr<CoverageProgress> progress = part_coverage(ahead, ci, 0.98);
        ASSERT_NE(progress, nullptr);
        EXPECT_EQ(progress->coverage(), 0.0);
        EXPECT_EQ(progress->target(), 0.98);
    }
    EXPECT_EQ(parts, 1u);  // the gear; the chamber and the sonotrode are not logged
    EXPECT_EQ(part_coverage(ahead, 0, 0.98) == nullptr, ahead.part(0) == nullptr);
}

// The threads of this process now (Linux: one entry each in /proc/self/task).
std::size_t threads_now() {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) ++n;
    return n;
}

// A run interrupted (or failing) before the geometry is done destroys it at once: the thread
// stops between chunks of its work and is joined with its helpers, whatever it was doing.
TEST(CoverageGeometry, DestroyedBeforeItIsDoneItStopsAndLeavesNoThread) {
    const std::shared_ptr<const Model> model = shipped_gear();
    const std::size_t before = threads_now();
    for (int k = 0; k < 3; ++k) {
        CoverageGeometry ahead(model, nullptr, 2);
        EXPECT_GT(threads_now(), before);
    }
    EXPECT_EQ(threads_now(), before);
}

}  // namespace
}  // namespace peensim
