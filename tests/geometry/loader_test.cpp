// load_mesh on STL (binary and ASCII), OBJ and PLY files: welding, scaling, the map from
// triangles back to file facets, groups, dropped degenerate facets, and the errors a user
// sees for missing, garbage and empty files; the STL writers' file format.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.h"
#include "geometry/mesh_checks.h"
#include "geometry/mesh_generators.h"
#include "geometry/mesh_loader.h"
#include "geometry/stl_writer.h"
#include "support/mesh_error.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

class GeometryLoader : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("peensim-geometry-" + std::to_string(::getpid()) + "-" + info->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::string write_text(const std::string& name, const std::string& text) const {
        std::ofstream(path(name)) << text;
        return path(name);
    }

    fs::path dir_;
};

std::string error_of(const std::string& file) {
    return testing::mesh_error_of(file, [&] { load_mesh(file, 1e-3); });
}

TEST_F(GeometryLoader, BinaryStlRoundTripInMillimetres) {
    const TriangleMesh written = box(BoxSpec{Vec3(0.06, 0.03, 0.005), Vec3(0, 0, -0.0025), Eigen::Vector3i(2, 1, 1)});
    write_binary_stl(written, path("plate.stl"), 1e-3, "plate");
    EXPECT_EQ(fs::file_size(path("plate.stl")), 84u + 50u * written.triangle_count());
    EXPECT_FALSE(fs::exists(path("plate.stl.partial")));
    std::ifstream in(path("plate.stl"), std::ios::binary);
    std::string header(80, '\0');
    in.read(header.data(), 80);
    EXPECT_NE(header.rfind("solid", 0), 0u);  // would make readers guess ASCII
    EXPECT_NE(header.find("unit mm"), std::string::npos);

    const TriangleMesh read = load_mesh(path("plate.stl"), 1e-3);
    ASSERT_EQ(read.triangle_count(), written.triangle_count());
    EXPECT_EQ(read.vertices.size(), written.vertices.size());  // welded again
    EXPECT_TRUE(is_closed(read));
    for (std::size_t t = 0; t < read.triangle_count(); ++t) {
        EXPECT_EQ(read.source_facet[t], static_cast<int>(t));
        for (int k = 0; k < 3; ++k) EXPECT_LT((read.corner(t, k) - written.corner(t, k)).norm(), 1e-9);
    }
    EXPECT_NEAR(enclosed_volume(read), 0.06 * 0.03 * 0.005, 1e-12);
    EXPECT_EQ(read.group_names, (std::vector<std::string>{""}));  // binary STL: one unnamed solid
}

TEST_F(GeometryLoader, AsciiStlSolidsBecomeGroups) {
    const TriangleMesh written = cylinder(CylinderSpec{0.005, 0.03, 12, Axis::y, Vec3::Zero(), true, 2, 1});
    write_ascii_stl(written, path("rod.stl"), 1e-3);
    const TriangleMesh read = load_mesh(path("rod.stl"), 1e-3);
    ASSERT_EQ(read.triangle_count(), written.triangle_count());
    EXPECT_EQ(read.group_names, written.group_names);              // "wall", "cap-low", "cap-high"
    EXPECT_EQ(read.group_of_triangle, written.group_of_triangle);  // groups were contiguous
    EXPECT_TRUE(is_closed(read));
    EXPECT_NEAR(enclosed_volume(read), enclosed_volume(written), 1e-6 * enclosed_volume(written));
}

TEST_F(GeometryLoader, ScalesByTheUnit) {
    const TriangleMesh written = box(BoxSpec{Vec3(2, 3, 4), Vec3::Zero(), Eigen::Vector3i::Ones()});
    write_binary_stl(written, path("box-m.stl"), 1.0);
    EXPECT_NEAR(enclosed_volume(load_mesh(path("box-m.stl"), 1.0)), 24.0, 1e-12);
    EXPECT_NEAR(enclosed_volume(load_mesh(path("box-m.stl"), 0.5)), 3.0, 1e-12);
}

