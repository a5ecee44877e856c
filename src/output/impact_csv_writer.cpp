#include "output/impact_csv_writer.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <stdexcept>
#include <utility>

#include "output/posix_file.h"

namespace peensim {
namespace {

// Widest shortest-round-trip double is 24 chars ("-2.2250738585072014e-308"); int32 is 11.
constexpr std::size_t kMaxDoubleChars = 32;
constexpr std::size_t kMaxIntChars = 12;
constexpr std::size_t kDoubleFields = 13;
constexpr std::size_t kIntFields = 3;

std::string join_path(const std::string& dir, std::string_view name) {
    std::string path = dir.empty() ? std::string(".") : dir;
    if (path.back() != '/') path += '/';
    return path.append(name);
}

// RFC 4180: a field with a comma, quote or line break is quoted, inner quotes doubled.
std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + '"';
}

std::vector<std::string> csv_fields(const std::vector<std::string>& names) {
    std::vector<std::string> fields;
    fields.reserve(names.size());
    for (const auto& name : names) fields.push_back(csv_field(name));
    return fields;
}

char* put_double(char* p, double value) { return std::to_chars(p, p + kMaxDoubleChars, value).ptr; }

char* put_int(char* p, std::int32_t value) { return std::to_chars(p, p + kMaxIntChars, value).ptr; }

char* put_vec(char* p, const Vec3& v) {
    p = put_double(p, v.x());
    *p++ = ',';
    p = put_double(p, v.y());
    *p++ = ',';
    p = put_double(p, v.z());
    return p;
}

void remove_if_present(const std::string& path) {
    if (::unlink(path.c_str()) != 0 && errno != ENOENT) {
        posix_file::throw_errno("cannot remove stale", path);
    }
}

std::uint64_t file_size(int fd, const std::string& path) {
    struct stat st {};
    if (::fstat(fd, &st) != 0) posix_file::throw_errno("cannot stat", path);
    return static_cast<std::uint64_t>(st.st_size);
}

// Reads `size` bytes at `offset` (for the resume checks).
std::string read_at(int fd, std::uint64_t offset, std::size_t size, const std::string& path) {
    std::string bytes(size, '\0');
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = ::pread(fd, bytes.data() + done, size - done, static_cast<off_t>(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) posix_file::throw_errno("cannot read", path);
        if (n == 0) break;
        done += static_cast<std::size_t>(n);
    }
    bytes.resize(done);
    return bytes;
}

}  // namespace

ImpactCsvWriter::ImpactCsvWriter(AdoptOpenFile, std::string dir, std::vector<std::string> component_names, bool shot_diameter, int fd,
                                 std::uint64_t bytes, std::uint64_t rows)
    : dir_(std::move(dir)),
      partial_path_(join_path(dir_, kImpactCsvPartialFileName)),
      final_path_(join_path(dir_, kImpactCsvFileName)),
      csv_names_(csv_fields(component_names)),
      shot_diameter_(shot_diameter),
      fd_(fd),
      bytes_written_(bytes),
      rows_written_(rows) {
    std::size_t longest_name = 0;
    for (const auto& name : csv_names_) longest_name = std::max(longest_name, name.size());
    // One char after each field: a comma, or the newline after the last.
    max_row_bytes_ = (kDoubleFields + (shot_diameter ? 1 : 0)) * (kMaxDoubleChars + 1) + kIntFields * (kMaxIntChars + 1) + longest_name + 1;
    capacity_ = std::max(kImpactCsvBufferBytes, 2 * max_row_bytes_);
    buffer_ = std::make_unique<char[]>(capacity_);
}

ImpactCsvWriter::ImpactCsvWriter(std::string dir, std::vector<std::string> component_names, bool shot_diameter)
    : ImpactCsvWriter(AdoptOpenFile{}, std::move(dir), std::move(component_names), shot_diameter, -1, 0, 0) {
    remove_if_present(final_path_);
    fd_ = posix_file::open_or_throw(partial_path_, O_WRONLY | O_CREAT | O_TRUNC);
    const std::string header = impact_csv_header(shot_diameter);
    std::copy(header.begin(), header.end(), buffer_.get());
    used_ = header.size();
    buffer_[used_++] = '\n';
    bytes_written_ = used_;
}

ImpactCsvWriter ImpactCsvWriter::resume(std::string dir, std::vector<std::string> component_names, std::uint64_t bytes, std::uint64_t rows,
                                        bool shot_diameter) {
    const std::string partial = join_path(dir, kImpactCsvPartialFileName);
    // A run that failed after finish() (a full disk while writing its summary) has its rows in
    // impacts.csv already and a checkpoint still: they go back to the .partial to be continued.
    const std::string final_path = join_path(dir, kImpactCsvFileName);
    if (::access(partial.c_str(), F_OK) != 0 && ::access(final_path.c_str(), F_OK) == 0) posix_file::rename_or_throw(final_path, partial);
    const int fd = ::open(partial.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        posix_file::throw_errno("cannot resume impacts from checkpoint: cannot open", partial);
    }
    try {
        const std::uint64_t size = file_size(fd, partial);
        const auto fail = [&](const std::string& problem) {
            throw std::runtime_error("cannot resume impacts from checkpoint: '" + partial + "' " + problem);
        };
        if (size < bytes) {
            fail("has " + std::to_string(size) + " bytes, the checkpoint recorded " + std::to_string(bytes));
        }
        const std::string header = impact_csv_header(shot_diameter) + '\n';
        if (bytes < header.size() || read_at(fd, 0, header.size(), partial) != header) {
            fail("does not start with the impacts.csv header, or the checkpoint offset " + std::to_string(bytes) + " is inside it");
        }
        if (read_at(fd, bytes - 1, 1, partial) != "\n") {
            fail("has no row end at the checkpoint offset " + std::to_string(bytes));
        }
        if (::ftruncate(fd, static_cast<off_t>(bytes)) != 0) {
            posix_file::throw_errno("cannot truncate", partial);
        }
        if (::lseek(fd, static_cast<off_t>(bytes), SEEK_SET) < 0) {
            posix_file::throw_errno("cannot seek", partial);
        }
        posix_file::fsync_or_throw(fd, partial);
    } catch (...) {
        ::close(fd);
        throw;
    }
    ImpactCsvWriter writer(AdoptOpenFile{}, std::move(dir), std::move(component_names), shot_diameter, fd, bytes, rows);
    remove_if_present(writer.final_path_);
    return writer;
}

