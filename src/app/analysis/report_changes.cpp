#include "app/analysis/report_changes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "app/analysis/analysis_format.h"
#include "app/analysis/coverage_verdict.h"

namespace peensim {

namespace {

std::string mm_rounded(double m, int digits = 3) { return fmt(m * 1e3, digits) + " mm"; }

// A length rounded down to two significant digits (a shot size a user can ask for and that still
// reaches what the finer figure reached).
double round_down_2(double x) {
    if (!(x > 0.0)) return 0.0;
    const double scale = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    return std::floor(x / scale) * scale;
}

std::string vector_mm(const Vec3& v) {
    const auto c = [](double x) { return fmt(std::abs(x) < 1e-9 ? 0.0 : x * 1e3, 5) + " mm"; };
    return "[" + c(v.x()) + ", " + c(v.y()) + ", " + c(v.z()) + "]";
}

std::string vector_unit(const Vec3& v) {
    const auto c = [](double x) { return fmt(std::abs(x) < 1e-9 ? 0.0 : x, 5); };
    return "[" + c(v.x()) + ", " + c(v.y()) + ", " + c(v.z()) + "]";
}

const ComponentDesc* described(const SceneDescription& scene, const std::string& name) {
    for (const ComponentDesc& c : scene.components)
        if (c.name == name) return &c;
    return nullptr;
}

// A uniformity (the part's time over everywhere's) whose interval reaches this counts as even.
constexpr double kEvenUniformity = 0.95;

// "path=a,b,c" with each value once: a sweep refuses a value given twice (two that round alike).
std::string vary_spec(const std::string& path, const std::vector<std::string>& values) {
    std::string spec = path + "=";
    std::vector<std::string> given;
    for (const std::string& v : values)
        if (std::find(given.begin(), given.end(), v) == given.end()) {
            spec += (given.empty() ? "" : ",") + v;
            given.push_back(v);
        }
    return spec;
}

// A sweep of this run's scene, two seeds, as long as this window: or a whole turn of the rotating
// part where the window is shorter (the report says that is too short to say anything; so would
// the sweep's runs).
std::string sweep_command(const ReportContext& x, const std::string& suffix, const std::string& vary) {
    const AnalysisWindow& w = x.window;
    const double duration_s = w.shorter_than_a_turn() ? std::ceil((w.from_s + w.turn_s) * 1000.0) / 1000.0 : w.to_s;
    return "peensim sweep " + (x.run_dir / "scene.resolved.yaml").string() + " -o " + x.run_dir.string() + "-" + suffix + " --vary \"" +
           vary + "\" --seeds 2 --set \"process.duration=" + fmt(duration_s, 8) + " s\"";
}

}  // namespace

TurningAxis turning_axis(const TriangleMesh& mesh, const ComponentDesc& placement) {
    const auto triangle_area = [&](std::size_t t) {  // m2
        return 0.5 * (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0)).norm();
    };
    double area = 0.0;
    Vec3 centroid = Vec3::Zero();
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const double a = triangle_area(t);
        area += a;
        centroid += a * (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
    }
    TurningAxis axis;
    if (!(area > 0.0)) return axis;
    centroid /= area;
    Mat3 spread = Mat3::Zero();  // m2, the surface's second moment about its centroid
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Vec3 d = (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0 - centroid;
        spread += triangle_area(t) * d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(spread);
    const Vec3 l = solver.eigenvalues();  // increasing
    // A disc (a gear) has its two large moments alike, a shaft its two small ones: the odd one out
    // is the axis of symmetry.
    const Vec3 local = (l(1) - l(0) > l(2) - l(1)) ? Vec3(solver.eigenvectors().col(0)) : Vec3(solver.eigenvectors().col(2));
    axis.direction = (placement.rotation * local).normalized();
    // The sign a user would write: the largest component positive.
    int big = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(axis.direction(k)) > std::abs(axis.direction(big))) big = k;
    if (axis.direction(big) < 0.0) axis.direction = -axis.direction;
    axis.point_m = placement.rotation * centroid + placement.translation_m;
    return axis;
}

