// Generated meshes against closed forms: areas and volumes (exact for the polygonal shapes,
// within discretisation error of the round ones), watertightness, outward orientation, the
// involute gear's profile, tooth count and triangle counts; the blade's volume, sharp edges and twist.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "common/input_error.h"
#include "geometry/mesh_checks.h"
#include "geometry/mesh_generators.h"

namespace peensim {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_closed_and_outward(const TriangleMesh& m) {
    const EdgeReport r = edge_report(m);
    EXPECT_EQ(r.boundary_edges, 0u);
    EXPECT_EQ(r.non_manifold_edges, 0u);
    EXPECT_EQ(r.misoriented_edges, 0u);
    EXPECT_TRUE(is_closed(m));
    EXPECT_GT(enclosed_volume(m), 0.0);
    EXPECT_EQ(m.source_facet.size(), m.triangle_count());
    EXPECT_EQ(m.group_of_triangle.size(), m.triangle_count());
}

// Mean normal of the triangles of one group, area-weighted.
Vec3 group_normal(const TriangleMesh& m, const std::string& name) {
    const auto g = static_cast<int>(std::find(m.group_names.begin(), m.group_names.end(), name) - m.group_names.begin());
    Vec3 sum = Vec3::Zero();
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        if (m.group_of_triangle[t] == g) sum += triangle_area(m, t) * triangle_normal(m, t);
    }
    return sum.normalized();
}

TEST(GeometryGenerators, BoxMatchesClosedForms) {
    const BoxSpec spec{Vec3(0.06, 0.03, 0.005), Vec3(0.0, 0.0, -0.0025), Eigen::Vector3i(1, 1, 1)};
    const TriangleMesh m = box(spec);
    expect_closed_and_outward(m);
    EXPECT_EQ(m.triangle_count(), 12u);
    EXPECT_EQ(m.vertices.size(), 8u);
    EXPECT_NEAR(surface_area(m), 2 * (0.06 * 0.03 + 0.03 * 0.005 + 0.005 * 0.06), 1e-15);
    EXPECT_NEAR(enclosed_volume(m), 0.06 * 0.03 * 0.005, 1e-15);
    EXPECT_TRUE(bounds(m).min_m.isApprox(Vec3(-0.03, -0.015, -0.005)));
    EXPECT_NEAR(bounds(m).max_m.z(), 0.0, 1e-18);
    EXPECT_TRUE(group_normal(m, "+z").isApprox(Vec3(0, 0, 1)));
    EXPECT_TRUE(group_normal(m, "-x").isApprox(Vec3(-1, 0, 0)));
}

TEST(GeometryGenerators, SubdividedBoxStaysWatertight) {
    const BoxSpec spec{Vec3(0.3, 0.7, 1.1), Vec3(0.1, 0.2, 0.3), Eigen::Vector3i(3, 5, 7)};
    const TriangleMesh m = box(spec);
    expect_closed_and_outward(m);
    EXPECT_EQ(m.triangle_count(), 2u * 2u * (3 * 5 + 5 * 7 + 7 * 3));
    EXPECT_EQ(m.vertices.size(), 4u * 6 * 8 - 2u * 4 * 6);  // grid points minus the interior ones
    EXPECT_NEAR(enclosed_volume(m), 0.3 * 0.7 * 1.1, 1e-14);
}

TEST(GeometryGenerators, OpenBoxLeavesOneFaceOutAndFacesInward) {
    const BoxSpec spec{Vec3(0.06, 0.03, 0.045), Vec3(0.0, 0.0, 0.0175), Eigen::Vector3i(2, 1, 3)};
    const TriangleMesh m = box_open(spec, BoxFace::minus_z, Facing::inward);
    const EdgeReport r = edge_report(m);
    EXPECT_EQ(r.boundary_edges, 2u * (2 + 1));  // the rim of the missing floor
    EXPECT_EQ(r.non_manifold_edges, 0u);
    EXPECT_EQ(r.misoriented_edges, 0u);
    EXPECT_EQ(m.group_names.size(), 5u);
    EXPECT_TRUE(group_normal(m, "+z").isApprox(Vec3(0, 0, -1)));  // the lid faces down into the cavity
    EXPECT_TRUE(group_normal(m, "+x").isApprox(Vec3(-1, 0, 0)));
    EXPECT_TRUE(group_normal(m, "-y").isApprox(Vec3(0, 1, 0)));

    const TriangleMesh outward = box_open(spec, BoxFace::plus_y, Facing::outward);
    EXPECT_TRUE(group_normal(outward, "-y").isApprox(Vec3(0, -1, 0)));
    EXPECT_EQ(edge_report(outward).boundary_edges, 2u * (2 + 3));
}

