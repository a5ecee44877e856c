#include "output/progress_reporter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace peensim {
namespace {

constexpr int kBarWidth = 20;  // chars

// "1h02m03s", "2m05s", "7s"; "--" when unknown.
void format_duration(char* out, std::size_t size, double seconds) {
    if (!std::isfinite(seconds) || seconds < 0.0) {
        std::snprintf(out, size, "--");
        return;
    }
    const auto total = static_cast<long long>(std::llround(seconds));
    const long long h = total / 3600;
    const long long m = (total / 60) % 60;
    const long long s = total % 60;
    if (h > 0) {
        std::snprintf(out, size, "%lldh%02lldm%02llds", h, m, s);
    } else if (m > 0) {
        std::snprintf(out, size, "%lldm%02llds", m, s);
    } else {
        std::snprintf(out, size, "%llds", s);
    }
}

}  // namespace

ProgressReporter::ProgressReporter(std::ostream& out, bool enabled) : out_(out), enabled_(enabled) {}

void ProgressReporter::update(double sim_time_s, double duration_s, std::uint64_t impacts) {
    if (!enabled_ || finished_) return;
    sim_time_s_ = sim_time_s;
    duration_s_ = duration_s;
    impacts_ = impacts;
    const auto now = Clock::now();
    if (!started_) {
        started_ = true;
        first_update_ = now;
        first_sim_time_s_ = sim_time_s;
        first_impacts_ = impacts;
    } else if (now < next_draw_) {
        return;
    }
    draw(now);
    next_draw_ = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / kProgressRedrawsPerSecond));
}

void ProgressReporter::finish() {
    if (!enabled_ || finished_ || !started_) return;
    finished_ = true;
    draw(Clock::now());
    out_ << '\n' << std::flush;
}

void ProgressReporter::draw(Clock::time_point now) {
    const double fraction = duration_s_ > 0.0 ? std::clamp(sim_time_s_ / duration_s_, 0.0, 1.0) : 0.0;
    const double wall_s = std::chrono::duration<double>(now - first_update_).count();
    const double sim_done_s = sim_time_s_ - first_sim_time_s_;
    const double eta_s = sim_done_s > 0.0 ? wall_s * std::max(0.0, duration_s_ - sim_time_s_) / sim_done_s : -1.0;
    const double impacts_per_s = wall_s > 0.0 ? static_cast<double>(impacts_ - first_impacts_) / wall_s : 0.0;

    char bar[kBarWidth + 1];
    const int filled = static_cast<int>(fraction * kBarWidth);
    for (int i = 0; i < kBarWidth; ++i) bar[i] = i < filled ? '#' : '.';
    bar[kBarWidth] = '\0';
    char eta[32];
    format_duration(eta, sizeof eta, eta_s);

    char line[256];
    const int length = std::snprintf(line, sizeof line, "[%s] %5.1f%%  sim %.4f/%.4f s  ETA %s  %.0f impacts/s", bar, 100.0 * fraction,
                                     sim_time_s_, duration_s_, eta, impacts_per_s);
    const int shown = std::clamp(length, 0, static_cast<int>(sizeof line) - 1);
    out_ << '\r';
    out_.write(line, shown);
    for (int i = shown; i < last_line_length_; ++i) out_.put(' ');
    out_.flush();
    last_line_length_ = shown;
}

}  // namespace peensim