std::string unreachable_section(const ComponentAnalysis& c, const ReportContext& x) {
    const UnreachableFindings& u = c.unreachable;
    if (!c.coverage || !(u.whole.area_m2 > 0.0)) return "";
    const PeenedAreas areas = peened_areas(c);
    std::ostringstream r;
    r << "\n### " << c.name << ": out of the shot's reach\n\n";
    r << "**" << fmt(u.whole.area_m2 * 1e6, 4) << " mm2 (" << fmt(100.0 * u.whole.area_m2 / areas.total_m2, 3) << " %) of " << c.name
      << " no " << mm_rounded(u.shot_diameter_m)
      << " shot can touch** in the assembly as placed: there is no room for a shot centre a radius "
         "away along the surface's normal. It is left out of coverage (the rest can reach 100 %) and no peening time changes it. ";
    const auto reached_by = [&](double d) {
        return d > 0.0 ? "a shot of " + mm_rounded(d) + " or smaller" : std::string("no shot at all (closed off)");
    };
    r << "Half of it would be reached by " << reached_by(u.whole.half_reached_by_m) << ", 90 % by " << reached_by(u.whole.most_reached_by_m)
      << " (the same reach test with a smaller shot, " << u.whole.points << " points of it).\n\n";
    // Its regions, largest first.
    std::vector<std::size_t> order;
    for (std::size_t k = 0; k < u.regions.size(); ++k)
        if (u.regions[k].area_m2 > 0.0 && !c.regions.excluded(k)) order.push_back(k);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return u.regions[a].area_m2 > u.regions[b].area_m2; });
    if (!order.empty()) {
        r << "| region | out of reach (mm2) | of the region | half reached by | 90 % reached by |\n|---|---|---|---|---|\n";
        const std::size_t shown = std::min<std::size_t>(order.size(), 12);
        for (std::size_t i = 0; i < shown; ++i) {
            const std::size_t k = order[i];
            const UnreachableArea& g = u.regions[k];
            const double area = c.coverage->classes().region_peened_area_m2(k) + g.area_m2;
            const auto d = [](double m) { return m > 0.0 ? "<= " + fmt(m * 1e3, 3) + " mm" : std::string("none"); };
            r << "| " << c.regions.name(k) << " | " << fmt(g.area_m2 * 1e6, 4) << " | "
              << (area > 0.0 ? fmt(100.0 * g.area_m2 / area, 3) + " %" : "") << " | " << d(g.half_reached_by_m) << " | "
              << d(g.most_reached_by_m) << " |\n";
        }
        if (shown < order.size()) r << "\n(" << order.size() - shown << " more regions in `" << c.name << "_regions.csv`.)\n";
    }
    for (const auto& [name, png] : x.unreachable_pngs)
        if (name == c.name) r << "\n![" << c.name << ": out of the shot's reach, highlighted](" << png << ")\n";
    return r.str();
}