TEST(GeometryGenerators, BoxRejectsBadSizes) {
    EXPECT_THROW(box(BoxSpec{Vec3(1, 0, 1), Vec3::Zero(), Eigen::Vector3i::Ones()}), InputError);
    EXPECT_THROW(box(BoxSpec{Vec3(1, 1, 1), Vec3::Zero(), Eigen::Vector3i(1, 0, 1)}), InputError);
}

TEST(GeometryGenerators, CylinderIsTheExactPrismOfItsPolygon) {
    const int n = 96;
    const double radius = 0.005, height = 0.03;
    CylinderSpec spec{radius, height, n, Axis::y, Vec3(0, 0, 0.02), true, 30, 3};
    const TriangleMesh m = cylinder(spec);
    expect_closed_and_outward(m);
    EXPECT_EQ(m.triangle_count(), static_cast<std::size_t>(n * 30 * 2 + 2 * n * (2 * 3 - 1)));
    const double polygon_area = 0.5 * n * radius * radius * std::sin(2 * kPi / n);
    const double polygon_perimeter = 2.0 * n * radius * std::sin(kPi / n);
    EXPECT_NEAR(enclosed_volume(m), polygon_area * height, 1e-12 * polygon_area * height);
    EXPECT_NEAR(surface_area(m), 2 * polygon_area + polygon_perimeter * height, 1e-12);
    // ... and within discretisation error of the circle.
    EXPECT_NEAR(enclosed_volume(m), kPi * radius * radius * height, 1e-3 * kPi * radius * radius * height);
    const Bounds b = bounds(m);
    EXPECT_NEAR(b.min_m.y(), -0.015, 1e-15);
    EXPECT_NEAR(b.max_m.y(), 0.015, 1e-15);
    EXPECT_NEAR(b.max_m.z(), 0.025, 1e-15);  // angle 0 points along +z for axis y
    EXPECT_NEAR(b.min_m.x(), -radius, 1e-6 * radius);
    EXPECT_TRUE(group_normal(m, "cap-high").isApprox(Vec3(0, 1, 0)));
    EXPECT_TRUE(group_normal(m, "cap-low").isApprox(Vec3(0, -1, 0)));
}

TEST(GeometryGenerators, CylinderAlongEachAxisHasPositiveVolume) {
    for (Axis axis : {Axis::x, Axis::y, Axis::z}) {
        const TriangleMesh m = cylinder(CylinderSpec{0.01, 0.02, 16, axis, Vec3(1, 2, 3), true, 2, 2});
        expect_closed_and_outward(m);
        EXPECT_NEAR(bounds(m).size_m()[static_cast<int>(axis)], 0.02, 1e-12);
    }
}

TEST(GeometryGenerators, UncappedCylinderIsAnOpenTube) {
    const TriangleMesh m = cylinder(CylinderSpec{0.01, 0.02, 24, Axis::z, Vec3::Zero(), false, 3, 1});
    EXPECT_EQ(edge_report(m).boundary_edges, 48u);
    EXPECT_FALSE(is_closed(m));
    EXPECT_THROW(cylinder(CylinderSpec{0.01, 0.02, 2, Axis::z, Vec3::Zero(), true, 1, 1}), InputError);
}

