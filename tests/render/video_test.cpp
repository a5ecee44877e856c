// The ffmpeg video encoder: frame count and size as ffprobe reads them back, the partial file
// and its rename, odd sizes, a dead ffmpeg, and finding executables on a search path.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include "render/video_encoder.h"
#include "support/shell_command.h"
#include "support/temp_dir.h"

namespace peensim::render {
namespace {

namespace fs = std::filesystem;

std::optional<std::string> ffprobe() {
    const char* path = std::getenv("PATH");
    return find_executable("ffprobe", path != nullptr ? path : "");
}

// "width,height,frames" of the first video stream, as ffprobe counts them by decoding. The
// path is a test temp dir (no shell metacharacters).
std::string probe(const std::string& ffprobe_path, const std::string& video) {
    const std::string command = ffprobe_path +
                                " -v error -count_frames -select_streams v:0 -show_entries stream=width,height,nb_read_frames"
                                " -of csv=p=0 '" +
                                video + "'";
    return peensim::testing::trimmed(peensim::testing::run_shell(command).output);
}

RgbaImage frame(int w, int h, int index) {
    RgbaImage image;
    image.resize(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = image.pixels.data() + (static_cast<std::size_t>(y) * w + x) * 4;
            p[0] = static_cast<std::uint8_t>(x + 10 * index);
            p[1] = static_cast<std::uint8_t>(y);
            p[2] = static_cast<std::uint8_t>(128);
            p[3] = 255;
        }
    }
    return image;
}

TEST(RenderVideo, FfprobeReadsBackTheFramesAndSize) {
    const auto ffprobe_path = ffprobe();
    if (!ffprobe_path) GTEST_SKIP() << "ffprobe is not installed";
    ASSERT_TRUE(ffmpeg_available());
    testing::TempDir dir;
    const std::string path = (dir.path / "run.mp4").string();
    VideoEncoder encoder(path, {.width = 160, .height = 120, .fps = 25.0});
    for (int i = 0; i < 12; ++i) encoder.add_frame(frame(160, 120, i));
    EXPECT_TRUE(fs::exists(path + ".partial"));
    EXPECT_FALSE(fs::exists(path));
    encoder.finish();
    EXPECT_EQ(encoder.frames(), 12);
    EXPECT_EQ(probe(*ffprobe_path, path), "160,120,12");
    EXPECT_FALSE(fs::exists(path + ".partial"));
    EXPECT_FALSE(fs::exists(path + ".log"));
}

TEST(RenderVideo, OddSizesAreCroppedToEven) {
    const auto ffprobe_path = ffprobe();
    if (!ffprobe_path) GTEST_SKIP() << "ffprobe is not installed";
    testing::TempDir dir;
    const std::string path = (dir.path / "odd.mp4").string();
    VideoEncoder encoder(path, {.width = 161, .height = 121});
    EXPECT_EQ(encoder.encoded_width(), 160);
    EXPECT_EQ(encoder.encoded_height(), 120);
    for (int i = 0; i < 3; ++i) encoder.add_frame(frame(161, 121, i));
    encoder.finish();
    EXPECT_EQ(probe(*ffprobe_path, path), "160,120,3");
}

TEST(RenderVideo, UnfinishedVideoLeavesNoFile) {
    if (!ffmpeg_available()) GTEST_SKIP() << "ffmpeg is not installed";
    testing::TempDir dir;
    const std::string path = (dir.path / "cut.mp4").string();
    {
        VideoEncoder encoder(path, {.width = 64, .height = 48});
        encoder.add_frame(frame(64, 48, 0));
    }
    EXPECT_TRUE(fs::is_empty(dir.path));
}

TEST(RenderVideo, DeadEncoderIsAnErrorNotASignal) {
    testing::TempDir dir;
    const std::string path = (dir.path / "dead.mp4").string();
    // /bin/true exits at once without reading: the frames hit a closed pipe. Without
    // MSG_NOSIGNAL this would kill the test process with SIGPIPE.
    VideoEncoder encoder(path, {.width = 320, .height = 240, .ffmpeg = "/bin/true"});
    const RgbaImage image = frame(320, 240, 0);
    try {
        for (int i = 0; i < 100; ++i) encoder.add_frame(image);
        FAIL() << "expected std::runtime_error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("ffmpeg stopped reading frames"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_empty(dir.path));
}

TEST(RenderVideo, FailingEncoderReportsItsStatus) {
    testing::TempDir dir;
    const std::string path = (dir.path / "false.mp4").string();
    VideoEncoder encoder(path, {.width = 4, .height = 4, .ffmpeg = "/bin/false"});
    try {
        encoder.add_frame(frame(4, 4, 0));  // fits the socket buffer even if false has exited
        encoder.finish();
        FAIL() << "expected std::runtime_error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("status 1"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_empty(dir.path));
}

TEST(RenderVideo, MissingExecutableAndBadFramesArePlainErrors) {
    testing::TempDir dir;
    const std::string path = (dir.path / "x.mp4").string();
    EXPECT_THROW(VideoEncoder(path, {.width = 4, .height = 4, .ffmpeg = (dir.path / "no-ffmpeg").string()}), std::runtime_error);
    EXPECT_THROW(VideoEncoder(path, {.width = 0, .height = 4}), std::invalid_argument);
    if (!ffmpeg_available()) return;
    VideoEncoder encoder(path, {.width = 8, .height = 8});
    EXPECT_THROW(encoder.add_frame(frame(8, 6, 0)), std::invalid_argument);
}

TEST(RenderVideo, FindExecutableSearchesThePathInOrder) {
    testing::TempDir dir;
    const fs::path plain = dir.path / "tool";
    std::ofstream(plain) << "#!/bin/sh\n";
    EXPECT_FALSE(find_executable("tool", dir.path.string()).has_value()) << "not executable yet";
    fs::permissions(plain, fs::perms::owner_all);
    EXPECT_EQ(find_executable("tool", "/nonexistent:" + dir.path.string()), plain.string());
    EXPECT_FALSE(find_executable("tool", "/nonexistent").has_value());
    EXPECT_FALSE(find_executable("", dir.path.string()).has_value());
    EXPECT_TRUE(find_executable("sh", "/usr/bin:/bin").has_value());
}

}  // namespace
}  // namespace peensim::render
