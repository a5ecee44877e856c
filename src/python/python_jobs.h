// The jobs of the command line (check, run, analyze, sweep) as functions of the Python module: the
// GIL released while they work, their messages to sys.stdout / sys.stderr as they come, Ctrl-C
// (Python's KeyboardInterrupt) stopping them at a checkpoint, bad input raised as InputError.
#pragma once

#include <pybind11/pybind11.h>

namespace peensim::python {

void bind_jobs(pybind11::module_& m);

}  // namespace peensim::python
