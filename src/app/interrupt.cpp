#include "app/interrupt.h"

#include <csignal>

namespace peensim {

namespace {
volatile std::sig_atomic_t g_interrupt = 0;  // the only state a signal handler may touch
void on_signal(int) { g_interrupt = 1; }
using Handler = void (*)(int);
Handler g_previous_int = SIG_DFL;
Handler g_previous_term = SIG_DFL;
}  // namespace

InterruptGuard::InterruptGuard() {
    g_interrupt = 0;
    g_previous_int = std::signal(SIGINT, on_signal);
    g_previous_term = std::signal(SIGTERM, on_signal);
}

InterruptGuard::~InterruptGuard() {
    std::signal(SIGINT, g_previous_int);
    std::signal(SIGTERM, g_previous_term);
}

bool InterruptGuard::requested() { return g_interrupt != 0; }
void InterruptGuard::request() { g_interrupt = 1; }
void InterruptGuard::clear() { g_interrupt = 0; }

}  // namespace peensim