TEST(GeometryGenerators, SteppedChamberFacesItsCavity) {
    SteppedChamberSpec spec;
    spec.lower_radius_m = 0.030;
    spec.upper_radius_m = 0.040;
    spec.bottom_z_m = -0.010;
    spec.step_z_m = 0.015;
    spec.lid_z_m = 0.075;
    spec.segments = 128;
    spec.lower_layers = 5;
    spec.upper_layers = 12;
    spec.step_rings = 2;
    spec.lid_rings = 8;
    const TriangleMesh m = stepped_tube_chamber(spec);
    const EdgeReport r = edge_report(m);
    EXPECT_EQ(r.boundary_edges, 128u);  // the open bottom rim
    EXPECT_EQ(r.non_manifold_edges, 0u);
    EXPECT_EQ(r.misoriented_edges, 0u);
    EXPECT_TRUE(group_normal(m, "lid").isApprox(Vec3(0, 0, -1)));
    EXPECT_TRUE(group_normal(m, "step").isApprox(Vec3(0, 0, 1)));
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        const Vec3 centroid = (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0;
        const Vec3 radial(centroid.x(), centroid.y(), 0.0);
        if (m.group_names[static_cast<std::size_t>(m.group_of_triangle[t])].find("wall") != std::string::npos) {
            EXPECT_LT(triangle_normal(m, t).dot(radial.normalized()), -0.99);
        }
    }

    // Closing the bottom with a disk that also faces the cavity (+z) makes a closed surface
    // whose divergence volume is minus the cavity's volume.
    TriangleMesh closed = m;
    const TriangleMesh floor = cylinder(CylinderSpec{0.030, 1e-3, 128, Axis::z, Vec3(0, 0, -0.0105), true, 1, 1});
    const auto floor_group = static_cast<int>(closed.group_names.size());
    closed.group_names.push_back("floor");
    std::vector<int> vertex_of;  // weld the disk's top ring onto the chamber rim
    for (const Vec3& v : floor.vertices) {
        int index = -1;
        for (std::size_t k = 0; k < closed.vertices.size(); ++k) {
            if ((closed.vertices[k] - v).norm() < 1e-12) index = static_cast<int>(k);
        }
        if (index < 0) {
            index = static_cast<int>(closed.vertices.size());
            closed.vertices.push_back(v);
        }
        vertex_of.push_back(index);
    }
    const int cap_high =
        static_cast<int>(std::find(floor.group_names.begin(), floor.group_names.end(), "cap-high") - floor.group_names.begin());
    for (std::size_t t = 0; t < floor.triangle_count(); ++t) {
        if (floor.group_of_triangle[t] != cap_high) continue;
        const auto& tri = floor.triangles[t];
        closed.triangles.push_back({vertex_of[static_cast<std::size_t>(tri[0])], vertex_of[static_cast<std::size_t>(tri[1])],
                                    vertex_of[static_cast<std::size_t>(tri[2])]});
        closed.source_facet.push_back(static_cast<int>(closed.source_facet.size()));
        closed.group_of_triangle.push_back(floor_group);
    }
    EXPECT_TRUE(is_closed(closed));
    EXPECT_EQ(edge_report(closed).misoriented_edges, 0u);
    const auto polygon_area = [](double radius) { return 0.5 * 128 * radius * radius * std::sin(2 * kPi / 128); };
    const double cavity = polygon_area(0.030) * 0.025 + polygon_area(0.040) * 0.060;
    EXPECT_NEAR(enclosed_volume(closed), -cavity, 1e-12 * cavity);

    spec.upper_radius_m = 0.020;
    EXPECT_THROW(stepped_tube_chamber(spec), InputError);
}

// The reference gear: module 2 mm, 20 teeth, 20 deg, 10 mm wide, 5 mm bore.
SpurGearSpec reference_gear() { return SpurGearSpec{}; }

// Exact area of the ideal gear outline minus the bore: root disk plus z teeth, each tooth
// integrated in polar strips (width 2 h(r) r dr).
double ideal_gear_area(const SpurGearSpec& spec) {
    const InvoluteToothProfile p(spec);
    const int steps = 200000;
    const double dr = (p.tip_radius_m() - p.root_radius_m()) / steps;
    double teeth = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double r = p.root_radius_m() + (i + 0.5) * dr;
        teeth += 2.0 * p.half_angle_rad(r) * r * dr;
    }
    return kPi * (p.root_radius_m() * p.root_radius_m() - spec.bore_radius_m * spec.bore_radius_m) + spec.teeth * teeth;
}

