#include "analysis/impact_log_reader.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "common/input_error.h"
#include "common/text_excerpt.h"
#include "output/impact_csv_writer.h"

namespace peensim {

namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

// The columns' names, in order, for messages ("time_s", ..., "shot_diameter_m").
std::vector<std::string> column_names(bool shot_diameter) {
    std::vector<std::string> names;
    std::string_view header = kImpactCsvHeader;
    for (std::size_t at = 0;;) {
        const std::size_t comma = header.find(',', at);
        names.emplace_back(header.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at));
        if (comma == std::string_view::npos) break;
        at = comma + 1;
    }
    if (shot_diameter) names.emplace_back(kImpactCsvDiameterColumn);
    return names;
}

// What is wrong with a field: the reader turns it into an InputError at the field's line and column.
struct BadField {
    std::size_t index = 0;   // 0-based column (npos: the whole row)
    std::size_t column = 0;  // 1-based byte of the line where the field starts (0: the whole row)
    std::string problem;
};
constexpr std::size_t kWholeRow = std::string_view::npos;

// Splits a line into its fields, parsing each in turn. Numbers must be finite: a NaN or an
// infinity in a log is damage (the writer logs only finite values), not a row to drop.
class Fields {
public:
    explicit Fields(std::string_view line) : line_(line), rest_(line) {}
    std::string_view text() {
        if (done_) throw BadField{index_, line_.size() + 1, "expected more fields (the row ends after " + std::to_string(index_) + ")"};
        offset_ = static_cast<std::size_t>(rest_.data() - line_.data());
        const std::size_t comma = rest_.find(',');
        std::string_view field = rest_.substr(0, comma);
        if (comma == std::string_view::npos) {
            done_ = true;
            rest_ = {};
        } else {
            rest_.remove_prefix(comma + 1);
        }
        ++index_;
        return field;
    }
    double number() {
        const std::string_view f = text();
        double v = 0.0;
        const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
        if (r.ec != std::errc() || r.ptr != f.data() + f.size()) fail("expected a number, got " + text_excerpt(f));
        if (!std::isfinite(v)) fail("expected a finite number, got " + text_excerpt(f));
        return v;
    }
    std::int32_t integer() {
        const std::string_view f = text();
        std::int32_t v = 0;
        const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
        if (r.ec != std::errc() || r.ptr != f.data() + f.size()) fail("expected an integer, got " + text_excerpt(f));
        return v;
    }
    Vec3 vec() {
        const double x = number(), y = number(), z = number();
        return {x, y, z};
    }
    bool finished() const { return done_; }
    // The last field read is bad.
    [[noreturn]] void fail(const std::string& problem) const { throw BadField{index_ - 1, offset_ + 1, problem}; }
    // The row goes on after its last column.
    [[noreturn]] void fail_extra(std::size_t columns) const {
        throw BadField{kWholeRow, static_cast<std::size_t>(rest_.data() - line_.data()) + 1,
                       "expected " + std::to_string(columns) + " fields, got more: " + text_excerpt(line_)};
    }

private:
    std::string_view line_, rest_;
    std::size_t index_ = 0, offset_ = 0;
    bool done_ = false;
};

}  // namespace

ImpactLogReader::ImpactLogReader(const std::string& path) : path_(path), buffer_(kBufferBytes) {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw std::runtime_error(path + ": cannot open the impact log (" + std::strerror(errno) + ")");
    std::string_view header;
    fill();
    const char* nl = static_cast<const char*>(std::memchr(buffer_.data() + begin_, '\n', end_ - begin_));
    if (!nl)
        fail(end_ == begin_ ? "the impact log is empty (no header): the run wrote nothing"
                            : "no complete header line; expected the header '" + std::string(kImpactCsvHeader) + "', got " +
                                  text_excerpt(std::string_view(buffer_.data() + begin_, end_ - begin_)));
    header = std::string_view(buffer_.data() + begin_, static_cast<std::size_t>(nl - (buffer_.data() + begin_)));
    shot_diameter_ = header == impact_csv_header(true);
    if (header != kImpactCsvHeader && !shot_diameter_)
        fail("not a peensim impact log: expected the header '" + std::string(kImpactCsvHeader) +
             "' (with ',shot_diameter_m' for a shot mix), got " + text_excerpt(header));
    begin_ += header.size() + 1;
    columns_ = column_names(shot_diameter_);
}

ImpactLogReader::~ImpactLogReader() {
    if (file_) std::fclose(file_);
}

bool ImpactLogReader::fill() {
    if (eof_) return false;
    if (begin_ > 0) {
        std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
        end_ -= begin_;
        begin_ = 0;
    }
    if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);  // a line longer than the buffer
    const std::size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
    end_ += got;
    if (got == 0) eof_ = true;
    return got > 0;
}

void ImpactLogReader::fail(const std::string& what) const { throw InputError({path_, static_cast<int>(line_), 0}, "", what); }

void ImpactLogReader::refuse_row(const std::string& column, const std::string& problem) const {
    throw InputError({path_, static_cast<int>(line_), 0}, column, "malformed impact row " + std::to_string(rows_) + ": " + problem);
}

bool ImpactLogReader::next(ImpactRow& row) {
    const char* nl = nullptr;
    while (!(nl = static_cast<const char*>(std::memchr(buffer_.data() + begin_, '\n', end_ - begin_)))) {
        if (!fill()) {
            // End of file: whatever is left is an incomplete last line (a run killed mid-write).
            truncated_ = end_ > begin_;
            if (truncated_) truncated_line_ = line_ + 1;
            begin_ = end_;
            return false;
        }
    }
    const std::string_view line(buffer_.data() + begin_, static_cast<std::size_t>(nl - (buffer_.data() + begin_)));
    begin_ += line.size() + 1;
    ++line_;
    try {
        if (has_binary_byte(line)) throw BadField{kWholeRow, 0, "expected a text row, got binary data " + text_excerpt(line)};
        Fields f(line);
        row.time_s = f.number();
        row.shot = f.integer();
        row.component = f.text();
        row.triangle = f.integer();
        row.point_m = f.vec();
        row.v_in_m_per_s = f.vec();
        row.vn_in_m_per_s = f.number();
        row.vt_in_m_per_s = f.number();
        row.v_out_m_per_s = f.vec();
        row.vn_out_m_per_s = f.number();
        if (shot_diameter_) {
            row.shot_diameter_m = f.number();
            if (!(row.shot_diameter_m > 0.0)) f.fail("expected a shot diameter > 0");
        }
        if (!f.finished()) f.fail_extra(columns_.size());
    } catch (const BadField& b) {
        const std::string field = b.index < columns_.size() ? columns_[b.index] : std::string();
        throw InputError({path_, static_cast<int>(line_), static_cast<int>(b.column)}, field,
                         "malformed impact row " + std::to_string(rows_ + 1) + ": " + b.problem);
    }
    ++rows_;
    return true;
}

}  // namespace peensim
