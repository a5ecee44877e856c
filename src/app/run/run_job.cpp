#include "app/run/run_job.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <span>
#include <thread>

#include "app/analysis/analyze_job.h"
#include "app/analysis/coverage_geometry.h"
#include "app/check/setup_checks.h"
#include "app/checkpoint/checkpoint.h"
#include "app/checkpoint/checkpoint_cadence.h"
#include "app/interrupt.h"
#include "app/mpi_launch.h"
#include "app/paraview/paraview_assembly.h"
#include "app/paraview/paraview_shot_series.h"
#include "app/render_module.h"
#include "app/report_errors.h"
#include "app/run/coverage_watch.h"
#include "app/run/loss_report.h"
#include "app/run/replica_pilot.h"
#include "app/run/replica_ranks.h"
#include "app/run/replica_rounds.h"
#include "app/run/replica_runs.h"
#include "app/run/round_ranks.h"
#include "app/run/round_runs.h"
#include "app/run/summary_builder.h"
#include "common/input_error.h"
#include "common/random.h"
#include "common/shell_quote.h"
#include "engine/run_loop.h"
#include "engine/simulation.h"
#include "model/assembly_checks.h"
#include "model/model.h"
#include "output/atomic_file.h"
#include "output/impact_csv_writer.h"
#include "output/progress_reporter.h"
#include "output/run_directory.h"
#include "output/summary_json.h"
#include "output/summary_text.h"
#include "scene/scene_difference.h"
#include "scene/scene_parser.h"
#include "scene/schema_defaults.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

using Clock = std::chrono::steady_clock;

std::vector<std::string> component_names(const Model& model) {
    std::vector<std::string> names;
    for (const Component& c : model.components) names.push_back(c.name);
    return names;
}

class Job {
public:
    Job(const RunOptions& options, std::ostream& out, std::ostream& err) : options_(options), out_(out), err_(err) {}

    int run() {
        const SceneDescription scene = parse_scene(options_.scene_path, options_.scene_text, options_.overrides);
        model_ = compile_model(scene);
        if (options_.replicas > 1 && !options_.resume) {
            if (const unsigned cores = std::thread::hardware_concurrency();
                cores > 0 && static_cast<unsigned>(options_.replicas) > cores && !options_.replica_ranks)
                err_ << "note: --replicas " << options_.replicas << " on a machine of " << cores
                     << " cores: the replicas share them (the same results as on " << options_.replicas << " cores, not faster)\n";
            if (const std::optional<std::string> why = replica_refusal(*model_))
                throw InputError(scene.process.where, "--replicas", *why + "; expected --replicas 1 for this scene");
        }
        // An animation asked for needs the render module (loaded now, as it would be at the first
        // frame): without it, refused before anything is written.
        if (options_.render.value_or(scene.render.has_value())) (void)render_module();
        // Before anything is written; a fresh run places its shot in the cavity the check built.
        SetupCheck setup = check_setup(*model_, options_.strict, err_);
        dir_ = run_output_directory(options_, scene);
        const bool made_dir = !fs::exists(dir_);
        fs::create_directories(dir_);
        lock_ = std::make_unique<RunDirectoryLock>(dir_);
        if (options_.resume && !fs::exists(checkpoint_path())) return already_finished();
        if (!options_.resume) {
            const std::vector<std::string> removed = clear_previous_outputs(dir_);
            if (!removed.empty()) {
                err_ << "note: replaced a previous run's outputs in " << dir_ << " (";
                for (std::size_t k = 0; k < removed.size(); ++k) err_ << (k ? ", " : "") << removed[k];
                err_ << ")\n";
            }
        }
        try {
            // A resume writes it once its checkpoint is found to be of this scene (start()): a
            // refused one leaves the run's own, which says what differs the next time.
            if (!options_.resume) write_resolved_scene();
            slots_ = logged_slots(*model_);
            start(setup);
            if (const std::optional<double> every = model_->description.output.shot_positions_s)
                shot_series_ = std::make_unique<ShotSeriesRecorder>(*model_, dir_, *every, sim_->state());
            // Coverage from the dents logged so far (a resumed run's), then as they come.
            if (model_->description.process.until_coverage)
                coverage_watch_ = std::make_unique<CoverageWatch>(
                    *coverage_geometry_, options_.resume ? (fs::path(dir_) / kImpactCsvPartialFileName).string() : std::string());
        } catch (const InputError&) {
            // Refused before its first step (the shot do not fit where they are placed; the watched
            // areas are known only once the reach of every coverage sample is): a fresh run leaves
            // nothing behind.
            if (!options_.resume) forget_fresh_run(made_dir);
            throw;
        }
        if (coverage_watch_) {
            for (const std::string& name : coverage_watch_->out_of_reach())
                err_ << "note: until_coverage_of: no shot can reach " << name << ": not waited for\n";
            if (coverage_watch_->done()) {
                err_ << "note: the coverage target was reached before this resumed run's checkpoint\n";
            }
        }
        try {
            {
                // Signals are caught from before the start's checkpoint (so a checkpoint on disk means
                // Ctrl-C is handled) until the final checkpoint of an interrupted run is written; a
                // finished run's outputs and analysis are left to Ctrl-C's default (the run is complete).
                StopRequest stop(options_.stop_requested, abandon_message());
                // A checkpoint from the start: whatever fails later (a full disk while streaming
                // impacts, before the first periodic checkpoint), --resume has a state to continue from.
                if (!options_.resume) checkpoint();
                start_rendering();
                if (!loop(stop)) return interrupted();
            }
            return complete();
        } catch (const std::exception&) {
            if (fs::exists(checkpoint_path()))
                err_ << "the run stopped on the error below; once it is fixed, " << resume_command()
                     << " continues from its last checkpoint\n";
            throw;
        }
    }

private:
    std::string checkpoint_path() const { return (fs::path(dir_) / kCheckpointFileName).string(); }