TEST(GeometryGenerators, InvoluteProfileHasTheStandardCircles) {
    const InvoluteToothProfile p(reference_gear());
    EXPECT_DOUBLE_EQ(p.pitch_radius_m(), 0.020);
    EXPECT_NEAR(p.base_radius_m(), 0.020 * std::cos(20 * kPi / 180), 1e-15);
    EXPECT_DOUBLE_EQ(p.tip_radius_m(), 0.022);
    EXPECT_DOUBLE_EQ(p.root_radius_m(), 0.0175);
    // Tooth thickness on the pitch circle is half the circular pitch: pi m / 2.
    EXPECT_NEAR(2 * p.half_angle_rad(0.020) * 0.020, kPi * 0.002 / 2, 1e-15);
    EXPECT_GT(p.half_angle_rad(p.tip_radius_m()), 0.0);
    EXPECT_DOUBLE_EQ(p.half_angle_rad(p.root_radius_m()), p.half_angle_rad(p.base_radius_m()));  // radial flank
    EXPECT_NEAR(p.radius_at_roll(p.roll_angle_at(0.021)), 0.021, 1e-15);
}

TEST(GeometryGenerators, CoarseGearIsClosedAndAbout5kTriangles) {
    const SpurGearSpec spec = reference_gear();
    const SpurGearResolution res = gear_resolution_for_triangle_count(spec, 5000);
    const TriangleMesh m = spur_gear(spec, res);
    expect_closed_and_outward(m);
    EXPECT_EQ(m.triangle_count(), gear_triangle_count(res, spec.teeth));
    EXPECT_NEAR(static_cast<double>(m.triangle_count()), 5000.0, 500.0);
    const InvoluteToothProfile p(spec);
    const auto disk = [&](double r) { return kPi * (r * r - spec.bore_radius_m * spec.bore_radius_m) * spec.face_width_m; };
    const double volume = enclosed_volume(m);
    EXPECT_GT(volume, disk(p.root_radius_m()));
    EXPECT_LT(volume, disk(p.tip_radius_m()));
    EXPECT_NEAR(volume, ideal_gear_area(spec) * spec.face_width_m, 0.01 * volume);
}

TEST(GeometryGenerators, FineGearIsClosedAndAbout500kTriangles) {
    const SpurGearSpec spec = reference_gear();
    const SpurGearResolution res = gear_resolution_for_triangle_count(spec, 500000);
    const TriangleMesh m = spur_gear(spec, res);
    // One edge report and one volume only: at 500k triangles these dominate the test's time.
    const EdgeReport r = edge_report(m);
    EXPECT_EQ(r.boundary_edges + r.non_manifold_edges + r.misoriented_edges, 0u);  // closed, consistent
    EXPECT_EQ(m.triangle_count(), gear_triangle_count(res, spec.teeth));
    EXPECT_NEAR(static_cast<double>(m.triangle_count()), 500000.0, 25000.0);
    const double ideal = ideal_gear_area(spec) * spec.face_width_m;
    EXPECT_NEAR(enclosed_volume(m), ideal, 1e-3 * ideal);  // positive: outward
}

