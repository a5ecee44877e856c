#include "render/frame_recorder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "render/png_io.h"
#include "render/render_view.h"
#include "render/video_encoder.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// Most recent impacts kept for their glow; older ones have faded long before the ring wraps at
// any impact rate a frame can show.
constexpr std::size_t kFlashCapacity = 16384;
constexpr double kTrailShrink = 0.4;     // a glow's radius shrinks by this share over its trail
constexpr double kTrailFadePower = 1.5;  // its alpha: (1 - age / trail)^this

std::string frame_name(std::int64_t k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06lld.png", static_cast<long long>(k));
    return name;
}

}  // namespace

// The recorder's parts (named, not anonymous: FrameRecorder::Impl, declared in the header, holds them).
namespace frame_recording {

// Writes PNG frames on its own thread, one frame at a time: the caller hands over a filled image
// and gets back the one written before, so drawing and encoding overlap without copies.
class PngWriterThread {
public:
    PngWriterThread() : thread_([this] { run(); }) {}
    ~PngWriterThread() {
        {
            std::lock_guard lock(mutex_);
            stop_ = true;
        }
        changed_.notify_all();
        thread_.join();
    }

    // Swaps `image` with the writer's idle buffer once the previous frame is written.
    void write(render::RgbaImage& image, std::string path) {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return !busy_; });
        if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
        std::swap(image, pending_);
        path_ = std::move(path);
        busy_ = true;
        changed_.notify_all();
    }

    void flush() {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return !busy_; });
        if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    }

private:
    void run() {
        std::unique_lock lock(mutex_);
        for (;;) {
            changed_.wait(lock, [&] { return busy_ || stop_; });
            if (!busy_) return;
            lock.unlock();
            std::exception_ptr error;
            try {
                render::write_png(path_, pending_);
            } catch (...) {
                error = std::current_exception();
            }
            lock.lock();
            error_ = error;
            busy_ = false;
            changed_.notify_all();
        }
    }

    render::RgbaImage pending_;
    std::string path_;
    bool busy_ = false, stop_ = false;
    std::exception_ptr error_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::thread thread_;  // last: starts after the members it uses
};

struct Flash {
    double time_s = 0.0;  // s
    int component = 0;
    Vec3 point_c;           // m, component frame
    double vn = 0.0;        // m/s
    double radius_m = 0.0;  // m, its shot's
};

}  // namespace frame_recording

using frame_recording::Flash;
using frame_recording::PngWriterThread;

struct FrameRecorder::Impl {
    const Model& model;
    RenderDesc desc;
    fs::path frames_dir;
    fs::path video_path;
    double interval_s;        // s of simulated time between frames
    double end_s;             // s, no frame after this
    std::int64_t next_frame;  // k of the next frame to draw

    render::OffscreenContext context;
    render::Renderer renderer;
    ModelView view;
    render::Camera camera;
    render::ColourBar bar;
    render::RgbaImage image;
    PngWriterThread writer;

    std::vector<Flash> flashes;  // ring of the latest impacts
    std::size_t flash_next = 0;
    std::vector<double> x, y, z;  // shot centres moved back to the frame time
    std::vector<double> radii;    // m, per shot (a shot mix)
    std::vector<render::ImpactGlow> glows;
    std::vector<std::string> text;

    Impl(const Model& m, const RenderDesc& d, const std::string& dir, const SimulationState& now)
        : model(m),
          desc(d),
          frames_dir(fs::path(dir) / "frames"),
          video_path(fs::path(dir) / "animation.mp4"),
          interval_s(d.slow_motion_s / d.fps),
          end_s(std::min(d.start_s + d.duration_s, m.duration_s)),
          next_frame(static_cast<std::int64_t>(std::ceil((now.time.seconds() - d.start_s) / interval_s - 1e-9))),
          context({.width = d.width_px, .height = d.height_px}),
          renderer(context),
          view(add_model(renderer, m)),
          camera(scene_camera(d, view, static_cast<double>(d.width_px) / d.height_px)) {
        if (next_frame < 0) next_frame = 0;
        fs::create_directories(frames_dir);
        bar.min = 0.0;
        bar.max = d.speed_scale_m_per_s;
        bar.title = "impact normal speed (m/s)";
        flashes.reserve(kFlashCapacity);
        glows.reserve(kFlashCapacity);
        const std::size_t n = static_cast<std::size_t>(m.shot_count);
        x.resize(n), y.resize(n), z.resize(n);
    }

    double frame_time(std::int64_t k) const { return desc.start_s + static_cast<double>(k) * interval_s; }

    void remember(std::span<const ImpactRecord> impacts) {
        for (const ImpactRecord& r : impacts) {
            const Flash f{r.time_s, r.component, r.point_m, r.vn_in_m_per_s, 0.5 * r.shot_diameter_m};
            if (flashes.size() < kFlashCapacity)
                flashes.push_back(f);
            else
                flashes[flash_next] = f;
            flash_next = (flash_next + 1) % kFlashCapacity;
        }
    }

