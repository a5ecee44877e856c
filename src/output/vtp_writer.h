// VTK XML PolyData (.vtp) outputs for ParaView: a component's triangle mesh with per-triangle
// fields (CELL data), and the impacts as points (VERTS) with per-impact fields (POINT data).
//
// Format: VTKFile version="1.0", byte_order="LittleEndian", header_type="UInt64", every array
// in one <AppendedData encoding="raw"> block (raw binary, no base64, no compression): each
// array there is an 8-byte byte count followed by its bytes, and its DataArray names its
// `offset` from the '_' that opens the block. Points and fields are Float64, connectivity and
// offsets Int64. Raw binary keeps a 500k-triangle mesh compact and fast to write, and it lets
// the impact writer copy streamed arrays into place without re-encoding them.
//
// Every file is written to `path.tmp`, fsynced, and renamed over `path`: a crash leaves either
// the previous file or the complete new one.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/vec.h"
#include "engine/impact_record.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

// One per-triangle array: values[t * components + c] is component c of triangle t
// (values.size() == triangles * components). Units belong in the name ("energy_J_per_m2").
struct CellField {
    std::string name;
    int components = 1;
    std::vector<double> values;
};

// One per-point array: values[i * components + c] is component c of point i.
struct PointField {
    std::string name;
    int components = 1;
    std::vector<double> values;
};

// Writes `mesh` (vertices in m, component frame) as polygons with `cell_fields` as CELL data.
// Throws std::invalid_argument for a field whose size is not triangles * components, a field
// with components < 1 or an empty or duplicate name or one that needs XML escaping;
// std::runtime_error (path + errno text) when the file cannot be written.
void write_mesh_vtp(const std::string& path, const TriangleMesh& mesh, const std::vector<CellField>& cell_fields);

// bytes, the buffer of each scratch array of ImpactPointsVtpWriter and of the file writer.
inline constexpr std::size_t kVtpStreamBufferBytes = std::size_t{1} << 20;

// Name and width of one streamed point field.
struct PointFieldLayout {
    std::string name;
    int components = 1;
};

// The point fields add(const ImpactRecord&) writes, in this order: the incoming velocity
// relative to the surface (m/s, 3 components, component frame), the normal approach speed
// (m/s), the time of impact (s).
std::vector<PointFieldLayout> impact_point_field_layouts();

// Streams millions of points with their fields to a .vtp without holding them in memory.
//
// While streaming, the point coordinates and each field go to their own scratch file next to
// the output (`path.points.part`, `path.field<i>.part`) through one fixed buffer each, so memory
// stays at (fields + 1) * kVtpStreamBufferBytes whatever the count. finish() then knows the
// count, hence every array's byte size and offset in the appended block: it writes the XML
// header to `path.tmp`, copies the scratch files in after it, generates the VERTS
// connectivity (0..n-1) and offsets (1..n), fsyncs, renames `path.tmp` to `path` and removes
// the scratch files. Without finish() (an exception, a killed run) the destructor removes the
// scratch files and `path` is left untouched.
class ImpactPointsVtpWriter {
public:
    // Throws std::invalid_argument for a bad layout (see write_mesh_vtp), std::runtime_error
    // when a scratch file cannot be created.
    ImpactPointsVtpWriter(std::string path, std::vector<PointFieldLayout> fields);
    ~ImpactPointsVtpWriter();
    ImpactPointsVtpWriter(const ImpactPointsVtpWriter&) = delete;
    ImpactPointsVtpWriter& operator=(const ImpactPointsVtpWriter&) = delete;

    // One point (m) and its field values, all fields concatenated in layout order
    // (values.size() == sum of components). Throws std::invalid_argument on a size mismatch,
    // std::logic_error after finish().
    void add(const Vec3& point_m, std::span<const double> values);

    // A chunk of points with one PointField per layout entry (same names, same order,
    // values.size() == points.size() * components).
    void add(std::span<const Vec3> points_m, const std::vector<PointField>& fields);

    // The impact's contact point with the impact_point_field_layouts() values. Throws
    // std::logic_error unless the writer was made with impact_point_field_layouts().
    void add(const ImpactRecord& impact);

    // Assembles and renames the .vtp (see the class comment). Throws std::runtime_error on a
    // write failure (then `path` is untouched and the writer is done), std::logic_error when
    // called twice.
    void finish();

    std::uint64_t points_written() const { return count_; }
    const std::string& path() const { return path_; }

private:
    class ScratchArray;

    std::string path_;
    std::vector<PointFieldLayout> fields_;
    std::unique_ptr<ScratchArray> points_;
    std::vector<std::unique_ptr<ScratchArray>> field_arrays_;
    std::size_t values_per_point_ = 0;
    bool impact_layout_ = false;
    bool finished_ = false;
    std::uint64_t count_ = 0;
};

}  // namespace peensim