TEST(GeometryGenerators, GearHasTwentyTeethAndItsBoundsAlongY) {
    const SpurGearSpec spec = reference_gear();
    const TriangleMesh m = spur_gear(spec, gear_resolution_for_edge_length(spec, 1e-3));
    const InvoluteToothProfile p(spec);
    // Angles (around y, from +z) of the vertices beyond the pitch circle form one cluster per tooth.
    std::vector<double> angles;
    for (const Vec3& v : m.vertices) {
        if (std::hypot(v.z(), v.x()) > p.pitch_radius_m() + 1e-9) angles.push_back(std::atan2(v.x(), v.z()));
    }
    std::sort(angles.begin(), angles.end());
    int clusters = 0;
    for (std::size_t i = 0; i < angles.size(); ++i) {
        const double previous = i == 0 ? angles.back() - 2 * kPi : angles[i - 1];
        if (angles[i] - previous > 0.5 * p.pitch_angle_rad()) ++clusters;
    }
    EXPECT_EQ(clusters, 20);
    // Tooth 0 is centred on +z.
    EXPECT_NEAR(bounds(m).max_m.z(), p.tip_radius_m(), 1e-12);
    EXPECT_NEAR(bounds(m).min_m.y(), -0.005, 1e-15);
    EXPECT_NEAR(bounds(m).max_m.y(), 0.005, 1e-15);
    // Every tip vertex lies on the tip circle, none beyond it.
    for (const Vec3& v : m.vertices) EXPECT_LE(std::hypot(v.z(), v.x()), p.tip_radius_m() * (1 + 1e-12));
}

TEST(GeometryGenerators, GearGroupsAreToothSectors) {
    const SpurGearSpec spec = reference_gear();
    const TriangleMesh m = spur_gear(spec, gear_resolution_for_triangle_count(spec, 5000));
    ASSERT_EQ(m.group_names.size(), 20u);
    EXPECT_EQ(m.group_names[7], "tooth-7");
    std::vector<int> per_group(20, 0);
    for (int g : m.group_of_triangle) ++per_group[static_cast<std::size_t>(g)];
    const double mean = static_cast<double>(m.triangle_count()) / 20.0;
    for (int n : per_group) EXPECT_NEAR(n, mean, 0.1 * mean);
    // Tooth 5's triangles lie around angle 5 * 18 deg (from +z towards +x, around +y).
    const double pitch = 2 * kPi / 20;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        if (m.group_of_triangle[t] != 5) continue;
        const Vec3 c = (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3.0;
        const double angle = std::atan2(c.x(), c.z());
        EXPECT_NEAR(angle, 5 * pitch, 0.5 * pitch + 1e-9);
    }
}

TEST(GeometryGenerators, GearTriangleCountFollowsTheTarget) {
    const SpurGearSpec spec = reference_gear();
    std::size_t previous = 0;
    for (std::size_t target : {2000u, 5000u, 20000u, 100000u}) {
        const std::size_t n = gear_triangle_count(gear_resolution_for_triangle_count(spec, target), spec.teeth);
        EXPECT_GT(n, previous);
        EXPECT_NEAR(static_cast<double>(n), static_cast<double>(target), 0.1 * static_cast<double>(target));
        previous = n;
    }
}

TEST(GeometryGenerators, GearAlongZWithManyTeethHasNoRadialFlank) {
    SpurGearSpec spec;
    spec.teeth = 50;  // root circle outside the base circle
    spec.module_m = 1e-3;
    spec.axis = Axis::z;
    spec.center_m = Vec3(0.1, 0.2, 0.3);
    const SpurGearResolution res = gear_resolution_for_edge_length(spec, 1e-3);
    EXPECT_EQ(res.radial_flank_segments, 0);
    const TriangleMesh m = spur_gear(spec, res);
    expect_closed_and_outward(m);
    EXPECT_NEAR(enclosed_volume(m), ideal_gear_area(spec) * spec.face_width_m, 0.005 * enclosed_volume(m));
    EXPECT_NEAR(bounds(m).max_m.z(), 0.305, 1e-12);
}

