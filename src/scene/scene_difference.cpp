#include "scene/scene_difference.h"

#include <filesystem>
#include <sstream>
#include <system_error>
#include <vector>

#include "scene/resolved_writer.h"
#include "scene/scene_parser.h"

namespace peensim {

namespace {

std::vector<std::string> resolved_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::string without_indent(const std::string& line) {
    const auto first = line.find_first_not_of(' ');
    return first == std::string::npos ? std::string() : line.substr(first);
}

// Where line k of a resolved scene is: its section ("components") and, in a list, its entry's
// name ("components, entry 'gear'").
std::string place_of_line(const std::vector<std::string>& lines, std::size_t k) {
    std::string entry;
    for (std::size_t i = k + 1; i-- > 0;) {
        const std::string& line = lines[i];
        if (entry.empty() && line.rfind("  - name: ", 0) == 0) entry = line.substr(10);
        if (!line.empty() && line[0] != ' ' && line[0] != '#') {
            const std::string section = line.substr(0, line.find(':'));
            return entry.empty() || i == k ? section : section + ", entry " + entry;
        }
    }
    return "the scene";
}

}  // namespace

std::string scene_difference(const std::string& resolved_yaml_path, const SceneDescription& now) {
    namespace fs = std::filesystem;
    std::string before_text;
    try {
        before_text = hashed_scene_yaml(parse_scene_file(resolved_yaml_path));
    } catch (const std::exception&) {
        return "";  // an older peensim's resolved scene, a damaged one, or its meshes gone
    }
    const std::vector<std::string> before = resolved_lines(before_text), after = resolved_lines(hashed_scene_yaml(now));
    for (std::size_t k = 0; k < before.size() || k < after.size(); ++k) {
        const std::string was = k < before.size() ? without_indent(before[k]) : "(nothing)";
        const std::string is = k < after.size() ? without_indent(after[k]) : "(nothing)";
        if (was == is) continue;
        // A mesh's line holds its bytes' digest: said in words, with the file as the scene names it
        // (the resolved scene's line, the same line of the same block).
        if (was.rfind("mesh: ", 0) == 0 && is.rfind("mesh: ", 0) == 0) {
            const std::vector<std::string> named = resolved_lines(resolved_scene_yaml(now));
            const std::string file = k < named.size() ? without_indent(named[k]) : std::string();
            return place_of_line(after, k) + ": the mesh file's bytes differ from the run's" +
                   (file.rfind("mesh: ", 0) == 0 ? " (now `" + file + "`)" : std::string());
        }
        return place_of_line(k < after.size() ? after : before, k) + ": the run had `" + was + "`, now `" + is + "`";
    }
    // The same settings: the meshes' bytes are what differs (read now for both), those written
    // after the run began first.
    std::error_code error;
    const auto run_began = fs::last_write_time(resolved_yaml_path, error);
    std::string newer;
    const auto check = [&](const std::string& mesh_path) {
        const auto written = fs::last_write_time(mesh_path, error);
        if (!error && written > run_began) newer += (newer.empty() ? "" : ", ") + mesh_path;
    };
    for (const ComponentDesc& c : now.components) check(c.mesh_path);
    for (const SinkDesc& s : now.sinks)
        if (s.region == SinkRegion::mesh) check(s.mesh_path);
    if (!newer.empty()) return "the same settings, but a mesh file was written since the run began: " + newer;
    return "the same settings: a mesh file's bytes differ (replaced by an older file), or the run was made by an earlier peensim";
}

}  // namespace peensim
