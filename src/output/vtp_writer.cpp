#include "output/vtp_writer.h"

#include <fcntl.h>
#include <algorithm>
#include <bit>
#include <charconv>
#include <cstring>
#include <set>
#include <stdexcept>
#include <utility>

namespace peensim {

// Raw appended data is written in host order and the header declares LittleEndian.
static_assert(std::endian::native == std::endian::little, "vtp_writer writes little-endian raw data");
static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");

namespace {

const char* type_name(VtkType t) {
    switch (t) {
        case VtkType::float64: return "Float64";
        case VtkType::int64: return "Int64";
        case VtkType::int32: return "Int32";
    }
    return "Float64";
}

std::uint64_t type_bytes(VtkType t) { return t == VtkType::int32 ? 4 : 8; }

void check_name(const std::string& name, std::set<std::string>& seen) {
    if (name.empty()) throw std::invalid_argument("vtp field with an empty name");
    if (name.find_first_of("<>&\"'") != std::string::npos) {
        throw std::invalid_argument("vtp field name '" + name + "' contains an XML special character");
    }
    if (!seen.insert(name).second) throw std::invalid_argument("duplicate vtp field '" + name + "'");
}

void check_field(const std::string& name, int components, std::set<std::string>& seen) {
    check_name(name, seen);
    if (components < 1) throw std::invalid_argument("vtp field '" + name + "' has components < 1");
}

// Shortest text that reads back as exactly `x`.
std::string round_trip(double x) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, x).ptr;
    return std::string(text, end);
}

// The <FieldData> element (empty string when there is none).
std::string field_data_xml(const std::vector<FieldValue>& values) {
    if (values.empty()) return "";
    std::set<std::string> seen;
    std::string xml = "    <FieldData>\n";
    for (const FieldValue& f : values) {
        check_name(f.name, seen);
        if (const auto* text = std::get_if<std::string>(&f.value)) {
            // VTK's String arrays in ASCII: each character's code, each string ended by a 0.
            xml += "      <Array type=\"String\" Name=\"" + f.name + "\" NumberOfTuples=\"1\" format=\"ascii\">\n        ";
            for (unsigned char c : *text) xml += std::to_string(static_cast<int>(c)) + " ";
            xml += "0\n      </Array>\n";
            continue;
        }
        const auto& numbers = std::get<std::vector<double>>(f.value);
        if (numbers.empty()) throw std::invalid_argument("vtp field data '" + f.name + "' has no value");
        xml += "      <DataArray type=\"Float64\" Name=\"" + f.name + "\" NumberOfComponents=\"" + std::to_string(numbers.size()) +
               "\" NumberOfTuples=\"1\" format=\"ascii\">\n        ";
        for (std::size_t i = 0; i < numbers.size(); ++i) xml += (i ? " " : "") + round_trip(numbers[i]);
        xml += "\n      </DataArray>\n";
    }
    return xml + "    </FieldData>\n";
}

// The arrays of the appended block in their order there: points, connectivity, offsets, the point
// arrays, the cell arrays. Checks the layout.
struct AppendedArray {
    std::string name;
    VtkType type = VtkType::float64;
    int components = 1;
    std::uint64_t tuples = 0;
    std::uint64_t data_bytes() const { return tuples * static_cast<std::uint64_t>(components) * type_bytes(type); }
};

std::vector<AppendedArray> appended_arrays(const PolyDataLayout& layout) {
    const bool polys = layout.cells == PolyDataLayout::Cells::triangles;
    if (!polys && layout.triangles != 0) throw std::invalid_argument("vtp layout: triangles given for a file of vertices");
    const std::uint64_t cells = polys ? layout.triangles : layout.points;
    std::vector<AppendedArray> arrays = {{"Points", VtkType::float64, 3, layout.points},
                                         {"connectivity", VtkType::int64, 1, polys ? 3 * cells : cells},
                                         {"offsets", VtkType::int64, 1, cells}};
    std::set<std::string> point_names, cell_names;
    for (const VtkArraySpec& a : layout.point_arrays) {
        check_field(a.name, a.components, point_names);
        arrays.push_back({a.name, a.type, a.components, layout.points});
    }
    for (const VtkArraySpec& a : layout.cell_arrays) {
        check_field(a.name, a.components, cell_names);
        arrays.push_back({a.name, a.type, a.components, cells});
    }
    return arrays;
}

