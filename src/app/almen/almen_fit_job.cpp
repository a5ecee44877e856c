#include "app/almen/almen_fit_job.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "analysis/almen_model.h"
#include "analysis/measured_curve.h"
#include "analysis/saturation_fit.h"
#include "app/analysis/almen_analysis.h"
#include "app/analysis/analysis_format.h"
#include "app/analysis/analysis_plots.h"
#include "app/report_errors.h"
#include "common/input_error.h"
#include "common/units.h"
#include "output/atomic_file.h"
#include "output/json_number.h"
#include "output/output_names.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

constexpr int kJ443MinimumExposures = 4;  // SAE J443: a saturation curve of at least four strips

// Shortest text that reads back as the same double (the calibration's round trip is exact).
std::string exact(double v) {
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), v);
    return ec == std::errc() ? std::string(buffer, end) : fmt(v, 17);
}

std::string with_se(double v, double se, const std::string& unit) {
    std::string s = fmt(v) + " " + unit;
    if (std::isfinite(se)) s += " (+- " + fmt(se, 2) + " " + unit + ", 1 s.e.)";
    return s;
}

// The strip in a run's figures.json: its dent size and covering rate.
struct RunStrip {
    std::string name;
    AlmenExposure exposure;
};

RunStrip strip_of_run(const std::string& run_dir, const std::string& component) {
    const fs::path figures = fs::path(run_dir) / "analysis" / "figures.json";
    std::ifstream in(figures);
    if (!in) {
        const bool is_run = fs::exists(fs::path(run_dir) / "scene.resolved.yaml");
        throw InputError(kCommandLine, "--calibrate",
                         is_run ? run_dir + " has no analysis/figures.json: run `peensim analyze " + run_dir + "` first"
                                : run_dir + " is not a peensim run directory (no scene.resolved.yaml)");
    }
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
        throw InputError({figures.string(), 0, 0}, "", std::string("not readable as JSON: ") + e.what());
    }
    std::vector<const nlohmann::json*> strips;
    std::string names;
    if (j.contains("components") && j["components"].is_array())
        for (const auto& c : j["components"])
            if (c.contains("almen_dose_J_per_m2")) {
                strips.push_back(&c);
                names += (names.empty() ? "" : ", ") + c.value("component", "");
            }
    if (strips.empty())
        throw InputError(kCommandLine, "--calibrate", "the run " + run_dir + " has no Almen strip (a component with role almen)");
    const nlohmann::json* chosen = nullptr;
    if (component.empty()) {
        if (strips.size() > 1) throw InputError(kCommandLine, "--component", "the run has several Almen strips (" + names + "): name one");
        chosen = strips.front();
    } else {
        for (const nlohmann::json* c : strips)
            if (c->value("component", "") == component) chosen = c;
        if (!chosen)
            throw InputError(kCommandLine, "--component", "the run has no Almen strip '" + component + "'; expected one of " + names);
    }
    RunStrip s;
    s.name = chosen->value("component", "");
    const auto figure = [&](const char* key) {
        return chosen->contains(key) && (*chosen)[key].is_number() ? (*chosen)[key].get<double>() : 0.0;
    };
    s.exposure.dent_size_m = figure("almen_dent_size_m");
    s.exposure.covering_rate_per_s = figure("almen_covering_rate_per_s");
    if (!s.exposure.valid())
        throw InputError(kCommandLine, "--calibrate",
                         "the run's strip '" + s.name + "' has no dent figures (almen_dent_size_m, almen_covering_rate_per_s in " +
                             figures.string() +
                             "): give the strip material a yield_stress in the scene, run it again, then calibrate on that run");
    return s;
}

