#include "render/video_encoder.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

extern char** environ;

namespace peensim::render {

namespace {

constexpr std::size_t kLogTailBytes = 2000;  // of ffmpeg's log quoted in an error

std::string log_path(const std::string& path) { return path + ".log"; }
std::string partial_path(const std::string& path) { return path + ".partial"; }

std::string log_tail(const std::string& path) {
    std::ifstream in(log_path(path), std::ios::binary);
    std::ostringstream all;
    all << in.rdbuf();
    std::string text = all.str();
    if (text.size() > kLogTailBytes) text = "..." + text.substr(text.size() - kLogTailBytes);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    return text.empty() ? "(ffmpeg printed nothing)" : text;
}

std::string format_number(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

}  // namespace

std::optional<std::string> find_executable(std::string_view name, std::string_view search_path) {
    if (name.empty()) return std::nullopt;
    std::size_t start = 0;
    while (start <= search_path.size()) {
        const std::size_t end = std::min(search_path.find(':', start), search_path.size());
        std::string dir(search_path.substr(start, end - start));
        if (dir.empty()) dir = ".";
        const std::string candidate = dir + "/" + std::string(name);
        struct stat st {};
        if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0) {
            return candidate;
        }
        start = end + 1;
    }
    return std::nullopt;
}

bool ffmpeg_available() {
    const char* path = std::getenv("PATH");
    return find_executable("ffmpeg", path != nullptr ? path : "").has_value();
}

VideoEncoder::VideoEncoder(std::string path, VideoOptions options) : path_(std::move(path)), options_(std::move(options)) {
    if (options_.width < 2 || options_.height < 2) {
        throw std::invalid_argument("video: frame size must be at least 2x2, got " + std::to_string(options_.width) + "x" +
                                    std::to_string(options_.height));
    }
    if (!(options_.fps > 0.0) || !std::isfinite(options_.fps)) throw std::invalid_argument("video: fps must be positive");
    if (options_.crf < 0 || options_.crf > 51) throw std::invalid_argument("video: crf must be in 0..51");

    std::string executable = options_.ffmpeg;
    if (executable.empty()) {
        const char* search = std::getenv("PATH");
        const std::optional<std::string> found = find_executable("ffmpeg", search != nullptr ? search : "");
        if (!found) throw std::runtime_error("video: ffmpeg is not installed (not found on PATH); install ffmpeg to record videos");
        executable = *found;
    }

    const std::string size = std::to_string(options_.width) + "x" + std::to_string(options_.height);
    std::vector<std::string> args = {executable,
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-f",
                                     "rawvideo",
                                     "-pix_fmt",
                                     "rgba",
                                     "-s",
                                     size,
                                     "-r",
                                     format_number(options_.fps),
                                     "-i",
                                     "-"};
    if ((options_.width | options_.height) & 1) {
        args.insert(args.end(), {"-vf", "crop=" + std::to_string(encoded_width()) + ":" + std::to_string(encoded_height()) + ":0:0"});
    }
    args.insert(args.end(), {"-c:v", "libx264", "-preset", options_.preset, "-crf", std::to_string(options_.crf), "-pix_fmt", "yuv420p",
                             "-movflags", "+faststart", "-f", "mp4", partial_path(path_)});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);

    int sockets[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0) {
        throw std::runtime_error(std::string("video: cannot create the pipe to ffmpeg: ") + std::strerror(errno));
    }
    // Frames flow one way; shutting the unused directions makes a dead reader show as EPIPE.
    ::shutdown(sockets[0], SHUT_RD);
    ::shutdown(sockets[1], SHUT_WR);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, sockets[1], STDIN_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    const std::string log = log_path(path_);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = -1;
    const int rc = ::posix_spawn(&pid, executable.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(sockets[1]);
    if (rc != 0) {
        ::close(sockets[0]);
        ::unlink(log.c_str());
        throw std::runtime_error("video: cannot start '" + executable + "': " + std::strerror(rc));
    }
    socket_ = sockets[0];
    child_ = pid;
}

VideoEncoder::~VideoEncoder() {
    if (!finished_) discard();
}

void VideoEncoder::discard() {
    if (socket_ >= 0) {
        ::close(socket_);
        socket_ = -1;
    }
    if (child_ > 0) {
        ::kill(child_, SIGTERM);
        wait_for_exit();
    }
    ::unlink(partial_path(path_).c_str());
    ::unlink(log_path(path_).c_str());
    finished_ = true;
}

int VideoEncoder::wait_for_exit() {
    int status = 0;
    while (::waitpid(child_, &status, 0) < 0) {
        if (errno != EINTR) {
            status = -1;
            break;
        }
    }
    child_ = -1;
    return status;
}

void VideoEncoder::fail(const std::string& what) {
    if (socket_ >= 0) {
        ::close(socket_);
        socket_ = -1;
    }
    std::string message = "video '" + path_ + "': " + what;
    if (child_ > 0) {
        const int status = wait_for_exit();
        if (WIFEXITED(status)) {
            message += " (ffmpeg exited with status " + std::to_string(WEXITSTATUS(status)) + ")";
        } else if (WIFSIGNALED(status)) {
            message += " (ffmpeg killed by signal " + std::to_string(WTERMSIG(status)) + ")";
        }
    }
    message += ": " + log_tail(path_);
    discard();
    throw std::runtime_error(message);
}

void VideoEncoder::add_frame(const RgbaImage& frame) {
    if (finished_) throw std::logic_error("video: add_frame after finish");
    if (frame.width != options_.width || frame.height != options_.height) {
        throw std::invalid_argument("video: frame is " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + ", the video " +
                                    std::to_string(options_.width) + "x" + std::to_string(options_.height));
    }
    const auto* data = reinterpret_cast<const char*>(frame.pixels.data());
    std::size_t left = frame.byte_size();
    while (left > 0) {
        const ssize_t n = ::send(socket_, data, left, MSG_NOSIGNAL);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(errno == EPIPE || errno == ECONNRESET ? "ffmpeg stopped reading frames" : std::strerror(errno));
        }
        data += n;
        left -= static_cast<std::size_t>(n);
    }
    ++frames_;
}

void VideoEncoder::finish() {
    if (finished_) throw std::logic_error("video: finish called twice");
    if (frames_ == 0) {
        discard();
        throw std::runtime_error("video '" + path_ + "': no frame was added");
    }
    ::close(socket_);
    socket_ = -1;
    const int status = wait_for_exit();
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::string message = "video '" + path_ + "': ffmpeg failed";
        if (WIFEXITED(status)) message += " with status " + std::to_string(WEXITSTATUS(status));
        if (WIFSIGNALED(status)) message += ", killed by signal " + std::to_string(WTERMSIG(status));
        message += ": " + log_tail(path_);
        discard();
        throw std::runtime_error(message);
    }
    if (::rename(partial_path(path_).c_str(), path_.c_str()) != 0) {
        const std::string message = "video: cannot rename '" + partial_path(path_) + "' to '" + path_ + "': " + std::strerror(errno);
        discard();
        throw std::runtime_error(message);
    }
    ::unlink(log_path(path_).c_str());
    finished_ = true;
}

}  // namespace peensim::render