// The XML before the raw data, with every array's offset in the appended block; the arrays must
// be appended in appended_arrays' order, each after its UInt64 byte count.
std::string polydata_header(const PolyDataLayout& layout, const std::vector<AppendedArray>& arrays) {
    const bool polys = layout.cells == PolyDataLayout::Cells::triangles;
    const std::uint64_t cells = polys ? layout.triangles : layout.points;
    std::string xml =
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
        "  <PolyData>\n" +
        field_data_xml(layout.field_data) + "    <Piece NumberOfPoints=\"" + std::to_string(layout.points) + "\" NumberOfVerts=\"" +
        std::to_string(polys ? 0 : cells) + "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" +
        std::to_string(polys ? cells : 0) + "\">\n";
    std::vector<std::uint64_t> offsets;
    std::uint64_t offset = 0;
    for (const AppendedArray& a : arrays) {
        offsets.push_back(offset);
        offset += sizeof(std::uint64_t) + a.data_bytes();
    }
    auto data_array = [&](std::size_t i) {
        const AppendedArray& a = arrays[i];
        xml += "        <DataArray type=\"" + std::string(type_name(a.type)) + "\" Name=\"" + a.name + "\" NumberOfComponents=\"" +
               std::to_string(a.components) + "\" format=\"appended\" offset=\"" + std::to_string(offsets[i]) + "\"/>\n";
    };
    const std::string topology = polys ? "Polys" : "Verts";
    xml += "      <Points>\n";
    data_array(0);
    xml += "      </Points>\n      <" + topology + ">\n";
    data_array(1);
    data_array(2);
    xml += "      </" + topology + ">\n      <PointData>\n";
    std::size_t i = 3;
    for (std::size_t k = 0; k < layout.point_arrays.size(); ++k) data_array(i++);
    xml += "      </PointData>\n      <CellData>\n";
    for (std::size_t k = 0; k < layout.cell_arrays.size(); ++k) data_array(i++);
    xml +=
        "      </CellData>\n    </Piece>\n  </PolyData>\n"
        "  <AppendedData encoding=\"raw\">\n   _";
    return xml;
}

constexpr const char* kPolyDataFooter = "\n  </AppendedData>\n</VTKFile>\n";

}  // namespace

// One array of the appended block as the writer fills it: handed by the caller, or generated.
struct PolyDataWriter::Segment {
    enum class Kind { points, triangles, values, vertex_ids, offsets };
    std::string name;
    Kind kind = Kind::values;
    VtkType type = VtkType::float64;
    std::uint64_t values = 0;  // numbers (tuples * components)
    std::uint64_t bytes = 0;
    std::int64_t offset_step = 1;  // Kind::offsets: points per cell
};

PolyDataWriter::PolyDataWriter(std::string path, PolyDataLayout layout, Durability durability)
    : path_(std::move(path)), durability_(durability) {
    const std::vector<AppendedArray> arrays = appended_arrays(layout);
    const bool polys = layout.cells == PolyDataLayout::Cells::triangles;
    for (std::size_t i = 0; i < arrays.size(); ++i) {
        const AppendedArray& a = arrays[i];
        Segment s{a.name, Segment::Kind::values, a.type, a.tuples * static_cast<std::uint64_t>(a.components), a.data_bytes(), 1};
        if (i == 0) s.kind = Segment::Kind::points;
        if (i == 1) s.kind = polys ? Segment::Kind::triangles : Segment::Kind::vertex_ids;
        if (i == 2) s.kind = Segment::Kind::offsets, s.offset_step = polys ? 3 : 1;
        segments_.push_back(s);
    }
    const std::string header = polydata_header(layout, arrays);
    out_ = std::make_unique<BufferedFile>(path_ + ".tmp", O_WRONLY);
    out_->write(header.data(), header.size());
    current_ = 0;
    filled_ = 0;
    open_next_segment();
}

