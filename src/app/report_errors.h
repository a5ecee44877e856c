// The one place where errors become messages and exit codes: bad input (InputError, with file,
// line and field) exits 2, anything else that went wrong exits 1. Library code only throws.
#pragma once

#include <exception>
#include <ostream>

#include "app/exit_codes.h"
#include "common/input_error.h"

namespace peensim {

template <class Job>
int report_errors(std::ostream& err, Job&& job) {
    try {
        return job();
    } catch (const InputError& e) {
        err << "error: " << e.what() << "\n";
        return kExitInputError;
    } catch (const std::exception& e) {
        err << "error: " << e.what() << "\n";
        return kExitRuntimeError;
    }
}

}  // namespace peensim