    // A fresh run refused before its first step: its outputs removed, and its directory if it made it.
    void forget_fresh_run(bool made_dir) {
        writer_.reset();
        coverage_geometry_.reset();
        clear_previous_outputs(dir_);
        lock_.reset();
        if (!made_dir) return;
        std::error_code ignored;
        fs::remove(fs::path(dir_) / kRunLockFileName, ignored);
        fs::remove(dir_, ignored);  // only if empty
    }

    std::string resume_command() const {
        if (options_.scene_text) return "the same run with resume into " + dir_;  // a scene in memory (Python): no command to give
        // Every --set, and every option that is one (--until-coverage): the scene must be the same.
        std::string command = "peensim run " + shell_quoted(options_.scene_path) + " -o " + shell_quoted(dir_) + " --resume";
        for (const std::string& o : options_.overrides) command += " --set " + shell_quoted(o);
        // And the options a resumed run does not take from its checkpoint: without --render it
        // would finish without the animation asked for.
        if (!options_.analyze) command += " --no-analyze";
        if (options_.render) command += *options_.render ? " --render" : " --no-render";
        if (options_.strict) command += " --strict";
        if (!options_.geometry_cache_dir.empty()) command += " --geometry-cache " + shell_quoted(options_.geometry_cache_dir);
        return command;
    }

    // What a second Ctrl-C prints as it ends the process without waiting for a checkpoint.
    std::string abandon_message() const {
        return "\ninterrupted again: run abandoned; " + resume_command() + " continues from the last checkpoint (if one was written)\n";
    }

    // " (<what differs>)" between the run's scene and this one, or "" (scene_difference.h).
    std::string what_differs() const {
        const std::string d = scene_difference((fs::path(dir_) / "scene.resolved.yaml").string(), model_->description);
        return d.empty() ? std::string() : " (what differs: " + d + ")";
    }

    void write_resolved_scene() const {
        write_file_atomically((fs::path(dir_) / "scene.resolved.yaml").string(), model_->resolved_scene_yaml);
    }

