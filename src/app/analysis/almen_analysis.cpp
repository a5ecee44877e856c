#include "app/analysis/almen_analysis.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "app/analysis/analysis_format.h"
#include "common/input_error.h"
#include "common/units.h"
#include "contact/dent.h"
#include "output/atomic_file.h"
#include "output/json_number.h"

namespace peensim {

namespace {

AlmenModelCalibration model_of(const AlmenCalibrationDesc& d) {
    AlmenModelCalibration m;
    m.measured.a = d.saturation_arc_height_m;
    m.measured.c = d.shape;
    m.measured.b = std::pow(d.time_constant_s, -d.shape);  // tau^-c
    m.run.dent_size_m = d.dent_size_m;
    m.run.covering_rate_per_s = d.covering_rate_per_s;
    m.strip = d.strip;
    return m;
}

// The dose model's paragraph (analysis/almen.h): needs its two constants.
void dose_model_text(std::ostringstream& r, const AlmenAnalysis& a, double rate, double duration) {
    const auto sat = almen_saturation(rate, *a.calibration, duration);
    r << "\nCalibration: a = " << fmt(a.calibration->saturation_arc_height_m * 1e3)
      << " mm, E_c = " << fmt(a.calibration->dose_constant_J_per_m2) << " J/m2. Arc height after " << fmt(duration)
      << " s: " << fmt(almen_arc_height(a.dose->dose_J_per_m2(), *a.calibration) * 1e3) << " mm.\n";
    if (sat)
        r << "Saturation curve h = " << fmt(a.calibration->saturation_arc_height_m * 1e3) << " mm (1 - exp(-"
          << fmt(sat->rate_constant_per_s) << " t / s)); saturation time T = " << fmt(sat->saturation_time_s) << " s, intensity "
          << fmt(sat->intensity_m * 1e3) << " mm" << (sat->extrapolated ? " (extrapolated: the run is shorter than 2T)" : "") << ".\n";
    else
        r << "No impact on the peened face: no saturation curve.\n";
}

// The predictive model's paragraph (analysis/almen_model.h).
void prediction_text(std::ostringstream& r, const AlmenAnalysis& a, const AlmenExposure& e, double duration) {
    const AlmenModelCalibration& m = *a.model;
    r << "\n### Predicted saturation curve\n\n"
      << "Calibrated on a measured curve h = " << fmt(m.measured.a * 1e3) << " mm (1 - exp(-(t / " << fmt(m.time_constant_s()) << " s)^"
      << fmt(m.measured.c) << ")) and the run that reproduced it (dent size " << fmt(m.run.dent_size_m * 1e6) << " um, covering rate "
      << fmt(m.run.covering_rate_per_s) << " /s): the saturated arc height follows the dent size, the time scale the covering rate "
      << "(docs/user-guide.md, \"Almen strips\").\n";
    if (!e.valid()) {
        r << "\nNo prediction: "
          << (a.yield_stress_pa > 0.0 ? "no dent on the peened face in this run"
                                      : "the strip material has no yield_stress (the dents need it)")
          << ".\n";
        return;
    }
    const AlmenPrediction p = predict_almen(m, e);
    r << "Against the calibration run: dent size x" << fmt(p.intensity_ratio) << ", covering rate x" << fmt(1.0 / p.time_ratio)
      << ", so intensity x" << fmt(p.intensity_ratio) << " and saturation time x" << fmt(p.time_ratio) << ".\n\n"
      << "Predicted saturation curve h = " << fmt(p.curve.a * 1e3) << " mm (1 - exp(-(t / " << fmt(std::pow(p.curve.b, -1.0 / p.curve.c))
      << " s)^" << fmt(p.curve.c) << ")).\n";
    if (!p.point.exists) {
        r << "The curve's shape never rises by 10 % on doubling: no J443 saturation point.\n";
        return;
    }
    r << "**Predicted J443 saturation time T = " << fmt(p.point.time) << " s, intensity "
      << almen_intensity_text(p.point.intensity, m.strip) << ".**";
    if (2.0 * p.point.time > duration)
        r << " The run covers " << fmt(duration) << " s: the prediction carries its steady rates on to 2T = " << fmt(2.0 * p.point.time)
          << " s.";
    r << " Arc height vs time: `predicted_arc_height_mm` in the strip's CSV.\n";
}

}  // namespace

AlmenAnalysis almen_analysis_of(const ComponentDesc& c, const TriangleMesh& mesh, double shot_mass, double shot_density,
                                double yield_stress) {
    AlmenAnalysis almen;
    try {
        almen.dose = std::make_unique<AlmenDose>(mesh, c.almen->face_normal, shot_mass);
    } catch (const std::invalid_argument& e) {
        throw InputError(c.almen->where, "almen.face_normal",
                         std::string(e.what()) + " (expected the outward normal of one face of the strip, in the component's frame)");
    }
    if (c.almen->saturation_arc_height_m)
        almen.calibration = AlmenCalibration{*c.almen->saturation_arc_height_m, *c.almen->dose_constant_J_per_m2};
    if (c.almen->calibration) almen.model = model_of(*c.almen->calibration);
    almen.shot_density_kg_per_m3 = shot_density;
    almen.yield_stress_pa = yield_stress;
    return almen;
}

void add_almen_impact(AlmenAnalysis& a, int triangle, double vn, double shot_diameter, double shot_mass) {
    if (a.dose->add(triangle, vn, shot_mass) && a.yield_stress_pa > 0.0)
        a.dose->add_dent(dent_diameter(shot_diameter, a.shot_density_kg_per_m3, vn, a.yield_stress_pa));
}

void sample_almen(AlmenAnalysis& a, double time_s) { a.curve.push_back(a.dose->point_at(time_s)); }

void write_almen_csv(const std::filesystem::path& path, const AlmenAnalysis& a, double window_start_s) {
    const AlmenExposure e = almen_exposure(a.curve);
    const bool dents = a.yield_stress_pa > 0.0, predicted = a.model && e.valid();
    std::ostringstream s;
    s << "time_s,dose_J_per_m2,arc_height_mm,dent_area_ratio,predicted_arc_height_mm\n";
    for (const AlmenDosePoint& p : a.curve)
        s << fmt(window_start_s + p.time_s, 8) << ',' << fmt(p.dose_J_per_m2, 8) << ','
          << (a.calibration ? fmt(almen_arc_height(p.dose_J_per_m2, *a.calibration) * 1e3, 6) : "") << ','
          << (dents ? fmt(p.dent_area_ratio, 8) : "") << ','
          << (predicted ? fmt(predicted_arc_height(*a.model, e, p.dent_area_ratio) * 1e3, 6) : "") << '\n';
    write_file_atomically(path.string(), s.str());
}

std::string almen_report_sections(const std::vector<ComponentAnalysis>& parts, double duration) {
    std::ostringstream r;
    for (const ComponentAnalysis& c : parts) {
        if (!c.almen) continue;
        const AlmenAnalysis& a = *c.almen;
        const double rate = almen_dose_rate(a.curve);  // J/(m2 s)
        r << "\n## Almen strip " << c.name << "\n\n"
          << "Peened face: " << fmt(a.dose->face_area_m2() * 1e6) << " mm2, " << a.dose->face_impacts() << " impacts at a mean "
          << "normal speed of " << fmt(a.dose->mean_normal_speed()) << " m/s. Impact energy dose (normal kinetic energy per "
          << "area): " << fmt(a.dose->dose_J_per_m2()) << " J/m2 after " << fmt(duration)
          << " s; steady rate (slope over the run's second half) r = " << fmt(rate) << " J/(m2 s) (`" << c.name << "_almen.csv`).\n";
        const AlmenExposure e = almen_exposure(a.curve);
        if (a.yield_stress_pa > 0.0 && e.valid())
            r << "\nDents on the face over the run's second half (eq. 10 with the strip's yield stress " << fmt(a.yield_stress_pa * 1e-6)
              << " MPa): dent size (dent-area-weighted mean diameter) " << fmt(e.dent_size_m * 1e6) << " um, covering rate "
              << fmt(e.covering_rate_per_s) << " /s (dent area ratio per second: the face's coverage 1 - exp(-k t) reaches 98 % after "
              << fmt(std::log(50.0) / e.covering_rate_per_s) << " s).\n";
        else if (a.yield_stress_pa > 0.0)
            r << "\nNo dent on the peened face.\n";
        else
            r << "\nNo dent sizes: the strip material has no `yield_stress` (the predictive model needs it).\n";
        if (a.model) {
            prediction_text(r, a, e, duration);
            continue;
        }
        if (a.calibration) {
            dose_model_text(r, a, rate, duration);
            continue;
        }
        r << "\n**Arc height needs calibration** on one measured saturation curve of this strip type, shot and process: "
             "`peensim almen-fit CURVE.csv --calibrate RUNDIR`, RUNDIR the run that reproduced the measurement, prints the "
             "scene's `almen.calibration`; the analysis then predicts the saturation curve, J443 saturation time and intensity "
             "of any run from its dents. (The older dose model h = a (1 - exp(-E / E_c)) takes `almen.saturation_arc_height` (a) "
             "and `almen.dose_constant` (E_c) instead: from a measured saturation time T_m and intensity h_m, a = h_m / 0.9, "
             "E_c = r T_m / ln 10 = "
          << fmt(rate / std::log(10.0)) << " J/m2 per second of T_m for this run.)\n\nNot calibrated in this scene: dose only.\n";
    }
    return r.str();
}

void add_almen_figures(nlohmann::ordered_json& o, const AlmenAnalysis& a) {
    o["almen_dose_J_per_m2"] = json_number(a.dose->dose_J_per_m2());
    const AlmenExposure e = almen_exposure(a.curve);
    o["almen_dent_size_m"] = json_number(e.valid() ? e.dent_size_m : NAN);
    o["almen_covering_rate_per_s"] = json_number(e.valid() ? e.covering_rate_per_s : NAN);
    double intensity = NAN, time = NAN;
    if (a.model && e.valid()) {
        const AlmenPrediction p = predict_almen(*a.model, e);
        if (p.point.exists) intensity = p.point.intensity, time = p.point.time;
    }
    o["almen_predicted_intensity_m"] = json_number(intensity);
    o["almen_predicted_saturation_time_s"] = json_number(time);
}

std::string almen_intensity_label(double intensity_m, const std::string& strip) {
    if (strip.empty() || !std::isfinite(intensity_m)) return "";
    std::ostringstream s;
    s << std::fixed << std::setprecision(4) << intensity_m / kMetresPerInch << strip;
    return s.str();
}

std::string almen_intensity_text(double intensity_m, const std::string& strip) {
    const double inches = intensity_m / kMetresPerInch;
    std::string text = fmt(intensity_m * 1e3) + " mm = " + fmt(inches) + " in = " + fmt(inches * 1e3) + " thou";
    if (!strip.empty()) text += " (" + almen_intensity_label(intensity_m, strip) + ")";
    return text;
}

}  // namespace peensim
