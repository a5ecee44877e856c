#include "app/sweep_job.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/interrupt.h"
#include "app/report_errors.h"
#include "app/run_job.h"
#include "app/sweep_compare.h"
#include "app/sweep_file.h"
#include "app/sweep_plan.h"
#include "common/input_error.h"
#include "scene/scene_parser.h"

extern char** environ;

namespace fs = std::filesystem;

namespace peensim {

namespace {

using Clock = std::chrono::steady_clock;

// A run that finished (its summary says so and its analysis is there): never run again.
bool finished(const SweepRun& run) {
    std::ifstream in(run.dir + "/summary.json");
    if (!in || !fs::exists(run.dir + "/analysis/figures.json")) return false;
    const auto j = nlohmann::json::parse(in, nullptr, false);
    return !j.is_discarded() && j.value("finished", false);
}

// Starts `peensim run` for one run: its output in its own directory, its messages in the sweep's
// log of it (sweep/logs/<variant>.s<k>.log). Resumes from the run's checkpoint if it has one.
pid_t start_run(const std::string& executable, const std::string& scene, const SweepRun& run, const std::string& log) {
    std::vector<std::string> args{executable, "run", scene, "-o", run.dir, "--quiet"};
    if (fs::exists(run.dir + "/checkpoint.bin")) args.push_back("--resume");
    for (const std::string& o : run.overrides) args.insert(args.end(), {"--set", o});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    // A process group of its own: a Ctrl-C at the terminal reaches the sweep alone, which passes one
    // SIGINT on (a run that got two would be abandoned at once instead of checkpointing).
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
    pid_t pid = 0;
    const int rc = ::posix_spawn(&pid, executable.c_str(), &actions, &attributes, argv.data(), environ);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("cannot start " + executable + ": " + std::strerror(rc));
    return pid;
}

std::string duration_text(double s) {
    if (!(s >= 0.0) || !std::isfinite(s)) return "?";
    const auto t = static_cast<long long>(std::llround(s));
    return t >= 3600 ? std::to_string(t / 3600) + "h" + std::to_string(t % 3600 / 60) + "m"
                     : (t >= 60 ? std::to_string(t / 60) + "m" + std::to_string(t % 60) + "s" : std::to_string(t) + "s");
}

std::string this_executable() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot find this program's own path (/proc/self/exe): " + ec.message());
    return self.string();
}

}  // namespace