TEST_F(GeometryLoader, StlFacetNormalsAreIgnoredAndDegenerateFacetsDropped) {
    const std::string file =
        write_text("three.stl",
                   "solid three\n"
                   "facet normal 0 0 -1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n"
                   "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 2 0 0\n endloop\nendfacet\n"
                   "facet normal 0 0 1\n outer loop\n  vertex 1 0 0\n  vertex 1 1 0\n  vertex 0 1 0\n endloop\nendfacet\n"
                   "endsolid three\n");
    const TriangleMesh m = load_mesh(file, 1e-3);
    ASSERT_EQ(m.triangle_count(), 2u);
    EXPECT_EQ(m.source_facet, (std::vector<int>{0, 2}));         // facet 1 is a line, dropped
    EXPECT_EQ(m.vertices.size(), 4u);                            // the unused (2, 0, 0) is gone
    EXPECT_TRUE(triangle_normal(m, 0).isApprox(Vec3(0, 0, 1)));  // winding, not the file's -z
    EXPECT_EQ(m.group_names, (std::vector<std::string>{"three"}));
    EXPECT_DOUBLE_EQ(m.corner(1, 1).x(), 1e-3);
}

TEST_F(GeometryLoader, ObjPolygonsKeepTheirFacetNumberAcrossGroups) {
    const std::string file = write_text("parts.obj",
                                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
                                        "g alpha\nf 1 2 3 4\nf 1 2 5\n"
                                        "g beta\nf 1 3 5\nl 1 2\n"
                                        "g alpha\nf 2 3 5\n");
    const TriangleMesh m = load_mesh(file, 1.0);
    ASSERT_EQ(m.triangle_count(), 5u);
    EXPECT_EQ(m.source_facet, (std::vector<int>{0, 0, 1, 2, 3}));  // the quad is facet 0, the line not counted
    EXPECT_EQ(m.group_names, (std::vector<std::string>{"alpha", "beta"}));
    EXPECT_EQ(m.group_of_triangle, (std::vector<int>{0, 0, 0, 1, 0}));
    EXPECT_EQ(m.vertices.size(), 5u);
    EXPECT_NEAR(surface_area(m), 1.0 + 0.5 + 2 * (0.5 * std::sqrt(2.0)), 1e-12);  // quad, 1-2-5, 1-3-5, 2-3-5
}

TEST_F(GeometryLoader, PlyPolygonsAreFanned) {
    const std::string file = write_text("square.ply",
                                        "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                                        "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                                        "0 0 0\n2 0 0\n2 2 0\n0 2 0\n0 0 2\n4 0 1 2 3\n3 0 4 1\n");
    const TriangleMesh m = load_mesh(file, 1e-3);
    ASSERT_EQ(m.triangle_count(), 3u);
    EXPECT_EQ(m.source_facet, (std::vector<int>{0, 0, 1}));
    EXPECT_NEAR(surface_area(m), (4.0 + 2.0) * 1e-6, 1e-15);
}

TEST_F(GeometryLoader, MissingGarbageAndEmptyFilesAreInputErrors) {
    const std::string missing = path("nowhere.stl");
    EXPECT_NE(error_of(missing).find("not found"), std::string::npos);
    EXPECT_NE(error_of(missing).find("nowhere.stl"), std::string::npos);

    const std::string garbage = write_text("garbage.stl", "this is not a mesh\n");
    EXPECT_NE(error_of(garbage).find("not an STL file: 19 bytes are too few for a binary STL"), std::string::npos) << error_of(garbage);

    const std::string empty = write_text("empty.stl", "");
    EXPECT_NE(error_of(empty).find("not an STL file: 0 bytes"), std::string::npos) << error_of(empty);

    // Long enough for a binary STL, not ASCII: its "count" is read from bytes 80-83.
    const std::string long_garbage = write_text("long-garbage.stl", std::string(100, 'x') + "\n");
    EXPECT_NE(error_of(long_garbage).find("the binary STL declares"), std::string::npos) << error_of(long_garbage);

    const std::string no_facets = write_text("nothing.stl", "solid nothing\nendsolid nothing\n");
    EXPECT_NE(error_of(no_facets).find("no triangles"), std::string::npos);

    const std::string all_degenerate = write_text(
        "flat.stl",
        "solid flat\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 1 0 0\n endloop\nendfacet\nendsolid flat\n");
    EXPECT_NE(error_of(all_degenerate).find("degenerate"), std::string::npos);

    EXPECT_NE(error_of(dir_.string()).find("not a regular file"), std::string::npos);
}

TEST_F(GeometryLoader, WritingIntoAMissingDirectoryIsAnInputError) {
    const TriangleMesh m = box(BoxSpec{});
    const std::string target = path("no/such/dir/box.stl");
    try {
        write_binary_stl(m, target);
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "output");
        EXPECT_EQ(e.where().file, target);
    }
}

}  // namespace
}  // namespace peensim