// An unfinished file removes itself (BufferedFile's destructor).
PolyDataWriter::~PolyDataWriter() = default;

// Writes the byte count of segments_[current_] and of every following segment the writer
// generates or that is empty, stopping at the first the caller must fill (or the end).
void PolyDataWriter::open_next_segment() {
    while (current_ < segments_.size()) {
        const Segment& s = segments_[current_];
        out_->put<std::uint64_t>(s.bytes);
        if (s.kind == Segment::Kind::vertex_ids) {
            for (std::uint64_t i = 0; i < s.values; ++i) out_->put<std::int64_t>(static_cast<std::int64_t>(i));
        } else if (s.kind == Segment::Kind::offsets) {
            for (std::uint64_t i = 1; i <= s.values; ++i) out_->put<std::int64_t>(static_cast<std::int64_t>(i) * s.offset_step);
        } else if (s.values > 0) {
            return;
        }
        ++current_;
    }
}

void PolyDataWriter::write_values(VtkType type, const void* data, std::uint64_t count, Item item) {
    const char* bytes = static_cast<const char*>(data);
    while (count > 0) {
        const char* kind = item == Item::point ? "point" : (item == Item::triangle ? "triangle" : "value");
        if (current_ >= segments_.size()) throw std::logic_error(path_ + ": " + kind + " after the last array of the layout");
        const Segment& s = segments_[current_];
        const bool fits = (item == Item::point && s.kind == Segment::Kind::points) ||
                          (item == Item::triangle && s.kind == Segment::Kind::triangles) ||
                          (item == Item::value && s.kind == Segment::Kind::values && s.type == type);
        if (!fits) {
            throw std::logic_error(path_ + ": a " + kind + " (" + type_name(type) + ") where '" + s.name + "' (" + type_name(s.type) +
                                   ") is due");
        }
        const std::uint64_t n = std::min(count, s.values - filled_);
        out_->write(bytes, n * type_bytes(type));
        bytes += n * type_bytes(type);
        filled_ += n;
        count -= n;
        if (filled_ == s.values) {
            ++current_;
            filled_ = 0;
            open_next_segment();
        }
    }
}

void PolyDataWriter::add_point(const Vec3& point_m) { write_values(VtkType::float64, point_m.data(), 3, Item::point); }

void PolyDataWriter::add_points(std::span<const Vec3> points_m) {
    write_values(VtkType::float64, points_m.data(), 3 * points_m.size(), Item::point);
}

void PolyDataWriter::add_triangle(const std::array<int, 3>& vertices) {
    const std::int64_t ids[3] = {vertices[0], vertices[1], vertices[2]};
    write_values(VtkType::int64, ids, 3, Item::triangle);
}

void PolyDataWriter::add_triangles(std::span<const std::array<int, 3>> triangles) {
    // Widened to Int64 a block at a time: one check and one copy per block, not per triangle (a
    // 500k-triangle part's mesh is written once per coverage step).
    constexpr std::size_t kBlock = 1024;
    std::int64_t ids[3 * kBlock];
    for (std::size_t first = 0; first < triangles.size(); first += kBlock) {
        const std::size_t n = std::min(kBlock, triangles.size() - first);
        for (std::size_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) ids[3 * i + static_cast<std::size_t>(k)] = triangles[first + i][static_cast<std::size_t>(k)];
        write_values(VtkType::int64, ids, 3 * n, Item::triangle);
    }
}

