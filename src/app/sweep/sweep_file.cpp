#include "app/sweep/sweep_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include <yaml-cpp/yaml.h>

#include "app/yaml_nodes.h"
#include "common/input_error.h"
#include "scene/schema.h"
#include "scene/yaml_access.h"
#include "scene/yaml_load.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

constexpr std::string_view kSweepKeys[] = {"scene", "seeds", "set", "vary", "variants", "baseline"};
constexpr std::string_view kSweepKeysText = "scene, seeds, set, vary, variants, baseline";

bool is_sweep_key(const std::string& key) { return std::find(std::begin(kSweepKeys), std::end(kSweepKeys), key) != std::end(kSweepKeys); }

}  // namespace

bool is_sweep_file(const std::string& path) {
    YAML::Node root;
    try {
        root = load_yaml_file(path);
    } catch (const std::exception&) {
        return false;  // not readable YAML: read as a scene, which says what is wrong
    }
    if (!root.IsMap()) return false;
    if (root["scene"]) return true;
    bool sweep_keys = false;
    for (const auto& kv : root) {
        if (!kv.first.IsScalar()) continue;
        const std::string key = kv.first.Scalar();
        if (find_schema_entry(key) != nullptr) return false;  // a scene's key: a scene (with a stray key, if any)
        sweep_keys = sweep_keys || is_sweep_key(key);
    }
    return sweep_keys;
}

SweepFile read_sweep_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError({path}, "", "cannot read the sweep file");
    std::ostringstream text;
    text << in.rdbuf();
    const YAML::Node root = parse_yaml(text.str(), path);
    SweepFile f;
    const auto fail = [&](const YAML::Node& n, const std::string& field, const std::string& problem) {
        throw InputError(yaml_location(path, n), field, problem);
    };
    if (!root.IsMap()) throw InputError({path, 1, 1}, "", "expected a sweep file: a map with scene, and vary or variants");
    for (const auto& kv : root) {
        const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : yaml_text(kv.first);
        if (!is_sweep_key(key)) fail(kv.first, key, "unknown key in a sweep file; expected " + std::string(kSweepKeysText));
    }
    if (!root["scene"])
        throw InputError({path, 1, 1}, "scene",
                         "missing the scene file: expected `scene:` with its path (relative to this sweep file) in a sweep file");
    const YAML::Node scene = root["scene"];
    if (!scene.IsScalar()) fail(scene, "scene", "expected the scene file's path");
    f.scene_path = (fs::path(path).parent_path() / scene.Scalar()).lexically_normal().string();
    if (const YAML::Node seeds = root["seeds"]) {
        try {
            f.seeds = seeds.as<int>();
        } catch (const YAML::Exception&) {
            fail(seeds, "seeds", sweep_seeds_problem(yaml_text(seeds)));
        }
        if (f.seeds < 1 || f.seeds > kMaxSweepSeeds) fail(seeds, "seeds", sweep_seeds_problem(yaml_text(seeds)));
    }
    if (const YAML::Node set = root["set"]) {
        if (!set.IsSequence()) fail(set, "set", "expected a list of path=value");
        f.set_origin = yaml_location(path, set);
        for (const auto& s : set) f.overrides.push_back(yaml_text(s));
    }
    const YAML::Node vary = root["vary"], variants = root["variants"];
    if (vary && variants) fail(variants, "variants", "give either vary (a grid) or variants (a list), not both");
    if (vary) {
        if (!vary.IsMap()) fail(vary, "vary", "expected a map of path: [values]");
        for (const auto& kv : vary) {
            SweepAxis axis{kv.first.Scalar(), {}, yaml_location(path, kv.first), "vary." + kv.first.Scalar()};
            if (!kv.second.IsSequence() || kv.second.size() == 0)
                fail(kv.second, "vary." + axis.path, "expected a list of one or more values");
            for (const auto& v : kv.second) axis.values.push_back(yaml_text(v));
            f.axes.push_back(std::move(axis));
        }
    }
    if (variants) {
        if (!variants.IsSequence() || variants.size() == 0) fail(variants, "variants", "expected a list of {name, set}");
        for (std::size_t k = 0; k < variants.size(); ++k) {
            const YAML::Node v = variants[k];
            const std::string field = "variants[" + std::to_string(k) + "]";
            if (!v.IsMap() || !v["name"] || !v["name"].IsScalar()) fail(v, field + ".name", "expected each variant's name");
            SweepVariant variant{v["name"].Scalar(), {}, yaml_location(path, v), field, {}};
            if (const YAML::Node set = v["set"]) {
                if (!set.IsMap()) fail(set, field + ".set", "expected a map of path: value");
                for (const auto& kv : set) variant.set.emplace_back(kv.first.Scalar(), yaml_text(kv.second));
            }
            f.variants.push_back(std::move(variant));
        }
    }
    if (const YAML::Node b = root["baseline"]) {
        f.baseline = yaml_text(b);
        f.baseline_origin = yaml_location(path, b);
    }
    return f;
}

}  // namespace peensim
