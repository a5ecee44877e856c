// A virtual SAE Almen strip: the kinetic energy its peened face receives from normal impacts,
// per unit area (the dose E, J/m2), and the arc-height saturation curve that dose gives once
// calibrated. Pure computation: no file I/O, no printing.
//
// Arc height. Almen intensity tracks the normal impact energy delivered (reference, "Outputs"),
// so we model h = a (1 - exp(-E / E_c)). With a steady dose rate r (E = r t) this is the usual
// saturation fit h = a (1 - exp(-b t)), b = r / E_c, and the SAE J443 saturation point T, where
// doubling the time raises h by 10 % (h(2T) = 1.1 h(T)), is exp(-b T) = 0.1: T = ln(10) / b,
// intensity h(T) = 0.9 a. a and E_c depend on strip type, shot and material and are not
// predictable from the impacts alone: they must be calibrated on a measured saturation curve
// (from a measured T_m and intensity h_m: a = h_m / 0.9, E_c = r T_m / ln 10).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "common/vec.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

// Triangles whose unit normal is within this angle of the face normal form the peened face.
inline constexpr double kAlmenFaceToleranceDeg = 1.0;

struct AlmenCalibration {
    double saturation_arc_height_m = 0.0;  // m, a
    double dose_constant_J_per_m2 = 0.0;   // J/m2, E_c
};

struct AlmenDosePoint {
    double time_s = 0.0;         // s
    double dose_J_per_m2 = 0.0;  // J/m2
    // The dents on the face (analysis/almen_model.h; 0 when the strip material has no yield stress):
    double dent_area_ratio = 0.0;         // -, A_r = sum of pi phi^2 / 4 over the face's impacts / face area
    double dent_size_area_ratio_m = 0.0;  // m, sum of (pi phi^2 / 4) phi / face area: A_r weighted by dent size
};

struct AlmenSaturation {
    double rate_constant_per_s = 0.0;  // 1/s, b = r / E_c
    double saturation_time_s = 0.0;    // s, T = ln(10) / b
    double intensity_m = 0.0;          // m, h(T) = 0.9 a
    bool extrapolated = false;         // 2T lies beyond the dose curve's last time
};

// h = a (1 - exp(-E / E_c)), m.
double almen_arc_height(double dose_J_per_m2, const AlmenCalibration& calibration);

// Steady dose rate r (J/(m2 s)): the least-squares slope of E(t) over the second half of the curve
// (t >= half its last time), so that the start of a run (the shot's first launch off the
// sonotrode, a burst of fast impacts) does not bias it. With fewer than two such points, the
// slope of the last point from the origin. Returns 0 for a curve without a point at t > 0.
double almen_dose_rate(const std::vector<AlmenDosePoint>& curve);

// The same steady slope for any quantity of the curve (per second), e.g. &AlmenDosePoint::dent_area_ratio.
double almen_steady_slope(const std::vector<AlmenDosePoint>& curve, double AlmenDosePoint::*quantity);
// The index of the first point of the steady part (t >= half the last time), or curve.size() when
// the curve has no point at t > 0.
std::size_t almen_steady_start(const std::vector<AlmenDosePoint>& curve);

// The J443 saturation point of h = a (1 - exp(-r t / E_c)); nullopt when r <= 0.
std::optional<AlmenSaturation> almen_saturation(double dose_rate_J_per_m2_s, const AlmenCalibration& calibration, double last_time_s);

class AlmenDose {
public:
    // mesh: the strip (component frame, m); face_normal: unit vector out of the peened face;
    // shot_mass_kg: one shot's mass. Throws std::invalid_argument if no triangle faces that way.
    AlmenDose(const TriangleMesh& mesh, const Vec3& face_normal, double shot_mass_kg);

    // One impact on triangle t (index in the mesh) at normal speed vn (m/s); impacts on the
    // strip's other faces (edges, back) do not count. Returns whether it was on the face.
    bool add(int triangle, double vn_m_per_s) { return add(triangle, vn_m_per_s, shot_mass_); }
    // The same for a shot of its own mass (kg; a mix's log gives each impact's shot).
    bool add(int triangle, double vn_m_per_s, double shot_mass_kg);
    // The dent (diameter, m) an impact on the face left (called after add() returned true).
    void add_dent(double dent_diameter_m);

    double face_area_m2() const { return face_area_; }
    std::uint64_t face_impacts() const { return impacts_; }
    double dose_J_per_m2() const { return energy_ / face_area_; }
    double mean_normal_speed() const;                                                  // m/s over the face's impacts (NaN without any)
    double dent_area_ratio() const { return dent_area_m2_ / face_area_; }              // -
    double dent_size_area_ratio_m() const { return dent_size_area_m3_ / face_area_; }  // m
    AlmenDosePoint point_at(double time_s) const { return {time_s, dose_J_per_m2(), dent_area_ratio(), dent_size_area_ratio_m()}; }

private:
    std::vector<std::uint8_t> on_face_;  // per triangle
    double shot_mass_;                   // kg
    double face_area_ = 0.0;             // m2
    double energy_ = 0.0;                // J
    double speed_sum_ = 0.0;             // m/s
    double dent_area_m2_ = 0.0;          // m2, sum of pi phi^2 / 4
    double dent_size_area_m3_ = 0.0;     // m3, sum of (pi phi^2 / 4) phi
    std::uint64_t impacts_ = 0;
};

}  // namespace peensim
