#include "app/sweep/sweep_job.h"

#include <algorithm>
#include <filesystem>
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
#include "app/sweep/sweep_runner.h"
#include "common/input_error.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// "1 seed", "2 seeds".
std::string counted(std::size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

// After the runs: the comparison (unless interrupted) and the exit code.
int finish(const SweepOutcome& outcome, const SweepPlan& plan, const std::string& sweep_dir, const SweepOptions& o,
           const SceneDescription& scene, std::ostream& out, std::ostream& err) {
    if (outcome.stopped) {
        err << "sweep: interrupted; " << outcome.done << "/" << outcome.total
            << " runs finished, the others checkpointed: run the same command to go on\n";
        return kExitInterrupted;
    }
    const SweepCompareResult compared = write_sweep_comparison(plan, sweep_dir, o.baseline, scene.name.empty() ? o.scene_path : scene.name);
    out << "comparison: " << sweep_dir << "/{comparison.csv, report.md, report.html" << (compared.pngs.empty() ? "" : ", *.png") << "}\n";
    if (!compared.plot_note.empty()) out << "plots: " << compared.plot_note << "\n";
    out << sweep_geometry_cache_line(sweep_dir + "/logs");
    if (outcome.failed.empty()) return kExitOk;
    const bool one = outcome.failed.size() == 1;
    err << "sweep: " << outcome.failed.size() << " of " << counted(outcome.total, "run", "runs")
        << (one ? " failed for good (why: its log in " : " failed for good (why: their logs in ") << sweep_dir
        << "/logs); the comparison leaves " << (one ? "it" : "them") << " out\n";
    return kExitRuntimeError;
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
    check_sweep_variants(o.scene_path, plan, overrides, out);
    check_finished_runs(o.scene_path, plan);
    if (!o.baseline.empty() &&
        std::none_of(plan.variants.begin(), plan.variants.end(), [&](const SweepVariant& v) { return v.name == o.baseline; }))
        throw InputError(
            baseline_origin, baseline_origin.line > 0 ? "baseline" : "",
            "no variant is named '" + o.baseline + "'; expected one of the sweep's (e.g. '" + plan.variants.front().name + "')");
    const std::string executable = o.executable.empty() ? this_executable() : o.executable;
    const std::string sweep_dir = o.output_dir + "/sweep";
    fs::create_directories(sweep_dir + "/logs");
    const StopRequest stop(o.stop_requested, "peensim sweep: second interrupt, stopping at once (the runs keep their last checkpoints)\n");

    SweepRunner runner{executable, o.scene_path, sweep_dir + "/logs", 1, nullptr, "sweep", "sweep"};
    const std::string headline = "sweep: " + counted(plan.variants.size(), "variant", "variants") + " x " +
                                 counted(static_cast<std::size_t>(plan.seeds), "seed", "seeds");
    if (launched_by_mpi()) {
        // Across the ranks of an MPI job: rank 0 hands the runs out and compares them.
        MpiSweep mpi;
        runner.jobs = o.jobs > 0 ? o.jobs : 1;  // one run per rank, as MPI places one rank per core
        if (mpi.rank() != 0) {
            mpi.work(executable, o.scene_path, plan, runner.logs_dir, stop);
            return kExitOk;
        }
        runner.mpi = &mpi;
        return finish(run_sweep_plan(plan, runner, stop, headline, out, err), plan, sweep_dir, o, scene, out, err);
    }
    runner.jobs = o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    return finish(run_sweep_plan(plan, runner, stop, headline, out, err), plan, sweep_dir, o, scene, out, err);
}

}  // namespace peensim
