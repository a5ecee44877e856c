#include "app/bench/bench_job.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <span>
#include <sstream>
#include <string_view>

#include "app/report_errors.h"
#include "app/run/replica_pilot.h"
#include "app/run/replica_runs.h"
#include "app/run/run_job.h"
#include "common/float_limits.h"
#include "common/input_error.h"
#include "common/random.h"
#include "engine/run_loop.h"
#include "engine/simulation.h"
#include "model/model.h"
#include "model/shot_cavity.h"
#include "model/shot_placement.h"
#include "output/atomic_file.h"
#include "output/output_names.h"
#include "scene/scene_parser.h"

namespace fs = std::filesystem;

namespace peensim {

// ---------------------------------------------------------------------------------------------
// Batch means

BatchedImpactStats::BatchedImpactStats(double duration_s) : duration_s_(duration_s) {}

void BatchedImpactStats::add(double time_s, double vn_m_per_s) {
    // An impact exactly at the end of the run belongs to the last batch.
    const double position = time_s / duration_s_ * kBenchBatches;
    const int batch = std::clamp(static_cast<int>(std::floor(position)), 0, kBenchBatches - 1);
    ++count_;
    speed_sum_ += vn_m_per_s;
    ++batch_count_[batch];
    batch_speed_sum_[batch] += vn_m_per_s;
}

void BatchedImpactStats::merge(const BatchedImpactStats& other) {
    count_ += other.count_;
    speed_sum_ += other.speed_sum_;
    for (int k = 0; k < kBenchBatches; ++k) {
        batch_count_[k] += other.batch_count_[k];
        batch_speed_sum_[k] += other.batch_speed_sum_[k];
    }
}

double BatchedImpactStats::rate_per_s() const { return static_cast<double>(count_) / duration_s_; }

double BatchedImpactStats::rate_se_per_s() const {
    // Standard error of the mean of the kBenchBatches batch rates (sample standard deviation / sqrt(B)).
    const double batch_s = duration_s_ / kBenchBatches;
    const double mean = rate_per_s();
    double sq = 0.0;
    for (int k = 0; k < kBenchBatches; ++k) {
        const double d = static_cast<double>(batch_count_[k]) / batch_s - mean;
        sq += d * d;
    }
    return std::sqrt(sq / (kBenchBatches * (kBenchBatches - 1.0)));
}

double BatchedImpactStats::mean_speed_m_per_s() const {
    return count_ ? speed_sum_ / static_cast<double>(count_) : std::numeric_limits<double>::quiet_NaN();
}

double BatchedImpactStats::mean_speed_se_m_per_s() const {
    // The overall mean is a ratio (sum of speeds / count) and batches hold different counts, so
    // the batch means are weighted by their counts: the ratio estimator's variance
    // B / (B - 1) * sum_k (S_k - m n_k)^2 / N^2 (it reduces to sd(batch means)^2 / B when every
    // batch holds the same number of impacts, and an empty batch simply contributes nothing).
    if (count_ == 0) return std::numeric_limits<double>::quiet_NaN();
    const double m = mean_speed_m_per_s();
    double sq = 0.0;
    for (int k = 0; k < kBenchBatches; ++k) {
        const double d = batch_speed_sum_[k] - m * static_cast<double>(batch_count_[k]);
        sq += d * d;
    }
    const double n = static_cast<double>(count_);
    return std::sqrt(kBenchBatches / (kBenchBatches - 1.0) * sq) / n;
}

BenchDifference bench_difference(double a, double se_a, double b, double se_b) {
    BenchDifference d;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(se_a) || !std::isfinite(se_b)) {
        d.percent = d.bound_percent = nan;
        return d;  // nothing to compare (no impacts in one run): reported as n/a, not as a difference
    }
    const double bound = 3.0 * std::hypot(se_a, se_b);
    d.within_noise = std::abs(b - a) <= bound;
    d.percent = a != 0.0 ? 100.0 * (b - a) / std::abs(a) : (b == a ? 0.0 : nan);
    d.bound_percent = a != 0.0 ? 100.0 * bound / std::abs(a) : nan;
    return d;
}

// ---------------------------------------------------------------------------------------------
// Where the shipped scenes are