    // --resume without a checkpoint: a finished run (its summary says so, of this scene) has
    // nothing to resume, which is said with where its results are (exit 0: the run is done, and
    // a script resuming until done stops); anything else cannot be resumed.
    int already_finished() {
        const fs::path summary = fs::path(dir_) / "summary.json";
        nlohmann::json j;
        if (std::ifstream in(summary); in) {
            try {
                j = nlohmann::json::parse(in);
            } catch (const std::exception&) {}  // damaged: not a finished run's
        }
        const bool finished = j.is_object() && j.value("finished", false) && fs::exists(fs::path(dir_) / kImpactCsvFileName);
        if (!finished)
            throw std::runtime_error(checkpoint_path() + ": no checkpoint to resume from (the run in " + dir_ +
                                     " did not write one: it ended before its first); run it again without --resume");
        if (j.value("scene_hash", std::string()) != scene_hash_text(*model_))
            throw InputError({summary.string(), 0, 0}, "scene_hash",
                             "the run in " + dir_ +
                                 " finished with another scene (or other --set values, or mesh files whose bytes have changed since) than "
                                 "this one" +
                                 what_differs() +
                                 "; nothing to resume: run without --resume to run this scene (that replaces its outputs)");
        err_ << "nothing to resume: the run in " << dir_ << " already finished (" << j.value("simulated_time_s", 0.0)
             << " s simulated); its results are in " << dir_ << "/{impacts.csv, summary.json, analysis/}\n";
        return kExitOk;
    }

    void start(SetupCheck& setup) {
        // The cavity (up to ~8 M cells) places the shot, then goes to the coverage geometry (freed
        // once that is computed), or is freed once they are placed.
        std::unique_ptr<ShotCavity> cavity = std::move(setup.cavity);
        const std::size_t logged = static_cast<std::size_t>(std::count_if(slots_.begin(), slots_.end(), [](int s) { return s >= 0; }));
        if (options_.resume) {
            Checkpoint c = load_checkpoint(checkpoint_path());
            check_resumable(checkpoint_path(), c, *model_, logged);
            write_resolved_scene();
            sim_ = std::make_unique<Simulation>(model_, std::move(c.state));
            writer_ = std::make_unique<ImpactCsvWriter>(
                ImpactCsvWriter::resume(dir_, component_names(*model_), c.csv_bytes, c.csv_rows, model_->has_size_mix()));
            speeds_ = std::move(c.normal_speeds);
            wall_before_ = c.wall_time_s;
            // A run until coverage as replicas goes on as replica 0 alone, its slot where it was.
            shift_s_ = c.log_shift_s;
            others_impacts_ = std::move(c.replica_impacts);
            others_slow_ = std::move(c.replica_slow_contacts);
            sim_->end_at(model_->duration_s - shift_s_);
            // The summary of the session that was interrupted describes a time this run goes past:
            // removed, so that nothing (analyze) reads it as this run's if this session is killed.
            // A finished or interrupted session writes its own.
            fs::remove(fs::path(dir_) / "summary.json");
            fs::remove_all(fs::path(dir_) / kReplicaSpillDirectory);  // an interrupted replicas run's: dropped
            if (options_.replicas > 1) err_ << "note: a resumed run goes on as one replica (--replicas is for a fresh run)\n";
            if (options_.replica_ranks) release_replica_ranks();
        } else {
            fs::remove(checkpoint_path());
            fs::remove(fs::path(dir_) / kImpactCsvFileName);
            sim_ = std::make_unique<Simulation>(model_, cavity ? place_shots(*model_, *cavity, setup.rng) : InitialShots{});
            // The other replicas' loads, each from its own seed, placed now: the cavity goes below
            // (over MPI ranks, each rank places its own).
            replicas_wanted_ = cavity && options_.replicas > 1;
            for (int k = 1; cavity && k < options_.replicas && !options_.replica_ranks; ++k) {
                Random rng(replica_seed(model_->seed, k));
                replica_shots_.push_back(place_shots(*model_, *cavity, rng));
            }
            writer_ = std::make_unique<ImpactCsvWriter>(dir_, component_names(*model_), model_->has_size_mix());
            speeds_.assign(logged, SpeedHistogram());
        }
        logged_impacts_ = writer_->rows_written();
        // What the coverage watch and the analysis need of the parts' geometry, computed on a
        // thread of its own while the run steps (coverage_geometry.h).
        if (options_.analyze || model_->description.process.until_coverage) {
            // On the cores the run's own threads (its replicas') leave, if any; else when asked.
            const unsigned cores = std::thread::hardware_concurrency();
            const auto busy = static_cast<unsigned>(options_.replicas > 1 && !options_.replica_ranks ? options_.replicas : 1);
            coverage_geometry_ = std::make_shared<CoverageGeometry>(model_, std::move(cavity), cores > busy ? cores - busy : 0,
                                                                    std::move(setup.regions), options_.geometry_cache_dir);
        }
    }