nlohmann::ordered_json fit_json(const SaturationFit& f, const MeasuredCurve& m, const std::string& strip) {
    nlohmann::ordered_json o;
    o["form"] = saturation_form_name(f.form);
    o["fitted"] = f.fitted;
    o["problem"] = f.problem.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(f.problem);
    if (!f.fitted) return o;
    const bool time = m.exposure_unit.is_time();
    o["a_m"] = f.curve.a;
    o["b"] = f.curve.b;
    o["b_unit"] = "1/" + m.exposure_unit.name + (f.curve.c == 1.0 ? "" : "^c");
    o["c"] = f.curve.c;
    o["rms_residual_m"] = f.rms_residual;
    o["residual_sd_m"] = json_number(f.residual_sd);
    o["saturation_point"] = f.point.exists;
    o["saturation_time"] = json_number(f.point.exists ? f.point.time : NAN);
    o["saturation_time_se"] = json_number(f.time_standard_error);
    o["saturation_time_s"] = json_number(f.point.exists && time ? f.point.time * m.exposure_unit.seconds : NAN);
    o["intensity_m"] = json_number(f.point.exists ? f.point.intensity : NAN);
    o["intensity_se_m"] = json_number(f.intensity_standard_error);
    o["intensity_in"] = json_number(f.point.exists ? f.point.intensity / kMetresPerInch : NAN);
    o["intensity_thou"] = json_number(f.point.exists ? f.point.intensity / kMetresPerInch * 1e3 : NAN);
    o["intensity_label"] = f.point.exists && !strip.empty() ? nlohmann::ordered_json(almen_intensity_label(f.point.intensity, strip))
                                                            : nlohmann::ordered_json(nullptr);
    return o;
}

void print_fit(std::ostream& out, const SaturationFit& f, const MeasuredCurve& m, const std::string& strip) {
    const std::string u = m.exposure_unit.name;
    out << saturation_form_name(f.form) << "  "
        << (f.form == SaturationForm::two_parameter ? "h = a (1 - exp(-b t))" : "h = a (1 - exp(-b t^c))") << "\n";
    if (!f.fitted) {
        out << "    not fitted: " << f.problem << "\n";
        return;
    }
    out << "    a = " << fmt(f.curve.a * 1e3) << " mm, b = " << fmt(f.curve.b) << " /" << u
        << (f.form == SaturationForm::three_parameter ? "^c" : "");
    if (f.form == SaturationForm::three_parameter) out << ", c = " << fmt(f.curve.c);
    out << "; RMS residual " << fmt(f.rms_residual * 1e3, 3) << " mm (" << fmt(f.rms_residual / kMetresPerInch * 1e3, 3) << " thou)\n";
    if (!f.point.exists) {
        out << "    no saturation point: " << f.problem << "\n";
        return;
    }
    out << "    saturation time T = " << with_se(f.point.time, f.time_standard_error, u) << "\n"
        << "    intensity h(T) = " << almen_intensity_text(f.point.intensity, strip);
    if (std::isfinite(f.intensity_standard_error)) out << " (+- " << fmt(f.intensity_standard_error * 1e3, 2) << " mm, 1 s.e.)";
    out << "\n";
}

// J443's conditions on the data around the chosen fit's saturation point.
std::vector<std::string> j443_warnings(const MeasuredCurve& m, const SaturationFit& f) {
    std::vector<std::string> w;
    const std::string u = m.exposure_unit.name;
    const int n = m.distinct_exposures();
    if (n < kJ443MinimumExposures)
        w.push_back("only " + std::to_string(n) +
                    " distinct exposures: SAE J443 asks for a saturation curve of at least four strips at different exposures");
    if (!f.point.exists) return w;
    double shortest = 0.0, longest = 0.0;
    for (const SaturationDatum& p : m.points) {
        if (p.exposure > 0.0 && (shortest == 0.0 || p.exposure < shortest)) shortest = p.exposure;
        longest = std::max(longest, p.exposure);
    }
    const double T = f.point.time;
    if (T < shortest || T > longest)
        w.push_back("the saturation time T = " + fmt(T) + " " + u + " lies outside the measured exposures (" + fmt(shortest) + " to " +
                    fmt(longest) + " " + u + "): the intensity is extrapolated, not bracketed by strips");
    if (longest < 2.0 * T)
        w.push_back("no strip was peened for 2T = " + fmt(2.0 * T) + " " + u + " or longer (the longest: " + fmt(longest) + " " + u +
                    "): J443's 10 % rise on doubling is then extrapolated; the standard asks for a strip at or beyond 2T");
    return w;
}