// The blade: closed and outward; its volume the lens area (2/3) t c times the span (the cosine
// spacing resolves the section's parabolas); its edges sharp wedges of 2 atan(2 t / c); its ends
// turned by +-twist/2 about the span axis.
TEST(GeometryGenerators, BladeIsAClosedTwistedLensWithSharpEdges) {
    BladeSpec spec;
    spec.chord_m = 0.02;
    spec.span_m = 0.04;
    spec.thickness_m = 0.0008;
    spec.twist_rad = kPi / 4.0;
    spec.axis = Axis::x;
    spec.center_m = Vec3(0.001, 0.002, 0.003);
    const TriangleMesh m = blade(spec);
    expect_closed_and_outward(m);
    EXPECT_EQ(m.triangle_count(),
              static_cast<std::size_t>(2 * 2 * spec.chord_points * (spec.span_stations - 1) + 2 * (2 * spec.chord_points - 2)));
    EXPECT_NEAR(enclosed_volume(m), 2.0 / 3.0 * spec.thickness_m * spec.chord_m * spec.span_m, 0.005 * enclosed_volume(m));
    // The end caps face along the span axis.
    EXPECT_NEAR(group_normal(m, "end-high").dot(Vec3::UnitX()), 1.0, 1e-12);
    EXPECT_NEAR(group_normal(m, "end-low").dot(Vec3::UnitX()), -1.0, 1e-12);
    // Leading edge at each end: the point farthest from the span axis, turned by +-twist/2 from y.
    const auto edge_angle_at = [&](double x) {
        double best = -1.0, angle = 0.0;
        for (const Vec3& v : m.vertices) {
            if (std::abs(v.x() - (spec.center_m.x() + x)) > 1e-12) continue;
            const Vec3 r = v - spec.center_m;
            if (r.y() > 0.0 && r.squaredNorm() > best) best = r.squaredNorm(), angle = std::atan2(r.z(), r.y());
        }
        return angle;
    };
    EXPECT_NEAR(edge_angle_at(0.5 * spec.span_m), spec.twist_rad / 2.0, 1e-12);
    EXPECT_NEAR(edge_angle_at(-0.5 * spec.span_m), -spec.twist_rad / 2.0, 1e-12);
    // Sharp: untwisted (so that no quad is warped), the two surface facets at the edge meet at the
    // lens's wedge angle (to the first chord point's secant, within 2 %).
    BladeSpec straight = spec;
    straight.twist_rad = 0.0;
    const TriangleMesh m2 = blade(straight);
    const double wedge = 2.0 * std::atan(2.0 * spec.thickness_m / spec.chord_m);
    double sharpest = 0.0;
    for (std::size_t t = 0; t < m2.triangle_count(); ++t)
        for (std::size_t u = t + 1; u < m2.triangle_count(); ++u) {
            if (m2.group_names[static_cast<std::size_t>(m2.group_of_triangle[t])] != "surface" ||
                m2.group_of_triangle[u] != m2.group_of_triangle[t])
                continue;
            int shared = 0;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    shared += m2.triangles[t][static_cast<std::size_t>(a)] == m2.triangles[u][static_cast<std::size_t>(b)];
            if (shared == 2)
                sharpest = std::max(sharpest, std::acos(std::clamp(triangle_normal(m2, t).dot(triangle_normal(m2, u)), -1.0, 1.0)));
            if (u > t + 8 * static_cast<std::size_t>(spec.chord_points)) break;  // neighbours lie within a few rows
        }
    EXPECT_NEAR(kPi - sharpest, wedge, 0.02 * wedge);
}

TEST(GeometryGenerators, ImpossibleBladesAreRejected) {
    BladeSpec thick;
    thick.thickness_m = thick.chord_m;
    EXPECT_THROW(blade(thick), InputError);
    BladeSpec coarse;
    coarse.span_stations = 1;
    EXPECT_THROW(blade(coarse), InputError);
    BladeSpec flat;
    flat.span_m = 0.0;
    try {
        blade(flat);
        ADD_FAILURE() << "a blade without span was built";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "blade");
    }
}

TEST(GeometryGenerators, ImpossibleGearsAreRejected) {
    SpurGearSpec pointed = reference_gear();
    pointed.addendum_coefficient = 2.0;
    EXPECT_THROW(InvoluteToothProfile{pointed}, InputError);
    SpurGearSpec big_bore = reference_gear();
    big_bore.bore_radius_m = 0.018;
    EXPECT_THROW(spur_gear(big_bore, SpurGearResolution{}), InputError);
    SpurGearResolution none;
    none.axial_layers = 0;
    EXPECT_THROW(spur_gear(reference_gear(), none), InputError);
    try {
        InvoluteToothProfile{pointed};
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "gear");
        EXPECT_NE(std::string(e.what()).find("pointed"), std::string::npos);
    }
}

}  // namespace
}  // namespace peensim
