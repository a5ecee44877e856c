// peensim_bench: runs scenes without writing outputs and prints what a step costs.
//   peensim_bench SCENE [--set path=value ...] [--label NAME] [--render DIR]
// Prints one block per scene: wall time, shot-steps per second, simulated seconds per wall
// second, peak memory, the time split between the stages of a step, and the work counters.
// --render DIR records the scene's animation (its `render` block, or the defaults) into DIR as
// `peensim run --render` does, and prints the frames and the time spent drawing them.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/render_module.h"
#include "engine/run_loop.h"
#include "engine/simulation.h"
#include "model/model.h"
#include "output/peak_memory.h"
#include "scene/scene_parser.h"
#include "scene/schema_defaults.h"

int main(int argc, char** argv) {
    using namespace peensim;
    if (argc < 2) {
        std::cerr << "usage: peensim_bench SCENE [--set path=value ...] [--label NAME]\n";
        return 2;
    }
    const std::string scene_path = argv[1];
    std::vector<std::string> overrides;
    std::string label = scene_path;
    std::string render_dir;
    for (int k = 2; k + 1 < argc; k += 2) {
        const std::string flag = argv[k];
        if (flag == "--set")
            overrides.emplace_back(argv[k + 1]);
        else if (flag == "--label")
            label = argv[k + 1];
        else if (flag == "--render")
            render_dir = argv[k + 1];
        else {
            std::cerr << "unknown option " << flag << "\n";
            return 2;
        }
    }
    try {
        using Clock = std::chrono::steady_clock;
        const auto t_load = Clock::now();
        const auto model = compile_model(parse_scene_file(scene_path, overrides));
        Simulation sim(model);
        const double load_s = std::chrono::duration<double>(Clock::now() - t_load).count();
        std::unique_ptr<FrameSink> recorder;
        if (!render_dir.empty())
            recorder = render_module().make_recorder(*model, model->description.render.value_or(default_render()), render_dir, sim.state());
        // The logged impacts' count and mean speed, and the recorder's frames, step by step.
        struct Tally final : RunListener {
            FrameSink* recorder = nullptr;
            std::uint64_t logged = 0;
            double speed_sum = 0.0;  // m/s, normal impact speeds on logged components
            void after_step(const Simulation& s, const std::vector<ImpactRecord>& impacts) override {
                logged += impacts.size();
                for (const ImpactRecord& r : impacts) speed_sum += r.vn_in_m_per_s;
                if (recorder) recorder->after_step(s.state(), impacts, logged);
            }
        } tally;
        tally.recorder = recorder.get();
        RunLoop loop(sim);
        loop.add(tally);
        const auto t0 = Clock::now();
        if (recorder) recorder->after_step(sim.state(), {}, 0);
        loop.run();
        const std::uint64_t logged = tally.logged;
        const double speed_sum = tally.speed_sum;
        if (recorder) recorder->flush();
        const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
        const SimulationState& st = sim.state();
        const StepStats& stats = sim.scheme().stats();
        std::size_t triangles = 0;
        for (const Component& c : model->components) triangles += c.mesh->triangle_count();
        std::printf("== %s\n", label.c_str());
        std::printf("  shot %d of %.3g mm, %zu triangles, %.3g s simulated, setup %.2f s\n", model->shot_count,
                    2e3 * model->max_shot_radius_m, triangles, st.time.seconds(), load_s);
        std::printf("  wall %.3f s   sim s per wall s %.4f   shot-steps/s %.3e (%.0f ns per shot-step)   steps %llu\n", wall,
                    st.time.seconds() / wall, static_cast<double>(st.shot_steps) / wall, 1e9 * wall / static_cast<double>(st.shot_steps),
                    static_cast<unsigned long long>(st.steps));
        std::printf("  peak memory %.1f MB   logged impacts %llu (%.0f per simulated s, mean normal speed %.4f m/s)   shot lost %llu\n",
                    static_cast<double>(peak_resident_bytes()) / 1e6, static_cast<unsigned long long>(logged),
                    static_cast<double>(logged) / st.time.seconds(), logged ? speed_sum / static_cast<double>(logged) : 0.0,
                    static_cast<unsigned long long>(st.health.shot_lost));
        if (recorder)
            std::printf(
                "  render: %d frames of %dx%d, drawing %.1f ms per frame (PNG written by a second thread), %.1f %% of the wall time\n",
                recorder->frames_drawn(), model->description.render.value_or(default_render()).width_px,
                model->description.render.value_or(default_render()).height_px, 1e3 * recorder->draw_seconds() / recorder->frames_drawn(),
                100.0 * recorder->draw_seconds() / wall);
        std::printf("  stages:");
        for (std::size_t k = 0; k < kStageNames.size(); ++k)
            if (stats.seconds[k] > 0.0) std::printf(" %s %.0f%%", std::string(kStageNames[k]).c_str(), 100.0 * stats.seconds[k] / wall);
        const double ss = static_cast<double>(st.shot_steps);
        if (stats.events > 0) {
            // Event-driven: shot_steps counts events.
            const double ev = static_cast<double>(stats.events), sim_s = st.time.seconds();
            std::printf(
                "\n  events %.3g per simulated s (%.0f ns each): stale %.1f%%, window ends %.1f%%, substeps %.1f%%; per event: pair tests "
                "%.2f, mesh predictions %.2f, BVH sweeps %.2f (%.0f%% answered by the occupied cells), leaves %.2f; rides %.3g/s, sleeps "
                "%llu, collapse guards %.3g/s, hand-overs "
                "to time stepping %llu\n",
                ev / sim_s, wall / ev * 1e9, 100.0 * static_cast<double>(stats.stale_events) / ev,
                100.0 * static_cast<double>(stats.box_renewals) / ev, 100.0 * static_cast<double>(stats.substeps) / ev,
                static_cast<double>(stats.pair_tests) / ev, static_cast<double>(stats.mesh_predictions) / ev,
                static_cast<double>(stats.bvh_queries) / ev,
                stats.bvh_queries > 0 ? 100.0 * static_cast<double>(stats.bvh_sweeps_gated) / static_cast<double>(stats.bvh_queries) : 0.0,
                static_cast<double>(stats.triangle_tests) / ev, static_cast<double>(stats.rides) / sim_s,
                static_cast<unsigned long long>(stats.sleeps), static_cast<double>(stats.collapse_guards) / sim_s,
                static_cast<unsigned long long>(stats.hand_overs));
            return 0;
        }
        std::printf(
            "\n  per shot-step: gate checks %.2f, skipped %.2f, memo skips %.3f, BVH queries %.3f (hits %.3f), triangles returned %.3f, "
            "tested %.3f, touch searches %.4f\n",
            static_cast<double>(stats.gate_checks) / ss, static_cast<double>(stats.gate_skips) / ss,
            static_cast<double>(stats.memo_skips) / ss, static_cast<double>(stats.bvh_queries) / ss,
            static_cast<double>(stats.bvh_hits) / ss, static_cast<double>(stats.triangles_returned) / ss,
            static_cast<double>(stats.triangle_tests) / ss, static_cast<double>(stats.touch_searches) / ss);
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
