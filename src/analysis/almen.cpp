#include "analysis/almen.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace peensim {

double almen_arc_height(double dose_J_per_m2, const AlmenCalibration& c) {
    return c.saturation_arc_height_m * -std::expm1(-dose_J_per_m2 / c.dose_constant_J_per_m2);
}

double almen_steady_slope(const std::vector<AlmenDosePoint>& curve, double AlmenDosePoint::*quantity) {
    if (curve.empty() || !(curve.back().time_s > 0.0)) return 0.0;
    const double from = 0.5 * curve.back().time_s;
    double n = 0.0, st = 0.0, se = 0.0, stt = 0.0, ste = 0.0;
    for (const AlmenDosePoint& p : curve) {
        if (p.time_s < from) continue;
        const double e = p.*quantity;
        n += 1.0;
        st += p.time_s;
        se += e;
        stt += p.time_s * p.time_s;
        ste += p.time_s * e;
    }
    const double spread = n * stt - st * st;
    if (n < 2.0 || !(spread > 0.0)) return curve.back().*quantity / curve.back().time_s;
    return (n * ste - st * se) / spread;
}

double almen_dose_rate(const std::vector<AlmenDosePoint>& curve) { return almen_steady_slope(curve, &AlmenDosePoint::dose_J_per_m2); }

std::size_t almen_steady_start(const std::vector<AlmenDosePoint>& curve) {
    if (curve.empty() || !(curve.back().time_s > 0.0)) return curve.size();
    const double from = 0.5 * curve.back().time_s;
    std::size_t i = 0;
    while (curve[i].time_s < from) ++i;
    return i;
}

std::optional<AlmenSaturation> almen_saturation(double rate, const AlmenCalibration& c, double last_time_s) {
    if (!(rate > 0.0)) return std::nullopt;
    AlmenSaturation s;
    s.rate_constant_per_s = rate / c.dose_constant_J_per_m2;
    s.saturation_time_s = std::log(10.0) / s.rate_constant_per_s;
    s.intensity_m = 0.9 * c.saturation_arc_height_m;
    s.extrapolated = 2.0 * s.saturation_time_s > last_time_s;
    return s;
}

AlmenDose::AlmenDose(const TriangleMesh& mesh, const Vec3& face_normal, double shot_mass_kg)
    : on_face_(mesh.triangle_count(), 0), shot_mass_(shot_mass_kg) {
    const double cos_tolerance = std::cos(kAlmenFaceToleranceDeg * M_PI / 180.0);
    const Vec3 n = face_normal.normalized();
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 cross = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
        const double area = 0.5 * cross.norm();
        if (!(area > 0.0) || cross.normalized().dot(n) < cos_tolerance) continue;
        on_face_[t] = 1;
        face_area_ += area;
    }
    if (!(face_area_ > 0.0)) throw std::invalid_argument("no triangle of the Almen strip faces along its face_normal");
}

bool AlmenDose::add(int triangle, double vn, double shot_mass_kg) {
    if (triangle < 0 || static_cast<std::size_t>(triangle) >= on_face_.size() || !on_face_[static_cast<std::size_t>(triangle)])
        return false;
    energy_ += 0.5 * shot_mass_kg * vn * vn;
    speed_sum_ += vn;
    ++impacts_;
    return true;
}

void AlmenDose::add_dent(double phi) {
    const double area = 0.25 * M_PI * phi * phi;  // m2
    dent_area_m2_ += area;
    dent_size_area_m3_ += area * phi;
}

double AlmenDose::mean_normal_speed() const {
    return impacts_ > 0 ? speed_sum_ / static_cast<double>(impacts_) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace peensim
