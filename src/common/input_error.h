// The one error type for bad input (scene files, meshes, command-line overrides).
// It carries where the problem is (file, line, field) and what was expected, so every
// message a user sees can point at the line to fix. Numerical trouble during a run is
// not an InputError: it goes to the health counters (engine/health.h).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace peensim {

struct SourceLocation {
    std::string file;  // path as the user gave it
    int line = 0;      // 1-based; 0 = unknown (e.g. a --set override)
    int column = 0;    // 1-based; 0 = unknown
};

// Where an error in a command-line option is: no file, no line.
inline const SourceLocation kCommandLine{"<command line>", 0, 0};

class InputError : public std::runtime_error {
public:
    InputError(SourceLocation where, std::string field, std::string problem)
        : std::runtime_error(format(where, field, problem)),
          where_(std::move(where)),
          field_(std::move(field)),
          problem_(std::move(problem)) {}

    const SourceLocation& where() const { return where_; }
    const std::string& field() const { return field_; }
    const std::string& problem() const { return problem_; }
    // The problem with the place it was found ("gear.ply:7: ..."), for an error re-thrown at the
    // field of another file that named this one (a scene's mesh).
    std::string problem_at_its_place() const { return format(where_, "", problem_); }

    // "scene.yaml:12:5: shot.diameter: expected a positive length, got '-2 mm'"
    static std::string format(const SourceLocation& where, const std::string& field, const std::string& problem) {
        // Built with append (not operator+): GCC 12 warns falsely (-Wrestrict) on long + chains.
        std::string s;
        s.append(where.file.empty() ? std::string_view("<input>") : std::string_view(where.file));
        if (where.line > 0) {
            s.append(":").append(std::to_string(where.line));
            if (where.column > 0) s.append(":").append(std::to_string(where.column));
        }
        s.append(": ");
        if (!field.empty()) s.append(field).append(": ");
        s.append(problem);
        return s;
    }

private:
    SourceLocation where_;
    std::string field_;
    std::string problem_;
};

}  // namespace peensim