std::vector<std::string> shipped_scene_search_dirs(const std::string& executable_path) {
    const fs::path exe_dir = fs::path(executable_path).parent_path();
    std::vector<std::string> dirs{(exe_dir / "scenes").lexically_normal().string(),
                                  (exe_dir.parent_path() / "scenes").lexically_normal().string()};
#ifdef PEENSIM_SOURCE_DIR
    dirs.push_back((fs::path(PEENSIM_SOURCE_DIR) / "scenes").lexically_normal().string());
#endif
    return dirs;
}

std::vector<std::string> shipped_scenes(const std::string& executable_path) {
    const std::vector<std::string> dirs = shipped_scene_search_dirs(executable_path);
    for (const std::string& dir : dirs) {
        std::error_code ec;
        if (!fs::is_directory(dir, ec)) continue;
        std::vector<std::string> scenes;
        for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
            if (e.path().extension() == ".yaml" && e.is_regular_file(ec)) scenes.push_back(e.path().string());
        if (scenes.empty()) continue;
        std::sort(scenes.begin(), scenes.end());
        return scenes;
    }
    std::string looked;
    for (const std::string& dir : dirs) looked += (looked.empty() ? "" : ", ") + dir;
    throw InputError(
        SourceLocation{"peensim bench", 0, 0}, "scene",
        "no scene given and no shipped scenes (*.yaml) found; looked in " + looked + " (name the scene files on the command line)");
}

namespace {

using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------------------
// Schemes and runs

struct SchemeSpec {
    std::string label;                   // as given on --schemes, "#k" added when two are the same
    std::string name;                    // step | event | soft
    std::vector<std::string> overrides;  // its own path=value overrides
    int replicas = 1;                    // `:replicas=K`: the run as K replicas (run --replicas)
};

std::vector<SchemeSpec> parse_schemes(const std::vector<std::string>& texts) {
    const auto fail = [](const std::string& problem) { throw InputError(SourceLocation{"command line", 0, 0}, "--schemes", problem); };
    if (texts.size() < 2)
        fail("expected at least two schemes to compare, e.g. --schemes step,event (got " + std::to_string(texts.size()) + ")");
    std::vector<SchemeSpec> specs;
    for (const std::string& text : texts) {
        SchemeSpec s;
        s.label = text;
        std::stringstream parts(text);
        std::getline(parts, s.name, ':');
        if (s.name != "step" && s.name != "event" && s.name != "soft")
            fail("expected step, event or soft, optionally followed by :path=value overrides, got '" + text + "'");
        for (std::string o; std::getline(parts, o, ':');) {
            if (o.find('=') == std::string::npos) fail("expected path=value after ':' in '" + text + "', got '" + o + "'");
            if (o.rfind("replicas=", 0) == 0) {
                const std::string k = o.substr(9);
                const auto [end, ec] = std::from_chars(k.data(), k.data() + k.size(), s.replicas);
                if (ec != std::errc() || end != k.data() + k.size() || s.replicas < 1 || s.replicas > 1024)
                    fail("expected replicas=K with K from 1 to 1024 in '" + text + "', got '" + o + "'");
                continue;
            }
            s.overrides.push_back(o);
        }
        specs.push_back(std::move(s));
    }
    // Two identical specs (`--schemes step,step`) get their position appended to tell the rows apart.
    for (std::size_t i = 0; i < specs.size(); ++i)
        if (std::count(texts.begin(), texts.end(), texts[i]) > 1) specs[i].label += "#" + std::to_string(i + 1);
    return specs;
}

struct ComponentFigures {
    std::string name;  // component name, or "all logged"
    bool logged = false;
    bool total = false;                       // the "all logged" row
    std::uint64_t impacts = 0;                // every impact on it in the run
    std::optional<BatchedImpactStats> stats;  // logged components (and the total) only
};

struct SchemeRun {
    SchemeSpec spec;
    double duration_s = 0.0;   // s, the scene's process.duration
    double simulated_s = 0.0;  // s, reached
    double wall_s = 0.0;       // s, the stepping loop only (not compiling the model or placing shot)
    int shot_count = 0;
    std::uint64_t steps = 0;  // units of work of the scheme (time steps, or event stretches)
    std::uint64_t shot_steps = 0;
    std::uint64_t shot_shot_impacts = 0;
    HealthCounters health;
    StepStats stats;
    std::vector<ComponentFigures> components;  // model order, then "all logged" when more than one is logged
    std::size_t logged_row = 0;                // the row the summary compares: the only logged component or the total

