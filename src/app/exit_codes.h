// The exit codes of every job (documented in docs/user-guide.md, "Using peensim"). Their own header so that the pieces
// every job shares (report_errors.h, interrupt.*) need not include the run's (run/run_job.h).
#pragma once

namespace peensim {

enum ExitCode : int {
    kExitOk = 0,
    kExitRuntimeError = 1,   // I/O failure, resume impossible, internal error
    kExitInputError = 2,     // bad scene file, mesh or command line
    kExitHealthFailure = 3,  // --strict and numerical trouble (lost shot, NaN, deep penetration)
    kExitInterrupted = 130,  // Ctrl-C / SIGTERM: checkpoint written, resume with --resume
};

}  // namespace peensim
