#include "app/run/replica_runs.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "app/run/summary_builder.h"
#include "engine/run_loop.h"
#include "engine/simulation.h"

namespace peensim {

namespace fs = std::filesystem;

std::vector<std::uint64_t> impact_counts(const SimulationState& state) {
    std::vector<std::uint64_t> out{state.shot_shot_impacts};
    out.insert(out.end(), state.impacts_per_component.begin(), state.impacts_per_component.end());
    return out;
}

std::vector<std::uint64_t> slow_counts(const SimulationState& state) {
    std::vector<std::uint64_t> out{state.shot_shot_slow_contacts};
    out.insert(out.end(), state.slow_contacts_per_component.begin(), state.slow_contacts_per_component.end());
    return out;
}

void replay_spill(const std::string& path, const std::function<void(std::span<const ImpactRecord>)>& sink) {
    {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw std::runtime_error("cannot read " + path);
        std::vector<ImpactRecord> batch(4096);
        while (in) {
            in.read(reinterpret_cast<char*>(batch.data()), static_cast<std::streamsize>(batch.size() * sizeof(ImpactRecord)));
            const auto n = static_cast<std::size_t>(in.gcount()) / sizeof(ImpactRecord);
            if (n > 0) sink(std::span<const ImpactRecord>(batch.data(), n));
        }
    }
    fs::remove(path);
}

namespace {

// One replica's listener: pauses exactly at its window's start (the event schemes stop there) to
// take the counts, then spills the window's impacts, moved to their place in the run.
class WindowListener final : public RunListener {
public:
    WindowListener(const ReplicaWindow& w, ReplicaResult& result, const std::vector<int>& slots, const std::string& spill_path,
                   const std::function<bool()>& stop)
        : w_(w), result_(result), slots_(slots), spill_(spill_path, std::ios::binary | std::ios::trunc), stop_(stop) {
        if (!spill_) throw std::runtime_error("cannot write " + spill_path);
        buffer_.reserve(kBatch);
    }
    double pause_at_s() const override { return started_ ? std::numeric_limits<double>::infinity() : w_.log_from_s; }
    void after_step(const Simulation& sim, const std::vector<ImpactRecord>& impacts) override {
        for (const ImpactRecord& r : impacts) {
            if (!(r.time_s >= w_.log_from_s) || !(r.time_s < w_.run_to_s)) continue;
            ImpactRecord moved = r;
            moved.time_s += w_.shift_s;
            buffer_.push_back(moved);
            result_.speeds[static_cast<std::size_t>(slots_[static_cast<std::size_t>(r.component)])].add(r.vn_in_m_per_s);
            ++result_.logged_impacts;
            if (buffer_.size() == kBatch) flush();
        }
        if (!started_ && !(sim.state().time.seconds() < w_.log_from_s)) {
            started_ = true;
            result_.impacts_at_window_start = impact_counts(sim.state());
            result_.slow_contacts_at_window_start = slow_counts(sim.state());
        }
    }
    void flush() {
        spill_.write(reinterpret_cast<const char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size() * sizeof(ImpactRecord)));
        if (!spill_) throw std::runtime_error("cannot write a replica's impacts (disk full?)");
        buffer_.clear();
    }
    void close() {
        flush();
        spill_.close();
        if (!spill_) throw std::runtime_error("cannot write a replica's impacts (disk full?)");
    }
    bool stopping() const { return stop_(); }

private:
    static constexpr std::size_t kBatch = 4096;
    const ReplicaWindow& w_;
    ReplicaResult& result_;
    const std::vector<int>& slots_;
    std::ofstream spill_;
    const std::function<bool()>& stop_;
    std::vector<ImpactRecord> buffer_;
    bool started_ = false;
};

}  // namespace

std::vector<int> logged_slots(const Model& model) {
    std::vector<int> slots;
    int next = 0;
    for (const Component& c : model.components) slots.push_back(c.logged ? next++ : -1);
    return slots;
}

std::string replica_spill_name(int replica) {
    return std::string(kReplicaSpillDirectory) + "/replica-" + std::to_string(replica) + ".impacts.bin";
}

ReplicaResult run_replica(std::shared_ptr<const Model> model, const ReplicaWindow& w, const InitialShots& shots, const std::string& run_dir,
                          const std::vector<int>& slots, const std::function<bool()>& stop) {
    const auto started = std::chrono::steady_clock::now();
    ReplicaResult result;
    result.window = w;
    std::size_t logged = 0;
    for (const int s : slots) logged += s >= 0 ? 1 : 0;
    result.speeds.assign(logged, SpeedHistogram());
    Simulation sim(std::move(model), shots);
    sim.end_at(w.run_to_s);
    WindowListener listener(w, result, slots, (fs::path(run_dir) / replica_spill_name(w.replica)).string(), stop);
    RunLoop loop(sim);
    loop.add(listener);
    const bool finished = loop.run([&](std::uint64_t) { return listener.stopping(); });
    listener.close();
    result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    result.summary = build_summary(sim, "", result.speeds, result.wall_s, finished);
    result.lost = sim.state().lost;
    result.health = sim.state().health;
    if (result.impacts_at_window_start.empty()) {  // stopped before its window
        result.impacts_at_window_start = impact_counts(sim.state());
        result.slow_contacts_at_window_start = slow_counts(sim.state());
    }
    return result;
}

