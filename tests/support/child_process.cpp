#include "support/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <stdexcept>
#include <thread>

namespace peensim::testing {

namespace {

constexpr auto kPollPeriod = std::chrono::milliseconds(2);  // between two looks at the child

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Pending signals of a process, from the SigPnd (thread) and ShdPnd (process) masks in
// /proc/<pid>/status; 0 if the process is gone.
unsigned long long pending_signals(pid_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    unsigned long long mask = 0;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("SigPnd:", 0) == 0 || line.rfind("ShdPnd:", 0) == 0) mask |= std::stoull(line.substr(7), nullptr, 16);
    }
    return mask;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& stdout_path, const std::string& stderr_path) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
        // In the child: only async-signal-safe calls until exec.
        const int out = ::open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || err < 0 || ::dup2(out, STDOUT_FILENO) < 0 || ::dup2(err, STDERR_FILENO) < 0) ::_exit(127);
        ::execv(args[0], args.data());
        ::_exit(127);
    }
}

ChildProcess::~ChildProcess() {
    if (reaped_) return;
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
}

void ChildProcess::signal(int signal_number) const { ::kill(pid_, signal_number); }

bool ChildProcess::wait_signal_delivered(int signal_number, double limit_s) const {
    const unsigned long long bit = 1ull << (signal_number - 1);
    const auto t0 = std::chrono::steady_clock::now();
    while (seconds_since(t0) < limit_s) {
        if (::access(("/proc/" + std::to_string(pid_)).c_str(), F_OK) != 0) return false;
        if ((pending_signals(pid_) & bit) == 0) return true;
        std::this_thread::yield();
    }
    return false;
}

bool ChildProcess::running() {
    if (reaped_) return false;
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == 0) return true;
    reaped_ = true;
    if (r == pid_ && WIFEXITED(status)) exit_code_ = WEXITSTATUS(status);
    return false;
}

std::optional<int> ChildProcess::wait_exit(double limit_s) {
    const auto t0 = std::chrono::steady_clock::now();
    while (running()) {
        if (seconds_since(t0) >= limit_s) return std::nullopt;
        std::this_thread::sleep_for(kPollPeriod);
    }
    return exit_code_;
}

}  // namespace peensim::testing
