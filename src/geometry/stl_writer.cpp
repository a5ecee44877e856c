#include "geometry/stl_writer.h"

#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "common/input_error.h"
#include "geometry/mesh_checks.h"

namespace peensim {

namespace {

[[noreturn]] void fail_write(const std::string& path, const std::string& problem) {
    throw InputError(SourceLocation{path, 0, 0}, "output", problem);
}

// Opens "<path>.partial"; commit() closes it and renames it to path.
class PartialFile {
public:
    PartialFile(const std::string& path, std::ios::openmode mode)
        : path_(path), partial_(path + ".partial"), stream_(partial_, mode | std::ios::trunc) {
        if (!stream_) fail_write(path_, "cannot open '" + partial_ + "' for writing");
    }
    PartialFile(const PartialFile&) = delete;
    PartialFile& operator=(const PartialFile&) = delete;
    ~PartialFile() {
        if (!committed_) {
            stream_.close();
            std::error_code ignored;
            std::filesystem::remove(partial_, ignored);
        }
    }

    std::ofstream& stream() { return stream_; }

    void commit() {
        stream_.close();
        if (!stream_) fail_write(path_, "writing '" + partial_ + "' failed (disk full?)");
        std::error_code error;
        std::filesystem::rename(partial_, path_, error);
        if (error) fail_write(path_, "cannot rename '" + partial_ + "' into place: " + error.message());
        committed_ = true;
    }

private:
    std::string path_;
    std::string partial_;
    std::ofstream stream_;
    bool committed_ = false;
};

void put_u32(std::ofstream& out, std::uint32_t value) {
    const std::array<char, 4> bytes{static_cast<char>(value & 0xffU), static_cast<char>((value >> 8) & 0xffU),
                                    static_cast<char>((value >> 16) & 0xffU), static_cast<char>((value >> 24) & 0xffU)};
    out.write(bytes.data(), bytes.size());
}

void put_f32(std::ofstream& out, double value) { put_u32(out, std::bit_cast<std::uint32_t>(static_cast<float>(value))); }

void put_vec(std::ofstream& out, const Vec3& v) {
    for (int k = 0; k < 3; ++k) put_f32(out, v[k]);
}

std::string unit_label(double unit_m) {
    if (unit_m == 1.0) return "m";
    if (unit_m == 1e-3) return "mm";
    char text[40];
    std::snprintf(text, sizeof text, "%.6g m", unit_m);
    return text;
}

std::string ascii_vec(const Vec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "%.9g %.9g %.9g", v.x(), v.y(), v.z());
    return text;
}

void write_ascii_facet(std::ofstream& out, const TriangleMesh& mesh, std::size_t t, double unit_m) {
    out << "  facet normal " << ascii_vec(triangle_normal(mesh, t)) << "\n    outer loop\n";
    for (int k = 0; k < 3; ++k) out << "      vertex " << ascii_vec(mesh.corner(t, k) / unit_m) << "\n";
    out << "    endloop\n  endfacet\n";
}

}  // namespace

void write_binary_stl(const TriangleMesh& mesh, const std::string& path, double unit_m, const std::string& solid_name) {
    PartialFile file(path, std::ios::binary);
    std::ofstream& out = file.stream();

    std::string header = "peensim binary STL, unit " + unit_label(unit_m);
    if (!solid_name.empty()) header += ", " + solid_name;
    header.resize(80, ' ');
    out.write(header.data(), 80);

    put_u32(out, static_cast<std::uint32_t>(mesh.triangle_count()));
    const char no_attributes[2] = {0, 0};
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        put_vec(out, triangle_normal(mesh, t));
        for (int k = 0; k < 3; ++k) put_vec(out, mesh.corner(t, k) / unit_m);
        out.write(no_attributes, 2);
    }
    file.commit();
}

void write_ascii_stl(const TriangleMesh& mesh, const std::string& path, double unit_m, const std::string& solid_name) {
    PartialFile file(path, std::ios::out);
    std::ofstream& out = file.stream();
    const bool grouped = !mesh.group_names.empty() && mesh.group_of_triangle.size() == mesh.triangle_count();
    const std::size_t solids = grouped ? mesh.group_names.size() : 1;
    for (std::size_t g = 0; g < solids; ++g) {
        const std::string name = grouped ? mesh.group_names[g] : solid_name;
        out << "solid " << name << "\n";
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
            if (!grouped || mesh.group_of_triangle[t] == static_cast<int>(g)) write_ascii_facet(out, mesh, t, unit_m);
        }
        out << "endsolid " << name << "\n";
    }
    file.commit();
}

}  // namespace peensim
