// Runs a program (the `peensim` binary) as a child process the test can signal and wait for with
// a time limit, its stdout and stderr going to files.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace peensim::testing {

class ChildProcess {
public:
    // Starts `argv[0]` (a path) with these arguments; stdout and stderr to the two files.
    ChildProcess(const std::vector<std::string>& argv, const std::string& stdout_path, const std::string& stderr_path);
    ~ChildProcess();  // kills the child (SIGKILL) if it is still running
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    pid_t pid() const { return pid_; }
    void signal(int signal_number) const;
    // Waits until the child has taken `signal_number` off its pending set (its handler ran or
    // runs), at most `limit_s` seconds of wall time; false if it did not (or it is gone).
    bool wait_signal_delivered(int signal_number, double limit_s) const;
    // Waits at most `limit_s` seconds of wall time for the child to end; its exit code, or empty
    // if it is still running (or was killed by a signal).
    std::optional<int> wait_exit(double limit_s);
    bool running();

private:
    pid_t pid_ = -1;
    bool reaped_ = false;
    std::optional<int> exit_code_;
};

}  // namespace peensim::testing