    double per_simulated_s(double v) const { return v / duration_s; }
};

// A scheme's run as replicas (run --replicas): the other replicas' loads placed beforehand, the
// pilot listening to replica 0 (the bench's own simulation), then the others on threads, their
// windows' impacts handed to `add` once all have ended. Their spills go to a folder of their own
// under the system's temporary directory, removed at the end.
class BenchReplicas {
public:
    BenchReplicas(std::shared_ptr<const Model> model, Simulation& sim, const std::vector<int>& slots, int replicas)
        : model_(std::move(model)), sim_(sim), slots_(slots) {
        if (const std::optional<std::string> why = replica_refusal(*model_))
            throw InputError(model_->description.process.where, "--schemes replicas", *why);
        for (int k = 1; k < replicas; ++k) {
            Random rng(replica_seed(model_->seed, k));
            ShotCavity cavity(*model_, rng);
            shots_.push_back(place_shots(*model_, cavity, rng));
        }
        pilot_ = std::make_unique<ReplicaPilot>(
            first_pilot_s(model_->duration_s, replicas), last_pilot_s(model_->duration_s, replicas),
            plan_windows_then(*model_, replicas,
                              [this](const ReplicaPlan& plan) {
                                  sim_.end_at(plan.windows.front().run_to_s);
                                  dir_ = fs::temp_directory_path() / ("peensim-bench-replicas-" + std::to_string(::getpid()));
                                  runs_ = std::make_unique<ReplicaRuns>(
                                      model_, std::vector<ReplicaWindow>(plan.windows.begin() + 1, plan.windows.end()), std::move(shots_),
                                      dir_.string(), slots_);
                              }),
            [this](const std::string& why) { note_ = why; });
    }
    ~BenchReplicas() {
        if (runs_) runs_->discard();
        std::error_code ignored;
        if (!dir_.empty()) fs::remove_all(dir_, ignored);
    }
    RunListener& pilot() { return *pilot_; }
    const std::string& note() const { return note_; }
    // Waits for the others and hands their windows' impacts to `add`; their results.
    std::vector<ReplicaResult> gather(const std::function<void(const ImpactRecord&)>& add) {
        if (!runs_) return {};
        std::vector<ReplicaResult> results = runs_->wait();
        for (std::size_t k = 0; k < results.size(); ++k)
            runs_->replay(k, [&](std::span<const ImpactRecord> batch) {
                for (const ImpactRecord& r : batch) add(r);
            });
        return results;
    }

private:
    std::shared_ptr<const Model> model_;
    Simulation& sim_;
    const std::vector<int>& slots_;
    std::vector<InitialShots> shots_;
    std::unique_ptr<ReplicaPilot> pilot_;
    std::unique_ptr<ReplicaRuns> runs_;
    fs::path dir_;
    std::string note_;
};

SchemeRun run_scheme(const SceneDescription& scene, const SchemeSpec& spec, std::ostream& err) {
    const std::shared_ptr<const Model> model = compile_model(scene);
    Simulation sim(model);
    const std::size_t n = model->components.size();
    std::vector<int> slot(n, -1);  // index into `logged` of each logged component
    std::vector<BatchedImpactStats> logged;
    for (std::size_t c = 0; c < n; ++c)
        if (model->components[c].logged) {
            slot[c] = static_cast<int>(logged.size());
            logged.emplace_back(model->duration_s);
        }

    // Each logged component's impacts, binned by time batch as they come (none is kept).
    struct Binning final : RunListener {
        const std::vector<int>& slot;
        std::vector<BatchedImpactStats>& logged;
        Binning(const std::vector<int>& s, std::vector<BatchedImpactStats>& l) : slot(s), logged(l) {}
        void add(const ImpactRecord& r) {
            const int s = slot[static_cast<std::size_t>(r.component)];
            if (s >= 0) logged[static_cast<std::size_t>(s)].add(r.time_s, r.vn_in_m_per_s);
        }
        void after_step(const Simulation& sim, const std::vector<ImpactRecord>& impacts) override {
            // As replicas, replica 0's window ends at its end (time stepping's last step may go past it).
            for (const ImpactRecord& r : impacts)
                if (r.time_s < sim.end_s()) add(r);
        }
    } binning(slot, logged);
    RunLoop loop(sim);
    std::unique_ptr<BenchReplicas> replicas;
    if (spec.replicas > 1) {
        replicas = std::make_unique<BenchReplicas>(model, sim, slot, spec.replicas);
        loop.add(replicas->pilot());
    }
    loop.add(binning);
    const auto t0 = Clock::now();
    loop.run();
    const std::vector<ReplicaResult> others =
        replicas ? replicas->gather([&](const ImpactRecord& r) { binning.add(r); }) : std::vector<ReplicaResult>{};
    const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
    if (replicas && !replicas->note().empty())
        err << "note: " << spec.label << ": the run went on as one replica: " << replicas->note() << "\n";

    const SimulationState& st = sim.state();
    SchemeRun run;
    run.spec = spec;
    run.duration_s = model->duration_s;
    run.simulated_s = others.empty() ? st.time.seconds() : others.back().window.window_end_s();
    run.wall_s = wall;
    run.shot_count = model->shot_count;
    run.steps = st.steps;
    run.shot_steps = st.shot_steps;
    run.shot_shot_impacts = st.shot_shot_impacts;
    run.health = st.health;
    run.stats = sim.scheme().stats();
    // The others' work (their warm-ups too) and their windows' impacts (the summary's entries:
    // shot-shot first, then each component).
    std::vector<std::uint64_t> window_impacts(n, 0);
    for (const ReplicaResult& r : others) {
        run.steps += r.summary.steps;
        run.shot_steps += r.summary.shot_steps;
        run.shot_shot_impacts += r.summary.impacts_per_component[0].count - r.impacts_at_window_start[0];
        for (std::size_t c = 0; c < n; ++c)
            window_impacts[c] += r.summary.impacts_per_component[c + 1].count - r.impacts_at_window_start[c + 1];
        r.health.for_each([&](const char* name, std::uint64_t count) {
            run.health.for_each([&](const char* own, std::uint64_t& total) {
                if (std::string_view(own) == name) total += count;
            });
        });
    }
    BatchedImpactStats total(model->duration_s);
    for (std::size_t c = 0; c < n; ++c) {
        ComponentFigures f;
        f.name = model->components[c].name;
        f.logged = slot[c] >= 0;
        f.impacts = (c < st.impacts_per_component.size() ? st.impacts_per_component[c] : 0) + window_impacts[c];
        if (f.logged) {
            f.stats = logged[static_cast<std::size_t>(slot[c])];
            f.impacts = f.stats->count();
            total.merge(*f.stats);
            run.logged_row = c;
        }
        run.components.push_back(std::move(f));
    }
    if (logged.size() > 1) {
        ComponentFigures f;
        f.name = "all logged";
        f.logged = true;
        f.total = true;
        f.impacts = total.count();
        f.stats = total;
        run.logged_row = run.components.size();
        run.components.push_back(std::move(f));
    }
    return run;
}

// The figures of `run` compared with those of `reference` (same scene, same component rows).
struct Comparison {
    double speed_ratio = kNaN;                                // -, wall of the reference / wall of the run
    std::vector<std::optional<BenchDifference>> rate, speed;  // per component row; empty for unlogged rows
    bool within_noise = true;
};

Comparison compare(const SchemeRun& reference, const SchemeRun& run) {
    Comparison c;
    c.speed_ratio = reference.wall_s / run.wall_s;
    for (std::size_t k = 0; k < run.components.size(); ++k) {
        const ComponentFigures& a = reference.components[k];
        const ComponentFigures& b = run.components[k];
        if (!a.stats || !b.stats) {
            c.rate.emplace_back();
            c.speed.emplace_back();
            continue;
        }
        c.rate.push_back(
            bench_difference(a.stats->rate_per_s(), a.stats->rate_se_per_s(), b.stats->rate_per_s(), b.stats->rate_se_per_s()));
        c.speed.push_back(bench_difference(a.stats->mean_speed_m_per_s(), a.stats->mean_speed_se_m_per_s(), b.stats->mean_speed_m_per_s(),
                                           b.stats->mean_speed_se_m_per_s()));
        c.within_noise = c.within_noise && c.rate.back()->within_noise && c.speed.back()->within_noise;
    }
    return c;
}

const char* verdict(bool within_noise) { return within_noise ? "within noise" : "DIFFERS"; }

// ---------------------------------------------------------------------------------------------
// Text

std::string format(const char* fmt, auto... args) {
    char buf[512];
    std::snprintf(buf, sizeof buf, fmt, args...);
    return buf;
}

// "12.3 +- 0.4" with `decimals` digits, or "-" for NaN.
std::string value_se(double v, double se, int decimals) {
    if (!std::isfinite(v)) return "-";
    return std::isfinite(se) ? format("%.*f +- %.*f", decimals, v, decimals, se) : format("%.*f", decimals, v);
}

std::string difference_text(const BenchDifference& d) {
    if (!std::isfinite(d.percent)) return "n/a";
    return format("%+.2f %% (3 SE +-%.2f %%)", d.percent, d.bound_percent);
}

std::string pad(const std::string& s, std::size_t width, bool right = false) {
    if (s.size() >= width) return s;
    return right ? std::string(width - s.size(), ' ') + s : s + std::string(width - s.size(), ' ');
}

void print_scene(const std::string& scene_path, const std::vector<SchemeRun>& runs, std::ostream& out) {
    const SchemeRun& first = runs.front();
    std::string logged_names;
    for (const ComponentFigures& f : first.components)
        if (f.logged && !f.total) logged_names += (logged_names.empty() ? "" : ", ") + f.name;
    out << "== " << scene_path << ": " << format("%g", first.duration_s) << " s simulated, " << first.shot_count
        << " shot, logged: " << (logged_names.empty() ? "none" : logged_names) << "\n";

    std::size_t label_w = 6, component_w = 9;
    for (const SchemeRun& r : runs) label_w = std::max(label_w, r.spec.label.size());
    for (const ComponentFigures& f : first.components) component_w = std::max(component_w, f.name.size());
    out << pad("scheme", label_w) << "  " << pad("wall s", 9, true) << "  " << pad("wall s/sim s", 12, true) << "  "
        << pad("component", component_w) << "  " << pad("impacts/s", 20, true) << "  " << pad("mean vn m/s", 20, true) << "  "
        << pad("shot-shot/s", 12, true) << "  " << pad("serious", 7, true) << "\n";
    for (const SchemeRun& r : runs) {
        for (const ComponentFigures& f : r.components) {
            if (!f.stats) continue;
            out << pad(r.spec.label, label_w) << "  " << pad(format("%.3f", r.wall_s), 9, true) << "  "
                << pad(format("%.4f", r.wall_s / r.simulated_s), 12, true) << "  " << pad(f.name, component_w) << "  "
                << pad(value_se(f.stats->rate_per_s(), f.stats->rate_se_per_s(), 1), 20, true) << "  "
                << pad(value_se(f.stats->mean_speed_m_per_s(), f.stats->mean_speed_se_m_per_s(), 4), 20, true) << "  "
                << pad(format("%.1f", r.per_simulated_s(static_cast<double>(r.shot_shot_impacts))), 12, true) << "  "
                << pad(std::to_string(r.health.serious()), 7, true) << "\n";
        }
    }
    for (const SchemeRun& r : runs) {
        out << "  " << r.spec.label << ": " << r.steps << " steps; stages, % of wall:";
        for (std::size_t k = 0; k < kStageNames.size(); ++k)
            if (r.stats.seconds[k] > 0.0) out << " " << kStageNames[k] << format(" %.0f", 100.0 * r.stats.seconds[k] / r.wall_s);
        out << "\n  " << pad("", r.spec.label.size()) << "  impacts/s on every component:";
        for (const ComponentFigures& f : r.components)
            if (!f.total) out << " " << f.name << format(" %.1f,", r.per_simulated_s(static_cast<double>(f.impacts)));
        out << format(" shot-shot %.1f", r.per_simulated_s(static_cast<double>(r.shot_shot_impacts)));
        if (r.stats.events > 0)
            out << "\n  " << pad("", r.spec.label.size()) << "  work: " << r.stats.events << " events, " << r.stats.rides << " rides, "
                << r.stats.substeps << " sustained substeps, " << r.stats.hand_overs << " hand-overs";
        if (r.stats.soft_steps > 0)
            out << "; soft contacts: " << r.stats.soft_steps << " steps, " << r.stats.soft_member_steps << " shot steps, "
                << r.stats.soft_contact_evaluations << " contact evaluations, " << r.stats.soft_joins << " joins, " << r.stats.soft_rests
                << " left to rest";
        if (r.health.serious() > 0) {
            out << "; health:";
            r.health.for_each([&](const char* name, std::uint64_t v) {
                if (v > 0) out << " " << name << " " << v;
            });
        }
        out << "\n";
    }
    for (std::size_t i = 1; i < runs.size(); ++i) {
        const Comparison c = compare(first, runs[i]);
        out << "  " << runs[i].spec.label << " against " << first.spec.label << ": speed ratio " << format("%.3f", c.speed_ratio)
            << " (wall " << first.spec.label << " / wall " << runs[i].spec.label << ")\n";
        for (std::size_t k = 0; k < runs[i].components.size(); ++k) {
            if (!c.rate[k]) continue;
            const std::string& name = runs[i].components[k].name;
            out << "    " << pad(name, component_w) << "  impacts/s    " << pad(difference_text(*c.rate[k]), 30) << "  "
                << verdict(c.rate[k]->within_noise) << "\n";
            out << "    " << pad(name, component_w) << "  mean vn      " << pad(difference_text(*c.speed[k]), 30) << "  "
                << verdict(c.speed[k]->within_noise) << "\n";
        }
    }
}

std::string summary_line(const std::string& scene_path, const std::vector<SchemeRun>& runs) {
    std::string line = scene_path + ":";
    for (std::size_t i = 1; i < runs.size(); ++i) {
        const Comparison c = compare(runs.front(), runs[i]);
        const std::size_t row = runs[i].logged_row;
        line += (i > 1 ? ";" : "") + std::string(" ") + runs[i].spec.label + " vs " + runs.front().spec.label +
                format(" speed ratio %.3f", c.speed_ratio);
        if (c.rate.size() > row && c.rate[row]) {
            const std::string& name = runs[i].components[row].name;
            line += ", " + name + " impacts/s " + difference_text(*c.rate[row]) + ", mean vn " + difference_text(*c.speed[row]);
        }
        line += std::string(": ") + verdict(c.within_noise);
    }
    return line;
}

// ---------------------------------------------------------------------------------------------
// CSV

std::string csv_number(double v) {
    if (!std::isfinite(v)) return "";
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

std::string csv_text(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
}

std::string csv_header() {
    std::string h =
        "scene,scheme_label,scheme,compared_with,component,logged,duration_s,simulated_s,wall_s,"
        "wall_s_per_simulated_s,steps,shot_steps,impacts,impact_rate_per_s,impact_rate_se_per_s,"
        "mean_normal_speed_m_per_s,mean_normal_speed_se_m_per_s,shot_shot_impacts_per_s,serious_health";
    HealthCounters{}.for_each([&](const char* name, std::uint64_t) { h += std::string(",health_") + name; });
    for (std::string_view stage : kStageNames) h += ",stage_" + std::string(stage) + "_s";
    h += ",speed_ratio,impact_rate_difference_percent,impact_rate_bound_percent,mean_normal_speed_difference_percent,"
         "mean_normal_speed_bound_percent,verdict\n";
    return h;
}

void csv_rows(const std::string& scene_path, const std::vector<SchemeRun>& runs, std::string& csv) {
    for (std::size_t i = 0; i < runs.size(); ++i) {
        const SchemeRun& r = runs[i];
        const std::optional<Comparison> c = i > 0 ? std::optional<Comparison>(compare(runs.front(), r)) : std::nullopt;
        for (std::size_t k = 0; k < r.components.size(); ++k) {
            const ComponentFigures& f = r.components[k];
            std::string row = csv_text(scene_path) + "," + csv_text(r.spec.label) + "," + r.spec.name + "," +
                              (c ? csv_text(runs.front().spec.label) : "") + "," + csv_text(f.name) + "," + (f.logged ? "1" : "0");
            for (double v : {r.duration_s, r.simulated_s, r.wall_s, r.wall_s / r.simulated_s}) row += "," + csv_number(v);
            row += "," + std::to_string(r.steps) + "," + std::to_string(r.shot_steps) + "," + std::to_string(f.impacts);
            row += "," + csv_number(r.per_simulated_s(static_cast<double>(f.impacts)));
            for (double v :
                 {f.stats ? f.stats->rate_se_per_s() : kNaN, f.stats ? f.stats->mean_speed_m_per_s() : kNaN,
                  f.stats ? f.stats->mean_speed_se_m_per_s() : kNaN, r.per_simulated_s(static_cast<double>(r.shot_shot_impacts))})
                row += "," + csv_number(v);
            row += "," + std::to_string(r.health.serious());
            r.health.for_each([&](const char*, std::uint64_t v) { row += "," + std::to_string(v); });
            for (double s : r.stats.seconds) row += "," + csv_number(s);
            if (c && c->rate[k]) {
                row += "," + csv_number(c->speed_ratio);
                for (double v : {c->rate[k]->percent, c->rate[k]->bound_percent, c->speed[k]->percent, c->speed[k]->bound_percent})
                    row += "," + csv_number(v);
                row += std::string(",") + verdict(c->rate[k]->within_noise && c->speed[k]->within_noise);
            } else {
                row += c ? "," + csv_number(c->speed_ratio) + ",,,,," : ",,,,,,";
            }
            csv += row + "\n";
        }
    }
}

std::string own_executable() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string() : exe.string();
}

int bench(const BenchOptions& options, std::ostream& out, std::ostream& err) {
    if (!options.csv_path.empty()) check_output_file_directory("--csv", options.csv_path);  // before minutes of runs
    const std::vector<SchemeSpec> schemes = parse_schemes(options.schemes);
    const std::vector<std::string> scenes =
        options.scene_paths.empty() ? shipped_scenes(options.executable_path.empty() ? own_executable() : options.executable_path)
                                    : options.scene_paths;

    // Every scene is read (with every scheme's overrides) before the first run, so a typo in the
    // last scene fails in a second, not after minutes of simulation.
    std::vector<std::vector<SceneDescription>> descriptions;
    for (const std::string& path : scenes) {
        std::vector<SceneDescription> per_scheme;
        for (const SchemeSpec& s : schemes) {
            std::vector<std::string> overrides = options.overrides;
            if (!options.duration.empty()) overrides.push_back("process.duration=" + options.duration);
            overrides.insert(overrides.end(), s.overrides.begin(), s.overrides.end());
            overrides.push_back("accuracy.scheme=" + s.name);
            per_scheme.push_back(parse_scene_file(path, overrides));
        }
        descriptions.push_back(std::move(per_scheme));
    }

    out << "# peensim bench: " << scenes.size() << " scene(s), schemes";
    for (const SchemeSpec& s : schemes) out << " " << s.label;
    out << "; process.duration " << (options.duration.empty() ? "from each scene" : options.duration)
        << "; +- is one standard error by batch means over " << kBenchBatches << " time batches\n";
    std::vector<std::string> summary;
    std::string csv = csv_header();
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        std::vector<SchemeRun> runs;
        for (std::size_t s = 0; s < schemes.size(); ++s) runs.push_back(run_scheme(descriptions[i][s], schemes[s], err));
        print_scene(scenes[i], runs, out);
        out.flush();
        summary.push_back(summary_line(scenes[i], runs));
        csv_rows(scenes[i], runs, csv);
    }
    out << "# summary (speed ratio = wall of " << schemes.front().label
        << " / wall of the other; differences of the other from it, with 3 combined standard errors)\n";
    for (const std::string& line : summary) out << line << "\n";
    if (!options.csv_path.empty()) {
        write_file_atomically(options.csv_path, csv);
        out << "# written: " << options.csv_path << "\n";
    }
    return kExitOk;
}

}  // namespace

int bench_job(const BenchOptions& options, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] { return bench(options, out, err); });
}

}  // namespace peensim
