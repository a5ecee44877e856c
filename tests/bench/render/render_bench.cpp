// Frame time of the off-screen renderer on the gear case: the shipped chamber, sonotrode, axle
// and gear (assets/*.stl, mm), N shot of 1 mm radius spread inside and moving, impact flashes,
// text and a colour bar, at 1280x720. Prints ms per frame for draw + read-back (split by layer:
// meshes only, + shot, full frame) and for PNG encoding + writing, and optionally for feeding
// ffmpeg.
//   peensim_render_bench [--frames N] [--shot N] [--samples S] [--size WxH] [--part file.stl]
//                        [--keep DIR] [--video]
// Run from the repository root (or pass --assets DIR). LP_NUM_THREADS in the environment
// overrides the renderer's choice of one rasteriser thread.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "geometry/mesh_loader.h"
#include "render/png_io.h"
#include "render/renderer.h"
#include "render/video_encoder.h"

namespace fs = std::filesystem;
using namespace peensim;
using namespace peensim::render;

namespace {

constexpr double kMm = 1e-3;
constexpr double kShotRadius = 1.0 * kMm;                         // m
constexpr double kGearAxisHeight = 42.0 * kMm;                    // m, as in scenes/gear.yaml
constexpr double kSpawnRadius = 25.0 * kMm;                       // m, shot start inside this cylinder
constexpr double kSpawnLow = 3.0 * kMm, kSpawnHigh = 70.0 * kMm;  // m
constexpr double kShotStep = 0.4 * kMm;                           // m, shot travel per frame (random walk)
constexpr double kFrameTime = 1.0 / 30.0;                         // s, simulated time per frame
constexpr int kMarkers = 64;                                      // impact flashes alive in each frame
constexpr int kWarmup = 3;                                        // frames not timed (shader JIT, buffer growth)

struct Args {
    int frames = 60;
    int shot = 512;
    int samples = 0;
    int width = 1280, height = 720;
    std::string assets = "assets";
    std::string part;
    std::string keep;
    bool video = false;
};

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct Stats {
    double median = 0.0, mean = 0.0, min = 0.0;
};
Stats stats(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return {v[v.size() / 2], std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()), v.front()};
}
void print(const char* what, const Stats& s) {
    std::printf("  %-34s median %7.2f ms   mean %7.2f ms   min %7.2f ms\n", what, s.median, s.mean, s.min);
}

Args parse(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--frames")
            a.frames = std::stoi(next());
        else if (arg == "--shot")
            a.shot = std::stoi(next());
        else if (arg == "--samples")
            a.samples = std::stoi(next());
        else if (arg == "--size") {
            const std::string s = next();
            if (std::sscanf(s.c_str(), "%dx%d", &a.width, &a.height) != 2) throw std::runtime_error("--size WxH");
        } else if (arg == "--assets")
            a.assets = next();
        else if (arg == "--part")
            a.part = next();
        else if (arg == "--keep")
            a.keep = next();
        else if (arg == "--video")
            a.video = true;
        else
            throw std::runtime_error("unknown argument " + arg);
    }
    if (a.frames < 1 || a.shot < 0) throw std::runtime_error("--frames must be >= 1 and --shot >= 0");
    return a;
}

Mat3 rotation_about_y(double angle) { return Eigen::AngleAxisd(angle, Vec3::UnitY()).toRotationMatrix(); }

}  // namespace

