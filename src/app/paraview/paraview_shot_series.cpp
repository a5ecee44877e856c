#include "app/paraview/paraview_shot_series.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "app/paraview/paraview_assembly.h"
#include "output/vtk_collection.h"
#include "output/vtp_writer.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// Steps are taken within this fraction of the interval of their time: the event scheme stops at
// the time asked, and a run's end may fall an ulp short of the last step's time.
constexpr double kStepTolerance = 1e-9;

std::string step_file(std::int64_t k) {
    char name[40];
    std::snprintf(name, sizeof name, "shots/shots_%06lld.vtp", static_cast<long long>(k));
    return name;
}

}  // namespace

ShotSeriesRecorder::ShotSeriesRecorder(const Model& model, const std::string& run_dir, double interval_s, const SimulationState& now)
    : model_(model),
      dir_((fs::path(run_dir) / kParaviewDirName).string()),
      interval_s_(interval_s),
      last_(static_cast<std::int64_t>(std::floor(model.duration_s / interval_s + kStepTolerance))),
      next_(std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(now.time.seconds() / interval_s - kStepTolerance)))) {
    for (std::size_t i = 0; i < model.components.size(); ++i)
        if (model.components[i].kinematics.moves()) moving_.push_back(static_cast<int>(i));
    fs::create_directories(fs::path(dir_) / "shots");
    write_due(now, kStepTolerance * interval_s_);
    flush();
}

double ShotSeriesRecorder::pause_at_s() const { return next_ <= last_ ? step_time(next_) : std::numeric_limits<double>::infinity(); }

void ShotSeriesRecorder::after_step(const Simulation& sim, const std::vector<ImpactRecord>& /*impacts*/) {
    const std::int64_t before = next_;
    write_due(sim.state(), kStepTolerance * interval_s_);
    if (next_ != before && std::chrono::steady_clock::now() - pvd_written_ >= std::chrono::duration<double>(kPvdRewriteInterval_s)) flush();
}

void ShotSeriesRecorder::write_due(const SimulationState& state, double tolerance_s) {
    while (next_ <= last_ && step_time(next_) <= state.time.seconds() + tolerance_s) {
        const auto start = std::chrono::steady_clock::now();
        write_step(state, next_);
        ++next_;
        write_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
}

void ShotSeriesRecorder::flush() {
    std::vector<TimeStepFile> steps;
    steps.reserve(static_cast<std::size_t>(next_));
    for (std::int64_t k = 0; k < next_; ++k) steps.push_back({step_time(k), step_file(k)});
    const auto start = std::chrono::steady_clock::now();
    write_pvd((fs::path(dir_) / kShotSeriesFileName).string(), steps, Durability::process_crash);
    pvd_written_ = std::chrono::steady_clock::now();
    write_seconds_ += std::chrono::duration<double>(pvd_written_ - start).count();
}

std::string ShotSeriesRecorder::finish(const SimulationState& state) {
    write_due(state, kStepTolerance * interval_s_);
    flush();
    char note[160];
    std::snprintf(note, sizeof note, "%lld steps, every %g s; writing took %.2f s", static_cast<long long>(next_), interval_s_,
                  write_seconds_);
    return (fs::path(dir_) / kShotSeriesFileName).string() + " (" + note + ")";
}

// The state is `behind` seconds past t_k (time stepping; 0 for the event-driven schemes, which
// stop at t_k): the shot are moved back along their parabola, p(t) = p(t + d) - v(t + d) d + g d^2 / 2.
void ShotSeriesRecorder::write_step(const SimulationState& state, std::int64_t k) {
    const double t = step_time(k);
    const double behind = std::max(0.0, state.time.seconds() - t);  // s
    const ShotArrays& s = state.shots;
    const Vec3& g = model_.gravity_m_per_s2;
    auto position = [&](std::size_t i) { return Vec3(s.position(i) - s.velocity(i) * behind + 0.5 * g * behind * behind); };
    auto velocity = [&](std::size_t i) { return Vec3(s.velocity(i) - g * behind); };

    std::vector<FieldValue> field_data = {{"time_s", std::vector<double>{t}}};
    for (int m : moving_) {
        const Component& c = model_.components[static_cast<std::size_t>(m)];
        const Kinematics& kin = c.kinematics;
        if (kin.kind == Kinematics::Kind::vibrating)
            field_data.push_back({c.name + "_displacement_m", std::vector<double>{kin.displacement(state.time, -behind)}});
        else
            field_data.push_back(
                {c.name + "_angle_rad",
                 std::vector<double>{2.0 * M_PI * state.time.cycle_fraction(kin.omega_rad_per_s / (2.0 * M_PI), -behind)}});
    }
    const auto n = static_cast<std::uint64_t>(std::count(s.active.begin(), s.active.end(), 1));
    PolyDataLayout layout{n,  PolyDataLayout::Cells::vertices,
                          0,  {{"shot", VtkType::int64, 1}, {"v_mps", VtkType::float64, 3}, {"speed_mps"}, {"shot_diameter_m"}},
                          {}, std::move(field_data)};
    PolyDataWriter out((fs::path(dir_) / step_file(k)).string(), std::move(layout), Durability::process_crash);
    // One pass per array, in the file's order: nothing is gathered in memory.
    for (std::size_t i = 0; i < s.size(); ++i)
        if (s.active[i]) out.add_point(position(i));
    for (std::size_t i = 0; i < s.size(); ++i)
        if (s.active[i]) out.add(static_cast<std::int64_t>(i));
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (!s.active[i]) continue;
        const Vec3 v = velocity(i);
        out.add(std::span<const double>(v.data(), 3));
    }
    for (std::size_t i = 0; i < s.size(); ++i)
        if (s.active[i]) out.add(velocity(i).norm());
    for (std::size_t i = 0; i < s.size(); ++i)
        if (s.active[i]) out.add(2.0 * model_.shot_sizes[s.size_class[i]].radius_m);
    out.finish();
}

}  // namespace peensim
