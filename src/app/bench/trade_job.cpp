#include "app/bench/trade_job.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>

#include "analysis/part_coverage.h"
#include "analysis/sample_mean.h"
#include "app/analysis/analysis_plots.h"
#include "app/report_errors.h"
#include "common/float_limits.h"
#include "common/input_error.h"
#include "common/units.h"
#include "contact/dent.h"
#include "engine/run_loop.h"
#include "engine/simulation.h"
#include "model/model.h"
#include "output/atomic_file.h"
#include "output/output_names.h"
#include "scene/scene_parser.h"
#include "scene/shot_mix.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kBatches = 10;        // time batches of the measured window (batch-means standard errors)
constexpr double kSpeedBin = 1e-3;  // m/s, bin of the normal-speed histograms (percentiles)
constexpr int kSpeedBins = 200000;  // up to 200 m/s (faster: the last bin)

struct Knob {
    std::string label;
    std::string scheme;  // step | event | soft
    std::vector<std::string> overrides;
    bool reference = false;
};

std::string knob_number(double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

// Every knob: the reference first (soft, finest), the soft scheme's resolution and stiffness, the
// rigid schemes. Stiffness is every material's youngs_modulus scaled.
std::vector<Knob> knobs_of(const SceneDescription& scene, double reference_steps) {
    const auto soft = [](double steps) {
        return std::vector<std::string>{"accuracy.scheme=soft", "accuracy.soft_steps_per_contact=" + knob_number(steps)};
    };
    std::vector<Knob> k;
    k.push_back({"soft, " + knob_number(reference_steps) + " steps/contact (reference)", "soft", soft(reference_steps), true});
    for (const double steps : {40.0, 20.0, 10.0})
        if (steps < reference_steps) k.push_back({"soft, " + knob_number(steps) + " steps/contact", "soft", soft(steps)});
    for (const double factor : {0.1, 0.01}) {
        Knob s{"soft, 20 steps, E x " + knob_number(factor), "soft", soft(20.0)};
        for (const MaterialDesc& m : scene.materials)
            if (m.youngs_modulus_pa)
                s.overrides.push_back("materials." + m.name + ".youngs_modulus=" + knob_number(*m.youngs_modulus_pa * factor) + " Pa");
        k.push_back(s);
    }
    k.push_back({"rigid, event-driven", "event", {"accuracy.scheme=event"}});
    for (const double travel : {0.25, 0.1, 0.05})
        k.push_back({"rigid, time step R x " + knob_number(travel),
                     "step",
                     {"accuracy.scheme=step", "accuracy.travel_fraction=" + knob_number(travel)}});
    return k;
}

// One figure with its standard error and its error against the reference.
struct Figure {
    double value = kNaN, se = kNaN;
    double error_percent = kNaN, error_se = kNaN;  // against the reference: %, and in combined standard errors
};

void compare_figure(Figure& f, const Figure& ref) {
    if (!(ref.value != 0.0) || std::isnan(f.value) || std::isnan(ref.value)) return;
    f.error_percent = 100.0 * (f.value - ref.value) / ref.value;
    const double se = std::sqrt(std::pow(std::isnan(f.se) ? 0.0 : f.se, 2) + std::pow(std::isnan(ref.se) ? 0.0 : ref.se, 2));
    if (se > 0.0) f.error_se = (f.value - ref.value) / se;
}

// Standard error of the mean of the batches' values (those that have one: a batch without impacts
// has no mean speed); NaN with fewer than two.
double mean_se(const std::array<double, kBatches>& x) { return sample_mean(x).standard_error; }

// The logged part's impacts of one run, binned as they come (nothing kept): counts, speeds and dent
// areas per time batch of the measured window, speed histograms, and the coverage map (every impact).
class PartFigures final : public RunListener {
public:
    PartFigures(int part, double settle_s, double end_s, std::unique_ptr<CoverageMap> coverage, double shot_density_kg_per_m3,
                double yield_stress_pa)
        : part_(part),
          settle_(settle_s),
          end_(end_s),
          coverage_(std::move(coverage)),
          rho_(shot_density_kg_per_m3),
          sigma_(yield_stress_pa),
          histograms_(kBatches, std::vector<std::uint32_t>(kSpeedBins, 0)) {}

    void after_step(const Simulation&, const std::vector<ImpactRecord>& impacts) override {
        for (const ImpactRecord& r : impacts) {
            if (r.component != part_) continue;
            // Each impact's own shot (a mix's sizes dent differently).
            const double dent = coverage_ ? dent_diameter(r.shot_diameter_m, rho_, r.vn_in_m_per_s, sigma_) : 0.0;
            if (coverage_) coverage_->add_dent(r.point_m, dent);
            if (r.time_s < settle_) continue;
            const int b = std::clamp(static_cast<int>((r.time_s - settle_) / (end_ - settle_) * kBatches), 0, kBatches - 1);
            counts_[static_cast<std::size_t>(b)] += 1.0;
            speeds_[static_cast<std::size_t>(b)] += r.vn_in_m_per_s;
            dent_areas_[static_cast<std::size_t>(b)] += M_PI * dent * dent / 4.0;
            ++histograms_[static_cast<std::size_t>(b)]
                         [static_cast<std::size_t>(std::clamp(static_cast<int>(r.vn_in_m_per_s / kSpeedBin), 0, kSpeedBins - 1))];
        }
    }

    Figure rate() const {
        std::array<double, kBatches> r{};
        const double batch = (end_ - settle_) / kBatches;
        double total = 0.0;
        for (int b = 0; b < kBatches; ++b)
            r[static_cast<std::size_t>(b)] = counts_[static_cast<std::size_t>(b)] / batch, total += counts_[static_cast<std::size_t>(b)];
        return {total / (end_ - settle_), mean_se(r)};
    }
    Figure mean_speed() const {
        std::array<double, kBatches> m{};
        double n = 0.0, sum = 0.0;
        for (int b = 0; b < kBatches; ++b) {
            const auto k = static_cast<std::size_t>(b);
            m[k] = counts_[k] > 0.0 ? speeds_[k] / counts_[k] : kNaN;
            n += counts_[k], sum += speeds_[k];
        }
        return {n > 0.0 ? sum / n : kNaN, mean_se(m)};
    }
    Figure p90() const {
        std::vector<std::uint32_t> all(kSpeedBins, 0);
        std::array<double, kBatches> each{};
        for (int b = 0; b < kBatches; ++b) {
            each[static_cast<std::size_t>(b)] = quantile(histograms_[static_cast<std::size_t>(b)], 0.9);
            for (int k = 0; k < kSpeedBins; ++k)
                all[static_cast<std::size_t>(k)] += histograms_[static_cast<std::size_t>(b)][static_cast<std::size_t>(k)];
        }
        return {quantile(all, 0.9), mean_se(each)};
    }
    // Coverage after the run (%), its error from the batches' spread of the dent area they add: the
    // dent area ratio A = -ln(1 - C) scales with it, and C = 1 - exp(-A).
    Figure coverage() const {
        if (!coverage_) return {};
        const double c = coverage_->coverage();
        double sum = 0.0;
        for (double a : dent_areas_) sum += a;
        const double relative = sum > 0.0 ? mean_se(dent_areas_) / (sum / kBatches) : kNaN;
        const double area_ratio = -std::log(std::max(1e-300, 1.0 - c));
        return {100.0 * c, 100.0 * (1.0 - c) * area_ratio * relative};
    }

private:
    static double quantile(const std::vector<std::uint32_t>& h, double q) {
        std::uint64_t n = 0;
        for (std::uint32_t v : h) n += v;
        if (n == 0) return kNaN;
        const double target = q * static_cast<double>(n);
        std::uint64_t below = 0;
        for (std::size_t k = 0; k < h.size(); ++k) {
            if (static_cast<double>(below + h[k]) >= target) {
                // Linear within the bin.
                const double f = h[k] > 0 ? (target - static_cast<double>(below)) / h[k] : 0.0;
                return (static_cast<double>(k) + f) * kSpeedBin;
            }
            below += h[k];
        }
        return static_cast<double>(h.size()) * kSpeedBin;
    }

    int part_;
    double settle_, end_;  // s
    std::unique_ptr<CoverageMap> coverage_;
    double rho_, sigma_;
    std::array<double, kBatches> counts_{}, speeds_{}, dent_areas_{};
    std::vector<std::vector<std::uint32_t>> histograms_;
};

struct KnobResult {
    Knob knob;
    double wall_s = 0.0;  // s, the stepping loop
    Figure rate, mean, p90, coverage;
    std::uint64_t serious = 0;
};

// The logged part whose figures are traded: the first logged part (or Almen strip), else the first logged component.
int traded_component(const Model& m) {
    int any = -1;
    for (std::size_t c = 0; c < m.components.size(); ++c) {
        if (!m.components[c].logged) continue;
        if (m.components[c].role == ComponentRole::part || m.components[c].role == ComponentRole::almen) return static_cast<int>(c);
        if (any < 0) any = static_cast<int>(c);
    }
    return any;
}

KnobResult run_once(const TradeOptions& o, const Knob& knob, double settle_s, int seed_offset) {
    std::vector<std::string> overrides = o.overrides;
    if (!o.duration.empty()) overrides.push_back("process.duration=" + o.duration);
    overrides.insert(overrides.end(), knob.overrides.begin(), knob.overrides.end());
    if (seed_offset > 0) {
        const SceneDescription first = parse_scene_file(o.scene_path, overrides);
        overrides.push_back("process.seed=" + std::to_string(first.process.seed + static_cast<std::uint64_t>(seed_offset)));
    }
    const SceneDescription scene = parse_scene_file(o.scene_path, overrides);
    const std::shared_ptr<const Model> model = compile_model(scene);
    const int part = traded_component(*model);
    if (part < 0) throw InputError({o.scene_path, 0, 0}, "output.log", "expected a logged component to trade the figures of, found none");
    const Component& comp = model->components[static_cast<std::size_t>(part)];
    std::optional<double> sigma;
    for (const MaterialDesc& mat : scene.materials)
        if (mat.name == comp.material) sigma = mat.yield_stress_pa;
    PartFigures figures(part, settle_s, model->duration_s,
                        sigma ? part_coverage_map(*comp.mesh, smallest_diameter_m(scene.shot), largest_diameter_m(scene.shot),
                                                  scene.shot.density_kg_per_m3, *sigma)
                              : nullptr,
                        scene.shot.density_kg_per_m3, sigma.value_or(1.0));
    Simulation sim(model);
    RunLoop loop(sim);
    loop.add(figures);
    const auto t0 = Clock::now();
    loop.run();
    KnobResult r;
    r.knob = knob;
    r.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
    r.rate = figures.rate();
    r.mean = figures.mean_speed();
    r.p90 = figures.p90();
    r.coverage = figures.coverage();
    r.serious = sim.state().health.serious();
    return r;
}

// A knob over o.seeds runs: each figure the mean of the runs' (its standard error combined), the
// wall time the mean of a run's.
KnobResult run_knob(const TradeOptions& o, const Knob& knob, double settle_s) {
    std::vector<KnobResult> runs;
    for (int k = 0; k < o.seeds; ++k) runs.push_back(run_once(o, knob, settle_s, k));
    if (runs.size() == 1) return runs.front();
    KnobResult r;
    r.knob = knob;
    const auto n = static_cast<double>(runs.size());
    const auto average = [&](Figure KnobResult::*f) {
        Figure out{0.0, 0.0};
        for (const KnobResult& x : runs) out.value += (x.*f).value / n, out.se += (x.*f).se * (x.*f).se;
        out.se = std::sqrt(out.se) / n;
        return out;
    };
    r.rate = average(&KnobResult::rate);
    r.mean = average(&KnobResult::mean);
    r.p90 = average(&KnobResult::p90);
    r.coverage = average(&KnobResult::coverage);
    for (const KnobResult& x : runs) r.wall_s += x.wall_s / n, r.serious += x.serious;
    return r;
}

std::string table_cell(const Figure& f, int digits, bool reference) {
    char b[96];
    if (std::isnan(f.value)) return "-";
    if (reference || std::isnan(f.error_percent))
        std::snprintf(b, sizeof b, "%.*f +- %.*f", digits, f.value, digits, f.se);
    else
        std::snprintf(b, sizeof b, "%.*f +- %.*f %+.1f%% (%+.1f SE)", digits, f.value, digits, f.se, f.error_percent, f.error_se);
    return b;
}

std::string padded_cell(const std::string& s, std::size_t w) { return s.size() >= w ? s + " " : s + std::string(w - s.size(), ' '); }

void write_csv(const std::string& path, const std::vector<KnobResult>& results) {
    std::ostringstream c;
    c << "knob,scheme,wall_s";
    for (const char* f : {"rate_per_s", "mean_vn_mps", "p90_vn_mps", "coverage_pct"})
        c << "," << f << "," << f << "_se," << f << "_error_pct," << f << "_error_se";
    c << ",serious\n";
    for (const KnobResult& r : results) {
        c << "\"" << r.knob.label << "\"," << r.knob.scheme << "," << r.wall_s;
        for (const Figure* f : {&r.rate, &r.mean, &r.p90, &r.coverage})
            c << "," << f->value << "," << f->se << "," << f->error_percent << "," << f->error_se;
        c << "," << r.serious << "\n";
    }
    write_file_atomically(path, c.str());
}

// Error against wall time, one point per knob and figure, log-log.
std::string plot(const std::string& png_path, const std::vector<KnobResult>& results, const std::string& title) {
    const fs::path png(png_path);
    const std::string dir = png.has_parent_path() ? png.parent_path().string() : ".";
    const std::string stem = png.stem().string();
    std::ostringstream data;
    data << "# wall_s, |error| % of: impact rate, mean vn, p90 vn, coverage; knob\n";
    for (const KnobResult& r : results) {
        if (r.knob.reference) continue;
        data << r.wall_s;
        for (const Figure* f : {&r.rate, &r.mean, &r.p90, &r.coverage})
            data << "," << (std::isnan(f->error_percent) ? std::string("NaN") : knob_number(std::max(0.01, std::abs(f->error_percent))));
        data << ",\"" << r.knob.label << "\"\n";
    }
    write_file_atomically((fs::path(dir) / (stem + ".csv")).string(), data.str());
    double ref_wall = 0.0, noise = 1.0;
    for (const KnobResult& r : results)
        if (r.knob.reference) ref_wall = r.wall_s, noise = std::max(0.01, 300.0 * r.rate.se / r.rate.value);
    std::ostringstream s;
    s << "# Written by peensim trade; rerun from this directory: gnuplot " << stem << ".gp\n"
      << "if (!exists(\"out\")) out = " << gnuplot_string(stem + ".png") << "\n"
      << "set terminal pngcairo enhanced size 1000,700 font 'sans,10'\n"
      << "set output out\nset datafile separator ','\nset grid\nset logscale xy\n"
      << "set title " << gnuplot_string(gnuplot_text(title)) << "\n"
      << "set xlabel 'wall time of the run (s)'\nset ylabel '|error| against the reference (%)'\n"
      << "set key outside right\n"
      << "set arrow from " << ref_wall << ", graph 0 to " << ref_wall << ", graph 1 nohead dt 2\n"
      << "set arrow from graph 0, first " << noise << " to graph 1, first " << noise << " nohead dt 3 lc 'gray'\n"
      << "set label 'noise: 3 SE of the reference rate' at graph 0.02, first " << noise << " offset 0,0.7 textcolor 'gray40'\n"
      << "set label 'reference' at " << ref_wall << ", graph 0.97 right offset -0.5,0\n"
      << "file = " << gnuplot_string(stem + ".csv") << "\n"
      << "plot file using 1:2 with points pt 7 ps 1.3 title 'impact rate', \\\n"
      << "     file using 1:3 with points pt 5 ps 1.2 title 'mean v_n', \\\n"
      << "     file using 1:4 with points pt 9 ps 1.3 title 'p90 v_n', \\\n"
      << "     file using 1:5 with points pt 13 ps 1.3 title 'coverage', \\\n"
      << "     file using 1:2:6 with labels left offset 1,0 font 'sans,8' notitle\n";
    return plot_with_gnuplot(dir, stem, s.str());
}

// The options that need no scene, checked before it is read: a bad one is refused at once.
void check_options(const TradeOptions& o) {
    if (!(o.reference_steps >= 20.0 && o.reference_steps <= 10000.0))  // CLI11's range lets nan through
        throw InputError(kCommandLine, "--reference-steps", "expected a number from 20 to 10000, got " + knob_number(o.reference_steps));
    if (!(o.seeds >= 1 && o.seeds <= 1000))
        throw InputError(kCommandLine, "--seeds", "expected a count from 1 to 1000, got " + std::to_string(o.seeds));
    if (!o.csv_path.empty()) check_output_file_directory("--csv", o.csv_path);
    if (!o.plot_path.empty()) check_output_file_directory("--plot", o.plot_path);
}

// --settle in s: a time >= 0 (nan and inf are not times), or a tenth of the run when not given.
double settle_time(const TradeOptions& o, double duration_s) {
    if (o.settle.empty()) return 0.1 * duration_s;
    double s = 0.0;
    try {
        s = parse_quantity(o.settle, Dimension::time);
    } catch (const QuantityError& e) {
        throw InputError(kCommandLine, "--settle", e.what());  // it quotes the text
    }
    if (!(s >= 0.0)) throw InputError(kCommandLine, "--settle", "expected a time >= 0, got '" + o.settle + "'");
    return s;
}

}  // namespace

