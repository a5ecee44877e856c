#include "output/vtp_writer.h"

#include <fcntl.h>
#include <unistd.h>
#include <algorithm>
#include <bit>
#include <cstring>
#include <set>
#include <stdexcept>
#include <utility>

#include "output/posix_file.h"

namespace peensim {

// Raw appended data is written in host order and the header declares LittleEndian.
static_assert(std::endian::native == std::endian::little, "vtp_writer writes little-endian raw data");
static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");

namespace {

// An output file written through a fixed buffer. finish_as(path) flushes, fsyncs and renames
// it; a file never finished is removed by the destructor.
class BufferedFile {
public:
    BufferedFile(std::string path, int flags)
        : path_(std::move(path)),
          fd_(posix_file::open_or_throw(path_, flags | O_CREAT | O_TRUNC)),
          buffer_(new char[kVtpStreamBufferBytes]) {}
    ~BufferedFile() {
        if (fd_ >= 0) {
            ::close(fd_);
            ::unlink(path_.c_str());
        }
    }
    BufferedFile(const BufferedFile&) = delete;
    BufferedFile& operator=(const BufferedFile&) = delete;

    void write(const void* data, std::size_t size) {
        const char* bytes = static_cast<const char*>(data);
        if (size >= kVtpStreamBufferBytes) {  // large blocks skip the buffer
            flush();
            posix_file::write_all(fd_, bytes, size, path_);
            bytes_ += size;
            return;
        }
        if (used_ + size > kVtpStreamBufferBytes) flush();
        std::memcpy(buffer_.get() + used_, bytes, size);
        used_ += size;
        bytes_ += size;
    }
    template <class T>
    void put(T value) {
        write(&value, sizeof value);
    }

    void flush() {
        posix_file::write_all(fd_, buffer_.get(), used_, path_);
        used_ = 0;
    }

    // Appends the whole content of `source` (already flushed) after this file's bytes: in the
    // kernel with copy_file_range (hundreds of MB for millions of impacts, never through our
    // memory), or by reading and writing where the file system cannot.
    void append_contents_of(BufferedFile& source) {
        flush();
        off64_t from = 0;
        for (;;) {
            const ssize_t n = ::copy_file_range(source.fd_, &from, fd_, nullptr, std::size_t{1} << 30, 0);
            if (n > 0) {
                bytes_ += static_cast<std::uint64_t>(n);
                continue;
            }
            if (n == 0) return;
            if (errno == EINTR) continue;
            if (errno == EXDEV || errno == ENOSYS || errno == EINVAL || errno == EOPNOTSUPP) break;
            posix_file::throw_errno("cannot copy", source.path_);
        }
        if (::lseek(source.fd_, from, SEEK_SET) < 0) posix_file::throw_errno("cannot seek", source.path_);
        for (;;) {
            const ssize_t n = ::read(source.fd_, buffer_.get(), kVtpStreamBufferBytes);
            if (n < 0) {
                if (errno == EINTR) continue;
                posix_file::throw_errno("cannot read", source.path_);
            }
            if (n == 0) break;
            posix_file::write_all(fd_, buffer_.get(), static_cast<std::size_t>(n), path_);
            bytes_ += static_cast<std::uint64_t>(n);
        }
    }

    void finish_as(const std::string& final_path) {
        flush();
        posix_file::fsync_or_throw(fd_, path_);
        const int fd = std::exchange(fd_, -1);
        try {
            posix_file::close_or_throw(fd, path_);
            posix_file::rename_or_throw(path_, final_path);
        } catch (...) {
            ::unlink(path_.c_str());
            throw;
        }
        posix_file::fsync_directory(posix_file::parent_directory(final_path));
    }

