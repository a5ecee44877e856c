// Regions: scene `regions` entries -> selections of a surface: each triangle by the share of its
// area inside (sub-triangle samples), each point exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>

#include "analysis/coverage_progress.h"
#include "analysis/region_stats.h"
#include "analysis/regions.h"
#include "analysis/sample_classes.h"
#include "common/input_error.h"
#include "common/parallel_chunks.h"
#include "geometry/box_mesh.h"
#include "geometry/cylinder_mesh.h"
#include "geometry/mesh_builder.h"
#include "geometry/mesh_checks.h"
#include "geometry/mesh_loader.h"
#include "geometry/spur_gear_mesh.h"

namespace peensim {
namespace {

constexpr double deg = std::numbers::pi / 180.0;  // rad per degree
constexpr double pi = std::numbers::pi;

Vec3 centroid(const TriangleMesh& m, std::size_t t) { return (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0; }

RegionDesc named(const std::string& name) {
    RegionDesc r;
    r.name = name;
    return r;
}

RegionDesc gear_teeth() {
    RegionDesc r = named("teeth");
    r.sectors = SectorsCondition{{Vec3::Zero(), Vec3::UnitY(), Vec3::UnitZ()}, 20, 18 * deg, 0.0, "tooth-"};
    return r;
}

RegionDesc half_space(const std::string& name, const Vec3& point, const Vec3& normal) {
    RegionDesc r = named(name);
    r.half_space = HalfSpaceCondition{point, normal};
    return r;
}

// A flat square [-1, 1]^2 at z = 0 cut into `n` x `n` quads (2 n^2 triangles), normal +z.
TriangleMesh plate(int n) {
    MeshBuilder b;
    const int g = b.group("plate");
    const double h = 2.0 / n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 a(-1 + i * h, -1 + j * h, 0), c(-1 + (i + 1) * h, -1 + (j + 1) * h, 0);
            b.add_triangle(a, Vec3(c.x(), a.y(), 0), c, g);
            b.add_triangle(a, c, Vec3(a.x(), c.y(), 0), g);
        }
    return b.take();
}

double share_sum(const RegionSet& set, std::size_t r, const TriangleMesh& m) {
    double area = 0.0;
    for (const RegionShare& s : set.shares(r)) area += s.fraction * triangle_area(m, static_cast<std::size_t>(s.triangle));
    return area;
}

// Every point of the gear in exactly one tooth (shares sum to 1 per triangle), the teeth alike
// (equal areas to `area_tolerance` relative), tooth 0 along +z, tooth 5 along +x, tooth 10 along -z.
void expect_twenty_equal_teeth(const TriangleMesh& gear, double area_tolerance) {
    const RegionSet teeth(gear, {gear_teeth()});
    ASSERT_EQ(teeth.size(), 20u);
    std::vector<double> owned(gear.triangle_count(), 0.0);
    double total = 0.0;
    for (std::size_t t = 0; t < gear.triangle_count(); ++t) total += triangle_area(gear, t);
    for (std::size_t i = 0; i < teeth.size(); ++i) {
        EXPECT_EQ(teeth.name(i), "tooth-" + std::to_string(i));
        for (const RegionShare& s : teeth.shares(i)) owned[static_cast<std::size_t>(s.triangle)] += s.fraction;
        EXPECT_NEAR(teeth.area_m2(i), share_sum(teeth, i, gear), 1e-18);
    }
    for (std::size_t t = 0; t < owned.size(); ++t) EXPECT_NEAR(owned[t], 1.0, 1e-12) << "triangle " << t;
    for (std::size_t i = 0; i < teeth.size(); ++i)
        EXPECT_NEAR(teeth.area_m2(i), total / 20.0, area_tolerance * total / 20.0) << teeth.name(i);
    auto mean_direction = [&](std::size_t r) {
        Vec3 s = Vec3::Zero();
        for (const RegionShare& x : teeth.shares(r))
            s += x.fraction * triangle_area(gear, static_cast<std::size_t>(x.triangle)) *
                 centroid(gear, static_cast<std::size_t>(x.triangle));
        return Vec3(Vec3(s.x(), 0.0, s.z()).normalized());
    };
    EXPECT_GT(mean_direction(0).z(), 0.999);
    EXPECT_LT(mean_direction(10).z(), -0.999);
    EXPECT_GT(mean_direction(5).x(), 0.999);
}

TEST(AnalysisRegions, ShippedGearTeethTileTheGearWithEqualTeeth) {
    // assets/gear.stl stores float32 coordinates (relative rounding ~6e-8 each).
    expect_twenty_equal_teeth(load_mesh(std::string(PEENSIM_SOURCE_DIR) + "/assets/gear.stl", 1e-3), 1e-6);
}

// The shares are tallied on every core, chunk by chunk of triangles, and joined in triangle order:
// the same set, to the bit, on one thread and on several (teeth, a bore mask and a facing entry
// that overlap them, so that candidates found by a corner only and masks both occur).
TEST(AnalysisRegions, TheSameSetToTheBitOnOneThreadAndOnSeveral) {
    const TriangleMesh gear = load_mesh(std::string(PEENSIM_SOURCE_DIR) + "/assets/gear.stl", 1e-3);
    RegionDesc bore = named("bore");
    bore.distance_to_axis = AxisDistanceCondition{Vec3::Zero(), Vec3::UnitY(), 0.0, 0.00501};
    bore.exclude = true;
    RegionDesc up = named("up");
    up.facing = FacingCondition{Vec3::UnitY(), 30 * deg};
    const std::vector<RegionDesc> entries = {gear_teeth(), bore, up};
    set_analysis_threads(1);
    const RegionSet one(gear, entries);
    set_analysis_threads(3);
    const RegionSet three(gear, entries);
    set_analysis_threads(0);
    ASSERT_EQ(one.size(), three.size());
    std::vector<std::uint32_t> a, b;
    for (std::size_t r = 0; r < one.size(); ++r) {
        EXPECT_EQ(one.area_m2(r), three.area_m2(r)) << one.name(r);
        ASSERT_EQ(one.shares(r).size(), three.shares(r).size()) << one.name(r);
        for (std::size_t k = 0; k < one.shares(r).size(); ++k) {
            EXPECT_EQ(one.shares(r)[k].triangle, three.shares(r)[k].triangle);
            EXPECT_EQ(one.shares(r)[k].fraction, three.shares(r)[k].fraction);
        }
    }
    for (std::size_t t = 0; t < gear.triangle_count(); ++t) {
        EXPECT_EQ(one.excluded_fraction(t), three.excluded_fraction(t)) << t;
        EXPECT_EQ(one.dominant_region(t), three.dominant_region(t)) << t;
        const Vec3 c = centroid(gear, t);
        one.regions_at(c, t, a);
        three.regions_at(c, t, b);
        EXPECT_EQ(a, b) << t;
    }
    EXPECT_GT(one.area_m2(20), 0.0);  // the bore is there
    EXPECT_GT(one.area_m2(21), 0.0);  // and the faces facing up
}

// A copy (the setup check's set, handed to the coverage geometry and the analysis) is the same
// set and stands alone: its regions read its own entries once the original is gone.
TEST(AnalysisRegions, ACopyIsTheSameSetAndOutlivesItsOriginal) {
    const TriangleMesh gear = load_mesh(std::string(PEENSIM_SOURCE_DIR) + "/assets/gear.stl", 1e-3);
    RegionDesc bore = named("bore");
    bore.distance_to_axis = AxisDistanceCondition{Vec3::Zero(), Vec3::UnitY(), 0.0, 0.00501};
    bore.exclude = true;
    auto original = std::make_unique<RegionSet>(gear, std::vector<RegionDesc>{gear_teeth(), bore});
    const RegionSet reference(gear, {gear_teeth(), bore});
    RegionSet copy(*original);
    RegionSet assigned;
    assigned = *original;
    original.reset();
    for (const RegionSet* set : {&copy, &assigned}) {
        ASSERT_EQ(set->size(), reference.size());
        for (std::size_t r = 0; r < reference.size(); ++r) {
            EXPECT_EQ(set->name(r), reference.name(r));
            EXPECT_EQ(set->entry(r).name, reference.entry(r).name);
            EXPECT_EQ(set->excluded(r), reference.excluded(r));
            EXPECT_EQ(set->area_m2(r), reference.area_m2(r));
        }
        std::vector<std::uint32_t> a, b;
        for (std::size_t t = 0; t < gear.triangle_count(); t += 7) {
            const Vec3 c = centroid(gear, t);
            set->regions_at(c, t, a);
            reference.regions_at(c, t, b);
            EXPECT_EQ(a, b) << t;
        }
    }
}

TEST(AnalysisRegions, GeneratedGearTeethAreEqualToRoundOff) {
    const SpurGearSpec spec;  // module 2 mm, 20 teeth, axis y, centred at the origin
    expect_twenty_equal_teeth(spur_gear(spec, gear_resolution_for_triangle_count(spec, 5000)), 1e-9);
}

TEST(AnalysisRegions, ATriangleCrossingABoundaryIsSplitByArea) {
    // The plate as 2 triangles: x >= 0.3 holds 0.7 x 2 = 1.4 m2 of its 4 m2; centroids alone would
    // give 0 or 2 m2. Each triangle gets kRegionSamplesPerEdge^2 samples; a straight cut of length L
    // misplaces at most half the sub-triangles it crosses: |error| <= L h / 2, h their leg.
    const TriangleMesh coarse = plate(1);
    const RegionSet set(coarse, {half_space("right", Vec3(0.3, 0, 0), Vec3::UnitX())});
    const double h = 2.0 / kRegionSamplesPerEdge;  // m
    EXPECT_NEAR(set.area_m2(0), 1.4, 2.0 * h / 2.0);
    ASSERT_EQ(set.shares(0).size(), 2u);
    // A fine tessellation of the same plate gives the same area.
    const RegionSet fine(plate(40), {half_space("right", Vec3(0.3, 0, 0), Vec3::UnitX())});
    EXPECT_NEAR(fine.area_m2(0), 1.4, 1e-3);
    // Points on either side of the cut within one triangle: exact membership.
    const std::size_t t = 0;
    EXPECT_TRUE(set.contains(0, Vec3(0.31, -0.9, 0), t));
    EXPECT_FALSE(set.contains(0, Vec3(0.29, -0.9, 0), t));
    std::vector<std::uint32_t> out{7, 7};
    set.regions_at(Vec3(0.31, -0.9, 0), t, out);
    EXPECT_EQ(out, (std::vector<std::uint32_t>{0}));
    set.regions_at(Vec3(0.29, -0.9, 0), t, out);
    EXPECT_TRUE(out.empty());
}

TEST(AnalysisRegions, SingleSectorMatchesTheSectorsEntry) {
    const TriangleMesh gear = load_mesh(std::string(PEENSIM_SOURCE_DIR) + "/assets/gear.stl", 1e-3);
    RegionDesc sector = named("lowest");
    sector.sector = SectorCondition{{Vec3::Zero(), Vec3::UnitY(), Vec3::UnitZ()}, 171 * deg, 189 * deg};  // tooth 10 is centred at 180 deg
    const RegionSet r(gear, {sector, gear_teeth()});
    ASSERT_EQ(r.size(), 21u);
    EXPECT_EQ(r.name(0), "lowest");
    ASSERT_EQ(r.shares(0).size(), r.shares(11).size());
    for (std::size_t k = 0; k < r.shares(0).size(); ++k) {
        EXPECT_EQ(r.shares(0)[k].triangle, r.shares(11)[k].triangle);
        EXPECT_EQ(r.shares(0)[k].fraction, r.shares(11)[k].fraction);
    }
}

TEST(AnalysisRegions, FacingSelectsByTheTrianglesNormal) {
    // Unit cube centred at the origin, outward normals: facing +z within 10 deg is the top face.
    const TriangleMesh cube = box(BoxSpec{Vec3::Ones(), Vec3::Zero(), Eigen::Vector3i(2, 2, 2)});
    RegionDesc top = named("top");
    top.facing = FacingCondition{Vec3::UnitZ(), 10 * deg};
    RegionDesc sides = named("sides");
    sides.facing = FacingCondition{Vec3::UnitX(), 91 * deg};  // +x and the four faces at 90 deg
    const RegionSet r(cube, {top, sides});
    EXPECT_NEAR(r.area_m2(0), 1.0, 1e-15);
    EXPECT_EQ(r.shares(0).size(), 8u);
    for (const RegionShare& s : r.shares(0)) EXPECT_EQ(s.fraction, 1.0);
    EXPECT_NEAR(r.area_m2(1), 5.0, 1e-14);
}

TEST(AnalysisRegions, DistancesToAnAxisAndToAPoint) {
    // A capped cylinder r = 10 mm, h = 20 mm: its wall lies 10 mm from the axis (inscribed polygon:
    // the wall's points lie between 10 cos(pi / 64) and 10 mm).
    const TriangleMesh tube = cylinder(CylinderSpec{0.01, 0.02, 64, Axis::z, Vec3::Zero(), false, 1, 1});
    const TriangleMesh can = cylinder(CylinderSpec{0.01, 0.02, 64, Axis::z, Vec3::Zero(), true, 1, 4});
    RegionDesc wall = named("wall");
    wall.distance_to_axis = AxisDistanceCondition{Vec3::Zero(), Vec3::UnitZ(), 0.0099, std::numeric_limits<double>::infinity()};
    RegionDesc hub = named("hub");  // the caps within 5 mm of the axis
    hub.distance_to_axis = AxisDistanceCondition{Vec3::Zero(), Vec3::UnitZ(), 0.0, 0.005};
    RegionDesc spot = named("spot");  // a disc of 4 mm on the top cap
    spot.distance_to_point = PointDistanceCondition{Vec3(0, 0, 0.01), 0.0, 0.004};
    const double wall_area = 64 * 2 * 0.01 * std::sin(pi / 64) * 0.02;  // the 64 flat sides
    EXPECT_NEAR(RegionSet(tube, {wall}).area_m2(0), wall_area, 1e-12);
    const RegionSet r(can, {hub, spot});
    EXPECT_NEAR(r.area_m2(0), 2 * pi * 0.005 * 0.005, 0.01 * 2 * pi * 0.005 * 0.005);
    EXPECT_NEAR(r.area_m2(1), pi * 0.004 * 0.004, 0.01 * pi * 0.004 * 0.004);
}

TEST(AnalysisRegions, ConditionsOfOneEntrySelectTheirIntersection) {
    // Sectors and facing together: each tooth's faces toward +y only (one end face's share).
    const TriangleMesh gear = load_mesh(std::string(PEENSIM_SOURCE_DIR) + "/assets/gear.stl", 1e-3);
    RegionDesc ends = gear_teeth();
    ends.name = "ends";
    ends.sectors->name_prefix = "end-";
    ends.facing = FacingCondition{Vec3::UnitY(), 1 * deg};
    RegionDesc end_faces = named("front");
    end_faces.facing = FacingCondition{Vec3::UnitY(), 1 * deg};
    const RegionSet r(gear, {ends, end_faces});
    double sum = 0.0;
    for (std::size_t i = 0; i < 20; ++i) sum += r.area_m2(i);
    EXPECT_NEAR(sum, r.area_m2(20), 1e-12 * r.area_m2(20));
    EXPECT_NEAR(r.area_m2(3), r.area_m2(20) / 20.0, 1e-6 * r.area_m2(20));
    for (const RegionShare& s : r.shares(3)) EXPECT_GT(triangle_normal(gear, static_cast<std::size_t>(s.triangle)).y(), 0.999);
}

TEST(AnalysisRegions, ExcludedRegionsAreAUnionNotASum) {
    const TriangleMesh p = plate(10);  // cells of 0.2 m: x = 0 and x = 0.4 lie on cell edges
    RegionDesc left = half_space("left", Vec3::Zero(), -Vec3::UnitX());
    left.exclude = true;
    RegionDesc middle = named("middle");  // overlaps `left` on -0.4 <= x <= 0
    middle.box = BoxCondition{Vec3(-0.4, -2, -1), Vec3(0.4, 2, 1)};
    middle.exclude = true;
    const RegionSet r(p, {left, middle, half_space("kept", Vec3::Zero(), Vec3::UnitX())});
    EXPECT_TRUE(r.excluded(0));
    EXPECT_FALSE(r.excluded(2));
    double excluded = 0.0;
    for (std::size_t t = 0; t < p.triangle_count(); ++t) {
        excluded += r.excluded_fraction(t) * triangle_area(p, t);
        const double x = centroid(p, t).x();
        EXPECT_EQ(r.excluded_fraction(t), x < 0.4 ? 1.0 : 0.0) << x;
        EXPECT_EQ(r.dominant_region(t), x < 0.0 ? 0 : x < 0.4 ? 1 : 2) << x;
    }
    EXPECT_NEAR(excluded, 1.4 * 2.0, 1e-12);
    // A mask listed after a region it overlaps names the triangles it masks (the gear's bore in a
    // tooth's sector): of equal shares, the excluded region.
    RegionDesc mask = half_space("mask", Vec3::Zero(), -Vec3::UnitX());
    mask.exclude = true;
    const RegionSet masked(p, {named("everything"), mask});
    for (std::size_t t = 0; t < p.triangle_count(); ++t) EXPECT_EQ(masked.dominant_region(t), centroid(p, t).x() < 0.0 ? 1 : 0);
    // Without an excluded region nothing is.
    const RegionSet none(p, {half_space("kept", Vec3::Zero(), Vec3::UnitX())});
    EXPECT_EQ(none.excluded_fraction(3), 0.0);
}

TEST(AnalysisRegions, GroupSelectsTheNamedSolid) {
    MeshBuilder b;
    const int a = b.group("A");
    const int g = b.group("B");
    b.add_triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), a);
    b.add_triangle(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), g);
    b.add_triangle(Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(0, 1, 2), a);
    const TriangleMesh m = b.take();
    RegionDesc solid = named("solid-A");
    solid.group = "A";
    const RegionSet r(m, {solid});
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r.triangles(0), (std::vector<int>{0, 2}));

    solid.group = "C";
    solid.where = SourceLocation{"scene.yaml", 12, 9};
    try {
        RegionSet unknown(m, {solid});
        FAIL() << "an unknown group was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where().line, 12);
        EXPECT_EQ(e.field(), "regions[solid-A].group");
        EXPECT_NE(std::string(e.what()).find("no group 'C'; its groups: 'A', 'B'"), std::string::npos) << e.what();
    }
}

