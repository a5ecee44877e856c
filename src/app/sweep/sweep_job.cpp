#include "app/sweep/sweep_job.h"

#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <thread>

#include "app/interrupt.h"
#include "app/report_errors.h"
#include "app/run/run_job.h"
#include "app/sweep/sweep_book.h"
#include "app/sweep/sweep_checks.h"
#include "app/sweep/sweep_compare.h"
#include "app/sweep/sweep_file.h"
#include "app/sweep/sweep_mpi.h"
#include "app/sweep/sweep_plan.h"
#include "common/input_error.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

std::string this_executable() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot find this program's own path (/proc/self/exe): " + ec.message());
    return self.string();
}

// After the runs: the comparison (unless interrupted) and the exit code.
int finish(const SweepBook& book, const SweepPlan& plan, const std::string& sweep_dir, const SweepOptions& o, const SceneDescription& scene,
           std::ostream& out, std::ostream& err) {
    if (book.stopped()) {
        err << "sweep: interrupted; " << book.done() << "/" << book.total()
            << " runs finished, the others checkpointed: run the same command to go on\n";
        return kExitInterrupted;
    }
    const SweepCompareResult compared = write_sweep_comparison(plan, sweep_dir, o.baseline, scene.name.empty() ? o.scene_path : scene.name);
    out << "comparison: " << sweep_dir << "/{comparison.csv, report.md, report.html" << (compared.pngs.empty() ? "" : ", *.png") << "}\n";
    if (!compared.plot_note.empty()) out << "plots: " << compared.plot_note << "\n";
    return book.failed().empty() ? kExitOk : kExitRuntimeError;
}

}  // namespace

int sweep_job(const SweepOptions& options, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] { return run_sweep(options, out, err); });
}

int run_sweep(const SweepOptions& options, std::ostream& out, std::ostream& err) {
    SweepOptions o = options;
    if (o.output_dir.empty()) throw InputError({"-o"}, "", "expected the sweep's output directory (-o DIR)");
    // --seeds, then each --vary on its own (its values, their number), before any file is read.
    if (o.seeds && (*o.seeds < 1 || *o.seeds > kMaxSweepSeeds))
        throw InputError({"--seeds"}, "", sweep_seeds_problem(std::to_string(*o.seeds)));
    std::vector<SweepAxis> axes;
    for (const std::string& spec : o.vary) axes.push_back(parse_sweep_axis(spec));
    // A sweep file: its scene, set, variants, seeds and baseline (the command line's --set after its own).
    std::vector<SweepVariant> listed;
    SweepOverrides overrides{{}, {}, o.overrides};
    SourceLocation baseline_origin{"--baseline"};
    if (is_sweep_file(o.scene_path)) {
        if (!o.vary.empty()) throw InputError({"--vary"}, "", "the sweep file gives the variants; expected no --vary with a sweep file");
        SweepFile f = read_sweep_file(o.scene_path);
        o.scene_path = f.scene_path;
        overrides.from_file = f.overrides;
        overrides.file_origin = f.set_origin;
        if (!o.seeds && f.seeds > 0) o.seeds = f.seeds;
        if (o.baseline.empty() && !f.baseline.empty()) o.baseline = f.baseline, baseline_origin = f.baseline_origin;
        axes = f.axes;
        listed = f.variants;
    }
    const int seeds = static_cast<int>(o.seeds.value_or(1));
    // The scene as every run reads it; the plan (its size checked from the counts alone, before the
    // grid is built); then each variant as its runs will read it: every error before anything runs.
    const SceneDescription scene = read_sweep_scene(o.scene_path, overrides);
    std::vector<std::string> all = overrides.from_file;
    all.insert(all.end(), overrides.from_command_line.begin(), overrides.from_command_line.end());
    SweepPlan plan = listed.empty() ? plan_sweep(axes, seeds, scene.process.seed, all, o.output_dir)
                                    : plan_sweep_variants(listed, seeds, scene.process.seed, all, o.output_dir);
    check_sweep_variants(o.scene_path, plan, out);
    if (!o.baseline.empty() &&
        std::none_of(plan.variants.begin(), plan.variants.end(), [&](const SweepVariant& v) { return v.name == o.baseline; }))
        throw InputError(
            baseline_origin, baseline_origin.line > 0 ? "baseline" : "",
            "no variant is named '" + o.baseline + "'; expected one of the sweep's (e.g. '" + plan.variants.front().name + "')");
    const std::string executable = o.executable.empty() ? this_executable() : o.executable;
    const std::string sweep_dir = o.output_dir + "/sweep";
    fs::create_directories(sweep_dir + "/logs");
    const StopRequest stop(o.stop_requested, "peensim sweep: second interrupt, stopping at once (the runs keep their last checkpoints)\n");

    if (launched_by_mpi()) {
        // Across the ranks of an MPI job: rank 0 hands the runs out and compares them.
        MpiSweep mpi;
        const int slots = o.jobs > 0 ? o.jobs : 1;  // one run per rank, as MPI places one rank per core
        if (mpi.rank() != 0) {
            mpi.work(executable, o.scene_path, plan, sweep_dir + "/logs", stop);
            return kExitOk;
        }
        SweepBook book(plan, sweep_dir + "/logs", slots * mpi.size(), out, err);
        out << "sweep: " << plan.variants.size() << " variants x " << plan.seeds << " seeds = " << book.total() << " runs over "
            << mpi.size() << " MPI ranks" << (book.done() ? ", " + std::to_string(book.done()) + " finished before" : std::string())
            << "\n";
        mpi.coordinate(book, executable, o.scene_path, plan, slots, stop);
        return finish(book, plan, sweep_dir, o, scene, out, err);
    }
    const int jobs = o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    SweepBook book(plan, sweep_dir + "/logs", jobs, out, err);
    out << "sweep: " << plan.variants.size() << " variants x " << plan.seeds << " seeds = " << book.total() << " runs, " << jobs
        << " at once" << (book.done() ? ", " + std::to_string(book.done()) + " finished before" : std::string()) << "\n";
    // Each run's analysis its share of the cores: `jobs` runs at once on all of them would
    // oversubscribe them.
    const unsigned threads_per_run = std::max(1u, std::max(1u, std::thread::hardware_concurrency()) / static_cast<unsigned>(jobs));
    std::map<pid_t, std::size_t> running;
    while (book.has_queued() || !running.empty()) {
        if (stop.requested() && !book.stopped()) {
            book.stop();  // every run checkpoints and stops; nothing new starts
            for (const auto& [pid, k] : running) ::kill(pid, SIGINT);
        }
        while (book.has_queued() && static_cast<int>(running.size()) < jobs) {
            const std::size_t k = book.take();
            running[start_sweep_run(executable, o.scene_path, plan.runs[k], book.log_of(k), threads_per_run)] = k;
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
        book.outcome(k, exit_code_of(status));
    }
    return finish(book, plan, sweep_dir, o, scene, out, err);
}

}  // namespace peensim