ReplicaRunner::ReplicaRunner(std::vector<ReplicaWindow> windows, std::string run_dir)
    : windows_(std::move(windows)), dir_(std::move(run_dir)) {
    fs::create_directories(fs::path(dir_) / kReplicaSpillDirectory);
}

void ReplicaRunner::replay(std::size_t k, const std::function<void(std::span<const ImpactRecord>)>& sink) const {
    replay_spill((fs::path(dir_) / replica_spill_name(windows_.at(k).replica)).string(), sink);
}

void ReplicaRunner::discard() const {
    std::error_code ignored;
    fs::remove_all(fs::path(dir_) / kReplicaSpillDirectory, ignored);
}

ReplicaRuns::ReplicaRuns(std::shared_ptr<const Model> model, std::vector<ReplicaWindow> windows, std::vector<InitialShots> shots,
                         std::string run_dir, std::vector<int> slots)
    : ReplicaRunner(std::move(windows), std::move(run_dir)), model_(std::move(model)), shots_(std::move(shots)), slots_(std::move(slots)) {
    if (shots_.size() != windows_.size()) throw std::invalid_argument("ReplicaRuns: one placement per window");
    results_.resize(windows_.size());
    failures_.resize(windows_.size());
    threads_.reserve(windows_.size());
    for (std::size_t k = 0; k < windows_.size(); ++k) threads_.emplace_back([this, k] { run_one(k); });
}

ReplicaRuns::~ReplicaRuns() {
    stop();
    for (std::thread& t : threads_)
        if (t.joinable()) t.join();
}

void ReplicaRuns::stop() { stop_.store(true, std::memory_order_relaxed); }

void ReplicaRuns::run_one(std::size_t k) {
    try {
        results_[k] = run_replica(model_, windows_[k], shots_[k], dir_, slots_, [this] { return stop_.load(std::memory_order_relaxed); });
    } catch (...) {
        failures_[k] = std::current_exception();
        stop();  // the others are of no use without it
    }
}

std::vector<ReplicaResult> ReplicaRuns::wait() {
    for (std::thread& t : threads_)
        if (t.joinable()) t.join();
    threads_.clear();
    for (const std::exception_ptr& f : failures_)
        if (f) std::rethrow_exception(f);
    return results_;
}

void add_replica_work(RunSummary& s, const RunSummary& replica) {
    for (std::size_t i = 0; i < s.health_counters.size() && i < replica.health_counters.size(); ++i)
        s.health_counters[i].count += replica.health_counters[i].count;
    for (std::size_t i = 0; i < s.stage_times.size() && i < replica.stage_times.size(); ++i)
        s.stage_times[i].seconds += replica.stage_times[i].seconds;
    s.steps += replica.steps;
    s.shot_steps += replica.shot_steps;
    s.shot_lost += replica.shot_lost;
}

void merge_replica_summaries(RunSummary& s, const ReplicaPlan& plan, const std::vector<ReplicaResult>& results,
                             std::uint64_t own_logged_impacts) {
    RunSummary::Replicas info;
    info.pilot_s = plan.pilot_s;
    info.warm_up_s = plan.warm_up_s;
    info.turn_s = plan.turn_s;
    const ReplicaWindow& own = plan.windows.front();
    info.windows.push_back({0, own.seed, 0.0, own.run_to_s, 0.0, own_logged_impacts});
    for (const ReplicaResult& r : results) {
        const RunSummary& c = r.summary;
        for (std::size_t i = 0; i < s.impacts_per_component.size() && i < c.impacts_per_component.size(); ++i)
            s.impacts_per_component[i].count += c.impacts_per_component[i].count - r.impacts_at_window_start.at(i);
        for (std::size_t i = 0; i < s.slow_contacts_per_component.size() && i < c.slow_contacts_per_component.size(); ++i)
            s.slow_contacts_per_component[i].count += c.slow_contacts_per_component[i].count - r.slow_contacts_at_window_start.at(i);
        add_replica_work(s, c);
        const ReplicaWindow& w = r.window;
        info.windows.push_back({w.replica, w.seed, w.window_start_s(), w.window_end_s(), w.log_from_s, r.logged_impacts});
    }
    if (!results.empty()) {
        // The chamber at the run's end is the last window's.
        s.shots_in_flight = results.back().summary.shots_in_flight;
        s.shots_at_rest = results.back().summary.shots_at_rest;
        s.simulated_time_s = results.back().window.window_end_s();
    }
    s.shot_steps_per_s = s.wall_time_s > 0.0 ? static_cast<double>(s.shot_steps) / s.wall_time_s : 0.0;
    s.sim_seconds_per_wall_second = s.wall_time_s > 0.0 ? s.simulated_time_s / s.wall_time_s : 0.0;
    s.replicas = std::move(info);
}

}  // namespace peensim