// The files --plot writes beside its PNG: the script and the points (named so that a curve called
// like the PNG is not the points file).
struct PlotFiles {
    std::string dir, stem;
    std::vector<fs::path> written() const {
        return {fs::path(dir) / (stem + ".png"), fs::path(dir) / (stem + ".gp"), fs::path(dir) / (stem + "_points.csv")};
    }
};

PlotFiles plot_files(const std::string& png) {
    const fs::path path(png);
    PlotFiles f{path.parent_path().empty() ? "." : path.parent_path().string(), path.filename().string()};
    if (f.stem.size() > 4 && f.stem.substr(f.stem.size() - 4) == ".png") f.stem.resize(f.stem.size() - 4);
    return f;
}

// The outputs go into directories that exist (peensim creates none: the other commands' --plot,
// --csv, --json do not either), and none may be the curve being read: refused (exit 2) before
// anything is read or written.
void check_output_paths(const AlmenFitOptions& o) {
    if (!o.json_path.empty()) check_output_file_directory("--json", o.json_path);
    if (!o.plot_path.empty()) check_output_file_directory("--plot", o.plot_path);
    std::error_code ec;
    const auto same = [&](const fs::path& a) { return fs::exists(a, ec) && fs::equivalent(a, o.curve_path, ec); };
    if (!o.json_path.empty() && same(o.json_path))
        throw InputError(kCommandLine, "--json", "'" + o.json_path + "' is the curve being read; give the JSON another name");
    if (!o.plot_path.empty())
        for (const fs::path& p : plot_files(o.plot_path).written())
            if (same(p))
                throw InputError(kCommandLine, "--plot",
                                 "'" + o.plot_path + "' would write " + p.string() + ", the curve being read; give the plot another name");
}

// The lines (file, 1-based) of the rows at `exposure`, as "lines 4, 7" (at most five named).
std::string lines_at(const MeasuredCurve& m, double exposure) {
    std::vector<int> lines;
    for (std::size_t i = 0; i < m.points.size(); ++i)
        if (m.points[i].exposure == exposure) lines.push_back(m.lines[i]);
    std::string s = lines.size() == 1 ? "line " : "lines ";
    for (std::size_t k = 0; k < lines.size() && k < 5; ++k) s += (k ? ", " : "") + std::to_string(lines[k]);
    if (lines.size() > 5) s += " and " + std::to_string(lines.size() - 5) + " more";
    return s;
}

// Arc heights falling with exposure are refused before any fit, naming the rows: the fits would
// only say "every strip at the plateau", which sends the user to peen shorter.
void refuse_falling_arc_heights(const MeasuredCurve& m) {
    const ArcHeightFall f = arc_height_fall(m.points);
    if (!f.falls) return;
    const double scale = 1.0 / m.height_unit.metres;
    const std::string u = m.exposure_unit.name, hu = m.height_unit.name;
    std::size_t last = 0;
    for (std::size_t i = 0; i < m.points.size(); ++i)
        if (m.points[i].exposure == f.longest_exposure) last = i;
    throw InputError({m.path, m.lines[last], 0}, m.height_column,
                     "arc heights must not fall with exposure: " + fmt(f.shortest_height * scale) + " " + hu +
                         " at the shortest exposure, " + fmt(f.shortest_exposure) + " " + u + " (" + lines_at(m, f.shortest_exposure) +
                         "), but " + fmt(f.longest_height * scale) + " " + hu + " at the longest, " + fmt(f.longest_exposure) + " " + u +
                         " (" + lines_at(m, f.longest_exposure) +
                         "); expected a saturation curve, rising with exposure, then levelling off (SAE J443): check those rows, and "
                         "that the exposure is the first column and the arc height the second");
}