    // Draws frame k of the state, which is `behind` seconds past the frame's time.
    void draw(const SimulationState& st, std::int64_t k, std::uint64_t logged_impacts) {
        const double t = frame_time(k);
        const double behind = st.time.seconds() - t;  // s, >= 0
        const Vec3& g = model.gravity_m_per_s2;
        const ShotArrays& s = st.shots;
        // Sources add shot during a run: as many centres as the state has slots (grown, never shrunk).
        if (x.size() < s.size()) x.resize(s.size()), y.resize(s.size()), z.resize(s.size());
        if (model.has_size_mix()) {
            radii.resize(s.size());
            for (std::size_t i = 0; i < s.size(); ++i) radii[i] = model.shot_sizes[s.size_class[i]].radius_m;
        }
        // Back along the parabola: p(t) = p(t + d) - v(t + d) d + g d^2 / 2.
        for (std::size_t i = 0; i < s.size(); ++i) {
            x[i] = s.x[i] - s.vx[i] * behind + 0.5 * g.x() * behind * behind;
            y[i] = s.y[i] - s.vy[i] * behind + 0.5 * g.y() * behind * behind;
            z[i] = s.z[i] - s.vz[i] * behind + 0.5 * g.z() * behind * behind;
        }
        pose_model(renderer, view, model, st.time, -behind);

        const double window = kTrailFrames * interval_s;
        const double radius_px = std::max(3.0, kGlowRadiusPerHeight * desc.height_px);
        glows.clear();
        // Oldest first, so that the newest glows are drawn over them.
        for (std::size_t k = 0; k < flashes.size(); ++k) {
            const Flash& f = flashes[flashes.size() < kFlashCapacity ? k : (flash_next + k) % kFlashCapacity];
            const double age = t - f.time_s;
            if (age < 0.0 || age >= window) continue;
            const double fade = age / window;  // 0 for an impact of the frame's own interval
            const Pose pose = model.components[static_cast<std::size_t>(f.component)].kinematics.pose(st.time, -behind);
            render::Rgba colour = bar.map.map(f.vn, bar.min, bar.max);
            colour.a = static_cast<float>(std::pow(1.0 - fade, kTrailFadePower));
            glows.push_back({pose.to_world(f.point_c), kGlowLiftRadii * f.radius_m,
                             static_cast<float>(radius_px * (1.0 - kTrailShrink * fade)), colour});
        }
        char line[96];
        text.clear();
        if (!model.description.name.empty()) text.push_back(model.description.name);
        std::snprintf(line, sizeof line, "t = %.4f s", t);
        text.emplace_back(line);
        std::snprintf(line, sizeof line, "impacts logged: %llu", static_cast<unsigned long long>(logged_impacts));
        text.emplace_back(line);

        const std::size_t n = s.size();
        const render::SphereSet shot{std::span<const double>(x.data(), n),
                                     std::span<const double>(y.data(), n),
                                     std::span<const double>(z.data(), n),
                                     s.active,
                                     model.shot_sizes.front().radius_m,
                                     {0.85f, 0.86f, 0.9f, 1.0f},
                                     model.has_size_mix() ? std::span<const double>(radii.data(), n) : std::span<const double>()};
        renderer.render(camera, {.spheres = {&shot, 1}, .glows = glows, .text = text, .colour_bar = &bar}, image);
        writer.write(image, (frames_dir / frame_name(k)).string());
    }
};

FrameRecorder::FrameRecorder(const Model& model, const RenderDesc& desc, const std::string& dir, const SimulationState& now)
    : impl_(std::make_unique<Impl>(model, desc, dir, now)) {}

FrameRecorder::~FrameRecorder() = default;

void FrameRecorder::after_step(const SimulationState& state, std::span<const ImpactRecord> impacts, std::uint64_t logged_impacts) {
    Impl& m = *impl_;
    m.remember(impacts);
    const double now = state.time.seconds();
    while (m.frame_time(m.next_frame) <= now && m.frame_time(m.next_frame) <= m.end_s + 1e-12) {
        const auto t0 = std::chrono::steady_clock::now();
        m.draw(state, m.next_frame, logged_impacts);
        draw_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        ++frames_drawn_;
        ++m.next_frame;
    }
}

double FrameRecorder::next_frame_s() const {
    const double t = impl_->frame_time(impl_->next_frame);
    return t <= impl_->end_s + 1e-12 ? t : std::numeric_limits<double>::infinity();
}

void FrameRecorder::flush() { impl_->writer.flush(); }

std::string FrameRecorder::finish_video() {
    Impl& m = *impl_;
    flush();
    std::vector<fs::path> frames;
    for (const auto& entry : fs::directory_iterator(m.frames_dir))
        if (entry.path().extension() == ".png" && entry.path().filename().string().starts_with("frame_")) frames.push_back(entry.path());
    std::sort(frames.begin(), frames.end());
    const std::string where = m.frames_dir.string() + "/frame_*.png";
    if (frames.empty()) return "no frame (the recorded interval lies outside the run)";
    if (!m.desc.video) return std::to_string(frames.size()) + " frames in " + where + " (video: none)";
    if (!render::ffmpeg_available())
        return std::to_string(frames.size()) + " frames in " + where +
               "; no MP4: ffmpeg not found (apt-get install ffmpeg, or render.video: none)";
    render::VideoEncoder encoder(m.video_path.string(),
                                 {.width = m.desc.width_px, .height = m.desc.height_px, .fps = static_cast<double>(m.desc.fps)});
    for (const fs::path& f : frames) encoder.add_frame(render::read_png(f.string()));
    encoder.finish();
    return std::to_string(frames.size()) + " frames in " + where + ", video " + m.video_path.string() + " (" + std::to_string(m.desc.fps) +
           " fps, " + std::to_string(m.desc.slow_motion_s * 1e3) + " ms simulated per second)";
}

}  // namespace peensim
