#include "python/python_stream.h"

namespace py = pybind11;

namespace peensim::python {

PythonLineBuffer::~PythonLineBuffer() {
    // Destroyed with the GIL held (the owner's scope): the last unfinished line, if any.
    if (!pending_.empty() && !target_.is_none()) {
        try {
            target_.attr("write")(pending_);
        } catch (const py::error_already_set&) {}
    }
}

int PythonLineBuffer::overflow(int c) {
    if (c == traits_type::eof()) return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    pending_ += ch;
    if (ch == '\n') {
        write_out(pending_);
        pending_.clear();
    }
    return c;
}

std::streamsize PythonLineBuffer::xsputn(const char* s, std::streamsize n) {
    pending_.append(s, static_cast<std::size_t>(n));
    const std::size_t end = pending_.rfind('\n');
    if (end != std::string::npos) {
        write_out(pending_.substr(0, end + 1));
        pending_.erase(0, end + 1);
    }
    return n;
}

int PythonLineBuffer::sync() {
    if (!pending_.empty()) {
        write_out(pending_);
        pending_.clear();
    }
    return 0;
}

void PythonLineBuffer::write_out(const std::string& text) {
    py::gil_scoped_acquire gil;
    if (target_.is_none()) return;
    try {
        target_.attr("write")(text);
        target_.attr("flush")();
    } catch (py::error_already_set& e) {
        e.discard_as_unraisable("peensim: writing a message to Python");  // a closed stream: the job goes on
    }
}

}  // namespace peensim::python