    // The animation, when the scene asks for one (or --render) and --no-render does not forbid it.
    void start_rendering() {
        const std::optional<RenderDesc>& scene_render = model_->description.render;
        const bool wanted = options_.render.value_or(scene_render.has_value());
        if (!wanted) return;
        recorder_ = render_module().make_recorder(*model_, scene_render.value_or(default_render()), dir_, sim_->state());
        recorder_->after_step(sim_->state(), {}, logged_impacts_);
    }

    // Returns true when the scene's duration was reached, false when interrupted.
    bool loop(const StopRequest& stop) {
        // What the run does with each step, in this order: the impacts to impacts.csv and the speed
        // histograms, the recorder's frames, the progress bar; at restart points, checkpoints.
        struct Listener final : RunListener {
            Job& job;
            ProgressReporter progress;
            CheckpointCadence cadence;
            Clock::time_point next_callback = Clock::now();
            Listener(Job& j, bool show_progress)
                : job(j),
                  progress(j.err_, show_progress),
                  cadence(j.model_->description.output.checkpoint_interval_s, j.options_.checkpoint_clock) {}
            void call_back(Clock::time_point now) {
                next_callback =
                    now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kProgressCallbackInterval_s));
                job.options_.on_progress(RunProgress{job.run_time_s(), job.model_->duration_s, job.logged_impacts_, job.wall_time()});
            }
            double pause_at_s() const override {
                const double frame_s = job.recorder_ ? job.recorder_->next_frame_s() : std::numeric_limits<double>::infinity();
                return std::min(frame_s, job.own_slot_end_s_);
            }
            void after_step(const Simulation& sim, const std::vector<ImpactRecord>& all) override {
                // A replica's window ends at its end; time stepping's last step may go past it.
                const std::vector<ImpactRecord>& own = job.replicas_ ? job.before_end(all) : all;
                job.log_own(own);
                if (job.recorder_) job.recorder_->after_step(sim.state(), own, job.logged_impacts_);
                if (job.rounds_ && !job.log_closed_ && !(sim.state().time.seconds() < job.own_slot_end_s_)) job.end_round();
                progress.update(job.run_time_s(), job.shift_s_ + sim.end_s(), job.logged_impacts_);
                if (job.options_.on_progress) {
                    const auto now = Clock::now();
                    if (now >= next_callback) call_back(now);
                }
            }
            // The clock is read only here: reading it at every unit of work would decide the same.
            void at_restart_point(const Simulation&) override {
                if (cadence.due()) job.checkpoint();
            }
            bool done() const override { return job.coverage_watch_ && job.coverage_watch_->done(); }
            // The bar's last line, and the caller's last progress, whichever way the run ends.
            void at_finish(const Simulation&) override { end(); }
            void at_interrupt(const Simulation&) override { end(); }
            void end() {
                progress.finish();
                if (job.options_.on_progress) call_back(Clock::now());
            }
        } listener(*this, options_.progress && isatty(STDERR_FILENO));
        started_ = Clock::now();
        RunLoop run(*sim_);
        std::unique_ptr<ReplicaPilot> pilot;
        if (replicas_wanted_) {
            // Until coverage the end is not known: the replicas run in rounds (replica_rounds.h).
            const bool rounds = model_->description.process.until_coverage.has_value();
            const double duration_s = model_->duration_s;
            pilot = std::make_unique<ReplicaPilot>(
                rounds ? first_round_pilot_s(duration_s, options_.replicas) : first_pilot_s(duration_s, options_.replicas),
                last_pilot_s(duration_s, options_.replicas),
                rounds ? std::function<std::optional<std::string>(const PilotReading&)>(
                             [this](const PilotReading& r) { return start_rounds(r); })
                       : plan_windows_then(*model_, options_.replicas, [this](const ReplicaPlan& plan) { start_replicas(plan); }),
                [this](const std::string& why) {
                    err_ << "note: --replicas " << options_.replicas << ": the run goes on as one replica: " << why << "\n";
                    replica_shots_.clear();
                    replicas_wanted_ = false;
                    if (options_.replica_ranks) release_replica_ranks();
                });
            run.add(*pilot);
        }
        run.add(listener);
        if (shot_series_) run.add(*shot_series_);
        // Checkpoints (and so stops) wait for a restart point: time stepping reaches one at every
        // step, the event-driven scheme at its restart interval.
        return run.run(
            [&](std::uint64_t steps) { return stop.requested() || (options_.stop_after_steps && steps >= *options_.stop_after_steps); });
    }

    // The pilot found the warm-up: replica 0 (this run) now ends at its window's end, and the others start.
    void start_replicas(const ReplicaPlan& plan) {
        plan_ = plan;
        sim_->end_at(plan.windows.front().run_to_s);
        std::vector<ReplicaWindow> others(plan.windows.begin() + 1, plan.windows.end());
        if (options_.replica_ranks)
            replicas_ = std::make_unique<ReplicaRanks>(std::move(others), dir_);
        else
            replicas_ = std::make_unique<ReplicaRuns>(model_, std::move(others), std::move(replica_shots_), dir_, slots_);
        replica_shots_.clear();
    }

    // Until coverage: the pilot measured the warm-up and the rate; the rounds start (replica 0 is in
    // its first slot, [0, A)).
    std::optional<std::string> start_rounds(const PilotReading& reading) {
        std::optional<RoundPlan> plan =
            plan_rounds(options_.replicas, reading.pilot_s, reading.warm_up_s, reading.impacts, turn_period_s(*model_), model_->seed);
        if (!plan) return "the pilot found no impacts to plan rounds from";
        if (!(plan->first_s < model_->duration_s)) {
            std::ostringstream why;
            why << "the run's duration (" << model_->duration_s << " s, its longest) ends within replica 0's first slot (" << plan->first_s
                << " s: the pilot, the warm-up and a round of " << plan->round_s << " s)";
            return why.str();
        }
        rounds_ = std::move(plan);
        own_slot_end_s_ = rounds_->first_s;
        if (options_.replica_ranks)
            round_runs_ = std::make_unique<RoundRanks>(*rounds_, dir_);
        else
            round_runs_ = std::make_unique<RoundRuns>(model_, *rounds_, std::move(replica_shots_), dir_, slots_);
        replica_shots_.clear();
        return std::nullopt;
    }

    // s, the run's time now: replica 0's own, moved to its slot's place in the run.
    double run_time_s() const { return sim_->state().time.seconds() + shift_s_; }

    // Replica 0's impacts of a step into the log: at their place in the run, and in rounds only
    // those of its current slot (the rest are the next slot's, logged after the other replicas').
    void log_own(const std::vector<ImpactRecord>& own) {
        if (log_closed_ || own.empty()) return;
        if (!rounds_ && shift_s_ == 0.0) return log(own);
        moved_.clear();
        for (const ImpactRecord& r : own) {
            if (rounds_ && !(r.time_s < own_slot_end_s_)) {
                carry_.push_back(r);
                continue;
            }
            moved_.push_back(r);
            moved_.back().time_s += shift_s_;
        }
        log(moved_);
    }

    // Impacts at their place in the run, in time order: their dents to the coverage, then to
    // impacts.csv and the speed histograms.
    void log(std::span<const ImpactRecord> impacts) {
        if (impacts.empty()) return;
        if (coverage_watch_) coverage_watch_->add(impacts);
        const auto t = Clock::now();
        writer_->write(impacts);
        for (const ImpactRecord& r : impacts)
            speeds_[static_cast<std::size_t>(slots_[static_cast<std::size_t>(r.component)])].add(r.vn_in_m_per_s);
        logged_impacts_ += impacts.size();
        output_seconds_ += std::chrono::duration<double>(Clock::now() - t).count();
    }

    // Replica 0 ended its slot of this round: the others' slots of the round follow it in the log,
    // in replica order, unless the target was reached in it; the run ends in the slot where the
    // target is reached (or the duration), else the next round starts.
    void end_round() {
        const ReplicaWindow own = rounds_->slot(round_, 0);
        const double own_end_s = std::min(rounds_->slot_start_s(round_, 1), model_->duration_s);  // where the next begins
        add_round_window(round_, own, own_end_s, logged_impacts_ - slot_logged_from_);
        if (coverage_watch_ && coverage_watch_->done()) return close_log(own_end_s);
        const std::vector<SlotResult> others = round_runs_->wait_round(round_);
        for (const SlotResult& slot : others) {
            const std::uint64_t before = logged_impacts_;
            replay_spill(slot.spill, [this](std::span<const ImpactRecord> batch) { log(batch); });
            const double end_s = std::min(rounds_->slot_end_s(round_, slot.window.replica), model_->duration_s);
            add_round_window(round_, slot.window, end_s, logged_impacts_ - before);
            if (others_impacts_.empty()) others_impacts_.assign(slot.impacts_at_end.size(), 0);
            if (others_slow_.empty()) others_slow_.assign(slot.slow_contacts_at_end.size(), 0);
            for (std::size_t i = 0; i < others_impacts_.size(); ++i)
                others_impacts_[i] += slot.impacts_at_end.at(i) - slot.impacts_at_start.at(i);
            for (std::size_t i = 0; i < others_slow_.size(); ++i)
                others_slow_[i] += slot.slow_contacts_at_end.at(i) - slot.slow_contacts_at_start.at(i);
            if ((coverage_watch_ && coverage_watch_->done()) || !(end_s < model_->duration_s)) return close_log(end_s);
        }
        if (static_cast<int>(others.size()) + 1 < rounds_->replicas()) return close_log(log_end_s_);  // one reached the duration
        ++round_;
        const ReplicaWindow next = rounds_->slot(round_, 0);
        if (!(next.window_start_s() < model_->duration_s)) return close_log(log_end_s_);
        shift_s_ = next.shift_s;
        own_slot_end_s_ = next.run_to_s;
        sim_->end_at(model_->duration_s - shift_s_);
        slot_logged_from_ = logged_impacts_;
        round_runs_->go(round_);
        std::vector<ImpactRecord> carried;
        carried.swap(carry_);
        log_own(carried);
    }

    // A slot of the run's log, for the summary.
    // round: the slot's (its start is the plan's, exactly where the last one ended).
    void add_round_window(int round, const ReplicaWindow& w, double end_s, std::uint64_t logged) {
        round_windows_.push_back({w.replica, w.seed, rounds_->slot_start_s(round, w.replica), end_s, w.log_from_s, logged});
        log_end_s_ = end_s;
    }

    // The log ends at end_s (run time): replica 0 stops now, the other replicas' later work is dropped.
    void close_log(double end_s) {
        log_closed_ = true;
        log_end_s_ = end_s;
        carry_.clear();
        sim_->end_at(sim_->state().time.seconds());
        round_runs_->stop();
    }

    // The impacts of a step before replica 0's end (a copy only when some are past it).
    const std::vector<ImpactRecord>& before_end(const std::vector<ImpactRecord>& impacts) {
        const double end = sim_->end_s();
        if (std::all_of(impacts.begin(), impacts.end(), [end](const ImpactRecord& r) { return r.time_s < end; })) return impacts;
        kept_.clear();
        for (const ImpactRecord& r : impacts)
            if (r.time_s < end) kept_.push_back(r);
        return kept_;
    }

    // The other replicas, once replica 0 has finished: their windows' impacts after its own in
    // impacts.csv (in window order: the run's time order), their speeds into the histograms.
    void gather_replicas() {
        replica_results_ = replicas_->wait();
        own_logged_impacts_ = logged_impacts_;
        for (std::size_t k = 0; k < replica_results_.size(); ++k) {
            replicas_->replay(k, [this](std::span<const ImpactRecord> batch) { writer_->write(batch); });
            for (std::size_t slot = 0; slot < speeds_.size(); ++slot) speeds_[slot].merge(replica_results_[k].speeds[slot]);
            logged_impacts_ += replica_results_[k].logged_impacts;
        }
        replicas_->discard();
    }

    // An interrupted run drops the other replicas' work: --resume goes on from replica 0's checkpoint.
    void drop_replicas() {
        replicas_->stop();
        try {
            replicas_->wait();
        } catch (const std::exception&) {}  // of no use now either way
        replicas_->discard();
        err_ << "note: the other replicas' work is dropped; --resume continues this run as one replica\n";
    }

    double wall_time() const { return wall_before_ + std::chrono::duration<double>(Clock::now() - started_).count(); }

    void checkpoint() {
        writer_->flush_durable();
        Checkpoint c;
        c.scene_hash = model_->scene_hash;
        c.state = sim_->state();
        c.csv_bytes = writer_->bytes_written();
        c.csv_rows = writer_->rows_written();
        c.normal_speeds = speeds_;
        c.wall_time_s = wall_time();
        c.log_shift_s = shift_s_;
        c.replica_impacts = others_impacts_;
        c.replica_slow_contacts = others_slow_;
        save_checkpoint(checkpoint_path(), c);
    }

    RunSummary summary(bool finished) const {
        RunSummary s = build_summary(*sim_, options_.scene_path, speeds_, wall_time(), finished);
        s.overrides = options_.overrides;
        if (coverage_watch_) {
            RunSummary::CoverageGoal g;
            g.target = coverage_watch_->target();
            for (const WatchedArea& a : coverage_watch_->areas()) g.areas.push_back({a.name, a.reached_at_s, a.coverage});
            g.reached = coverage_watch_->done();
            s.until_coverage = std::move(g);
        }
        for (StageTime& st : s.stage_times)
            if (st.stage == "record_impacts") st.seconds += output_seconds_;
        if (finished && plan_) merge_replica_summaries(s, *plan_, replica_results_, own_logged_impacts_);
        // Replica 0 moved into the run, and the other replicas' logged slots (until coverage).
        s.simulated_time_s = rounds_ && log_closed_ ? log_end_s_ : s.simulated_time_s + shift_s_;
        add_slot_counts(s, others_impacts_, others_slow_);
        if (finished && rounds_) merge_round_summaries(s, *rounds_, round_windows_, round_results_);
        return s;
    }

    int interrupted() {
        if (replicas_) drop_replicas();
        if (round_runs_) {
            round_runs_->stop();
            try {
                round_runs_->finish();
            } catch (const std::exception&) {}  // of no use now either way
            round_runs_->discard();
            err_ << "note: the other replicas' work since their last logged round is dropped; --resume continues this run as "
                    "one replica\n";
        }
        if (recorder_) recorder_->flush();  // the frames drawn so far are complete files
        if (shot_series_) shot_series_->flush();
        checkpoint();
        write_summary((fs::path(dir_) / "summary.json").string(), summary(false));
        write_paraview_assembly(*model_, dir_);
        err_ << "interrupted at t = " << run_time_s() << " s of " << model_->duration_s << " s; outputs in " << dir_
             << " are consistent up to that time.\n"
             << "resume with: " << resume_command() << "\n";
        return kExitInterrupted;
    }

    int complete() {
        if (replicas_) gather_replicas();
        if (round_runs_) {
            // A run that ended in replica 0's slot closes its log here.
            if (!log_closed_) add_round_window(round_, rounds_->slot(round_, 0), run_time_s(), logged_impacts_ - slot_logged_from_);
            round_results_ = round_runs_->finish();
            round_runs_->discard();
        }
        writer_->finish();
        // The ParaView files before the checkpoint goes: a full disk here still leaves a run to resume.
        const std::string series = shot_series_ ? shot_series_->finish(sim_->state()) : "";
        write_paraview_assembly(*model_, dir_);
        const RunSummary s = summary(true);
        write_summary((fs::path(dir_) / "summary.json").string(), s);
        fs::remove(checkpoint_path());
        out_ << summary_to_text(s);
        out_ << "outputs: " << dir_ << "/{impacts.csv, summary.json, scene.resolved.yaml, paraview/assembly.vtm}\n";
        if (shot_series_) out_ << "shot positions: " << series << "\n";
        if (recorder_) {
            const int n = recorder_->frames_drawn();
            const std::string video = recorder_->finish_video();
            out_ << "render: " << video << "; drawing took " << recorder_->draw_seconds() << " s"
                 << (n > 0 ? " (" + std::to_string(recorder_->draw_seconds() / n * 1e3) + " ms per frame)" : std::string()) << "\n";
        }
        for (const LostShot& l : sim_->state().lost) err_ << describe_loss(*model_, l) << "\n";
        for (const ReplicaResult& r : replica_results_)
            for (const LostShot& l : r.lost)
                err_ << "replica " << r.window.replica << " (its own time): " << describe_loss(*model_, l) << "\n";
        for (const RoundReplicaResult& r : round_results_)
            for (const LostShot& l : r.lost) err_ << "replica " << r.replica << " (its own time): " << describe_loss(*model_, l) << "\n";
        if (options_.analyze) {
            AnalyzeOptions analysis;
            analysis.model = model_;
            analysis.geometry = coverage_geometry_;
            analysis.geometry_cache_dir = options_.geometry_cache_dir;
            const int code = analyze_job(dir_, out_, err_, analysis);
            if (code != kExitOk) {
                err_ << "error: the run finished (its outputs are complete) but its analysis failed; fix the cause above and run "
                        "'peensim analyze "
                     << dir_ << "'\n";
                return code;
            }
        }
        std::uint64_t serious = sim_->state().health.serious();
        for (const ReplicaResult& r : replica_results_) serious += r.health.serious();
        for (const RoundReplicaResult& r : round_results_) serious += r.health.serious();
        if (options_.strict && serious > 0) {
            err_ << "error: --strict: the run had numerical trouble (see health counters in summary.json)\n";
            return kExitHealthFailure;
        }
        return kExitOk;
    }

    const RunOptions& options_;
    std::ostream& out_;
    std::ostream& err_;
    std::shared_ptr<const Model> model_;
    std::string dir_;
    std::unique_ptr<RunDirectoryLock> lock_;  // held for the whole run
    std::vector<int> slots_;
    std::unique_ptr<Simulation> sim_;
    std::unique_ptr<ImpactCsvWriter> writer_;
    std::unique_ptr<FrameSink> recorder_;                  // only when rendering (the module is loaded then)
    std::unique_ptr<ShotSeriesRecorder> shot_series_;      // only when the scene asks (output.shot_positions)
    std::shared_ptr<CoverageGeometry> coverage_geometry_;  // when the run analyses itself or runs until coverage
    std::unique_ptr<CoverageWatch> coverage_watch_;        // only when running until coverage
    std::vector<SpeedHistogram> speeds_;
    // --replicas (fresh run): the other replicas' loads until the pilot plans them, then their runs.
    std::vector<InitialShots> replica_shots_;
    bool replicas_wanted_ = false;  // a fresh run with --replicas, until the pilot plans them or gives up
    std::optional<ReplicaPlan> plan_;
    std::unique_ptr<ReplicaRunner> replicas_;
    std::vector<ReplicaResult> replica_results_;
    std::uint64_t own_logged_impacts_ = 0;  // replica 0's share of logged_impacts_
    std::vector<ImpactRecord> kept_;        // before_end()'s scratch
    // Until coverage as replicas (replica_rounds.h): the rounds, the other replicas' runs, and
    // replica 0's current slot.
    std::optional<RoundPlan> rounds_;
    std::unique_ptr<RoundRunner> round_runs_;
    std::vector<RoundReplicaResult> round_results_;
    std::vector<RunSummary::Replicas::Window> round_windows_;  // the slots logged, in time order
    int round_ = 0;
    double own_slot_end_s_ = std::numeric_limits<double>::infinity();  // s, replica 0's own time its slot ends
    std::uint64_t slot_logged_from_ = 0;                               // logged impacts when replica 0's slot began
    std::vector<ImpactRecord> carry_;                                  // replica 0's impacts past its slot's end, for its next
    std::vector<ImpactRecord> moved_;                                  // log_own()'s scratch
    bool log_closed_ = false;                                          // the log ended (the target or the duration reached in a round)
    double log_end_s_ = 0.0;                                           // s, run time: the end of the last slot logged
    // s, added to replica 0's times in the log (its slot's place in the run; a resumed run's too).
    double shift_s_ = 0.0;
    // The other replicas' counts in their logged slots (summary entries: shot-shot, then each component).
    std::vector<std::uint64_t> others_impacts_, others_slow_;
    std::uint64_t logged_impacts_ = 0;
    double wall_before_ = 0.0;     // s, wall time of earlier sessions of a resumed run
    double output_seconds_ = 0.0;  // s, spent writing impacts
    Clock::time_point started_;
};

}  // namespace

std::string run_output_directory(const RunOptions& options, const SceneDescription& scene) {
    if (!options.output_dir.empty()) return options.output_dir;
    if (!scene.output.directory.empty()) return scene.output.directory;
    return "out/" + fs::path(options.scene_path).stem().string();
}

int run_job(const RunOptions& options, std::ostream& out, std::ostream& err) {
    // Replicas under an MPI launcher: one a rank (a run without --replicas stays one process a rank,
    // as a sweep's runs are).
    if (options.replicas > 1 && !options.replica_ranks && launched_by_mpi()) return run_replicas_over_mpi(options, out, err);
    return report_errors(err, [&] { return run_scene(options, out, err); });
}

int run_scene(const RunOptions& options, std::ostream& out, std::ostream& err) { return Job(options, out, err).run(); }

}  // namespace peensim
