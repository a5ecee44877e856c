#include "app/sweep/sweep_mpi.h"

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <thread>

#include <mpi.h>

#include "app/interrupt.h"
#include "app/run/run_job.h"

namespace peensim {

namespace {

constexpr int kTagAsk = 1;  // worker -> rank 0: {the run it ran, its exit code} ({-1, 0}: none yet)
constexpr int kTagRun = 2;  // rank 0 -> worker: the run to do next, -1: no more

// Waits for child `pid`; on an interrupt passes one SIGINT on (it checkpoints) and goes on waiting.
int wait_for(pid_t pid, const StopRequest& stop) {
    bool passed_on = false;
    for (;;) {
        int status = 0;
        if (::waitpid(pid, &status, WNOHANG) == pid) return exit_code_of(status);
        if (stop.requested() && !passed_on) {
            ::kill(pid, SIGINT);
            passed_on = true;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

}  // namespace

MpiSweep::MpiSweep() {
    MPI_Init(nullptr, nullptr);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSweep::~MpiSweep() { MPI_Finalize(); }

std::string MpiSweep::broadcast(const std::string& text) const {
    long size = rank_ == 0 ? static_cast<long>(text.size()) : 0;
    MPI_Bcast(&size, 1, MPI_LONG, 0, MPI_COMM_WORLD);
    std::string got = rank_ == 0 ? text : std::string(static_cast<std::size_t>(size), '\0');
    if (size > 0) MPI_Bcast(got.data(), static_cast<int>(size), MPI_CHAR, 0, MPI_COMM_WORLD);
    return got;
}

void MpiSweep::work(const std::string& executable, const std::string& scene, const SweepPlan& plan, const std::string& logs_dir,
                    const StopRequest& stop) {
    long report[2] = {-1, 0};
    for (;;) {
        MPI_Send(report, 2, MPI_LONG, 0, kTagAsk, MPI_COMM_WORLD);
        long k = -1;
        MPI_Recv(&k, 1, MPI_LONG, 0, kTagRun, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (k < 0) return;
        const auto run = static_cast<std::size_t>(k);
        std::filesystem::create_directories(std::filesystem::path(plan.runs[run].dir).parent_path());
        const pid_t pid = start_sweep_run(executable, scene, plan.runs[run], sweep_run_log(plan, logs_dir, run), 1);  // a rank a core
        report[0] = k;
        report[1] = wait_for(pid, stop);
    }
}

void MpiSweep::coordinate(SweepBook& book, const std::string& executable, const std::string& scene, const SweepPlan& plan, int slots,
                          const StopRequest& stop) {
    int workers = size_ - 1;               // ranks still asking (a rank told "no more" has ended)
    std::map<pid_t, std::size_t> running;  // this rank's own runs
    while (workers > 0 || !running.empty() || book.has_queued()) {
        bool busy = false;
        if (stop.requested() && !book.stopped()) {
            book.stop();  // the other ranks' launcher passes the interrupt on to them
            for (const auto& [pid, k] : running) ::kill(pid, SIGINT);
        }
        while (book.has_queued() && static_cast<int>(running.size()) < slots) {
            const std::size_t k = book.take();
            running[start_sweep_run(executable, scene, plan.runs[k], book.log_of(k), 1)] = k;  // a rank a core
            busy = true;
        }
        int asking = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, kTagAsk, MPI_COMM_WORLD, &asking, &status);
        if (asking) {
            long report[2];
            MPI_Recv(report, 2, MPI_LONG, status.MPI_SOURCE, kTagAsk, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            if (report[0] >= 0) book.outcome(static_cast<std::size_t>(report[0]), static_cast<int>(report[1]));
            // A run failing elsewhere goes back into the queue: whoever asks next takes it.
            long next = -1;
            if (book.has_queued()) next = static_cast<long>(book.take());
            MPI_Send(&next, 1, MPI_LONG, status.MPI_SOURCE, kTagRun, MPI_COMM_WORLD);
            if (next < 0) --workers;
            busy = true;
        }
        int wait_status = 0;
        const pid_t pid = ::waitpid(-1, &wait_status, WNOHANG);
        if (pid > 0) {
            if (const auto it = running.find(pid); it != running.end()) {
                const std::size_t k = it->second;
                running.erase(it);
                book.outcome(k, exit_code_of(wait_status));
            }
            busy = true;
        }
        if (!busy) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

}  // namespace peensim
