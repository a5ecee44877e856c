// Runs a shell command and returns what it printed (stdout and stderr, in order) with its wait
// status: the tests' one way to call ffprobe, ldd, pvbatch and VTK's Python.
#pragma once

#include <cstdio>
#include <string>

namespace peensim::testing {

struct ShellResult {
    int status = -1;     // as pclose returns it (0: exited with 0); -1: could not start
    std::string output;  // stdout then stderr interleaved as written
};

inline ShellResult run_shell(const std::string& command) {
    ShellResult r;
    FILE* pipe = ::popen(("(" + command + ") 2>&1").c_str(), "r");
    if (pipe == nullptr) {
        r.output = "popen failed: " + command;
        return r;
    }
    char chunk[65536];
    std::size_t n = 0;
    while ((n = std::fread(chunk, 1, sizeof chunk, pipe)) > 0) r.output.append(chunk, n);
    r.status = ::pclose(pipe);
    return r;
}

// The output without its trailing line ends (a one-line answer such as ffprobe's).
inline std::string trimmed(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    return text;
}

}  // namespace peensim::testing