std::string changes_section(const SceneDescription& scene, const std::vector<ComponentAnalysis>& parts, const ReportContext& x) {
    std::ostringstream r;
    int changes = 0;
    const std::string goal = fmt(100.0 * x.window.target_coverage, 4) + " %";
    for (const ComponentAnalysis& c : parts) {
        if (!c.coverage) continue;
        const ComponentDesc* desc = described(scene, c.name);
        // Uneven peening: what the slowest area costs against the part's average.
        const Everywhere e = everywhere(c);
        const AreaForecast& whole = c.forecast.whole;
        // A time the run saw (a run until coverage of some areas, seen after the window) counts as a forecast's.
        const auto timed_area = [](const AreaForecast& f) { return f.status == AreaForecast::Status::forecast || f.seen_in_run; };
        const bool timed = timed_area(whole) && timed_area(e.time);
        // Its slowest area against the part as a whole, as both entries below say it.
        const auto slowest_against_whole = [&] {
            return "Its slowest area, " + slowest_area_name(c, e.slowest) + ", reaches " + goal + " at " + fmt(e.time.time_s, 4) +
                   " s, the part as a whole at " + fmt(whole.time_s, 4) + " s (uniformity " + fmt(e.uniformity, 3) + ", " +
                   fmt(e.uniformity_low, 3) + "-" + fmt(e.uniformity_high, 3) + ")";
        };
        if (timed && std::isfinite(e.uniformity) && e.uniformity_high < kEvenUniformity && desc != nullptr) {
            ++changes;
            r << "- **Even out " << c.name << "'s peening.** " << slowest_against_whole() << ": peened like the average, it would be done "
              << fmt(100.0 * (1.0 - e.uniformity), 2) << " % sooner. ";
            if (desc->rotation_motion) {
                const double rpm = std::abs(desc->rotation_motion->speed_rad_per_s) * 60.0 / (2.0 * std::numbers::pi);
                r << "It turns at " << fmt(rpm, 4) << " rpm; how the speed changes that, with 2 seeds:\n\n      "
                  << sweep_command(x, "speed",
                                   vary_spec("components[" + c.name + "].motion.speed",
                                             {fmt(rpm / 2.0, 4) + " rpm", fmt(rpm, 4) + " rpm", fmt(2.0 * rpm, 4) + " rpm"}))
                  << "\n\n";
            } else if (c.role == ComponentRole::part) {
                const TurningAxis axis = turning_axis(*c.mesh, *desc);
                const std::string turning = "{type: rotating, axis_point: " + vector_mm(axis.point_m) +
                                            ", axis_direction: " + vector_unit(axis.direction) + ", speed: ";
                r << "It stands still, so one side faces the sonotrode throughout; turning it about its axis (through its centroid along "
                  << vector_unit(axis.direction)
                  << ") evens the sides out. Test it, with 2 seeds (check the axis first: `peensim check` "
                     "refuses a part that would hit the chamber):\n\n      "
                  << sweep_command(x, "turning", "components[" + c.name + "].motion=" + turning + "15 rpm}," + turning + "30 rpm}")
                  << "\n\n";
            }
        } else if (timed && std::isfinite(e.uniformity) && e.uniformity < kEvenUniformity && desc != nullptr) {
            // Uneven by the estimate, but its interval reaches even: say so rather than nothing.
            ++changes;
            r << "- **" << c.name << " may peen unevenly, but this run cannot tell.** " << slowest_against_whole()
              << ": the interval reaches 0.95, which counts as even here. A longer run narrows it (its counting noise goes as one "
                 "over the square root of the run's length: four times as long, about half as wide).\n";
        }
        // The area out of reach: the shot that would reach it.
        const UnreachableFindings& u = c.unreachable;
        if (u.whole.area_m2 > 0.0) {
            ++changes;
            r << "- **Reach the " << fmt(u.whole.area_m2 * 1e6, 4) << " mm2 of " << c.name << " out of the shot's reach.** ";
            if (u.whole.most_reached_by_m > 0.0 && scene.shot.sizes.size() == 1) {
                const double half = round_down_2(u.whole.half_reached_by_m), most = round_down_2(u.whole.most_reached_by_m);
                r << "By this run's reach test a shot of " << mm_rounded(half, 2) << " reaches half of it and one of "
                  << mm_rounded(most, 2) << " 90 % (now " << mm_rounded(u.shot_diameter_m, 3)
                  << "); a smaller shot dents less (dent size goes with the diameter), so check the time and the Almen intensity it "
                     "gives:\n\n      "
                  << sweep_command(x, "shot",
                                   vary_spec("shot.diameter", {fmt(u.shot_diameter_m * 1e3, 4) + " mm", fmt(half * 1e3, 3) + " mm",
                                                               fmt(most * 1e3, 3) + " mm"}))
                  << "\n\n";
            } else if (u.whole.most_reached_by_m > 0.0) {
                r << "A shot of " << mm_rounded(u.whole.most_reached_by_m, 2)
                  << " or smaller reaches 90 % of it by this run's reach test "
                     "(the mix's sizes are the scene's `shot.sizes`).\n";
            } else {
                r << "Most of it no shot reaches at all (it is closed off, e.g. a bore an axle fills): mark it as a region with "
                     "`exclude: true` if it is not to be peened, or change what closes it off.\n";
            }
        }
        // Too short to say: the run that gives the number.
        if (e.time.status == AreaForecast::Status::too_short && std::isfinite(e.time.run_for_s)) {
            ++changes;
            r << "- **Run longer to know " << c.name << "'s time everywhere**: this window (" << fmt(x.window.length_s(), 4)
              << " s) leaves the slowest areas with too few impacts; about " << fmt(std::ceil(e.time.run_for_s), 6)
              << " s gives a number.\n";
        }
    }
    if (changes == 0) return "";
    return "\n## What to change\n\nEach change is backed by a figure this run measured; each command tests it (a sweep compares "
           "its variants' times to " +
           goal + " everywhere with their intervals: `sweep/report.md`).\n\n" + r.str();
}

}  // namespace peensim
