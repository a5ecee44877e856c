// The `peensim` command line: run, check, new, analyze, render-impacts, render-regions, sweep, optimise, bench, trade,
// export-fem, almen-fit, generate, schema.
#include <CLI/CLI.hpp>

#include <iostream>

#include "app/almen/almen_fit_job.h"
#include "app/analysis/analyze_job.h"
#include "app/bench/bench_job.h"
#include "app/bench/trade_job.h"
#include "app/check/check_job.h"
#include "app/fem/export_fem_job.h"
#include "app/new_scene/new_scene_job.h"
#include "app/optimise/optimise_job.h"
#include "app/render_module.h"
#include "app/run/run_job.h"
#include "app/sweep/sweep_job.h"
#include "app/sweep/sweep_plan.h"
#include "cli/generate_command.h"
#include "common/input_error.h"
#include "common/parallel_chunks.h"
#include "common/units.h"
#include "scene/schema.h"

namespace {

// A quantity given on the command line, in SI; bad text is an input error naming the option.
double parse_option_quantity(const char* option, const std::string& text, peensim::Dimension dim) {
    try {
        return peensim::parse_quantity(text, dim);
    } catch (const peensim::QuantityError& e) {
        throw peensim::InputError({option}, "", e.what());
    }
}

}  // namespace

