#include "app/interrupt.h"

#include <unistd.h>

#include <csignal>
#include <utility>

#include "app/exit_codes.h"

namespace peensim {

namespace {

// The only state the handler touches; set before the handlers are installed.
volatile std::sig_atomic_t g_signals = 0;  // signals received since the guard was installed
const char* g_abandon_message = nullptr;
std::size_t g_abandon_message_size = 0;
struct sigaction g_previous_int {};
struct sigaction g_previous_term {};

void on_signal(int) {
    if (g_signals == 0) {
        g_signals = 1;
        return;
    }
    // write(2) and _exit(2) are async-signal-safe; exit() is not (it runs destructors and flushes
    // streams the interrupted code may be in the middle of).
    const ssize_t ignored = ::write(STDERR_FILENO, g_abandon_message, g_abandon_message_size);
    (void)ignored;
    ::_exit(kExitInterrupted);
}

}  // namespace

InterruptGuard::InterruptGuard(std::string abandon_message) : abandon_message_(std::move(abandon_message)) {
    g_signals = 0;
    g_abandon_message = abandon_message_.data();
    g_abandon_message_size = abandon_message_.size();
    struct sigaction action {};
    action.sa_handler = on_signal;
    // Both signals blocked while the handler runs, so a SIGTERM cannot interrupt a SIGINT's handler
    // half-way; SA_RESTART so that the first signal does not fail a write the run is doing.
    sigemptyset(&action.sa_mask);
    sigaddset(&action.sa_mask, SIGINT);
    sigaddset(&action.sa_mask, SIGTERM);
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, &g_previous_int);
    sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptGuard::~InterruptGuard() {
    sigaction(SIGINT, &g_previous_int, nullptr);
    sigaction(SIGTERM, &g_previous_term, nullptr);
}

bool InterruptGuard::requested() { return g_signals != 0; }

StopRequest::StopRequest(std::function<bool()> caller_test, std::string abandon_message) : caller_test_(std::move(caller_test)) {
    if (!caller_test_) guard_.emplace(std::move(abandon_message));
}

}  // namespace peensim
