#include "analysis/impact_log_reader.h"

#include <charconv>
#include <cstring>
#include <stdexcept>

#include "output/impact_csv_writer.h"

namespace peensim {

namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

// Splits a line into its fields, parsing each in turn.
class Fields {
public:
    explicit Fields(std::string_view line) : rest_(line) {}
    std::string_view text() {
        if (done_) throw std::invalid_argument("too few fields");
        const std::size_t comma = rest_.find(',');
        std::string_view field = rest_.substr(0, comma);
        if (comma == std::string_view::npos) {
            done_ = true;
            rest_ = {};
        } else {
            rest_.remove_prefix(comma + 1);
        }
        return field;
    }
    double number() {
        const std::string_view f = text();
        double v = 0.0;
        const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
        if (r.ec != std::errc() || r.ptr != f.data() + f.size()) throw std::invalid_argument("not a number: '" + std::string(f) + "'");
        return v;
    }
    std::int32_t integer() {
        const std::string_view f = text();
        std::int32_t v = 0;
        const auto r = std::from_chars(f.data(), f.data() + f.size(), v);
        if (r.ec != std::errc() || r.ptr != f.data() + f.size()) throw std::invalid_argument("not an integer: '" + std::string(f) + "'");
        return v;
    }
    Vec3 vec() {
        const double x = number(), y = number(), z = number();
        return {x, y, z};
    }
    bool finished() const { return done_; }

private:
    std::string_view rest_;
    bool done_ = false;
};

}  // namespace

ImpactLogReader::ImpactLogReader(const std::string& path) : path_(path), buffer_(kBufferBytes) {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw std::runtime_error(path + ": cannot open the impact log (" + std::strerror(errno) + ")");
    std::string_view header;
    fill();
    const char* nl = static_cast<const char*>(std::memchr(buffer_.data() + begin_, '\n', end_ - begin_));
    if (!nl) fail(end_ == begin_ ? "the impact log is empty (no header): the run wrote nothing" : "no complete header line");
    header = std::string_view(buffer_.data() + begin_, static_cast<std::size_t>(nl - (buffer_.data() + begin_)));
    shot_diameter_ = header == impact_csv_header(true);
    if (header != kImpactCsvHeader && !shot_diameter_)
        fail("not a peensim impact log: expected the header '" + std::string(kImpactCsvHeader) + "' (with ',shot_diameter_m' for a shot mix)");
    begin_ += header.size() + 1;
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

void ImpactLogReader::fail(const std::string& what) const { throw std::runtime_error(path_ + ":" + std::to_string(line_) + ": " + what); }

bool ImpactLogReader::next(ImpactRow& row) {
    const char* nl = nullptr;
    while (!(nl = static_cast<const char*>(std::memchr(buffer_.data() + begin_, '\n', end_ - begin_)))) {
        if (!fill()) {
            // End of file: whatever is left is an incomplete last line (a run killed mid-write).
            truncated_ = end_ > begin_;
            begin_ = end_;
            return false;
        }
    }
    const std::string_view line(buffer_.data() + begin_, static_cast<std::size_t>(nl - (buffer_.data() + begin_)));
    begin_ += line.size() + 1;
    ++line_;
    try {
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
            if (!(row.shot_diameter_m > 0.0)) throw std::invalid_argument("a shot diameter that is not positive");
        }
        if (!f.finished()) throw std::invalid_argument("too many fields");
    } catch (const std::invalid_argument& e) {
        fail(std::string("malformed impact row: ") + e.what());
    }
    ++rows_;
    return true;
}

}  // namespace peensim