int main(int argc, char** argv) {
    try {
        const Args args = parse(argc, argv);
        const char* user_threads = std::getenv("LP_NUM_THREADS");  // before the context sets its default
        const std::string threads = user_threads ? std::string(user_threads) : "1 (the renderer's default)";
        const TriangleMesh chamber = load_mesh(args.assets + "/gear-chamber.stl", kMm);
        const TriangleMesh sonotrode = load_mesh(args.assets + "/gear-sonotrode.stl", kMm);
        const TriangleMesh axle = load_mesh(args.assets + "/axle.stl", kMm);
        const TriangleMesh gear = load_mesh(args.part.empty() ? args.assets + "/gear.stl" : args.part, kMm);

        OffscreenContext context({.width = args.width, .height = args.height, .samples = args.samples});
        Renderer empty(context, {.overlay = false});  // the fixed cost: clear + read-back
        Renderer renderer(context);
        renderer.add_mesh(chamber, {.colour = {0.55f, 0.58f, 0.62f, 1.0f}, .cull = Cull::back});
        const MeshId sonotrode_id = renderer.add_mesh(sonotrode, {.colour = {0.45f, 0.5f, 0.7f, 1.0f}});
        const MeshId axle_id = renderer.add_mesh(axle, {.colour = {0.9f, 0.9f, 0.85f, 1.0f}});
        const MeshId gear_id = renderer.add_mesh(gear, {.colour = {0.85f, 0.62f, 0.3f, 1.0f}});
        renderer.set_pose(axle_id, make_pose(Mat3::Identity(), Vec3(0.0, 0.0, kGearAxisHeight)));

        Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
        for (const Vec3& v : chamber.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        const Camera camera = Camera::framing(lo, hi, static_cast<double>(args.width) / args.height);

        std::mt19937_64 rng(20261122);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::vector<double> x(static_cast<std::size_t>(args.shot)), y(x.size()), z(x.size());
        for (std::size_t i = 0; i < x.size(); ++i) {
            const double r = kSpawnRadius * std::sqrt(unit(rng)), a = 2.0 * std::numbers::pi * unit(rng);
            x[i] = r * std::cos(a), y[i] = r * std::sin(a), z[i] = kSpawnLow + (kSpawnHigh - kSpawnLow) * unit(rng);
        }
        std::vector<ImpactMarker> markers(kMarkers);
        std::vector<double> marker_age(kMarkers);
        const ColourMap map = ColourMap::viridis();
        const ColourBar bar{map, 0.0, 3.0, "normal speed (m/s)"};
        std::vector<std::string> text(2);
        auto respawn_marker = [&](std::size_t k) {
            const std::size_t t = static_cast<std::size_t>(unit(rng) * static_cast<double>(gear.triangle_count() - 1));
            markers[k].point_m = (gear.corner(t, 0) + gear.corner(t, 1) + gear.corner(t, 2)) / 3.0 + Vec3(0, 0, kGearAxisHeight);
            markers[k].radius_m = 1.5 * kShotRadius;
            const Rgba c = map.map(3.0 * unit(rng), 0.0, 3.0);
            markers[k].colour = {c.r, c.g, c.b, 1.0f};
            marker_age[k] = 0.0;
        };
        for (std::size_t k = 0; k < markers.size(); ++k) respawn_marker(k), marker_age[k] = unit(rng) * 4.0;

        // One frame of the animation: shot random-walk inside the spawn cylinder, gear turns,
        // sonotrode vibrates (exaggerated to 1 mm so it shows), markers fade over 4 frames.
        auto advance = [&](int f) {
            std::normal_distribution<double> step(0.0, kShotStep);
            for (std::size_t i = 0; i < x.size(); ++i) {
                x[i] += step(rng), y[i] += step(rng), z[i] = std::clamp(z[i] + step(rng), kSpawnLow, kSpawnHigh);
                const double r = std::hypot(x[i], y[i]);
                if (r > kSpawnRadius) x[i] *= kSpawnRadius / r, y[i] *= kSpawnRadius / r;
            }
            renderer.set_pose(gear_id, make_pose(rotation_about_y(0.05 * f), Vec3(0.0, 0.0, kGearAxisHeight)));
            renderer.set_pose(sonotrode_id, make_pose(Mat3::Identity(), Vec3(0.0, 0.0, 1.0 * kMm * std::sin(0.7 * f))));
            for (std::size_t k = 0; k < markers.size(); ++k) {
                marker_age[k] += 1.0;
                if (marker_age[k] >= 4.0) respawn_marker(k);
                markers[k].colour.a = static_cast<float>(1.0 - marker_age[k] / 4.0);
            }
            char line[64];
            std::snprintf(line, sizeof line, "t = %.3f s", f * kFrameTime);
            text[0] = line;
            std::snprintf(line, sizeof line, "impacts: %d", 57 * f);
            text[1] = line;
        };

        const SphereSet shot{x, y, z, {}, kShotRadius, {0.82f, 0.84f, 0.88f, 1.0f}};
        const FrameContent meshes_only{};
        const FrameContent with_shot{.spheres = {&shot, 1}};
        const FrameContent full{.spheres = {&shot, 1}, .markers = markers, .text = text, .colour_bar = &bar};

        RgbaImage image;
        std::vector<double> t_empty, t_meshes, t_shot, t_full, t_png;
        const fs::path out_dir =
            args.keep.empty() ? fs::temp_directory_path() / ("peensim-render-bench-" + std::to_string(::getpid())) : fs::path(args.keep);
        fs::create_directories(out_dir);
        std::uintmax_t png_bytes = 0;
        for (int f = 0; f < kWarmup + args.frames; ++f) {
            advance(f);
            auto t0 = std::chrono::steady_clock::now();
            empty.render(camera, meshes_only, image);
            const double e = ms_since(t0);
            t0 = std::chrono::steady_clock::now();
            renderer.render(camera, meshes_only, image);
            const double a = ms_since(t0);
            t0 = std::chrono::steady_clock::now();
            renderer.render(camera, with_shot, image);
            const double b = ms_since(t0);
            t0 = std::chrono::steady_clock::now();
            renderer.render(camera, full, image);
            const double c = ms_since(t0);
            const std::string png = (out_dir / "frame.png").string();
            t0 = std::chrono::steady_clock::now();
            write_png(png, image);
            const double d = ms_since(t0);
            if (f >= kWarmup) {
                t_empty.push_back(e), t_meshes.push_back(a), t_shot.push_back(b), t_full.push_back(c), t_png.push_back(d);
                png_bytes = fs::file_size(png);
            }
        }

        std::printf("# peensim render benchmark: %dx%d, samples %d, LP_NUM_THREADS=%s, %d frames\n", args.width, args.height, args.samples,
                    threads.c_str(), args.frames);
        std::printf("  scene: chamber %zu, sonotrode %zu, axle %zu, gear %zu triangles; %d shot of r = 1 mm; %d markers\n",
                    chamber.triangle_count(), sonotrode.triangle_count(), axle.triangle_count(), gear.triangle_count(), args.shot,
                    kMarkers);
        std::printf("draw + read-back per frame:\n");
        print("empty frame (clear + read-back)", stats(t_empty));
        print("meshes only", stats(t_meshes));
        print("meshes + shot", stats(t_shot));
        print("full (+ markers, text, colour bar)", stats(t_full));
        std::printf("PNG encode + write (zlib 1, no filter), %.0f kB:\n", static_cast<double>(png_bytes) / 1e3);
        print("per frame", stats(t_png));

        if (args.video) {
            if (!ffmpeg_available()) {
                std::printf("video: skipped, ffmpeg is not on PATH\n");
            } else {
                const std::string mp4 = (out_dir / "frames.mp4").string();
                VideoEncoder encoder(mp4, {.width = args.width, .height = args.height, .fps = 30.0});
                std::vector<double> t_send;
                const auto t_all = std::chrono::steady_clock::now();
                for (int f = 0; f < args.frames; ++f) {
                    advance(f);
                    renderer.render(camera, full, image);
                    const auto t0 = std::chrono::steady_clock::now();
                    encoder.add_frame(image);
                    t_send.push_back(ms_since(t0));
                }
                const auto t_finish = std::chrono::steady_clock::now();
                encoder.finish();
                const double finish_ms = ms_since(t_finish);
                std::printf("video (libx264 veryfast, crf 20), %.0f kB for %d frames:\n", static_cast<double>(fs::file_size(mp4)) / 1e3,
                            args.frames);
                print("add_frame (blocks while ffmpeg is behind)", stats(t_send));
                std::printf("  finish %.0f ms; render + encode %.1f frames/s overall\n", finish_ms, args.frames / (ms_since(t_all) / 1e3));
            }
        }
        if (args.keep.empty())
            fs::remove_all(out_dir);
        else
            std::printf("kept %s\n", out_dir.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "peensim_render_bench: %s\n", e.what());
        return 1;
    }
}
