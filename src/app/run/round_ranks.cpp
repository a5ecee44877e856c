#include "app/run/round_ranks.h"

#include <filesystem>
#include <stdexcept>

#include "app/exit_codes.h"
#include "app/run/rank_messages.h"
#include "app/run/replica_result_codec.h"
#include "app/run/replica_runs.h"

namespace peensim {

namespace fs = std::filesystem;

RoundRanks::RoundRanks(const RoundPlan& plan, std::string run_dir) : RoundRunner(std::move(run_dir)) {
    if (plan.replicas() != rank_count()) throw std::invalid_argument("RoundRanks: one replica a rank");
    if (plan_went_out()) throw std::logic_error("RoundRanks: the plan went out already");
    fs::create_directories(fs::path(dir_) / kReplicaSpillDirectory);  // before the plan: the ranks look for it
    ranks_.resize(static_cast<std::size_t>(plan.replicas() - 1));
    const std::string bytes = encode_round_plan(plan);
    for (std::size_t k = 0; k < ranks_.size(); ++k) send_bytes(bytes, static_cast<int>(k) + 1, kTagPlan);
    mark_plan_sent();
}

RoundRanks::~RoundRanks() {
    if (finished_) return;
    try {
        finish();
    } catch (const std::exception&) {}  // a failing run: its own error is the one reported
}

bool RoundRanks::take_message(std::size_t k) {
    int tag = 0;
    std::string bytes;
    if (!receive_next(static_cast<int>(k) + 1, tag, bytes)) return false;
    Rank& r = ranks_[k];
    if (tag == kTagSlot) {
        r.slots.push_back(decode_slot_result(bytes));
    } else if (tag == kTagResult) {
        r.ended = true;
        if (!bytes.empty() && bytes.front() == 'R')
            r.result = decode_round_replica_result(std::string_view(bytes).substr(1));
        else
            r.failure = bytes.size() > 2 ? bytes.substr(2) : "replica " + std::to_string(k + 1) + ": no answer";
    } else {
        throw std::runtime_error("replica " + std::to_string(k + 1) + " (MPI rank " + std::to_string(k + 1) +
                                 "): an unexpected message (tag " + std::to_string(tag) + ")");
    }
    return true;
}

void RoundRanks::wait_until(std::size_t k, const std::function<bool(const Rank&)>& done) {
    while (!done(ranks_[k]))
        if (!take_message(k)) pause_briefly();
}

std::vector<SlotResult> RoundRanks::wait_round(int round) {
    const auto r = static_cast<std::size_t>(round);
    for (std::size_t k = 0; k < ranks_.size(); ++k) wait_until(k, [&](const Rank& x) { return x.ended || x.slots.size() > r; });
    for (const Rank& x : ranks_)
        if (!x.failure.empty()) throw std::runtime_error(x.failure);
    std::vector<SlotResult> out;
    for (const Rank& x : ranks_) {
        if (x.slots.size() <= r) break;
        out.push_back(x.slots[r]);
    }
    return out;
}

void RoundRanks::go(int round) {
    if (stopped_) return;
    for (std::size_t k = 0; k < ranks_.size(); ++k)
        if (!ranks_[k].ended) send_bytes(std::to_string(round), static_cast<int>(k) + 1, kTagGo);
}

void RoundRanks::stop() {
    if (stopped_ || finished_) return;
    stopped_ = true;
    // Also to a rank that ended: it takes every message until rank 0's bye.
    for (std::size_t k = 0; k < ranks_.size(); ++k) send_bytes("", static_cast<int>(k) + 1, kTagStop);
}

std::vector<RoundReplicaResult> RoundRanks::finish() {
    if (finished_) throw std::logic_error("RoundRanks: finished already");
    stop();
    std::string failure;
    std::vector<RoundReplicaResult> out;
    for (std::size_t k = 0; k < ranks_.size(); ++k) {
        try {
            wait_until(k, [](const Rank& x) { return x.ended; });
        } catch (const std::exception& e) {
            ranks_[k].ended = true;
            ranks_[k].failure = e.what();
        }
        send_bytes("", static_cast<int>(k) + 1, kTagBye);
        if (ranks_[k].result) out.push_back(*ranks_[k].result);
        if (failure.empty() && !ranks_[k].failure.empty()) failure = ranks_[k].failure;
    }
    finished_ = true;
    if (!failure.empty()) throw std::runtime_error(failure);
    return out;
}

int run_round_rank(const RoundRank& rank) {
    bool told_to_stop = false;
    int allowed_round = 0;  // round 0 starts at once
    // Whatever rank 0 sent so far: a stop, the rounds it let run.
    const auto take_messages = [&] {
        int tag = 0;
        std::string bytes;
        while (receive_next(0, tag, bytes)) {
            if (tag == kTagStop) told_to_stop = true;
            if (tag == kTagGo) allowed_round = std::max(allowed_round, std::stoi(bytes));
        }
    };
    std::string failure = rank.failure;
    std::string answer;
    if (failure.empty()) {
        try {
            const RoundPlan plan = decode_round_plan(rank.plan_bytes);
            if (plan.replicas() != rank_count()) throw std::runtime_error("a plan of " + std::to_string(plan.replicas()) + " replicas");
            std::uint64_t steps = 0;
            const RoundReplicaResult result = run_round_replica(
                rank.model, plan, rank.rank, rank.shots, rank.run_dir, rank.slots,
                [&](int round) {
                    for (;;) {
                        take_messages();
                        if (told_to_stop) return false;
                        if (allowed_round >= round) return true;
                        pause_briefly();
                    }
                },
                [&](const SlotResult& slot) { send_bytes(encode_slot_result(slot), 0, kTagSlot); },
                [&] {
                    if (++steps % 64 == 0) take_messages();
                    return told_to_stop;
                });
            answer = "R" + encode_round_replica_result(result);
        } catch (const std::exception& e) {
            failure = e.what();
        }
    }
    if (!failure.empty()) answer = "E replica " + std::to_string(rank.rank) + " (MPI rank " + std::to_string(rank.rank) + "): " + failure;
    send_bytes(answer, 0, kTagResult);
    // Until rank 0 says the result is in, its go and stop messages may still be on their way:
    // taken, so that every message is matched before MPI_Finalize.
    for (;;) {
        int tag = 0;
        std::string bytes;
        if (!receive_next(0, tag, bytes)) {
            pause_briefly();
            continue;
        }
        if (tag == kTagBye) return kExitOk;
    }
}

}  // namespace peensim