int trade_job(const TradeOptions& o, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] {
        check_options(o);
        std::vector<std::string> overrides = o.overrides;
        if (!o.duration.empty()) overrides.push_back("process.duration=" + o.duration);
        // Every knob's scene is read (and the soft one compiled) before the first run: a scene the
        // soft scheme cannot run is refused at once, with the law it lacks.
        const SceneDescription base = parse_scene_file(o.scene_path, overrides);
        {
            std::vector<std::string> soft = overrides;
            soft.push_back("accuracy.scheme=soft");
            (void)compile_model(parse_scene_file(o.scene_path, soft));
        }
        const double duration = base.process.duration_s;
        const double settle = settle_time(o, duration);
        if (!(settle < duration))
            throw InputError(kCommandLine, "--settle",
                             "expected less than the run's duration (" + knob_number(duration) + " s), got " + knob_number(settle) + " s");
        const std::vector<Knob> knobs = knobs_of(base, o.reference_steps);
        out << "== " << o.scene_path << ": " << knob_number(duration) << " s simulated"
            << (o.seeds > 1 ? " x " + std::to_string(o.seeds) + " seeds" : "") << "; rates and speeds from " << knob_number(settle)
            << " s on (10 batches: +- one standard error), coverage after the run; the reference: " << knobs.front().label << "\n";
        std::vector<KnobResult> results;
        for (const Knob& k : knobs) {
            err << "trade: " << k.label << " ..." << std::flush;
            results.push_back(run_knob(o, k, settle));
            err << " " << results.back().wall_s << " s\n";
        }
        const KnobResult& ref = results.front();
        for (KnobResult& r : results) {
            if (r.knob.reference) continue;
            compare_figure(r.rate, ref.rate);
            compare_figure(r.mean, ref.mean);
            compare_figure(r.p90, ref.p90);
            compare_figure(r.coverage, ref.coverage);
        }
        out << padded_cell("knob", 34) << padded_cell("wall s", 9) << padded_cell("impacts/s", 36) << padded_cell("mean vn m/s", 36)
            << padded_cell("p90 vn m/s", 36) << "coverage %\n";
        for (const KnobResult& r : results) {
            char wall[32];
            std::snprintf(wall, sizeof wall, "%.2f", r.wall_s);
            out << padded_cell(r.knob.label, 34) << padded_cell(wall, 9) << padded_cell(table_cell(r.rate, 0, r.knob.reference), 36)
                << padded_cell(table_cell(r.mean, 3, r.knob.reference), 36) << padded_cell(table_cell(r.p90, 3, r.knob.reference), 36)
                << table_cell(r.coverage, 2, r.knob.reference)
                << (r.serious ? " (" + std::to_string(r.serious) + " serious health counts)" : std::string()) << "\n";
        }
        for (const KnobResult& r : results) {
            if (r.knob.label != "rigid, event-driven") continue;
            out << "the rigid, instantaneous impact against the soft reference: impact rate " << table_cell(r.rate, 0, false)
                << ", mean vn " << table_cell(r.mean, 3, false) << ", in "
                << knob_number(std::round(r.wall_s / ref.wall_s * 1000.0) / 1000.0) << "x the reference's wall time\n";
        }
        if (!o.csv_path.empty()) write_csv(o.csv_path, results);
        if (!o.plot_path.empty()) {
            const std::string note =
                plot(o.plot_path, results, fs::path(o.scene_path).filename().string() + ": error against wall time per accuracy knob");
            if (!note.empty()) err << "trade: no picture: " << note << "\n";
        }
        return kExitOk;
    });
}

}  // namespace peensim
