#include "scene/scene_difference.h"

#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "common/file_digest.h"
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

std::size_t indent_of(const std::string& line) {
    const auto first = line.find_first_not_of(' ');
    return first == std::string::npos ? line.size() : first;
}

std::string without_indent(const std::string& line) { return line.substr(indent_of(line)); }

// A line without its trailing comment (a unit, a mesh's digest), for naming a setting.
std::string without_comment(const std::string& line) {
    const auto hash = line.find("  # ");
    return hash == std::string::npos ? line : line.substr(0, hash);
}

// Where line k of a resolved scene is: its section and the entries it lies in, each by its name
// ("components, rod, motion"; "contacts, shot-steel"), from the lines that hold it.
std::string place_of_line(const std::vector<std::string>& lines, std::size_t k) {
    std::vector<std::string> parents;  // innermost first
    // A list entry's first line ("  - name: rod") names the entry its keys (at 4) belong to.
    std::size_t indent = indent_of(lines[k]) + (without_indent(lines[k]).rfind("- name: ", 0) == 0 ? 1 : 0);
    for (std::size_t i = k + 1; i-- > 0 && indent > 0;) {
        const std::size_t at = indent_of(lines[i]);
        const std::string text = without_indent(lines[i]);
        if (text.empty() || text[0] == '#' || at >= indent) continue;
        parents.push_back(text.rfind("- name: ", 0) == 0 ? text.substr(8) : text.substr(0, text.find(':')));
        indent = at;
    }
    std::string place;
    for (auto p = parents.rbegin(); p != parents.rend(); ++p) place += (place.empty() ? "" : ", ") + *p;
    return place.empty() ? "the scene" : place;
}

// The mesh files the run's resolved scene gives digests for (in the order it writes them:
// components, then sinks) whose bytes differ now.
std::string meshes_rewritten(const std::string& resolved_text, const SceneDescription& before) {
    std::vector<std::string> digests;
    for (const std::string& line : resolved_lines(resolved_text)) {
        const std::string text = without_indent(line);
        const auto comment = text.find(kMeshDigestComment);
        if (text.rfind("mesh: ", 0) == 0 && comment != std::string::npos) digests.push_back(text.substr(comment + 4));
    }
    std::vector<std::string> paths;
    for (const ComponentDesc& c : before.components) paths.push_back(c.mesh_path);
    for (const SinkDesc& s : before.sinks)
        if (s.region == SinkRegion::mesh) paths.push_back(s.mesh_path);
    if (digests.size() != paths.size()) return "";  // an earlier peensim's resolved scene: no digests
    std::string changed;
    for (std::size_t k = 0; k < paths.size(); ++k)
        if (file_digest_text(paths[k]) != digests[k] && changed.find(paths[k]) == std::string::npos)
            changed += (changed.empty() ? "" : ", ") + paths[k];
    return changed;
}

}  // namespace

std::string scene_difference(const std::string& resolved_yaml_path, const SceneDescription& now) {
    std::string resolved_text;
    SceneDescription before;
    try {
        std::ifstream in(resolved_yaml_path, std::ios::binary);
        if (!in) return "";
        resolved_text.assign(std::istreambuf_iterator<char>(in), {});
        before = parse_scene_text(resolved_text, resolved_yaml_path);
    } catch (const std::exception&) {
        return "";  // a damaged resolved scene, or its meshes gone
    }
    const std::vector<std::string> was = resolved_lines(hashed_scene_yaml(before)), is = resolved_lines(hashed_scene_yaml(now));
    // The lines that differ: after the common beginning and before the common end (a setting
    // changed, a block added or removed, or one block in place of another).
    std::size_t k = 0;
    while (k < was.size() && k < is.size() && was[k] == is[k]) ++k;
    std::size_t tail = 0;
    while (tail < was.size() - k && tail < is.size() - k && was[was.size() - 1 - tail] == is[is.size() - 1 - tail]) ++tail;
    const std::size_t was_end = was.size() - tail, is_end = is.size() - tail;
    if (k < was_end || k < is_end) {
        // A block as said: its first lines without indent or comment, "; " between, "..." after three.
        const auto block = [](const std::vector<std::string>& lines, std::size_t from, std::size_t to) {
            constexpr std::size_t kShown = 3;
            std::string text;
            for (std::size_t i = from; i < to && i < from + kShown; ++i)
                text += (text.empty() ? "" : "; ") + without_comment(without_indent(lines[i]));
            return to - from > kShown ? text + "; ..." : text;
        };
        if (k == was_end) return place_of_line(is, k) + ": now also `" + block(is, k, is_end) + "`, which the run had not";
        if (k == is_end) return place_of_line(was, k) + ": the run also had `" + block(was, k, was_end) + "`, which is gone now";
        const std::string a = without_indent(was[k]), b = without_indent(is[k]);
        // A mesh's line holds its bytes' digest: said in words, with the file the scene names now.
        if (was_end - k == 1 && is_end - k == 1 && a.rfind("mesh: ", 0) == 0 && b.rfind("mesh: ", 0) == 0) {
            const std::vector<std::string> named = resolved_lines(resolved_scene_yaml(now));
            const std::string file = k < named.size() ? without_comment(without_indent(named[k])) : std::string();
            return place_of_line(is, k) + ": the mesh file's bytes differ from the run's" +
                   (file.rfind("mesh: ", 0) == 0 ? " (now `" + file + "`)" : std::string());
        }
        if (was_end - k == 1 && is_end - k == 1) return place_of_line(is, k) + ": the run had `" + a + "`, now `" + b + "`";
        return place_of_line(is, k) + ": the run had `" + block(was, k, was_end) + "`, now `" + block(is, k, is_end) + "`";
    }
    // The same settings: the meshes' bytes, compared with those the run's resolved scene recorded.
    if (const std::string changed = meshes_rewritten(resolved_text, before); !changed.empty())
        return "the same settings, but the bytes of a mesh file differ from the run's: " + changed;
    return "the same settings: a mesh file's bytes differ, or the run was made by an earlier peensim";
}

}  // namespace peensim
