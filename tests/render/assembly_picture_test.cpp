// `peensim check --render FILE.png`: the assembly at t = 0 with the placed shot, so a misplaced part
// is seen before a run. The rod scene's picture shows the rod (role part: orange) and the shot
// (light grey) on a non-blank image of the requested size; where meshes cross, the point is marked
// with a red ball and its message listed.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "app/check/check_job.h"
#include "app/run/run_job.h"
#include "render/png_io.h"
#include "support/temp_dir.h"

namespace peensim::testing {
namespace {

namespace fs = std::filesystem;

// The mark's red (1.0, 0.15, 0.1 lit): far redder than the part's orange.
int red_pixels(const render::RgbaImage& image) {
    int red = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const render::Rgba8 c = image.at(x, y);
            red += c.r > 120 && c.g * 3 < c.r && c.b * 3 < c.r;
        }
    return red;
}

TEST(AssemblyPicture, CheckDrawsTheRodAndTheShotWhereTheyStart) {
    TempDir dir;
    const fs::path png = dir.path / "assembly.png";
    std::ostringstream out, err;
    ASSERT_EQ(check_job(std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml", {}, false, out, err, png.string()), kExitOk) << err.str();
    EXPECT_NE(out.str().find("# picture of the assembly: " + png.string()), std::string::npos);
    const render::RgbaImage image = render::read_png(png.string());
    ASSERT_EQ(image.width, 1280);
    ASSERT_EQ(image.height, 720);
    int orange = 0, grey = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const render::Rgba8 c = image.at(x, y);
            orange += c.r > c.b + 60 && c.r > c.g + 20;
            grey += std::min({c.r, c.g, c.b}) > 150 && std::max({c.r, c.g, c.b}) - std::min({c.r, c.g, c.b}) < 25;
        }
    // The rod spans ~10 % of the width; 512 shot of 2 mm cover the sonotrode in three layers.
    EXPECT_GT(orange, 5000) << "orange pixels";
    EXPECT_GT(grey, 5000) << "light grey pixels";
    EXPECT_LT(red_pixels(image), 20) << "nothing to mark";
}

TEST(AssemblyPicture, AnAssemblyWithAnErrorIsStillDrawnWithoutShot) {
    // The rod lowered into the sonotrode: an error (exit 2), and the picture that shows why.
    TempDir dir;
    const fs::path png = dir.path / "assembly.png";
    std::ostringstream out, err;
    EXPECT_EQ(check_job(std::string(PEENSIM_SOURCE_DIR) + "/scenes/rod.yaml", {"components[rod].translation=[0, 0, -17 mm]"}, false, out,
                        err, png.string()),
              kExitInputError);
    EXPECT_NE(err.str().find("intersects the sonotrode"), std::string::npos) << err.str();
    EXPECT_NE(out.str().find("(without shot: the setup has an error)"), std::string::npos) << out.str();
    EXPECT_NE(out.str().find("point(s) marked where meshes cross"), std::string::npos) << out.str();
    const render::RgbaImage image = render::read_png(png.string());
    EXPECT_GT(red_pixels(image), 100) << "the crossing's mark";
    int orange = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const render::Rgba8 c = image.at(x, y);
            orange += c.r > c.b + 60 && c.r > c.g + 20;
        }
    EXPECT_GT(orange, 5000);
}

}  // namespace
}  // namespace peensim::testing
