// MP4 video of rendered frames: raw RGBA frames piped into an ffmpeg child process (H.264,
// yuv420p, which every player reads). ffmpeg is found on PATH at run time, not linked.
#pragma once

#include <sys/types.h>
#include <optional>
#include <string>
#include <string_view>

#include "render/image.h"

namespace peensim::render {

// Absolute path of the first executable file `name` in the ':'-separated directory list
// `search_path` (an empty entry means "."), or nullopt.
std::optional<std::string> find_executable(std::string_view name, std::string_view search_path);

// ffmpeg on $PATH? Check this before making a VideoEncoder to give the user a clear message
// (and go on without video) instead of failing mid-run.
bool ffmpeg_available();

struct VideoOptions {
    int width = 0;                    // px, of the frames given to add_frame
    int height = 0;                   // px
    double fps = 30.0;                // frames per second of the video
    int crf = 20;                     // libx264 quality, 0 (lossless) .. 51; ~18-23 looks clean
    std::string preset = "veryfast";  // libx264 speed/size trade-off; encoding runs beside the simulation
    std::string ffmpeg{};             // executable; empty: "ffmpeg" found on PATH
};

// Writes `path.partial` while frames come in and renames it to `path` when finish() succeeds,
// so an interrupted run never leaves a truncated MP4 under the final name. H.264 with yuv420p
// needs even sizes: an odd width or height is cropped by one pixel column or row.
//
// ffmpeg reads the frames from a Unix socket pair rather than a pipe: send() with MSG_NOSIGNAL
// reports a dead ffmpeg as EPIPE instead of raising SIGPIPE, without touching the process-wide
// signal disposition. ffmpeg's own messages go to `path.log`, which is quoted in the error when
// it fails and removed when it succeeds.
class VideoEncoder {
public:
    // Starts ffmpeg (posix_spawn with an argument vector: no shell, so no injection through the
    // path). Throws std::runtime_error with a plain message when ffmpeg is not found or cannot
    // start, std::invalid_argument for a bad size, fps or crf.
    VideoEncoder(std::string path, VideoOptions options);
    // Without finish(): stops ffmpeg and removes `path.partial` and the log.
    ~VideoEncoder();
    VideoEncoder(const VideoEncoder&) = delete;
    VideoEncoder& operator=(const VideoEncoder&) = delete;

    // Sends one frame (must be width x height). Blocks while ffmpeg is behind. Throws
    // std::runtime_error, quoting ffmpeg's log, when ffmpeg has died; std::invalid_argument for
    // a frame of the wrong size; std::logic_error after finish().
    void add_frame(const RgbaImage& frame);

    // Closes the input, waits for ffmpeg and renames the video into place. Throws
    // std::runtime_error (exit status + ffmpeg's log) when ffmpeg fails or no frame was added;
    // the partial file is then removed.
    void finish();

    int frames() const { return frames_; }
    int encoded_width() const { return options_.width & ~1; }
    int encoded_height() const { return options_.height & ~1; }
    const std::string& path() const { return path_; }

private:
    [[noreturn]] void fail(const std::string& what);
    int wait_for_exit();
    void discard();

    std::string path_;
    VideoOptions options_;
    int socket_ = -1;  // our end; ffmpeg's stdin is the other
    pid_t child_ = -1;
    int frames_ = 0;
    bool finished_ = false;
};

}  // namespace peensim::render