int main(int argc, char** argv) {
    using namespace peensim;
    CLI::App app{"peensim: ultrasonic shot peening simulator (rigid shot, Bullet collision detection)"};
    app.set_version_flag("--version", std::string(PEENSIM_VERSION));
    app.require_subcommand(1);

    RunOptions run;
    bool quiet = false;
    auto* run_cmd = app.add_subcommand("run", "simulate a scene: writes impacts.csv, summary.json, scene.resolved.yaml");
    run_cmd->add_option("scene", run.scene_path, "scene file (YAML)")->required();
    run_cmd->add_option("-o,--output", run.output_dir, "output directory (default: the scene's output.directory, else out/<scene>)");
    run_cmd->add_option("--set", run.overrides, "override a scene field, e.g. --set process.duration=0.2 --set shot.diameter=\"1 mm\"")
        ->allow_extra_args(false);
    run_cmd->add_flag("-q,--quiet", quiet, "no progress bar and no summary on stdout");
    run_cmd->add_flag("--resume", run.resume, "continue an interrupted run from its checkpoint in the output directory");
    run_cmd->add_flag("--strict", run.strict,
                      "assembly warnings are errors (exit 2), and exit 3 if any shot was lost or the numerics went wrong");
    bool no_analyze = false;
    run_cmd->add_flag("--no-analyze", no_analyze, "do not analyse the impacts when the run finishes");
    bool render_on = false, render_off = false;
    auto* render_flag = run_cmd->add_flag(
        "--render", render_on, "record the animation (frames/ and animation.mp4) with the scene's `render` block or its defaults");
    run_cmd->add_flag("--no-render", render_off, "do not record the animation even if the scene has a `render` block")
        ->excludes(render_flag);
    std::string scheme;
    run_cmd->add_option("--scheme", scheme, "stepping scheme, overriding the scene's accuracy.scheme")
        ->check(CLI::IsMember({"step", "event", "soft"}));
    std::string until_coverage;
    run_cmd->add_option("--until-coverage", until_coverage,
                        "run until coverage reaches this (e.g. 98%) on every region of the logged parts (or process.until_coverage_of); "
                        "process.duration caps the run");
    std::uint64_t stop_after = 0;
    run_cmd->add_option("--stop-after-steps", stop_after,
                        "stop (as if interrupted, resumable) after this many steps, at the next point a checkpoint can be taken (the "
                        "event scheme's restart points come by work done: a short run may end first)");
    unsigned threads = 0;  // 0: every core
    const std::string threads_help = "cores the analysis uses (default: every core; its figures are the same on any number)";
    run_cmd->add_option("--threads", threads, threads_help)->check(CLI::Range(1, 4096));
    int replicas = 1;
    run_cmd
        ->add_option("--replicas", replicas,
                     "run the chamber as this many independent replicas on as many cores, each warmed up and then run for "
                     "its share of the duration, logged one after another (a steady process: no sources, no impact-history "
                     "law); under mpirun -n K, one replica a rank")
        ->check(CLI::Range(1, 1024));
    const std::string cache_help =
        "a folder of the parts' coverage geometry (reach and regions of every sample) to reuse when an earlier run had the same "
        "assembly and shot, and to keep it in otherwise (a sweep gives its runs one)";
    run_cmd->add_option("--geometry-cache", run.geometry_cache_dir, cache_help);

    std::string check_scene;
    std::vector<std::string> check_overrides;
    auto* check_cmd = app.add_subcommand("check", "validate a scene and print it resolved (defaults filled in, SI units)");
    check_cmd->add_option("scene", check_scene, "scene file (YAML)")->required();
    check_cmd->add_option("--set", check_overrides, "override a scene field")->allow_extra_args(false);
    bool check_strict = false;
    check_cmd->add_flag("--strict", check_strict, "treat assembly warnings (a part through a chamber wall, dropped facets) as errors");
    std::string check_picture;
    check_cmd->add_option("--render", check_picture, "also draw the assembly with the placed shot into this PNG (1280x720)");

    std::string analyze_dir;
    AnalyzeOptions analyze;
    std::string analyze_from, analyze_to, analyze_min_speed, analyze_target;
    auto* analyze_cmd = app.add_subcommand("analyze", "analyse a run's impacts: coverage, per-triangle fields, histograms, report.md");
    analyze_cmd->add_option("outdir", analyze_dir, "the run's output directory")->required();
    analyze_cmd->add_option("--threads", threads, threads_help)->check(CLI::Range(1, 4096));
    analyze_cmd->add_option("--from", analyze_from, "leave out the impacts before this time, e.g. a start-up transient (s, or \"500 ms\")");
    analyze_cmd->add_option("--to", analyze_to, "leave out the impacts after this time (default: the end of the run)");
    analyze_cmd->add_option("--min-speed", analyze_min_speed, "leave out impacts with a slower normal speed (m/s, or \"20 cm/s\")");
    analyze_cmd->add_option(
        "--target", analyze_target,
        "the coverage the report measures against: \"0.98\" or \"98 %\" (default: the scene's process.until_coverage, else 98 %)");
    analyze_cmd->add_option("--smoothing-radius", analyze.smoothing_radius,
                            "radius of the surface the maps' fields are smoothed over, e.g. \"1.5 mm\" (default: the scene's "
                            "output.smoothing_radius, else from the dent size and the impact density)");
    analyze_cmd->add_option("--geometry-cache", analyze.geometry_cache_dir, cache_help);

    RenderRegionsOptions render_regions;
    auto* render_regions_cmd = app.add_subcommand(
        "render-regions",
        "draw the regions of the logged parts in their own colours, and what no shot can reach (a run directory or a scene)");
    render_regions_cmd->add_option("input", render_regions.input, "a run's output directory, or a scene file (YAML)")->required();
    render_regions_cmd->add_option("--set", render_regions.overrides, "override a field of the scene file")->allow_extra_args(false);
    render_regions_cmd->add_option("-o,--output", render_regions.output_dir,
                                   "directory for <component>_region_map.png (default: the run's analysis/, or here for a scene)");
    render_regions_cmd->add_option("--width", render_regions.width_px, "image width, pixels (2 x 2 views)")->check(CLI::Range(64, 7680));
    render_regions_cmd->add_option("--height", render_regions.height_px, "image height, pixels")->check(CLI::Range(64, 4320));

    RenderImpactsOptions render_impacts;
    auto* render_impacts_cmd =
        app.add_subcommand("render-impacts", "stills of the logged parts coloured by impacts, mean normal speed, coverage (after analyze)");
    render_impacts_cmd->add_option("outdir", render_impacts.output_dir, "the run's output directory")->required();
    render_impacts_cmd->add_option("--field", render_impacts.fields, "impacts, speed or coverage (repeatable; default: all)");
    render_impacts_cmd->add_option("--width", render_impacts.width_px, "image width, pixels (2 x 2 views)")->check(CLI::Range(64, 7680));
    render_impacts_cmd->add_option("--height", render_impacts.height_px, "image height, pixels")->check(CLI::Range(64, 4320));
    std::string render_target;
    render_impacts_cmd->add_option(
        "--target", render_target,
        "coverage target marked on the coverage map's colour bar: \"0.98\" or \"98 %\" (default: the analysis's)");

    SweepOptions sweep;
    auto* sweep_cmd = app.add_subcommand(
        "sweep", "what-if sweep: every combination of --vary values x --seeds replicates, run on the local cores, compared (DIR/sweep/)");
    sweep_cmd
        ->add_option("scene", sweep.scene_path,
                     "scene file (YAML), or a sweep file naming one (see docs/user-guide.md, \"What-if sweeps\")")
        ->required();
    sweep_cmd->add_option("-o,--output", sweep.output_dir, "the sweep's directory: a run directory per variant and seed, and sweep/")
        ->required();
    sweep_cmd->add_option("--vary", sweep.vary, "a scene field and its values: path=v1,v2,... (repeatable: every combination)")
        ->allow_extra_args(false);
    // Checked by the sweep itself (1 to kMaxSweepSeeds), with the message Python's sweep(seeds=) gets.
    long long sweep_seeds = 0;
    auto* sweep_seeds_option = sweep_cmd->add_option("--seeds", sweep_seeds,
                                                     "replicates per variant from process.seed, +1, ... (1 to " +
                                                         std::to_string(kMaxSweepSeeds) + "; default: the sweep file's, else 1)");
    sweep_cmd->add_option("--set", sweep.overrides, "override a scene field for every run")->allow_extra_args(false);
    sweep_cmd->add_option("--jobs", sweep.jobs, "runs at once (default: every core)")->check(CLI::Range(1, 4096));
    sweep_cmd->add_option("--baseline", sweep.baseline, "the variant the others are compared with (default: the first)");

    OptimiseOptions optimise;
    auto* optimise_cmd = app.add_subcommand(
        "optimise",
        "search a study's process variables for the best setting (Bayesian optimisation over runs), confirm it (DIR/optimise/)");
    optimise_cmd->alias("optimize");
    optimise_cmd
        ->add_option("study", optimise.study_path,
                     "study file (YAML): the scene, the variables and their bounds, the objective, the budget "
                     "(see docs/user-guide.md, \"Finding the best process\")")
        ->required();
    optimise_cmd
        ->add_option("-o,--output", optimise.output_dir,
                     "the optimisation's directory: a run directory per setting and seed, and optimise/")
        ->required();
    int optimise_runs = 0;
    auto* optimise_runs_option =
        optimise_cmd->add_option("--runs", optimise_runs, "the search's budget of runs (default: the study's, else 10 per variable + 10)")
            ->check(CLI::Range(2, 5000));
    optimise_cmd->add_option("--jobs", optimise.jobs, "runs at once (default: every core; under MPI, per rank: 1)")
        ->check(CLI::Range(1, 4096));

    BenchOptions bench;
    auto* bench_cmd = app.add_subcommand(
        "bench", "run stepping schemes side by side on scenes (default: the shipped ones): speed ratio and impact statistics");
    bench_cmd->add_option("scene", bench.scene_paths, "scene files (YAML); default: every *.yaml of the shipped scenes/");
    bench_cmd->add_option("--duration", bench.duration,
                          "simulated time of every scene (s, or with a unit: \"500 ms\"); default: each scene's process.duration");
    bench_cmd->add_option("--set", bench.overrides, "override a scene field for every scene and scheme")->allow_extra_args(false);
    bench_cmd
        ->add_option("--schemes", bench.schemes,
                     "schemes to compare with the first, e.g. step,event or step,step:accuracy.travel_fraction=0.1; :replicas=K runs one "
                     "as K replicas (run --replicas), e.g. event,event:replicas=2")
        ->delimiter(',')
        ->allow_extra_args(false)
        ->default_str("step,event");
    bench_cmd->add_option("--csv", bench.csv_path, "also write every figure to this CSV file");

    auto* generate_cmd =
        app.add_subcommand("generate", "write a generated mesh (gear, cylinder, box, chamber); see 'peensim generate --help'");
    generate_cmd->prefix_command();
    generate_cmd->set_help_flag();

    NewSceneOptions new_scene;
    auto* new_cmd = app.add_subcommand(
        "new", "write a ready scene around your part: a chamber and a sonotrode sized for it, shot, regions (prints what it chose)");
    new_cmd->add_option("part", new_scene.part_path, "the part's file (STL, OBJ, PLY; STEP or IGES)")->required();
    new_cmd->add_option("--unit", new_scene.unit,
                        "the part file's length unit: mm, cm, m, um or in (default mm; a STEP or IGES file's own)");
    new_cmd->add_option("--rotate-about", new_scene.rotate_about, "turn the part about its own x, y or z axis through its centre");
    new_cmd->add_option("--rpm", new_scene.rpm, "the turning speed (rev/min), with --rotate-about");
    new_cmd->add_option("--material", new_scene.material, "the part's material: steel, aluminium or titanium")->default_str("steel");
    new_cmd->add_option("--shot-diameter", new_scene.shot_diameter, "the shot's diameter (mm, or with a unit)")->default_str("2 mm");
    new_cmd->add_option("-o,--output", new_scene.scene_path, "the scene file to write (default: <part's name>.yaml here)");
    new_cmd->add_flag("--force", new_scene.force, "write over the files of an earlier `new` of the same name");

    TradeOptions trade;
    auto* trade_cmd = app.add_subcommand("trade",
                                         "the speed/accuracy trade: every accuracy knob (rigid event, time step, soft resolution and "
                                         "stiffness) against a converged soft reference");
    trade_cmd->add_option("scene", trade.scene_path, "scene file (YAML) whose contacts are hertz-mindlin")->required();
    trade_cmd->add_option("--duration", trade.duration, "simulated time of every run (default: the scene's process.duration)");
    trade_cmd->add_option("--settle", trade.settle,
                          "time left out of rates and speeds at the start, >= 0 (s, or \"20 ms\"; default: a tenth of the run)");
    trade_cmd->add_option("--reference-steps", trade.reference_steps, "soft steps per contact of the reference (default 80)")
        ->check(CLI::Range(20.0, 10000.0));
    trade_cmd->add_option("--seeds", trade.seeds, "runs per knob from consecutive seeds, figures averaged (default 1)")
        ->check(CLI::Range(1, 1000));
    trade_cmd->add_option("--set", trade.overrides, "override a scene field for every knob")->allow_extra_args(false);
    trade_cmd->add_option("--csv", trade.csv_path, "also write every figure to this CSV file");
    trade_cmd->add_option("--plot", trade.plot_path, "draw error against wall time to this PNG (gnuplot; its .gp and data beside it)");
    ExportFemOptions fem;
    auto* fem_cmd = app.add_subcommand(
        "export-fem", "write an Abaqus/CalculiX input deck (.inp) of a patch of a logged part with the run's impacts on it as shot");
    fem_cmd->add_option("rundir", fem.run_dir, "the run's output directory (optional with --single)");
    fem_cmd->add_option("-o,--output", fem.output_dir, "directory for the deck, impacts.csv and README.md")->required();
    fem_cmd->add_option("--name", fem.name, "the deck's file name without .inp (default patch)");
    fem_cmd->add_option("--component", fem.component, "the logged component (default: the only one)");
    fem_cmd->add_option("--center", fem.center, "patch centre x,y,z in the component's frame, e.g. \"12 mm, 0, 3.5 mm\"");
    fem_cmd->add_option("--radius", fem.radius, "patch radius (default max(3 shot radii, 2 dent diameters))");
    fem_cmd->add_option("--region", fem.region, "a region of the component: the patch is centred on it and takes only its impacts");
    int fem_impacts = 0;
    auto* fem_impacts_option = fem_cmd->add_option("--impacts", fem_impacts, "only the first N (>= 1) impacts of the patch (default all)");
    fem_cmd->add_option("--single", fem.single, "one synthetic impact x,y,z,vx,vy,vz instead of the run's, e.g. \"0,0,0,0,0,-50 m/s\"");
    fem_cmd->add_option("--shot-diameter", fem.shot_diameter,
                        "shot diameter (needed without a run directory; a run of a shot mix: the size whose impacts to export)");
    fem_cmd->add_option("--yield-stress", fem.yield_stress, "target yield stress (default: its material's, else 500 MPa)");
    fem_cmd->add_option("--hardening", fem.hardening, "slope of the yield stress against plastic strain (default 0: perfectly plastic)");
    fem_cmd->add_option(
        "--element-size", fem.element_size,
        "edge of the fine elements (default: the patch's 10th-percentile dent diameter, at least half its median, / --elements-per-dent)");
    fem_cmd->add_option("--elements-per-dent", fem.elements_per_dent, "fine elements across that dent (default 6)");
    fem_cmd->add_option("--shot-divisions", fem.shot_divisions, "cells along the shot mesh's cube edge, even (default 8)");
    fem_cmd->add_option("--element", fem.element,
                        "the block's brick: C3D8I (default, incompatible modes), C3D8R (reduced integration) or C3D8 (full; locks)");
    fem_cmd->add_option("--dynamics", fem.dynamics,
                        "the impacts' steps: explicit (default, *DYNAMIC, EXPLICIT) or implicit (Hilber-Hughes-Taylor)");
    fem_cmd->add_flag("--quarter", fem.quarter, "quarter model with symmetry planes (one normal impact at the centre only)");
    fem_cmd->add_option("--group-window", fem.group_window, "a step groups impacts within this much run time (default 1 ms)");
    fem_cmd->add_option("--contact-times", fem.contact_times, "a step lasts this many Hertz contact times (default 2.5)");
    AlmenFitOptions almen_fit;
    auto* almen_fit_cmd = app.add_subcommand("almen-fit",
                                             "fit a measured Almen saturation curve (SAE J443: 2P and 3P forms, saturation time, "
                                             "intensity); --calibrate the predictive model on a run");
    almen_fit_cmd
        ->add_option("curve", almen_fit.curve_path,
                     "the measured curve: CSV with a header (e.g. time_min,arc_height_in) and a row per strip")
        ->required();
    almen_fit_cmd->add_option("--time-unit", almen_fit.time_unit,
                              "the exposure's unit when the header does not say: s, min, h, passes, cycles");
    almen_fit_cmd->add_option("--height-unit", almen_fit.height_unit,
                              "the arc height's unit when the header does not say: mm, um, in, thou");
    almen_fit_cmd->add_option("--strip", almen_fit.strip, "the SAE J442 strip type A, N or C (printed with the intensity: 0.0118A)");
    almen_fit_cmd->add_option("--form", almen_fit.form, "use this fit, 2P or 3P, instead of the recommended one");
    almen_fit_cmd->add_option("--json", almen_fit.json_path, "also write every figure to this JSON file");
    almen_fit_cmd->add_option("--plot", almen_fit.plot_path,
                              "draw the points, both fits, T and 2T to this PNG (gnuplot; its .gp and <name>_points.csv beside it)");
    almen_fit_cmd->add_option("--calibrate", almen_fit.calibrate_run,
                              "the run (directory, analysed) that reproduced the measurement: print the scene's almen.calibration");
    almen_fit_cmd->add_option("--component", almen_fit.component, "the Almen strip of that run (default: its only one)");
    app.add_subcommand("schema", "print the scene file reference (Markdown)");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : kExitInputError;
    }

    set_analysis_threads(threads);
    if (*run_cmd) {
        if (stop_after > 0) run.stop_after_steps = stop_after;
        if (!scheme.empty()) run.overrides.push_back("accuracy.scheme=" + scheme);
        if (!until_coverage.empty()) {
            // Checked here, so that a bad value is named as the option the user gave (the scene
            // field it sets would be reported as a --set).
            try {
                const double c = parse_option_quantity("--until-coverage", until_coverage, Dimension::dimensionless);
                if (!(c > 0.0 && c <= 1.0))
                    throw InputError({"--until-coverage"}, "",
                                     "expected a coverage above 0 and at most 100 % (e.g. 98 % or 0.98), got '" + until_coverage + "'");
            } catch (const InputError& e) {
                std::cerr << "error: " << e.what() << "\n";
                return kExitInputError;
            }
            run.overrides.push_back("process.until_coverage=" + until_coverage);
        }
        std::ostream null_stream(nullptr);
        run.progress = !quiet;
        run.analyze = !no_analyze;
        run.replicas = replicas;
        if (render_on) run.render = true;
        if (render_off) run.render = false;
        return run_job(run, quiet ? null_stream : std::cout, std::cerr);
    }
    if (*check_cmd) return check_job(check_scene, check_overrides, check_strict, std::cout, std::cerr, check_picture);
    if (*analyze_cmd) {
        try {
            if (!analyze_from.empty()) analyze.from_s = parse_option_quantity("--from", analyze_from, Dimension::time);
            if (!analyze_to.empty()) analyze.to_s = parse_option_quantity("--to", analyze_to, Dimension::time);
            if (!analyze_min_speed.empty())
                analyze.min_speed_m_per_s = parse_option_quantity("--min-speed", analyze_min_speed, Dimension::speed);
            if (!analyze_target.empty())
                analyze.target_coverage = parse_option_quantity("--target", analyze_target, Dimension::dimensionless);
        } catch (const InputError& e) {
            std::cerr << "error: " << e.what() << "\n";
            return kExitInputError;
        }
        return analyze_job(analyze_dir, std::cout, std::cerr, analyze);
    }
    if (*render_regions_cmd) {
        try {
            return render_module().render_regions(render_regions, std::cout, std::cerr);
        } catch (const std::exception& e) {
            std::cerr << "error: " << e.what() << "\n";
            return kExitRuntimeError;
        }
    }
    if (*render_impacts_cmd) {
        try {
            if (!render_target.empty())
                render_impacts.coverage_target = parse_option_quantity("--target", render_target, Dimension::dimensionless);
        } catch (const InputError& e) {
            std::cerr << "error: " << e.what() << "\n";
            return kExitInputError;
        }
        try {
            return render_module().render_impacts(render_impacts, std::cout, std::cerr);
        } catch (const std::exception& e) {
            std::cerr << "error: " << e.what() << "\n";
            return kExitRuntimeError;
        }
    }
    if (*sweep_cmd) {
        if (sweep_seeds_option->count() > 0) sweep.seeds = sweep_seeds;
        return sweep_job(sweep, std::cout, std::cerr);
    }
    if (*optimise_cmd) {
        if (optimise_runs_option->count() > 0) optimise.runs = optimise_runs;
        return optimise_job(optimise, std::cout, std::cerr);
    }
    if (*bench_cmd) return bench_job(bench, std::cout, std::cerr);
    if (*trade_cmd) return trade_job(trade, std::cout, std::cerr);
    if (*new_cmd) {
        for (int i = 0; i < argc; ++i) new_scene.command_line += (i == 0 ? std::string("peensim") : " " + std::string(argv[i]));
        return new_scene_job(new_scene, std::cout, std::cerr);
    }
    if (*fem_cmd) {
        if (fem_impacts_option->count() > 0) fem.max_impacts = fem_impacts;
        return export_fem_job(fem, std::cout, std::cerr);
    }
    if (*almen_fit_cmd) return almen_fit_job(almen_fit, std::cout, std::cerr);
    if (*generate_cmd) return run_generate_command(generate_cmd->remaining(), std::cout, std::cerr);
    if (app.got_subcommand("schema")) {
        std::cout << scene_reference_markdown();
        return 0;
    }
    return kExitInputError;
}