    std::uint64_t bytes() const { return bytes_; }  // written so far, buffered ones included

private:
    std::string path_;
    int fd_ = -1;
    std::unique_ptr<char[]> buffer_;
    std::size_t used_ = 0;
    std::uint64_t bytes_ = 0;
};

void check_field(const std::string& name, int components, std::set<std::string>& seen) {
    if (name.empty()) throw std::invalid_argument("vtp field with an empty name");
    if (name.find_first_of("<>&\"'") != std::string::npos) {
        throw std::invalid_argument("vtp field name '" + name + "' contains an XML special character");
    }
    if (components < 1) throw std::invalid_argument("vtp field '" + name + "' has components < 1");
    if (!seen.insert(name).second) throw std::invalid_argument("duplicate vtp field '" + name + "'");
}

// One DataArray of the appended block; `tuples * components` values of `value_bytes` each.
struct ArrayEntry {
    std::string name;
    const char* type = "Float64";
    int components = 1;
    std::uint64_t tuples = 0;
    std::uint64_t value_bytes = 8;
    std::uint64_t data_bytes() const { return tuples * static_cast<std::uint64_t>(components) * value_bytes; }
};

// The XML before the raw data, with every array's offset in the appended block. `arrays` is:
// points, topology connectivity, topology offsets, then the attribute fields; they must be
// appended in this order, each after its UInt64 byte count.
std::string polydata_header(std::uint64_t points, const std::string& topology, std::uint64_t cells, const std::string& attribute_section,
                            const std::vector<ArrayEntry>& arrays) {
    std::string xml =
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
        "  <PolyData>\n"
        "    <Piece NumberOfPoints=\"" +
        std::to_string(points) + "\" NumberOfVerts=\"" + std::to_string(topology == "Verts" ? cells : 0) +
        "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" + std::to_string(topology == "Polys" ? cells : 0) + "\">\n";
    std::uint64_t offset = 0;
    auto data_array = [&](const ArrayEntry& a) {
        xml += "        <DataArray type=\"" + std::string(a.type) + "\" Name=\"" + a.name + "\" NumberOfComponents=\"" +
               std::to_string(a.components) + "\" format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
        offset += sizeof(std::uint64_t) + a.data_bytes();
    };
    xml += "      <Points>\n";
    data_array(arrays[0]);
    xml += "      </Points>\n      <" + topology + ">\n";
    data_array(arrays[1]);
    data_array(arrays[2]);
    xml += "      </" + topology + ">\n      <" + attribute_section + ">\n";
    for (std::size_t i = 3; i < arrays.size(); ++i) data_array(arrays[i]);
    xml += "      </" + attribute_section +
           ">\n    </Piece>\n  </PolyData>\n"
           "  <AppendedData encoding=\"raw\">\n   _";
    return xml;
}

constexpr const char* kPolyDataFooter = "\n  </AppendedData>\n</VTKFile>\n";

}  // namespace

void write_mesh_vtp(const std::string& path, const TriangleMesh& mesh, const std::vector<CellField>& cell_fields) {
    const std::uint64_t n_tri = mesh.triangle_count();
    const std::uint64_t n_vert = mesh.vertices.size();
    std::set<std::string> seen;
    std::vector<ArrayEntry> arrays = {
        {"Points", "Float64", 3, n_vert, 8}, {"connectivity", "Int64", 1, 3 * n_tri, 8}, {"offsets", "Int64", 1, n_tri, 8}};
    for (const CellField& f : cell_fields) {
        check_field(f.name, f.components, seen);
        if (f.values.size() != n_tri * static_cast<std::uint64_t>(f.components)) {
            throw std::invalid_argument("cell field '" + f.name + "' has " + std::to_string(f.values.size()) + " values for " +
                                        std::to_string(n_tri) + " triangles x " + std::to_string(f.components) + " components");
        }
        arrays.push_back({f.name, "Float64", f.components, n_tri, 8});
    }

    BufferedFile out(path + ".tmp", O_WRONLY);
    const std::string header = polydata_header(n_vert, "Polys", n_tri, "CellData", arrays);
    out.write(header.data(), header.size());

    out.put<std::uint64_t>(arrays[0].data_bytes());
    out.write(mesh.vertices.data(), n_vert * sizeof(Vec3));
    out.put<std::uint64_t>(arrays[1].data_bytes());
    for (const auto& tri : mesh.triangles) {
        for (int v : tri) out.put<std::int64_t>(v);
    }
    out.put<std::uint64_t>(arrays[2].data_bytes());
    for (std::uint64_t t = 1; t <= n_tri; ++t) out.put<std::int64_t>(static_cast<std::int64_t>(3 * t));
    for (const CellField& f : cell_fields) {
        out.put<std::uint64_t>(f.values.size() * sizeof(double));
        out.write(f.values.data(), f.values.size() * sizeof(double));
    }
    out.write(kPolyDataFooter, std::strlen(kPolyDataFooter));
    out.finish_as(path);
}

std::vector<PointFieldLayout> impact_point_field_layouts() {
    return {{"velocity_in_m_per_s", 3}, {"normal_speed_in_m_per_s", 1}, {"time_s", 1}};
}

// A scratch file holding one streamed array (read back by finish()).
class ImpactPointsVtpWriter::ScratchArray : public BufferedFile {
public:
    using BufferedFile::BufferedFile;
};

ImpactPointsVtpWriter::ImpactPointsVtpWriter(std::string path, std::vector<PointFieldLayout> fields)
    : path_(std::move(path)), fields_(std::move(fields)) {
    std::set<std::string> seen;
    for (const PointFieldLayout& f : fields_) {
        check_field(f.name, f.components, seen);
        values_per_point_ += static_cast<std::size_t>(f.components);
    }
    const std::vector<PointFieldLayout> impact = impact_point_field_layouts();
    impact_layout_ =
        std::equal(fields_.begin(), fields_.end(), impact.begin(), impact.end(),
                   [](const PointFieldLayout& a, const PointFieldLayout& b) { return a.name == b.name && a.components == b.components; });
    points_ = std::make_unique<ScratchArray>(path_ + ".points.part", O_RDWR);
    for (std::size_t i = 0; i < fields_.size(); ++i) {
        field_arrays_.push_back(std::make_unique<ScratchArray>(path_ + ".field" + std::to_string(i) + ".part", O_RDWR));
    }
}

// The scratch files remove themselves (BufferedFile's destructor) when never finished.
ImpactPointsVtpWriter::~ImpactPointsVtpWriter() = default;

void ImpactPointsVtpWriter::add(const Vec3& point_m, std::span<const double> values) {
    if (finished_) throw std::logic_error("ImpactPointsVtpWriter::add after finish: " + path_);
    if (values.size() != values_per_point_) {
        throw std::invalid_argument("point with " + std::to_string(values.size()) + " field values, " + std::to_string(values_per_point_) +
                                    " expected: " + path_);
    }
    points_->write(point_m.data(), sizeof(Vec3));
    std::size_t next = 0;
    for (std::size_t i = 0; i < fields_.size(); ++i) {
        const auto n = static_cast<std::size_t>(fields_[i].components);
        field_arrays_[i]->write(values.data() + next, n * sizeof(double));
        next += n;
    }
    ++count_;
}

void ImpactPointsVtpWriter::add(std::span<const Vec3> points_m, const std::vector<PointField>& fields) {
    if (finished_) throw std::logic_error("ImpactPointsVtpWriter::add after finish: " + path_);
    if (fields.size() != fields_.size()) {
        throw std::invalid_argument("chunk with " + std::to_string(fields.size()) + " fields, " + std::to_string(fields_.size()) +
                                    " expected: " + path_);
    }
    for (std::size_t i = 0; i < fields.size(); ++i) {
        if (fields[i].name != fields_[i].name || fields[i].components != fields_[i].components ||
            fields[i].values.size() != points_m.size() * static_cast<std::size_t>(fields_[i].components)) {
            throw std::invalid_argument("chunk field '" + fields[i].name + "' does not match layout field '" + fields_[i].name + "' for " +
                                        std::to_string(points_m.size()) + " points");
        }
    }
    points_->write(points_m.data(), points_m.size() * sizeof(Vec3));
    for (std::size_t i = 0; i < fields.size(); ++i) {
        field_arrays_[i]->write(fields[i].values.data(), fields[i].values.size() * sizeof(double));
    }
    count_ += points_m.size();
}

void ImpactPointsVtpWriter::add(const ImpactRecord& impact) {
    if (!impact_layout_) {
        throw std::logic_error("ImpactPointsVtpWriter::add(ImpactRecord) needs impact_point_field_layouts(): " + path_);
    }
    const double values[5] = {impact.v_in_m_per_s.x(), impact.v_in_m_per_s.y(), impact.v_in_m_per_s.z(), impact.vn_in_m_per_s,
                              impact.time_s};
    add(impact.point_m, values);
}

void ImpactPointsVtpWriter::finish() {
    if (finished_) throw std::logic_error("ImpactPointsVtpWriter::finish called twice: " + path_);
    finished_ = true;
    std::vector<ArrayEntry> arrays = {
        {"Points", "Float64", 3, count_, 8}, {"connectivity", "Int64", 1, count_, 8}, {"offsets", "Int64", 1, count_, 8}};
    for (const PointFieldLayout& f : fields_) arrays.push_back({f.name, "Float64", f.components, count_, 8});

    BufferedFile out(path_ + ".tmp", O_WRONLY);
    const std::string header = polydata_header(count_, "Verts", count_, "PointData", arrays);
    out.write(header.data(), header.size());

    points_->flush();
    out.put<std::uint64_t>(arrays[0].data_bytes());
    out.append_contents_of(*points_);
    out.put<std::uint64_t>(arrays[1].data_bytes());  // one vertex cell per point
    for (std::uint64_t i = 0; i < count_; ++i) out.put<std::int64_t>(static_cast<std::int64_t>(i));
    out.put<std::uint64_t>(arrays[2].data_bytes());
    for (std::uint64_t i = 1; i <= count_; ++i) out.put<std::int64_t>(static_cast<std::int64_t>(i));
    for (std::size_t i = 0; i < field_arrays_.size(); ++i) {
        field_arrays_[i]->flush();
        out.put<std::uint64_t>(arrays[3 + i].data_bytes());
        out.append_contents_of(*field_arrays_[i]);
    }
    out.write(kPolyDataFooter, std::strlen(kPolyDataFooter));
    out.finish_as(path_);

    points_.reset();  // removes the scratch files
    field_arrays_.clear();
}

}  // namespace peensim
