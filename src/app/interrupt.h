// Ctrl-C (SIGINT) and SIGTERM during a run.
// The first one only raises a flag: the run loop sees it at its next restart point, writes a
// checkpoint and leaves every output consistent (exit 130).
// A second one means the user will not wait for that: the handler prints one line and ends the
// process at once, exit 130, with async-signal-safe calls only (write, _exit). Nothing a resume
// needs is lost: checkpoints replace each other by atomic rename, so the last complete one stays.
#pragma once

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

}  // namespace peensim
