#include "app/sweep_book.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/run_job.h"

extern char** environ;

namespace fs = std::filesystem;

namespace peensim {

namespace {

// A run that finished (its summary says so and its analysis is there): never run again.
bool finished(const SweepRun& run) {
    std::ifstream in(run.dir + "/summary.json");
    if (!in || !fs::exists(run.dir + "/analysis/figures.json")) return false;
    const auto j = nlohmann::json::parse(in, nullptr, false);
    return !j.is_discarded() && j.value("finished", false);
}

std::string duration_text(double s) {
    if (!(s >= 0.0) || !std::isfinite(s)) return "?";
    const auto t = static_cast<long long>(std::llround(s));
    return t >= 3600 ? std::to_string(t / 3600) + "h" + std::to_string(t % 3600 / 60) + "m"
                     : (t >= 60 ? std::to_string(t / 60) + "m" + std::to_string(t % 60) + "s" : std::to_string(t) + "s");
}

}  // namespace

SweepBook::SweepBook(const SweepPlan& plan, std::string logs_dir, int slots, std::ostream& out, std::ostream& err)
    : plan_(plan), logs_(std::move(logs_dir)), slots_(std::max(1, slots)), out_(out), err_(err) {
    for (std::size_t k = 0; k < plan_.runs.size(); ++k) {
        if (finished(plan_.runs[k]))
            ++done_;
        else
            queue_.push_back(k);
    }
}

std::size_t SweepBook::take() {
    const std::size_t k = queue_.front();
    queue_.pop_front();
    ++attempts_[k];
    fs::create_directories(fs::path(plan_.runs[k].dir).parent_path());
    return k;
}

void SweepBook::stop() {
    stopped_ = true;
    queue_.clear();
}

std::string SweepBook::label_of(std::size_t k) const {
    return plan_.variants[plan_.runs[k].variant].name + "/s" + std::to_string(plan_.runs[k].replicate);
}

std::string SweepBook::log_of(std::size_t k) const { return sweep_run_log(plan_, logs_, k); }

std::string sweep_run_log(const SweepPlan& plan, const std::string& logs_dir, std::size_t k) {
    return logs_dir + "/" + plan.variants[plan.runs[k].variant].name + ".s" + std::to_string(plan.runs[k].replicate) + ".log";
}

void SweepBook::outcome(std::size_t k, int code) {
    if (code == kExitOk) {
        ++done_, ++done_here_;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
        const std::size_t left = total() - done_;
        const double eta = elapsed / static_cast<double>(done_here_) * static_cast<double>(left) /
                           static_cast<double>(std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(slots_), left)));
        out_ << "sweep: " << done_ << "/" << total() << " done (" << label_of(k) << ", " << duration_text(elapsed) << " elapsed"
             << (left > 0 ? ", about " + duration_text(eta) + " to go" : std::string()) << ")\n"
             << std::flush;
    } else if (code == kExitInterrupted && stopped_) {
        // Checkpointed: the next sweep resumes it.
    } else if (attempts_[k] < 2 && !stopped_) {
        err_ << "sweep: " << label_of(k) << " failed (exit " << code << ", see " << log_of(k) << "); trying it once more\n";
        queue_.push_back(k);
    } else {
        err_ << "sweep: " << label_of(k) << " failed again (exit " << code << ", see " << log_of(k) << "); the sweep goes on without it\n";
        failed_.push_back(k);
    }
}

pid_t start_sweep_run(const std::string& executable, const std::string& scene, const SweepRun& run, const std::string& log) {
    std::vector<std::string> args{executable, "run", scene, "-o", run.dir, "--quiet"};
    if (fs::exists(run.dir + "/checkpoint.bin")) args.push_back("--resume");
    for (const std::string& o : run.overrides) args.insert(args.end(), {"--set", o});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    // A process group of its own: a Ctrl-C at the terminal reaches the sweep alone, which passes one
    // SIGINT on (a run that got two would be abandoned at once instead of checkpointing).
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
    pid_t pid = 0;
    const int rc = ::posix_spawn(&pid, executable.c_str(), &actions, &attributes, argv.data(), environ);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("cannot start " + executable + ": " + std::strerror(rc));
    return pid;
}

int exit_code_of(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status); }

}  // namespace peensim
