// Ctrl-C (SIGINT) and SIGTERM during a run: the handler only raises a flag; the run loop sees
// it after the current step, writes a checkpoint and leaves every output file consistent.
#pragma once

namespace peensim {

class InterruptGuard {
public:
    InterruptGuard();   // installs the handlers
    ~InterruptGuard();  // restores the previous ones
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    static bool requested();
    static void request();  // for tests: behave as if Ctrl-C was pressed
    static void clear();
};

}  // namespace peensim