ImpactCsvWriter::ImpactCsvWriter(ImpactCsvWriter&& other) noexcept
    : dir_(std::move(other.dir_)),
      partial_path_(std::move(other.partial_path_)),
      final_path_(std::move(other.final_path_)),
      csv_names_(std::move(other.csv_names_)),
      shot_diameter_(other.shot_diameter_),
      max_row_bytes_(other.max_row_bytes_),
      capacity_(other.capacity_),
      buffer_(std::move(other.buffer_)),
      used_(std::exchange(other.used_, 0)),
      fd_(std::exchange(other.fd_, -1)),
      directory_synced_(other.directory_synced_),
      bytes_written_(other.bytes_written_),
      rows_written_(other.rows_written_) {}

ImpactCsvWriter& ImpactCsvWriter::operator=(ImpactCsvWriter&& other) noexcept {
    if (this != &other) {
        close_quietly();
        dir_ = std::move(other.dir_);
        partial_path_ = std::move(other.partial_path_);
        final_path_ = std::move(other.final_path_);
        csv_names_ = std::move(other.csv_names_);
        shot_diameter_ = other.shot_diameter_;
        max_row_bytes_ = other.max_row_bytes_;
        capacity_ = other.capacity_;
        buffer_ = std::move(other.buffer_);
        used_ = std::exchange(other.used_, 0);
        fd_ = std::exchange(other.fd_, -1);
        directory_synced_ = other.directory_synced_;
        bytes_written_ = other.bytes_written_;
        rows_written_ = other.rows_written_;
    }
    return *this;
}

ImpactCsvWriter::~ImpactCsvWriter() { close_quietly(); }

void ImpactCsvWriter::close_quietly() noexcept {
    if (fd_ < 0) return;
    try {
        flush_buffer();
    } catch (...) {
        // A destructor cannot report; the rows lost here are after the last checkpoint.
    }
    ::close(fd_);
    fd_ = -1;
}

void ImpactCsvWriter::write(const ImpactRecord& impact) {
    if (fd_ < 0) throw std::logic_error("ImpactCsvWriter::write after finish()");
    if (impact.component < 0 || static_cast<std::size_t>(impact.component) >= csv_names_.size()) {
        throw std::out_of_range("impact on component index " + std::to_string(impact.component) + " but only " +
                                std::to_string(csv_names_.size()) + " component names were given");
    }
    if (capacity_ - used_ < max_row_bytes_) flush_buffer();

    char* const start = buffer_.get() + used_;
    char* p = start;
    p = put_double(p, impact.time_s);
    *p++ = ',';
    p = put_int(p, impact.shot);
    *p++ = ',';
    const std::string& name = csv_names_[static_cast<std::size_t>(impact.component)];
    p = std::copy(name.begin(), name.end(), p);
    *p++ = ',';
    p = put_int(p, impact.triangle);
    *p++ = ',';
    p = put_vec(p, impact.point_m);
    *p++ = ',';
    p = put_vec(p, impact.v_in_m_per_s);
    *p++ = ',';
    p = put_double(p, impact.vn_in_m_per_s);
    *p++ = ',';
    p = put_double(p, impact.vt_in_m_per_s);
    *p++ = ',';
    p = put_vec(p, impact.v_out_m_per_s);
    *p++ = ',';
    p = put_double(p, impact.vn_out_m_per_s);
    if (shot_diameter_) {
        *p++ = ',';
        p = put_double(p, impact.shot_diameter_m);
    }
    *p++ = '\n';

    const auto row_bytes = static_cast<std::size_t>(p - start);
    used_ += row_bytes;
    bytes_written_ += row_bytes;
    ++rows_written_;
}

void ImpactCsvWriter::write(std::span<const ImpactRecord> impacts) {
    for (const auto& impact : impacts) write(impact);
}

void ImpactCsvWriter::flush_buffer() {
    if (used_ == 0) return;
    posix_file::write_all(fd_, buffer_.get(), used_, partial_path_);
    used_ = 0;
}

void ImpactCsvWriter::flush_durable() {
    if (fd_ < 0) throw std::logic_error("ImpactCsvWriter::flush_durable after finish()");
    flush_buffer();
    posix_file::fsync_or_throw(fd_, partial_path_);
    if (!directory_synced_) {
        // The .partial's directory entry must survive too, or the checkpoint points at nothing.
        posix_file::fsync_directory(dir_.empty() ? std::string(".") : dir_);
        directory_synced_ = true;
    }
}

void ImpactCsvWriter::finish() {
    if (fd_ < 0) throw std::logic_error("ImpactCsvWriter::finish called twice");
    flush_buffer();
    posix_file::fsync_or_throw(fd_, partial_path_);
    const int fd = std::exchange(fd_, -1);
    posix_file::close_or_throw(fd, partial_path_);
    posix_file::rename_or_throw(partial_path_, final_path_);
    posix_file::fsync_directory(dir_.empty() ? std::string(".") : dir_);
}

}  // namespace peensim
