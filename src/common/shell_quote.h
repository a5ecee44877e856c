// A word for /bin/sh, whatever it holds: the commands peensim prints for the user to paste (a
// resume, a gnuplot call) keep their spaces, quotes and % signs.
#pragma once

#include <string>

namespace peensim {

inline std::string shell_quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

}  // namespace peensim