void PolyDataWriter::add(double value) { write_values(VtkType::float64, &value, 1, Item::value); }
void PolyDataWriter::add(std::span<const double> values) { write_values(VtkType::float64, values.data(), values.size(), Item::value); }
void PolyDataWriter::add(std::int64_t value) { write_values(VtkType::int64, &value, 1, Item::value); }
void PolyDataWriter::add(std::int32_t value) { write_values(VtkType::int32, &value, 1, Item::value); }

void PolyDataWriter::finish() {
    if (!out_) throw std::logic_error(path_ + ": PolyDataWriter::finish called twice");
    if (current_ < segments_.size()) {
        throw std::logic_error(path_ + ": '" + segments_[current_].name + "' has " + std::to_string(filled_) + " of its " +
                               std::to_string(segments_[current_].values) + " values");
    }
    out_->write(kPolyDataFooter, std::strlen(kPolyDataFooter));
    const std::unique_ptr<BufferedFile> out = std::move(out_);
    out->finish_as(path_, durability_);
}

void write_mesh_vtp(const std::string& path, const TriangleMesh& mesh, const std::vector<CellField>& cell_fields,
                    const std::vector<FieldValue>& field_data, Durability durability) {
    const std::uint64_t n_tri = mesh.triangle_count();
    PolyDataLayout layout{mesh.vertices.size(), PolyDataLayout::Cells::triangles, n_tri, {}, {}, field_data};
    for (const CellField& f : cell_fields) {
        layout.cell_arrays.push_back({f.name, VtkType::float64, f.components});
        if (f.components >= 1 && f.values.size() != n_tri * static_cast<std::uint64_t>(f.components)) {
            throw std::invalid_argument("cell field '" + f.name + "' has " + std::to_string(f.values.size()) + " values for " +
                                        std::to_string(n_tri) + " triangles x " + std::to_string(f.components) + " components");
        }
    }
    PolyDataWriter out(path, std::move(layout), durability);
    out.add_points(mesh.vertices);
    out.add_triangles(mesh.triangles);
    for (const CellField& f : cell_fields) out.add(std::span<const double>(f.values));
    out.finish();
}

std::vector<PointFieldLayout> impact_point_field_layouts() { return {{"v_in_mps", 3}, {"vn_in_mps", 1}, {"time_s", 1}}; }

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
    points_ = std::make_unique<BufferedFile>(path_ + ".points.part", O_RDWR);
    for (std::size_t i = 0; i < fields_.size(); ++i) {
        field_arrays_.push_back(std::make_unique<BufferedFile>(path_ + ".field" + std::to_string(i) + ".part", O_RDWR));
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
    PolyDataLayout layout{count_, PolyDataLayout::Cells::vertices, 0, {}, {}, {}};
    for (const PointFieldLayout& f : fields_) layout.point_arrays.push_back({f.name, VtkType::float64, f.components});
    const std::vector<AppendedArray> arrays = appended_arrays(layout);

    BufferedFile out(path_ + ".tmp", O_WRONLY);
    const std::string header = polydata_header(layout, arrays);
    out.write(header.data(), header.size());

    out.put<std::uint64_t>(arrays[0].data_bytes());
    out.append_contents_of(*points_);
    out.put<std::uint64_t>(arrays[1].data_bytes());  // one vertex cell per point
    for (std::uint64_t i = 0; i < count_; ++i) out.put<std::int64_t>(static_cast<std::int64_t>(i));
    out.put<std::uint64_t>(arrays[2].data_bytes());
    for (std::uint64_t i = 1; i <= count_; ++i) out.put<std::int64_t>(static_cast<std::int64_t>(i));
    for (std::size_t i = 0; i < field_arrays_.size(); ++i) {
        out.put<std::uint64_t>(arrays[3 + i].data_bytes());
        out.append_contents_of(*field_arrays_[i]);
    }
    out.write(kPolyDataFooter, std::strlen(kPolyDataFooter));
    out.finish_as(path_);

    points_.reset();  // removes the scratch files
    field_arrays_.clear();
}

}  // namespace peensim