std::string plot_fits(const std::string& png, const MeasuredCurve& m, const SaturationFit& two, const SaturationFit& three,
                      const SaturationFit& used, const std::string& strip) {
    const auto [dir, stem] = plot_files(png);         // its directory exists (check_output_paths)
    const double scale = 1.0 / m.height_unit.metres;  // m -> the curve's unit
    std::ostringstream data;
    data << "# " << m.exposure_column << "," << m.height_column << "\n";
    double longest = 0.0;
    for (const SaturationDatum& p : m.points) {
        data << exact(p.exposure) << "," << exact(p.arc_height * scale) << "\n";
        longest = std::max(longest, p.exposure);
    }
    write_file_atomically((fs::path(dir) / (stem + "_points.csv")).string(), data.str());
    const double right = 1.15 * std::max(longest, used.point.exists ? 2.0 * used.point.time : 0.0);
    std::ostringstream s;
    s << "# Written by peensim almen-fit; rerun from this directory: gnuplot " << stem << ".gp\n"
      << "if (!exists(\"out\")) out = " << gnuplot_string(stem + ".png") << "\n"
      << "set terminal pngcairo enhanced size 900,600 font 'sans,11'\nset output out\nset datafile separator ','\nset grid\n"
      << "set title " << gnuplot_string(gnuplot_text("Saturation curve: " + fs::path(m.path).filename().string())) << "\n"
      << "set xlabel " << gnuplot_string(gnuplot_text("exposure (" + m.exposure_unit.name + ")")) << "\n"
      << "set ylabel " << gnuplot_string(gnuplot_text("arc height (" + m.height_unit.name + ")")) << "\n"
      << "set xrange [0:" << exact(right) << "]\nset yrange [0:*]\nset key bottom right\nset samples 400\n";
    std::string plot =
        "plot " + gnuplot_string(stem + "_points.csv") + " using 1:2 with points pt 7 ps 1.4 lc rgb '#202020' title 'measured'";
    const auto curve = [&](const SaturationFit& f, const char* style) {
        if (!f.fitted) return;
        const std::string name = saturation_form_name(f.form);
        s << "h" << name << "(x) = x <= 0 ? 0 : " << exact(f.curve.a * scale) << " * (1 - exp(-" << exact(f.curve.b) << " * x**"
          << exact(f.curve.c) << "))\n";
        plot += ", h" + name + "(x) with lines lw 2 " + style + " title '" + name + " fit" + (&f == &used ? " (used)" : "") + "'";
    };
    curve(two, "lc rgb '#3070b0'");
    curve(three, "lc rgb '#c05020' dt 2");
    if (used.point.exists) {
        const double T = used.point.time, I = used.point.intensity * scale;
        s << "set arrow from " << exact(T) << ", graph 0 to " << exact(T) << ", first " << exact(I) << " nohead dt 2\n"
          << "set arrow from " << exact(2.0 * T) << ", graph 0 to " << exact(2.0 * T) << ", first " << exact(1.1 * I) << " nohead dt 3\n"
          << "set label "
          << gnuplot_string(gnuplot_text("T = " + fmt(T) + " " + m.exposure_unit.name + ", intensity " + fmt(I) + " " + m.height_unit.name +
                                         (strip.empty() ? "" : " (" + almen_intensity_label(used.point.intensity, strip) + ")")))
          << " at " << exact(T) << ", first " << exact(I) << " offset 1,-1.2\n"
          << "set label '2T' at " << exact(2.0 * T) << ", graph 0.04 offset 0.5,0\n";
    }
    s << plot << "\n";
    return plot_with_gnuplot(dir, stem, s.str());
}

