#include "app/run/replica_ranks.h"

#include <chrono>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <thread>

#include <mpi.h>

#include "app/check/setup_checks.h"
#include "app/exit_codes.h"
#include "app/interrupt.h"
#include "app/report_errors.h"
#include "app/run/replica_result_codec.h"
#include "common/random.h"
#include "model/model.h"
#include "model/shot_placement.h"
#include "scene/scene_parser.h"

namespace peensim {

namespace {

namespace fs = std::filesystem;

constexpr int kTagPlan = 11;    // rank 0 -> rank k: the plan's bytes (no windows: none, end)
constexpr int kTagResult = 12;  // rank k -> rank 0: 'R' and its result's bytes, or 'E' and why it failed
constexpr int kTagStop = 13;    // rank 0 -> rank k: stop at the next step (the run was interrupted)
constexpr int kTagBye = 14;     // rank 0 -> rank k: its result is in; end

bool plan_sent = false;  // rank 0: the plan, or "none", went out (once per job)

// Waiting ranks poll, so that they leave their core to the ranks that work.
void pause_briefly() { std::this_thread::sleep_for(std::chrono::milliseconds(2)); }

bool waiting(int source, int tag) {
    int flag = 0;
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
    return flag != 0;
}

void send_bytes(const std::string& bytes, int to, int tag) {
    MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

std::string receive_bytes(int from, int tag) {
    while (!waiting(from, tag)) pause_briefly();
    MPI_Status status;
    MPI_Probe(from, tag, MPI_COMM_WORLD, &status);
    int size = 0;
    MPI_Get_count(&status, MPI_BYTE, &size);
    std::string bytes(static_cast<std::size_t>(size), '\0');
    MPI_Recv(bytes.data(), size, MPI_BYTE, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return bytes;
}

void send_int(int value, int to, int tag) { MPI_Send(&value, 1, MPI_INT, to, tag, MPI_COMM_WORLD); }

int receive_int(int from, int tag) {
    int value = 0;
    MPI_Recv(&value, 1, MPI_INT, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return value;
}

int ranks() {
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size;
}

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
    const ReplicaPlan plan = decode_replica_plan(receive_bytes(0, kTagPlan));
    if (plan.windows.empty()) return kExitOk;  // rank 0 goes on alone, or stopped before a plan
    // Rank 0 made the spills' folder before it sent the plan: a rank that cannot see it would spill
    // where rank 0 never reads.
    if (failure.empty() && !fs::is_directory(fs::path(dir) / kReplicaSpillDirectory))
        failure = "cannot see the run's directory " + dir + " as rank 0 made it (no " + std::string(kReplicaSpillDirectory) +
                  "/ in it): every rank must see the run's directory, on a shared file system and from the same working directory";
    std::string answer;
    if (failure.empty()) {
        try {
            bool told_to_stop = false;
            std::uint64_t steps = 0;
            const ReplicaResult result = run_replica(model, plan.windows.at(static_cast<std::size_t>(rank)), shots, dir, slots, [&] {
                if (!told_to_stop && ++steps % 64 == 0 && waiting(0, kTagStop)) {
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
        if (waiting(0, kTagStop)) receive_int(0, kTagStop);
        if (waiting(0, kTagBye)) {
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
    const int size = ranks();
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
    if (static_cast<int>(windows_.size()) + 1 != ranks()) throw std::invalid_argument("ReplicaRanks: one window a rank but rank 0");
    if (plan_sent) throw std::logic_error("ReplicaRanks: the plan went out already");
    ReplicaPlan plan;
    plan.windows.push_back({});  // replica 0's: rank 0's own, not read by the others
    plan.windows.insert(plan.windows.end(), windows_.begin(), windows_.end());
    const std::string bytes = encode_replica_plan(plan);
    for (std::size_t k = 0; k < windows_.size(); ++k) send_bytes(bytes, static_cast<int>(k) + 1, kTagPlan);
    plan_sent = true;
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
    if (plan_sent) return;
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) return;  // not a run over MPI ranks
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) return;
    const std::string none = encode_replica_plan(ReplicaPlan{});
    for (int k = 1; k < ranks(); ++k) send_bytes(none, k, kTagPlan);
    plan_sent = true;
}

}  // namespace peensim
