#include "app/run/round_runs.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>

#include "app/run/replica_runs.h"
#include "app/run/summary_builder.h"
#include "engine/run_loop.h"
#include "engine/simulation.h"

namespace peensim {

namespace fs = std::filesystem;

namespace {

std::string slot_spill_name(int replica, int round) {
    return std::string(kReplicaSpillDirectory) + "/replica-" + std::to_string(replica) + ".round-" + std::to_string(round) + ".impacts.bin";
}

// One replica's listener over its slots: spills the impacts of the current slot, moved to their
// place in the run; an impact past the slot's end (time stepping's last step may pass it) is
// kept for the next slot. It pauses at its first slot's start to take the counts there.
class SlotListener final : public RunListener {
public:
    SlotListener() { buffer_.reserve(kBatch); }

    void begin(const ReplicaWindow& w, int round, const std::string& run_dir) {
        slot_ = SlotResult{};
        slot_.window = w;
        slot_.spill = (fs::path(run_dir) / slot_spill_name(w.replica, round)).string();
        slot_.impacts_at_start = last_impacts_;  // a later slot starts where the last ended
        slot_.slow_contacts_at_start = last_slow_;
        spill_.open(slot_.spill, std::ios::binary | std::ios::trunc);
        if (!spill_) throw std::runtime_error("cannot write " + slot_.spill);
        std::vector<ImpactRecord> carried;
        carried.swap(carry_);
        for (const ImpactRecord& r : carried) take(r);
    }

    double pause_at_s() const override { return started_ ? std::numeric_limits<double>::infinity() : slot_.window.log_from_s; }

    void after_step(const Simulation& sim, const std::vector<ImpactRecord>& impacts) override {
        for (const ImpactRecord& r : impacts) take(r);
        if (!started_ && !(sim.state().time.seconds() < slot_.window.log_from_s)) {
            started_ = true;
            slot_.impacts_at_start = impact_counts(sim.state());
            slot_.slow_contacts_at_start = slow_counts(sim.state());
        }
    }

    SlotResult end(const Simulation& sim) {
        flush();
        spill_.close();
        if (!spill_) throw std::runtime_error("cannot write a replica's impacts (disk full?)");
        slot_.impacts_at_end = last_impacts_ = impact_counts(sim.state());
        slot_.slow_contacts_at_end = last_slow_ = slow_counts(sim.state());
        return std::move(slot_);
    }

private:
    void take(const ImpactRecord& r) {
        if (!(r.time_s >= slot_.window.log_from_s)) return;  // the warm-up's
        if (!(r.time_s < slot_.window.run_to_s)) {
            carry_.push_back(r);
            return;
        }
        ImpactRecord moved = r;
        moved.time_s += slot_.window.shift_s;
        buffer_.push_back(moved);
        ++slot_.logged_impacts;
        if (buffer_.size() == kBatch) flush();
    }
    void flush() {
        spill_.write(reinterpret_cast<const char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size() * sizeof(ImpactRecord)));
        if (!spill_) throw std::runtime_error("cannot write a replica's impacts (disk full?)");
        buffer_.clear();
    }

    static constexpr std::size_t kBatch = 4096;
    SlotResult slot_;
    std::vector<std::uint64_t> last_impacts_, last_slow_;  // at the last slot's end
    std::ofstream spill_;
    std::vector<ImpactRecord> buffer_;
    std::vector<ImpactRecord> carry_;
    bool started_ = false;
};

}  // namespace

struct RoundRuns::Worker {
    std::vector<SlotResult> slots;  // guarded by mutex_: its whole slots, round by round
    bool ended = false;             // guarded by mutex_
    std::exception_ptr failure;     // guarded by mutex_
    RoundReplicaResult result;      // its thread's until ended
};

RoundRuns::RoundRuns(std::shared_ptr<const Model> model, RoundPlan plan, std::vector<InitialShots> shots, std::string run_dir,
                     std::vector<int> slots)
    : RoundRunner(std::move(run_dir)),
      model_(std::move(model)),
      plan_(std::move(plan)),
      shots_(std::move(shots)),
      slots_(std::move(slots)) {
    if (shots_.size() + 1 != static_cast<std::size_t>(plan_.replicas()))
        throw std::invalid_argument("RoundRuns: one placement per replica but the run's own");
    fs::create_directories(fs::path(dir_) / kReplicaSpillDirectory);
    for (std::size_t i = 0; i < shots_.size(); ++i) workers_.push_back(std::make_unique<Worker>());
    threads_.reserve(shots_.size());
    for (std::size_t i = 0; i < shots_.size(); ++i) threads_.emplace_back([this, i] { run_one(i); });
}

RoundRuns::~RoundRuns() {
    stop();
    for (std::thread& t : threads_)
        if (t.joinable()) t.join();
}

void RoundRuns::go(int round) {
    const std::lock_guard<std::mutex> lock(mutex_);
    allowed_round_ = std::max(allowed_round_, round);
    changed_.notify_all();
}

void RoundRuns::stop() {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true, std::memory_order_relaxed);
    changed_.notify_all();
}

