#include "app/sweep/sweep_runner.h"

#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <thread>

#include "app/sweep/sweep_book.h"
#include "app/sweep/sweep_mpi.h"

namespace fs = std::filesystem;

namespace peensim {

std::string this_executable() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw std::runtime_error("cannot find this program's own path (/proc/self/exe): " + ec.message());
    return self.string();
}

SweepOutcome run_sweep_plan(const SweepPlan& plan, const SweepRunner& runner, const StopRequest& stop, const std::string& headline,
                            std::ostream& out, std::ostream& err) {
    fs::create_directories(runner.logs_dir);
    const int jobs = std::max(1, runner.jobs);
    const int ranks = runner.mpi != nullptr ? runner.mpi->size() : 1;
    SweepBook book(plan, runner.logs_dir, jobs * ranks, out, err, runner.job, runner.job_noun);
    out << headline << " = " << book.total() << (book.total() == 1 ? " run" : " runs")
        << (runner.mpi != nullptr ? " over " + std::to_string(ranks) + " MPI ranks" : ", " + std::to_string(jobs) + " at once")
        << (book.done() ? ", " + std::to_string(book.done()) + " finished before" : std::string()) << "\n";
    if (runner.mpi != nullptr) {
        runner.mpi->coordinate(book, runner.executable, runner.scene_path, plan, jobs, stop);
    } else {
        // Each run's analysis its share of the cores: `jobs` runs at once on all of them would
        // oversubscribe them.
        const unsigned threads_per_run = std::max(1u, std::max(1u, std::thread::hardware_concurrency()) / static_cast<unsigned>(jobs));
        std::map<pid_t, std::size_t> running;
        while (book.has_queued() || !running.empty()) {
            if (stop.requested() && !book.stopped()) {
                book.stop();  // every run checkpoints and stops; nothing new starts
                for (const auto& [pid, k] : running) ::kill(pid, SIGINT);
            }
            while (book.has_queued() && static_cast<int>(running.size()) < jobs) {
                const std::size_t k = book.take();
                running[start_sweep_run(runner.executable, runner.scene_path, plan.runs[k], book.log_of(k), threads_per_run)] = k;
            }
            int status = 0;
            const pid_t pid = ::waitpid(-1, &status, WNOHANG);
            if (pid <= 0) {
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
                continue;
            }
            const auto it = running.find(pid);
            if (it == running.end()) continue;
            const std::size_t k = it->second;
            running.erase(it);
            book.outcome(k, exit_code_of(status));
        }
    }
    return {book.stopped(), book.done(), book.total(), book.failed()};
}

}  // namespace peensim