int sweep_job(const SweepOptions& options, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&]() -> int {
        SweepOptions o = options;
        if (o.output_dir.empty()) throw InputError({"-o"}, "", "expected the sweep's output directory (-o DIR)");
        std::vector<SweepAxis> axes;
        try {
            for (const std::string& spec : o.vary) axes.push_back(parse_sweep_axis(spec));
        } catch (const std::invalid_argument& e) {
            throw InputError({"--vary"}, "", e.what());
        }
        // A sweep file: its scene, set, variants, seeds and baseline (the command line's --set after its own).
        std::vector<SweepVariant> listed;
        if (is_sweep_file(o.scene_path)) {
            if (!o.vary.empty()) throw InputError({"--vary"}, "", "the sweep file gives the variants; expected no --vary with a sweep file");
            SweepFile f = read_sweep_file(o.scene_path);
            o.scene_path = f.scene_path;
            f.overrides.insert(f.overrides.end(), o.overrides.begin(), o.overrides.end());
            o.overrides = f.overrides;
            if (o.seeds == 0) o.seeds = f.seeds;
            if (o.baseline.empty()) o.baseline = f.baseline;
            axes = f.axes;
            listed = f.variants;
        }
        if (o.seeds == 0) o.seeds = 1;
        // The scene as every run reads it: its errors (and each variant's) before anything runs.
        const SceneDescription scene = parse_scene_file(o.scene_path, o.overrides);
        SweepPlan plan;
        try {
            plan = listed.empty() ? plan_sweep(axes, o.seeds, scene.process.seed, o.overrides, o.output_dir)
                                  : plan_sweep_variants(listed, o.seeds, scene.process.seed, o.overrides, o.output_dir);
        } catch (const std::invalid_argument& e) {
            throw InputError({"--vary"}, "", e.what());
        }
        for (const SweepRun& run : plan.runs)
            if (run.replicate == 0) (void)parse_scene_file(o.scene_path, run.overrides);
        if (!o.baseline.empty() &&
            std::none_of(plan.variants.begin(), plan.variants.end(), [&](const SweepVariant& v) { return v.name == o.baseline; }))
            throw InputError({"--baseline"}, "", "no variant is named '" + o.baseline + "'; expected one of the sweep's (e.g. '" + plan.variants.front().name + "')");
        const std::string executable = o.executable.empty() ? this_executable() : o.executable;
        const int jobs = o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
        const std::string sweep_dir = o.output_dir + "/sweep", logs = sweep_dir + "/logs";
        fs::create_directories(logs);

        // The queue: every run not finished yet, in the plan's order; each may be retried once.
        std::deque<std::size_t> queue;
        std::size_t done = 0;
        for (std::size_t k = 0; k < plan.runs.size(); ++k) {
            if (finished(plan.runs[k]))
                ++done;
            else
                queue.push_back(k);
        }
        const std::size_t already = done, total = plan.runs.size();
        out << "sweep: " << plan.variants.size() << " variants x " << plan.seeds << " seeds = " << total << " runs, " << jobs << " at once"
            << (already ? ", " + std::to_string(already) + " finished before" : std::string()) << "\n";
        std::map<pid_t, std::size_t> running;
        std::map<std::size_t, int> attempts;
        std::vector<std::size_t> failed;
        const auto t0 = Clock::now();
        std::size_t finished_now = 0;
        bool interrupted = false;
        InterruptGuard guard("peensim sweep: second interrupt, stopping at once (the runs keep their last checkpoints)\n");
        const auto log_of = [&](std::size_t k) {
            return logs + "/" + plan.variants[plan.runs[k].variant].name + ".s" + std::to_string(plan.runs[k].replicate) + ".log";
        };
        while (!queue.empty() || !running.empty()) {
            if (InterruptGuard::requested() && !interrupted) {
                interrupted = true;  // every run checkpoints and stops; nothing new starts
                for (const auto& [pid, k] : running) ::kill(pid, SIGINT);
                queue.clear();
            }
            while (!interrupted && !queue.empty() && static_cast<int>(running.size()) < jobs) {
                const std::size_t k = queue.front();
                queue.pop_front();
                ++attempts[k];
                fs::create_directories(fs::path(plan.runs[k].dir).parent_path());
                running[start_run(executable, o.scene_path, plan.runs[k], log_of(k))] = k;
            }
            int status = 0;
            const pid_t pid = ::waitpid(-1, &status, WNOHANG);
            if (pid <= 0) {
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
                continue;
            }
            const auto it = running.find(pid);
            if (it == running.end()) continue;
            const std::size_t k = it->second;
            running.erase(it);
            const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            const SweepRun& run = plan.runs[k];
            const std::string label = plan.variants[run.variant].name + "/s" + std::to_string(run.replicate);
            if (code == kExitOk) {
                ++done, ++finished_now;
                const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
                const double eta = elapsed / static_cast<double>(finished_now) * static_cast<double>(total - done) /
                                   static_cast<double>(std::max<std::size_t>(1, std::min<std::size_t>(jobs, total - done)));
                out << "sweep: " << done << "/" << total << " done (" << label << ", " << duration_text(elapsed) << " elapsed"
                    << (done < total ? ", about " + duration_text(eta) + " to go" : std::string()) << ")\n"
                    << std::flush;
            } else if (code == kExitInterrupted && interrupted) {
                // Checkpointed: the next sweep resumes it.
            } else if (attempts[k] < 2 && !interrupted) {
                err << "sweep: " << label << " failed (exit " << code << ", see " << log_of(k) << "); trying it once more\n";
                queue.push_back(k);
            } else {
                err << "sweep: " << label << " failed again (exit " << code << ", see " << log_of(k) << "); the sweep goes on without it\n";
                failed.push_back(k);
            }
        }
        if (interrupted) {
            err << "sweep: interrupted; " << done << "/" << total << " runs finished, the others checkpointed: run the same command to go on\n";
            return kExitInterrupted;
        }
        const SweepCompareResult compared = write_sweep_comparison(plan, sweep_dir, o.baseline, scene.name.empty() ? o.scene_path : scene.name);
        out << "comparison: " << sweep_dir << "/{comparison.csv, report.md" << (compared.pngs.empty() ? "" : ", *.png") << "}\n";
        if (!compared.plot_note.empty()) out << "plots: " << compared.plot_note << "\n";
        return failed.empty() ? kExitOk : kExitRuntimeError;
    });
}

}  // namespace peensim