bool RoundRuns::may_run(int round) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return allowed_round_ >= round || stop_.load(std::memory_order_relaxed); });
    return !stop_.load(std::memory_order_relaxed);
}

void RoundRuns::publish(std::size_t i, std::optional<SlotResult> slot, bool ended) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (slot) workers_[i]->slots.push_back(std::move(*slot));
    workers_[i]->ended = workers_[i]->ended || ended;
    changed_.notify_all();
}

RoundReplicaResult run_round_replica(std::shared_ptr<const Model> model, const RoundPlan& plan, int replica, const InitialShots& shots,
                                     const std::string& run_dir, const std::vector<int>& slots, const std::function<bool(int)>& may_run,
                                     const std::function<void(SlotResult)>& publish, const std::function<bool()>& stop) {
    const auto started = std::chrono::steady_clock::now();
    RoundReplicaResult result;
    result.replica = replica;
    result.seed = plan.seeds.at(static_cast<std::size_t>(replica));
    result.first_from_s = plan.first_from_s.at(static_cast<std::size_t>(replica));
    Simulation sim(model, shots);
    SlotListener listener;
    RunLoop loop(sim);
    loop.add(listener);
    bool finished = true;
    for (int round = 0; may_run(round); ++round) {
        ReplicaWindow slot = plan.slot(round, replica);
        const double cap_s = model->duration_s - slot.shift_s;  // s, its own time at the run's duration
        if (!(slot.log_from_s < cap_s)) break;
        slot.run_to_s = std::min(slot.run_to_s, cap_s);
        listener.begin(slot, round, run_dir);
        sim.end_at(slot.run_to_s);
        finished = loop.run([&](std::uint64_t) { return stop(); });
        SlotResult done = listener.end(sim);
        if (!finished) break;  // stopped within the slot: not a whole one
        publish(std::move(done));
    }
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::size_t logged = 0;
    for (const int s : slots) logged += s >= 0 ? 1 : 0;
    result.summary = build_summary(sim, "", std::vector<SpeedHistogram>(logged), wall_s, finished);
    result.lost = sim.state().lost;
    result.health = sim.state().health;
    return result;
}

void RoundRuns::run_one(std::size_t i) {
    Worker& w = *workers_[i];
    try {
        w.result = run_round_replica(
            model_, plan_, static_cast<int>(i) + 1, shots_[i], dir_, slots_, [this](int round) { return may_run(round); },
            [this, i](SlotResult slot) { publish(i, std::move(slot), false); }, [this] { return stop_.load(std::memory_order_relaxed); });
    } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex_);
        w.failure = std::current_exception();
        stop_.store(true, std::memory_order_relaxed);  // the run cannot go on without it
    }
    publish(i, std::nullopt, true);
}

std::vector<SlotResult> RoundRuns::wait_round(int round) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto r = static_cast<std::size_t>(round);
    changed_.wait(lock, [&] {
        for (const auto& w : workers_)
            if (!w->ended && w->slots.size() <= r) return false;
        return true;
    });
    for (const auto& w : workers_)
        if (w->failure) std::rethrow_exception(w->failure);
    std::vector<SlotResult> out;
    for (const auto& w : workers_) {
        if (w->slots.size() <= r) break;
        out.push_back(w->slots[r]);
    }
    return out;
}

std::vector<RoundReplicaResult> RoundRuns::finish() {
    stop();
    for (std::thread& t : threads_)
        if (t.joinable()) t.join();
    threads_.clear();
    std::vector<RoundReplicaResult> out;
    for (const auto& w : workers_) {
        if (w->failure) std::rethrow_exception(w->failure);
        out.push_back(w->result);
    }
    return out;
}

void RoundRunner::discard() const {
    std::error_code ignored;
    fs::remove_all(fs::path(dir_) / kReplicaSpillDirectory, ignored);
}

void add_slot_counts(RunSummary& s, const std::vector<std::uint64_t>& impacts, const std::vector<std::uint64_t>& slow_contacts) {
    for (std::size_t i = 0; i < s.impacts_per_component.size() && i < impacts.size(); ++i) s.impacts_per_component[i].count += impacts[i];
    for (std::size_t i = 0; i < s.slow_contacts_per_component.size() && i < slow_contacts.size(); ++i)
        s.slow_contacts_per_component[i].count += slow_contacts[i];
}

void merge_round_summaries(RunSummary& s, const RoundPlan& plan, std::vector<RunSummary::Replicas::Window> slots,
                           const std::vector<RoundReplicaResult>& results) {
    for (const RoundReplicaResult& r : results) add_replica_work(s, r.summary);
    RunSummary::Replicas info;
    info.pilot_s = plan.pilot_s;
    info.warm_up_s = plan.warm_up_s;
    info.turn_s = plan.turn_s;
    info.round_s = plan.round_s;
    info.replica_count = plan.replicas();
    info.windows = std::move(slots);
    s.shot_steps_per_s = s.wall_time_s > 0.0 ? static_cast<double>(s.shot_steps) / s.wall_time_s : 0.0;
    s.sim_seconds_per_wall_second = s.wall_time_s > 0.0 ? s.simulated_time_s / s.wall_time_s : 0.0;
    s.replicas = std::move(info);
}

}  // namespace peensim
