#include "app/run/replica_ranks.h"

#include <filesystem>
#include <ostream>
#include <stdexcept>

#include <mpi.h>

#include "app/check/setup_checks.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/report_errors.h"
#include "app/run/rank_messages.h"
#include "app/run/replica_result_codec.h"
#include "app/run/round_ranks.h"
#include "common/random.h"
#include "model/model.h"
#include "model/shot_placement.h"
#include "scene/scene_parser.h"

namespace peensim {

namespace {

namespace fs = std::filesystem;

// Rank k: its replica, quietly; whatever happens it answers rank 0's plan and ends on its word.
int run_replica_rank(const RunOptions& options, int rank) {
    // Ctrl-C reaches every rank from the launcher: caught from the start, so that a rank waiting for
    // the plan is not ended by it (rank 0 checkpoints and tells the others).
    const StopRequest interrupt({}, "");
    std::shared_ptr<const Model> model;
    InitialShots shots;
    std::string dir;
    std::vector<int> slots;
    std::string failure;
    try {
        const SceneDescription scene = parse_scene(options.scene_path, options.scene_text, options.overrides);
        model = compile_model(scene);
        std::ostream quiet(nullptr);
        SetupCheck setup = check_setup(*model, options.strict, quiet);
        // The load `--replicas` on threads gives replica `rank` (app/run/run_job.cpp): the same bytes.
        if (setup.cavity) {
            Random rng(replica_seed(model->seed, rank));
            shots = place_shots(*model, *setup.cavity, rng);
        }
        dir = run_output_directory(options, scene);
        slots = logged_slots(*model);
    } catch (const std::exception& e) {
        failure = e.what();  // rank 0 reads the same scene and says what is wrong with it
    }
    const std::string plan_bytes = receive_bytes(0, kTagPlan);
    const bool rounds = is_round_plan(plan_bytes);
    const ReplicaPlan plan = rounds ? ReplicaPlan{} : decode_replica_plan(plan_bytes);
    if (!rounds && plan.windows.empty()) return kExitOk;  // rank 0 goes on alone, or stopped before a plan
    // Rank 0 made the spills' folder before it sent the plan: a rank that cannot see it would spill
    // where rank 0 never reads.
    if (failure.empty() && !fs::is_directory(fs::path(dir) / kReplicaSpillDirectory))
        failure = "cannot see the run's directory " + dir + " as rank 0 made it (no " + std::string(kReplicaSpillDirectory) +
                  "/ in it): every rank must see the run's directory, on a shared file system and from the same working directory";
    if (rounds) return run_round_rank(RoundRank{model, shots, dir, slots, failure, plan_bytes, rank});
    std::string answer;
    if (failure.empty()) {
        try {
            bool told_to_stop = false;
            std::uint64_t steps = 0;
            const ReplicaResult result = run_replica(model, plan.windows.at(static_cast<std::size_t>(rank)), shots, dir, slots, [&] {
                if (!told_to_stop && ++steps % 64 == 0 && message_waiting(0, kTagStop)) {
                    receive_int(0, kTagStop);
                    told_to_stop = true;
                }
                return told_to_stop || interrupt.requested();
            });
            answer = "R" + encode_replica_result(result);
        } catch (const std::exception& e) {
            failure = e.what();
        }
    }
    if (!failure.empty()) answer = "E replica " + std::to_string(rank) + " (MPI rank " + std::to_string(rank) + "): " + failure;
    send_bytes(answer, 0, kTagResult);
    // Until rank 0 says the result is in, a stop it sent may still be on its way: taken, so that
    // every message is matched before MPI_Finalize.
    for (;;) {
        if (message_waiting(0, kTagStop)) receive_int(0, kTagStop);
        if (message_waiting(0, kTagBye)) {
            receive_int(0, kTagBye);
            return kExitOk;
        }
        pause_briefly();
    }
}

}  // namespace

int run_replicas_over_mpi(const RunOptions& options, std::ostream& out, std::ostream& err) {
    MPI_Init(nullptr, nullptr);
    struct Finalize {
        ~Finalize() { MPI_Finalize(); }
    } finalize;
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    const int size = rank_count();
    if (size != options.replicas) {
        if (rank == 0)
            err << "error: --replicas " << options.replicas << " in an MPI job of " << size << " ranks: expected --replicas " << size
                << " (one replica a rank), or mpirun -n " << options.replicas << "\n";
        return kExitInputError;
    }
    if (rank != 0) return run_replica_rank(options, rank);
    RunOptions own = options;
    own.replica_ranks = true;
    const int code = report_errors(err, [&] { return run_scene(own, out, err); });
    release_replica_ranks();
    return code;
}

ReplicaRanks::ReplicaRanks(std::vector<ReplicaWindow> windows, std::string run_dir)
    : ReplicaRunner(std::move(windows), std::move(run_dir)) {
    if (static_cast<int>(windows_.size()) + 1 != rank_count()) throw std::invalid_argument("ReplicaRanks: one window a rank but rank 0");
    if (plan_went_out()) throw std::logic_error("ReplicaRanks: the plan went out already");
    ReplicaPlan plan;
    plan.windows.push_back({});  // replica 0's: rank 0's own, not read by the others
    plan.windows.insert(plan.windows.end(), windows_.begin(), windows_.end());
    const std::string bytes = encode_replica_plan(plan);
    for (std::size_t k = 0; k < windows_.size(); ++k) send_bytes(bytes, static_cast<int>(k) + 1, kTagPlan);
    mark_plan_sent();
}

ReplicaRanks::~ReplicaRanks() {
    if (collected_) return;
    stop();
    try {
        wait();
    } catch (const std::exception&) {}  // a failing run: its own error is the one reported
}

void ReplicaRanks::stop() {
    if (stopped_ || collected_) return;
    stopped_ = true;
    for (std::size_t k = 0; k < windows_.size(); ++k) send_int(1, static_cast<int>(k) + 1, kTagStop);
}

std::vector<ReplicaResult> ReplicaRanks::wait() {
    if (collected_) throw std::logic_error("ReplicaRanks: collected already");
    std::vector<ReplicaResult> results;
    std::string failure;
    for (std::size_t k = 0; k < windows_.size(); ++k) {
        const int from = static_cast<int>(k) + 1;
        const std::string answer = receive_bytes(from, kTagResult);
        send_int(0, from, kTagBye);
        if (!answer.empty() && answer.front() == 'R') {
            results.push_back(decode_replica_result(std::string_view(answer).substr(1)));
        } else if (failure.empty()) {
            failure = answer.empty() ? "replica " + std::to_string(from) + ": no answer" : answer.substr(2);
        }
    }
    collected_ = true;
    if (!failure.empty()) throw std::runtime_error(failure);
    return results;
}

void release_replica_ranks() {
    if (plan_went_out()) return;
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) return;  // not a run over MPI ranks
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) return;
    const std::string none = encode_replica_plan(ReplicaPlan{});
    for (int k = 1; k < rank_count(); ++k) send_bytes(none, k, kTagPlan);
    mark_plan_sent();
}

}  // namespace peensim
