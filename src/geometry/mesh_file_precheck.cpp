#include "geometry/mesh_file_precheck.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "common/input_error.h"
#include "geometry/ascii_stl_check.h"
#include "geometry/obj_check.h"

namespace peensim {

namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& problem) {
    throw InputError(SourceLocation{path, 0, 0}, "mesh", problem);
}

// Bytes of a PLY scalar type, 0 if unknown.
std::uint64_t ply_type_bytes(const std::string& type) {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32") return 4;
    if (type == "double" || type == "float64") return 8;
    return 0;
}

void precheck_ply(const std::string& path, std::ifstream& in, std::uint64_t file_bytes) {
    struct Element {
        std::string name;
        std::uint64_t count = 0;
        std::uint64_t min_bytes = 0;  // per element, binary
        std::uint64_t values = 0;     // per element, at least (ASCII)
        std::vector<std::string> properties;
        std::vector<bool> is_list;
    };
    std::vector<Element> elements;
    bool binary = false, has_format = false;
    std::string line;
    int lines = 0;
    bool ended = false;
    // The header's grammar, strictly: the reader loops for ever on some broken headers (found by
    // fuzzing: an unknown property type, a stray character in a keyword line).
    const auto bad_line = [&](const std::string& what) {
        refuse(path, "PLY header line " + std::to_string(lines) + ": " + what + ": a damaged file");
    };
    std::getline(in, line);  // "ply"
    lines = 1;
    while (std::getline(in, line)) {
        if (++lines > 10000) refuse(path, "a PLY header of more than 10000 lines");
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::string word, extra;
        words >> word;
        if (word == "comment" || word == "obj_info") continue;
        if (word == "end_header") {
            if (line != "end_header") bad_line("expected 'end_header' alone");
            ended = true;
            break;
        }
        if (word == "format") {
            std::string kind, version;
            words >> kind >> version;
            if ((kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian") || version != "1.0" || (words >> extra))
                bad_line("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
            binary = kind != "ascii";
            has_format = true;
        } else if (word == "element") {
            Element e;
            std::string count;
            words >> e.name >> count;
            if (e.name.empty() || count.empty() || count.find_first_not_of("0123456789") != std::string::npos || count.size() > 19 ||
                (words >> extra))
                bad_line("expected 'element NAME COUNT'");
            e.count = std::stoull(count);
            elements.push_back(e);
        } else if (word == "property") {
            if (elements.empty()) bad_line("a property before any element");
            std::string type, name;
            words >> type;
            Element& e = elements.back();
            ++e.values;
            e.is_list.push_back(type == "list");
            if (type == "list") {
                std::string length_type, item_type;
                words >> length_type >> item_type >> name;
                if (ply_type_bytes(length_type) == 0 || ply_type_bytes(item_type) == 0 || name.empty() || (words >> extra))
                    bad_line("expected 'property list TYPE TYPE NAME' with known types");
                e.min_bytes += ply_type_bytes(length_type);  // a list holds at least its length field
            } else {
                words >> name;
                if (ply_type_bytes(type) == 0 || name.empty() || (words >> extra))
                    bad_line("expected 'property TYPE NAME' with a known type");
                e.min_bytes += ply_type_bytes(type);
            }
            for (const std::string& other : e.properties)
                if (other == name) bad_line("property '" + name + "' twice in element '" + e.name + "'");
            e.properties.push_back(name);
        } else {
            bad_line("unknown keyword '" + word + "'");
        }
    }
    if (ended && !has_format) refuse(path, "the PLY header has no format line: a damaged file");
    // The reader loops for ever on some malformed headers (found by fuzzing): refuse them first.
    if (!ended) refuse(path, "the PLY header has no end_header line: a damaged or truncated file");
    for (const Element& e : elements)
        if (e.count > 0 && e.values == 0)
            refuse(path, "PLY element '" + e.name + "' has " + std::to_string(e.count) + " entries but no properties: a damaged file");
    const std::streamoff position = in.tellg();
    const std::uint64_t header_bytes = position < 0 ? file_bytes : static_cast<std::uint64_t>(position);
    const std::uint64_t body = file_bytes > header_bytes ? file_bytes - header_bytes : 0;
    for (const Element& e : elements) {
        // ASCII: every value takes a digit and a separator at least.
        const std::uint64_t per = binary ? e.min_bytes : 2 * e.values;
        if (per == 0 || e.count == 0) continue;
        if (e.count > body / per)
            refuse(path, "the PLY header declares " + std::to_string(e.count) + " " + e.name + " elements, but the file (" +
                             std::to_string(file_bytes) + " bytes) can hold at most " + std::to_string(body / per) +
                             ": a damaged or truncated file");
    }
    if (binary) return;
    // ASCII: one entry per line, each list's length no more than the values left on its line (the
    // reader allocates a list by its length field: a damaged one asked for 28 GB, found by fuzzing).
    std::uint64_t line_number = static_cast<std::uint64_t>(lines);
    for (const Element& e : elements) {
        for (std::uint64_t k = 0; k < e.count; ++k) {
            if (!std::getline(in, line)) return;  // short: the reader reports it
            ++line_number;
            std::istringstream words(line);
            std::vector<std::string> values;
            for (std::string w; words >> w;) values.push_back(w);
            std::size_t at = 0;
            for (std::size_t p = 0; p < e.properties.size(); ++p) {
                if (at >= values.size()) break;  // short line: the reader reports it
                if (!e.is_list[p]) {
                    ++at;
                    continue;
                }
                const std::string& length = values[at++];
                const bool whole = !length.empty() && length.size() <= 19 && length.find_first_not_of("0123456789") == std::string::npos;
                if (!whole || std::stoull(length) > values.size() - at)
                    refuse(path, "PLY line " + std::to_string(line_number) + ": a list of '" + length + "' values in element '" + e.name +
                                     "' with " + std::to_string(values.size() - at) + " values left on the line: a damaged file");
                at += static_cast<std::size_t>(std::stoull(length));
            }
        }
    }
}

void precheck_stl(const std::string& path, std::ifstream& in, std::uint64_t file_bytes) {
    // 80-byte header, a 32-bit facet count, 50 bytes per facet. An ASCII STL starts with "solid"
    // and has no count; a binary one may too (in its free header), so it is told by its length.
    // An ASCII one is checked line by line (geometry/ascii_stl_check.h).
    char header[84];
    if (!in.read(header, sizeof(header))) return;
    std::uint32_t count = 0;
    std::memcpy(&count, header + 80, sizeof(count));
    const bool looks_ascii = std::strncmp(header, "solid", 5) == 0 && 84 + 50ull * count != file_bytes;
    if (looks_ascii) {
        in.clear();
        in.seekg(0);
        check_ascii_stl(path, in);
        return;
    }
    if (84 + 50ull * count > file_bytes)
        refuse(path, "the binary STL declares " + std::to_string(count) + " facets, but the file (" + std::to_string(file_bytes) +
                         " bytes) holds at most " + std::to_string((file_bytes - 84) / 50) + ": a damaged or truncated file");
}

}  // namespace

void precheck_mesh_file(const std::string& path) {
    std::error_code error;
    const auto size = std::filesystem::file_size(path, error);
    if (error) return;  // the reader reports what is wrong
    std::ifstream in(path, std::ios::binary);
    if (!in) return;
    char magic[4] = {};
    in.read(magic, 4);
    in.clear();
    in.seekg(0);
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".ply" || std::strncmp(magic, "ply", 3) == 0) {
        // The reader takes either for a PLY file, and loops for ever on some broken ones.
        if (std::strncmp(magic, "ply", 3) != 0 || (magic[3] != '\n' && magic[3] != '\r'))
            refuse(path, "not a PLY file: its first line is not 'ply'");
        precheck_ply(path, in, size);
        return;
    }
    if (ext == ".obj") {
        check_obj(path, in);
        return;
    }
    if (ext == ".stl" && size >= 84)
        precheck_stl(path, in, size);
    else if (ext == ".stl" && std::strncmp(magic, "soli", 4) == 0)
        check_ascii_stl(path, in);  // too short to be binary
    else if (ext == ".stl")
        refuse(path, "not an STL file: " + std::to_string(size) +
                         " bytes are too few for a binary STL (84 at least) and it does not start with 'solid' as an ASCII STL does");
}

}  // namespace peensim
