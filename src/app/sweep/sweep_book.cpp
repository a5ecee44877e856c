#include "app/sweep/sweep_book.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/run/run_job.h"

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

std::string sweep_duration_text(double s) {
    if (!(s >= 0.0) || !std::isfinite(s)) return "?";
    const auto t = static_cast<long long>(std::llround(s));
    return t >= 3600 ? std::to_string(t / 3600) + "h" + std::to_string(t % 3600 / 60) + "m"
                     : (t >= 60 ? std::to_string(t / 60) + "m" + std::to_string(t % 60) + "s" : std::to_string(t) + "s");
}

}  // namespace

SweepBook::SweepBook(const SweepPlan& plan, std::string logs_dir, int slots, std::ostream& out, std::ostream& err, std::string job,
                     std::string job_noun)
    : plan_(plan),
      logs_(std::move(logs_dir)),
      slots_(std::max(1, slots)),
      out_(out),
      err_(err),
      job_(std::move(job)),
      job_noun_(std::move(job_noun)) {
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
        // Runs that failed for good are not to come.
        const std::size_t ended = done_ + failed_.size();
        const std::size_t left = total() > ended ? total() - ended : 0;
        const double eta = elapsed / static_cast<double>(done_here_) * static_cast<double>(left) /
                           static_cast<double>(std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(slots_), left)));
        out_ << job_ << ": " << done_ << "/" << total() << " done (" << label_of(k) << ", " << sweep_duration_text(elapsed) << " elapsed"
             << (left > 0 ? ", about " + sweep_duration_text(eta) + " to go" : std::string()) << ")\n"
             << std::flush;
    } else if (code == kExitInterrupted && stopped_) {
        // Checkpointed: the next sweep resumes it.
    } else if (code == kExitInputError) {
        // Its scene (a file it names) is refused: the same run again would be, for the same reason.
        err_ << job_ << ": " << label_of(k) << " refused its input (exit " << code << ", see " << log_of(k) << "); not run again, the "
             << job_noun_ << " goes on without it\n";
        failed_for_good(k);
    } else if (attempts_[k] < 2 && !stopped_) {
        err_ << job_ << ": " << label_of(k) << " failed (exit " << code << ", see " << log_of(k) << "); trying it once more\n";
        queue_.push_back(k);
    } else {
        err_ << job_ << ": " << label_of(k) << " failed again (exit " << code << ", see " << log_of(k) << "); the " << job_noun_
             << " goes on without it\n";
        failed_for_good(k);
    }
}

void SweepBook::failed_for_good(std::size_t k) {
    failed_.push_back(k);
    // Its folders, when it left them empty (a run refused before it wrote anything): the folder of
    // a variant none of whose runs ran is no result. Anything else at those paths (a file, a link,
    // a folder with anything in it) is left as it is.
    const auto remove_if_empty_folder = [](const fs::path& p) {
        std::error_code e;
        // symlink_status: a link (to a folder or not) is the user's, never followed nor removed.
        if (fs::is_directory(fs::symlink_status(p, e)) && fs::is_empty(p, e) && !e) fs::remove(p, e);
    };
    remove_if_empty_folder(plan_.runs[k].dir);
    remove_if_empty_folder(fs::path(plan_.runs[k].dir).parent_path());
}

std::string sweep_geometry_cache(const std::string& logs_dir) { return (fs::path(logs_dir).parent_path() / "geometry-cache").string(); }

std::string sweep_geometry_cache_line(const std::string& logs_dir) {
    std::size_t reused = 0, computed = 0;
    std::error_code ignored;
    for (const fs::directory_entry& e : fs::directory_iterator(logs_dir, ignored)) {
        std::ifstream log(e.path());
        for (std::string line; std::getline(log, line);) {
            if (line.rfind("note: ", 0) != 0) continue;
            if (line.find("'s coverage geometry reused from ") != std::string::npos) ++reused;
            if (line.find("'s coverage geometry kept in ") != std::string::npos) ++computed;
        }
    }
    if (reused + computed == 0) return {};
    const auto times = [](std::size_t n) { return std::to_string(n) + (n == 1 ? " time" : " times"); };
    return "geometry: the runs computed the parts' coverage geometry " + times(computed) + " and reused it " + times(reused) + " (" +
           sweep_geometry_cache(logs_dir) + ")\n";
}

pid_t start_sweep_run(const std::string& executable, const std::string& scene, const SweepRun& run, const std::string& log,
                      unsigned threads) {
    std::vector<std::string> args{executable,
                                  "run",
                                  scene,
                                  "-o",
                                  run.dir,
                                  "--quiet",
                                  "--threads",
                                  std::to_string(threads),
                                  "--geometry-cache",
                                  sweep_geometry_cache(fs::path(log).parent_path().string())};
    if (fs::exists(run.dir + "/checkpoint.bin")) args.push_back("--resume");
    for (const std::string& o : run.overrides) args.insert(args.end(), {"--set", o});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    // Everything the child needs is made before fork: between fork and exec only async-signal-safe calls.
    const int input = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    const int output = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    int exec_failed[2] = {-1, -1};  // the child's errno if execve fails; closed by a successful one
    if (input < 0 || output < 0 || ::pipe2(exec_failed, O_CLOEXEC) != 0) {
        const int error = errno;
        for (int fd : {input, output, exec_failed[0], exec_failed[1]})
            if (fd >= 0) ::close(fd);
        throw std::runtime_error("cannot start a run (" + log + "): " + std::strerror(error));
    }
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid == 0) {
        // A process group of its own: a Ctrl-C at the terminal reaches the sweep alone, which passes
        // one SIGINT on (a run that got two would be abandoned at once instead of checkpointing).
        ::setpgid(0, 0);
        // Dies with the sweep: a sweep (or an MPI rank) killed outright (SIGKILL, a crash) cannot
        // pass anything on, and a run left going would hold its directory's lock against the
        // rerun ("in use"). SIGKILL: the rerun resumes at once from the run's last checkpoint.
        // The sweep may have died before prctl: then this process was already handed to another
        // parent, and never runs.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(kExitInterrupted);
        ::dup2(input, STDIN_FILENO);
        ::dup2(output, STDOUT_FILENO);
        ::dup2(output, STDERR_FILENO);
        ::execve(executable.c_str(), argv.data(), environ);
        const int error = errno;
        [[maybe_unused]] const ssize_t said = ::write(exec_failed[1], &error, sizeof error);
        ::_exit(127);
    }
    const int fork_error = errno;
    for (int fd : {input, output, exec_failed[1]}) ::close(fd);
    if (pid < 0) {
        ::close(exec_failed[0]);
        throw std::runtime_error("cannot start " + executable + ": " + std::strerror(fork_error));
    }
    int exec_error = 0;
    ssize_t n = 0;
    do n = ::read(exec_failed[0], &exec_error, sizeof exec_error);
    while (n < 0 && errno == EINTR);
    ::close(exec_failed[0]);
    if (n == static_cast<ssize_t>(sizeof exec_error)) {
        int status = 0;
        ::waitpid(pid, &status, 0);
        throw std::runtime_error("cannot start " + executable + ": " + std::strerror(exec_error));
    }
    return pid;
}

int exit_code_of(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status); }

}  // namespace peensim
