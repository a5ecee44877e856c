// A std::ostream whose lines go to a Python file object (sys.stdout, sys.stderr), so the messages a
// job writes while the GIL is released (warnings, a sweep's progress) reach a notebook as they come.
// Each complete line takes the GIL for the write; nothing is written while a line is unfinished.
#pragma once

#include <pybind11/pybind11.h>

#include <ostream>
#include <streambuf>
#include <string>

namespace peensim::python {

class PythonLineBuffer final : public std::streambuf {
public:
    // `target`: a Python object with write() and flush(); None discards the text. Built and
    // destroyed with the GIL held.
    explicit PythonLineBuffer(pybind11::object target) : target_(std::move(target)) {}
    ~PythonLineBuffer() override;
    PythonLineBuffer(const PythonLineBuffer&) = delete;
    PythonLineBuffer& operator=(const PythonLineBuffer&) = delete;

protected:
    int overflow(int c) override;
    std::streamsize xsputn(const char* s, std::streamsize n) override;
    int sync() override;  // writes an unfinished line too (takes the GIL)

private:
    void write_out(const std::string& text);  // takes the GIL

    pybind11::object target_;
    std::string pending_;  // the unfinished line
};

// The stream over such a buffer.
class PythonStream final : public std::ostream {
public:
    explicit PythonStream(pybind11::object target) : std::ostream(nullptr), buffer_(std::move(target)) { rdbuf(&buffer_); }

private:
    PythonLineBuffer buffer_;
};

}  // namespace peensim::python
