// Streams a run's impacts.csv (or the impacts.csv.partial of a run that was killed) row by row,
// never holding the file: a 1 MiB buffer, fields parsed in place with std::from_chars. A last
// line without its newline (a run killed mid-write) is not a row: it is dropped and reported by
// truncated() and truncated_line() (the caller says so to the user). Any other malformed line --
// a field missing or too many, a number that is not one, NaN or infinite (the writer logs only
// finite values: such a row is damage, never dropped in silence), binary bytes -- is an InputError
// naming the file, line, column and the column's name, quoting at most a short escaped excerpt.
// Component names never need CSV quoting (the scene schema allows only [A-Za-z0-9_-]), so fields
// split at commas.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/vec.h"

namespace peensim {

struct ImpactRow {
    double time_s = 0.0;  // s
    std::int32_t shot = 0;
    std::string_view component;    // valid until the next call to next()
    std::int32_t triangle = 0;     // facet index in the component's mesh file
    Vec3 point_m;                  // m, component frame
    Vec3 v_in_m_per_s;             // m/s, relative to the surface, component frame
    double vn_in_m_per_s = 0.0;    // m/s
    double vt_in_m_per_s = 0.0;    // m/s
    Vec3 v_out_m_per_s;            // m/s
    double vn_out_m_per_s = 0.0;   // m/s
    double shot_diameter_m = 0.0;  // m, the impacting shot's diameter (a mix's log); 0 when the log has one size
};

class ImpactLogReader {
public:
    // Throws std::runtime_error if the file cannot be opened, InputError if its header is not peensim's.
    explicit ImpactLogReader(const std::string& path);
    ~ImpactLogReader();
    ImpactLogReader(const ImpactLogReader&) = delete;
    ImpactLogReader& operator=(const ImpactLogReader&) = delete;

    // Reads the next row; false at the end. Throws InputError (file:line:column: field: what) on a bad line.
    bool next(ImpactRow& row);

    // Refuses the row just read (an InputError at its line, in `column`), for a check the caller
    // makes: e.g. a component the run does not log, which no run of the scene wrote.
    [[noreturn]] void refuse_row(const std::string& column, const std::string& problem) const;

    bool truncated() const { return truncated_; }                     // the file ended inside a line
    std::uint64_t truncated_line() const { return truncated_line_; }  // that line (1-based; the header is line 1), 0 if none
    // The log has the shot_diameter_m column (a run of a shot mix): each row's shot_diameter_m is set.
    bool has_shot_diameter() const { return shot_diameter_; }
    std::uint64_t rows() const { return rows_; }
    const std::string& path() const { return path_; }

private:
    bool fill();  // moves the unread tail to the front and reads more; false at end of file
    [[noreturn]] void fail(const std::string& what) const;

    std::string path_;
    std::FILE* file_ = nullptr;
    std::vector<char> buffer_;
    std::size_t begin_ = 0, end_ = 0;  // unread bytes are buffer_[begin_, end_)
    bool eof_ = false;
    bool truncated_ = false;
    bool shot_diameter_ = false;
    std::uint64_t rows_ = 0;
    std::uint64_t truncated_line_ = 0;
    std::vector<std::string> columns_;  // the header's column names
    std::uint64_t line_ = 1;            // 1-based line number of the header
};

}  // namespace peensim