TEST(AnalysisRegions, StatsOfATallyAndCoverageOverThePeenedArea) {
    const TriangleMesh cube = box(BoxSpec{Vec3::Ones(), Vec3::Zero(), Eigen::Vector3i(2, 2, 2)});
    RegionDesc top = named("top");  // the +z face exactly (a box would take a band of the sides too: points count)
    top.facing = FacingCondition{Vec3::UnitZ(), 1 * deg};
    const RegionSet regions(cube, {top});
    RegionTally tally;
    const double shot_mass = 0.01;  // kg
    for (double v : {2.0, 4.0, 3.0}) tally.add(v, 0.5 * shot_mass * v * v);
    const double duration = 2.0;  // s
    const RegionStats s = region_stats(regions, 0, tally, nullptr, duration);
    EXPECT_EQ(s.triangles, 8u);
    EXPECT_NEAR(s.area_m2, 1.0, 1e-15);
    EXPECT_TRUE(std::isnan(s.peened_area_m2));  // no coverage: no peened area either
    EXPECT_EQ(s.impacts, 3u);
    EXPECT_NEAR(s.impacts_per_mm2_s, 3.0 / 1e6 / duration, 1e-20);
    EXPECT_NEAR(s.mean_normal_speed, 3.0, 1e-15);
    EXPECT_EQ(s.max_normal_speed, 4.0);
    EXPECT_NEAR(s.energy_per_area, 0.5 * shot_mass * (4.0 + 16.0 + 9.0) / 1.0, 1e-15);
    EXPECT_TRUE(std::isnan(s.coverage));

    // A dent of 0.00785 m2 on the top face, everything in reach, then half of the cube out of reach
    // (x < 0): coverage over the other half.
    const auto progress = [&](const ReachTest& reach) {
        auto map = std::make_unique<CoverageMap>(cube, 0.01, 0.13);
        SampleClasses classes(*map, cube, regions, reach, 0.01, 0.05);
        CoverageProgress p(std::move(map), std::move(classes), 0.98);
        p.add_dent(Vec3(0.25, 0.25, 0.5), 0.1, 1.0);
        return p;
    };
    const CoverageProgress all = progress([](const Vec3&, std::size_t, double) { return true; });
    const RegionStats whole = region_stats(regions, 0, tally, &all, duration);
    EXPECT_NEAR(whole.peened_area_m2, 1.0, 1e-12);
    EXPECT_NEAR(whole.coverage, pi * 0.05 * 0.05, 2e-3);
    const CoverageProgress half_reach = progress([](const Vec3& p, std::size_t, double) { return p.x() >= 0.0; });
    const RegionStats half = region_stats(regions, 0, tally, &half_reach, duration);
    EXPECT_NEAR(half.peened_area_m2, 0.5, 1e-12);
    EXPECT_NEAR(half.unreachable_area_m2, 0.5, 1e-12);
    EXPECT_NEAR(half.coverage, pi * 0.05 * 0.05 / 0.5, 4e-3);
    EXPECT_NEAR(half_reach.coverage(), half_reach.map().covered_area() / 3.0, 1e-12);  // 6 faces, 3 m2 peened
}

}  // namespace
}  // namespace peensim
