// Ctrl-C (SIGINT) and SIGTERM during a run.
// The first one only raises a flag: the run loop sees it at its next restart point, writes a
// checkpoint and leaves every output consistent (exit 130).
// A second one means the user will not wait for that: the handler prints one line and ends the
// process at once, exit 130, with async-signal-safe calls only (write, _exit). Nothing a resume
// needs is lost: checkpoints replace each other by atomic rename, so the last complete one stays.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace peensim {

class InterruptGuard {
public:
    // Installs the handlers; `abandon_message` (one line, ending in '\n') is what a second signal
    // prints to stderr before the process ends.
    explicit InterruptGuard(std::string abandon_message);
    ~InterruptGuard();  // restores the previous handlers
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    // True once a first signal arrived since this guard was installed.
    static bool requested();

private:
    std::string abandon_message_;  // the handler reads it; it must outlive the handlers
};

// How a job learns it was asked to stop. The command line: Ctrl-C and SIGTERM, caught by an
// InterruptGuard for the job's life. A caller that handles signals itself (the Python module,
// whose interpreter owns SIGINT) passes its own test instead, and no handler is installed.
class StopRequest {
public:
    // `caller_test`: empty = catch the signals here; else asked often (cheap, any thread of the job).
    StopRequest(std::function<bool()> caller_test, std::string abandon_message);
    bool requested() const { return caller_test_ ? caller_test_() : InterruptGuard::requested(); }

private:
    std::function<bool()> caller_test_;
    std::optional<InterruptGuard> guard_;
};

}  // namespace peensim