int run_almen_fit(const AlmenFitOptions& o, std::ostream& out, std::ostream& err) {
    if (!o.strip.empty() && o.strip != "A" && o.strip != "N" && o.strip != "C")
        throw InputError(kCommandLine, "--strip", "expected A, N or C (the SAE J442 strip type), got '" + o.strip + "'");
    if (!o.form.empty() && o.form != "2P" && o.form != "3P")
        throw InputError(kCommandLine, "--form", "expected 2P or 3P, got '" + o.form + "'");
    check_output_paths(o);
    const MeasuredCurve m = read_measured_curve(o.curve_path, o.time_unit, o.height_unit);
    refuse_falling_arc_heights(m);
    const SaturationFit two = fit_saturation_curve(m.points, SaturationForm::two_parameter);
    const SaturationFit three = fit_saturation_curve(m.points, SaturationForm::three_parameter);
    SaturationChoice choice = choose_saturation_fit(two, three);
    const std::string u = m.exposure_unit.name;

    out << "Saturation curve: " << m.path << " (" << m.points.size() << " strips at " << m.distinct_exposures()
        << " exposures; exposure in " << u << ", arc height in " << m.height_unit.name << ")\n\n";
    out << "  exposure (" << u << ")  arc height (" << m.height_unit.name << ")   2P fit   3P fit\n";
    const double scale = 1.0 / m.height_unit.metres;
    for (const SaturationDatum& p : m.points)
        out << "  " << std::setw(13) << fmt(p.exposure, 6) << "  " << std::setw(16) << fmt(p.arc_height * scale, 6) << "  " << std::setw(7)
            << (two.fitted ? fmt(two.curve.arc_height(p.exposure) * scale, 4) : "-") << "  " << std::setw(7)
            << (three.fitted ? fmt(three.curve.arc_height(p.exposure) * scale, 4) : "-") << "\n";
    out << "\n";
    print_fit(out, two, m, o.strip);
    print_fit(out, three, m, o.strip);
    if (!choice.any) {
        out << "\n";
        throw InputError({m.path, 0, 0}, "",
                         "no saturation point: 2P: " + (two.problem.empty() ? std::string("none") : two.problem) +
                             "; 3P: " + (three.problem.empty() ? std::string("none") : three.problem));
    }
    std::string reason = choice.reason;
    if (!o.form.empty()) {
        const SaturationForm wanted = o.form == "2P" ? SaturationForm::two_parameter : SaturationForm::three_parameter;
        const SaturationFit& f = wanted == SaturationForm::two_parameter ? two : three;
        if (!f.fitted || !f.point.exists)
            throw InputError(kCommandLine, "--form", "the " + o.form + " fit has no saturation point (" + f.problem + ")");
        if (wanted != choice.form)
            reason = "--form " + o.form + " (the recommendation was " + saturation_form_name(choice.form) + ": " + choice.reason + ")";
        choice.form = wanted;
    }
    const SaturationFit& used = choice.form == SaturationForm::two_parameter ? two : three;
    out << "\nUse the " << saturation_form_name(used.form) << " fit: " << reason << ".\n\n";
    out << "Intensity " << almen_intensity_text(used.point.intensity, o.strip) << ", saturation time T = " << fmt(used.point.time) << " "
        << u;
    if (m.exposure_unit.is_time() && m.exposure_unit.seconds != 1.0) out << " (" << fmt(used.point.time * m.exposure_unit.seconds) << " s)";
    out << " (" << saturation_form_name(used.form) << ").\n";
    const std::vector<std::string> warnings = j443_warnings(m, used);
    for (const std::string& w : warnings) err << "warning: " << m.path << ": " << w << "\n";

    nlohmann::ordered_json j;
    j["file"] = m.path;
    j["exposure_column"] = m.exposure_column;
    j["exposure_unit"] = u;
    j["exposure_unit_s"] = json_number(m.exposure_unit.is_time() ? m.exposure_unit.seconds : NAN);
    j["height_column"] = m.height_column;
    j["height_unit"] = m.height_unit.name;
    j["height_unit_m"] = m.height_unit.metres;
    j["points"] = m.points.size();
    j["distinct_exposures"] = m.distinct_exposures();
    j["strip"] = o.strip.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(o.strip);
    j["fits"] = {fit_json(two, m, o.strip), fit_json(three, m, o.strip)};
    j["used"] = saturation_form_name(used.form);
    j["reason"] = reason;
    j["intensity_m"] = used.point.intensity;
    j["intensity_in"] = used.point.intensity / kMetresPerInch;
    j["intensity_thou"] = used.point.intensity / kMetresPerInch * 1e3;
    j["intensity_label"] =
        o.strip.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(almen_intensity_label(used.point.intensity, o.strip));
    j["saturation_time"] = used.point.time;
    j["saturation_time_s"] = json_number(m.exposure_unit.is_time() ? used.point.time * m.exposure_unit.seconds : NAN);
    j["warnings"] = warnings;

    if (!o.calibrate_run.empty()) {
        if (!m.exposure_unit.is_time())
            throw InputError({m.path, 1, 0}, m.exposure_column,
                             "--calibrate needs exposure as a time (s, min, h) to compare with the run's seconds; this curve counts " + u +
                                 ": give the time of one " + (u == "passes" ? "pass" : "cycle") + " by converting the column to seconds");
        const RunStrip run_strip = strip_of_run(o.calibrate_run, o.component);
        const AlmenModelCalibration cal = almen_calibration(used.curve, m.exposure_unit.seconds, run_strip.exposure, o.strip);
        const std::string path = "components[" + run_strip.name + "].almen.calibration";
        out << "\nCalibration of the predictive model on " << o.calibrate_run << " (strip " << run_strip.name << ": dent size "
            << fmt(cal.run.dent_size_m * 1e6) << " um, covering rate " << fmt(cal.run.covering_rate_per_s) << " /s; "
            << saturation_form_name(used.form) << " fit): K = a / dent size = " << fmt(cal.arc_height_per_dent_size())
            << ", A_c = covering rate x time constant = " << fmt(cal.dent_area_ratio_constant()) << ".\n"
            << "Put this into the strip's `almen:` block of the scene (numbers exact, so that the run predicts the measured curve "
               "back):\n\n"
            << "      calibration:\n"
            << "        saturation_arc_height: " << exact(cal.measured.a) << " m  # " << fmt(cal.measured.a * 1e3) << " mm\n"
            << "        time_constant: " << exact(cal.time_constant_s()) << " s\n"
            << "        shape: " << exact(cal.measured.c) << "\n"
            << "        dent_size: " << exact(cal.run.dent_size_m) << " m  # " << fmt(cal.run.dent_size_m * 1e6) << " um\n"
            << "        covering_rate: " << exact(cal.run.covering_rate_per_s) << " 1/s\n";
        if (!o.strip.empty()) out << "        strip: " << o.strip << "\n";
        out << "\nor give it to a run: --set \"" << path << "={saturation_arc_height: " << exact(cal.measured.a)
            << " m, time_constant: " << exact(cal.time_constant_s()) << " s, shape: " << exact(cal.measured.c)
            << ", dent_size: " << exact(cal.run.dent_size_m) << " m, covering_rate: " << exact(cal.run.covering_rate_per_s) << " 1/s"
            << (o.strip.empty() ? "" : ", strip: " + o.strip) << "}\"\n";
        j["calibration"] = {{"run", o.calibrate_run},
                            {"component", run_strip.name},
                            {"saturation_arc_height_m", cal.measured.a},
                            {"time_constant_s", cal.time_constant_s()},
                            {"shape", cal.measured.c},
                            {"dent_size_m", cal.run.dent_size_m},
                            {"covering_rate_per_s", cal.run.covering_rate_per_s}};
    }
    // A column name need not be UTF-8 (a Latin-1 "µm"): its bytes are replaced, not a reason to fail.
    if (!o.json_path.empty()) write_file_atomically(o.json_path, j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    if (!o.plot_path.empty()) {
        const std::string note = plot_fits(o.plot_path, m, two, three, used, o.strip);
        if (!note.empty()) err << "note: no plot: " << note << "\n";
    }
    return kExitOk;
}

}  // namespace

int almen_fit_job(const AlmenFitOptions& options, std::ostream& out, std::ostream& err) {
    return report_errors(err, [&] { return run_almen_fit(options, out, err); });
}

}  // namespace peensim
