#include "app/optimise/study_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include <yaml-cpp/yaml.h>

#include "app/sweep/sweep_plan.h"
#include "app/yaml_nodes.h"
#include "scene/yaml_access.h"
#include "scene/yaml_load.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

constexpr std::string_view kStudyKeys[] = {"scene", "set",       "variables", "objective", "constraints", "runs", "initial",
                                           "seeds", "max_seeds", "tolerance", "batch",     "confirm",     "seed"};
constexpr std::string_view kStudyKeysText =
    "scene, set, variables, objective, constraints, runs, initial, seeds, max_seeds, tolerance, batch, confirm, seed";
constexpr std::string_view kVariableKeysText = "path or set, min, max, start, scale, integer";
constexpr std::string_view kFigures[] = {"impact_rate_per_s",
                                         "mean_vn_mps",
                                         "p90_vn_mps",
                                         "coverage",
                                         "time_to_target_s",
                                         "slowest_region_time_to_target_s",
                                         "time_to_target_everywhere_s",
                                         "uniformity",
                                         "share_below_target",
                                         "almen_dose_J_per_m2",
                                         "almen_predicted_intensity_m"};
constexpr std::string_view kRegionFigureEnds[] = {"_impact_rate_per_s", "_coverage", "_time_to_target_s"};

// The search's bounds: a study is a handful of variables and at most a few thousand runs.
constexpr std::size_t kMaxVariables = 12;
constexpr int kMaxRuns = 5000;

std::string figures_text() {
    std::string s;
    for (std::string_view f : kFigures) s.append(s.empty() ? "" : ", ").append(f);
    return s + ", region_<name>_impact_rate_per_s, region_<name>_coverage, region_<name>_time_to_target_s";
}

// "10 rpm" -> (10, "rpm"); "64" -> (64, ""). False if it does not start with a finite number.
bool number_and_unit(const std::string& text, double& number, std::string& unit) {
    std::size_t used = 0;
    try {
        number = std::stod(text, &used);
    } catch (const std::exception&) {
        return false;
    }
    if (!std::isfinite(number)) return false;
    const auto b = text.find_first_not_of(' ', used);
    unit = b == std::string::npos ? std::string() : text.substr(b);
    return true;
}

}  // namespace

bool is_study_figure(const std::string& name) {
    if (std::find(std::begin(kFigures), std::end(kFigures), name) != std::end(kFigures)) return true;
    if (name.rfind("region_", 0) != 0) return false;
    for (std::string_view end : kRegionFigureEnds)
        if (name.size() > 7 + end.size() && name.compare(name.size() - end.size(), end.size(), end) == 0) return true;
    return false;
}

std::string study_value_text(const StudyVariable& v, double value) {
    std::ostringstream s;
    s.precision(6);
    s << (v.integer ? std::round(value) : value);
    return v.unit.empty() ? s.str() : s.str() + " " + v.unit;
}

Study read_study_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError({path}, "", "cannot read the study file");
    std::ostringstream text;
    text << in.rdbuf();
    Study s;
    s.path = path;
    YAML::Node root;
    try {
        root = parse_yaml(text.str(), path);
    } catch (const InputError& e) {
        // The usual slip: a scene path with [ ] inside { } (YAML's flow map reads [ as a list).
        if (e.problem().find("flow") == std::string::npos) throw;
        throw InputError(e.where(), e.field(),
                         e.problem() + " (a scene path with [ ] inside { } needs quotes: {path: \"components[gear].motion.speed\", ...})");
    }
    const auto fail = [&](const YAML::Node& n, const std::string& field, const std::string& problem) {
        throw InputError(yaml_location(path, n), field, problem);
    };
    if (!root.IsMap()) throw InputError({path, 1, 1}, "", "expected a study file: a map with scene, variables and objective");
    for (const auto& kv : root) {
        const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : yaml_text(kv.first);
        if (std::find(std::begin(kStudyKeys), std::end(kStudyKeys), key) == std::end(kStudyKeys))
            fail(kv.first, key, "unknown key in a study file; expected " + std::string(kStudyKeysText));
    }
    const YAML::Node scene = root["scene"];
    if (!scene)
        throw InputError({path, 1, 1}, "scene", "missing the scene file: expected `scene:` with its path (relative to this study file)");
    if (!scene.IsScalar()) fail(scene, "scene", "expected the scene file's path");
    s.scene_path = (fs::path(path).parent_path() / scene.Scalar()).lexically_normal().string();
    if (std::error_code ec; !fs::is_regular_file(s.scene_path, ec))
        fail(scene, "scene", "no scene file at '" + s.scene_path + "'; expected a scene file's path, relative to this study file");
    if (const YAML::Node set = root["set"]) {
        if (!set.IsSequence()) fail(set, "set", "expected a list of path=value");
        s.set_origin = yaml_location(path, set);
        for (const auto& x : set) s.overrides.push_back(yaml_text(x));
    }
    // Whole numbers within bounds: runs, initial, seeds, ...
    const auto whole = [&](const char* key, int low, int high, int& into) {
        const YAML::Node n = root[key];
        if (!n) return;
        long long v = 0;
        bool ok = n.IsScalar();
        if (ok) try {
                std::size_t used = 0;
                v = std::stoll(n.Scalar(), &used);
                ok = used == n.Scalar().size();
            } catch (const std::exception&) {
                ok = false;
            }
        if (!ok || v < low || v > high)
            fail(n, key,
                 "expected a whole number from " + std::to_string(low) + " to " + std::to_string(high) + ", got '" + yaml_text(n) + "'");
        into = static_cast<int>(v);
    };
    whole("runs", 2, kMaxRuns, s.runs);
    s.runs_origin = root["runs"] ? yaml_location(path, root["runs"]) : SourceLocation{path, 1, 1};
    whole("initial", 2, kMaxRuns, s.initial);
    whole("seeds", 1, kMaxSweepSeeds, s.seeds);
    whole("max_seeds", 1, kMaxSweepSeeds, s.max_seeds);
    whole("batch", 1, 4096, s.batch);
    whole("confirm", 0, kMaxSweepSeeds, s.confirm);
    if (s.confirm == 1) fail(root["confirm"], "confirm", "expected 0 (none) or 2 and more: one run has no interval to compare with");
    int seed = 1;
    whole("seed", 0, 2147483647, seed);
    s.seed = static_cast<std::uint64_t>(seed);
    if (s.max_seeds < s.seeds) fail(root["max_seeds"], "max_seeds", "expected at least `seeds` (" + std::to_string(s.seeds) + ")");
    if (const YAML::Node t = root["tolerance"]) {
        double x = 0.0;
        std::string unit;
        if (!t.IsScalar() || !number_and_unit(t.Scalar(), x, unit) || (unit != "%" && !unit.empty()) ||
            (unit == "%" ? x / 100.0 : x) <= 0.0 || (unit == "%" ? x / 100.0 : x) >= 1.0)
            fail(t, "tolerance",
                 "expected a share of the winner's value above 0 and below 1, e.g. 5 % or 0.05, got '" + yaml_text(t) + "'");
        s.tolerance = unit == "%" ? x / 100.0 : x;
    }

    const YAML::Node vars = root["variables"];
    if (!vars)
        throw InputError({path, 1, 1}, "variables", "missing the variables: expected `variables:` with each one's path, min and max");
    if (!vars.IsMap() || vars.size() == 0) fail(vars, "variables", "expected a map of name: {path, min, max}");
    if (vars.size() > kMaxVariables)
        fail(
            vars, "variables",
            "expected at most " + std::to_string(kMaxVariables) + " variables (a search of more needs far more runs than a study affords)");
    for (const auto& kv : vars) {
        StudyVariable v;
        v.name = kv.first.Scalar();
        v.origin = yaml_location(path, kv.first);
        const std::string field = "variables." + v.name;
        for (const StudyVariable& other : s.variables)
            if (other.name == v.name)
                fail(kv.first, field,
                     "a second variable named '" + v.name + "' (the first at line " + std::to_string(other.origin.line) +
                         "); expected each name once");
        const YAML::Node n = kv.second;
        if (!n.IsMap()) fail(n, field, "expected a map: {path, min, max}");
        for (const auto& e : n) {
            const std::string k = e.first.Scalar();
            if (k != "path" && k != "set" && k != "min" && k != "max" && k != "start" && k != "scale" && k != "integer")
                fail(e.first, field + "." + k, "unknown key of a variable; expected " + std::string(kVariableKeysText));
        }
        if (n["path"] && n["set"]) fail(n["set"], field + ".set", "give either path (one field) or set (fields with templates), not both");
        if (n["path"]) {
            if (!n["path"].IsScalar()) fail(n["path"], field + ".path", "expected a scene path, e.g. components[gear].motion.speed");
            v.set.emplace_back(n["path"].Scalar(), "{}");
        } else if (const YAML::Node set = n["set"]) {
            if (!set.IsMap() || set.size() == 0) fail(set, field + ".set", "expected a map of scene path: template with {} for the value");
            for (const auto& e : set) {
                const std::string t = yaml_text(e.second);
                if (t.find("{}") == std::string::npos)
                    fail(e.second, field + ".set." + e.first.Scalar(),
                         "expected a template with {} where the value goes, e.g. \"[0, 0, {}]\"");
                v.set.emplace_back(e.first.Scalar(), t);
            }
        } else {
            fail(n, field, "expected path (the scene field it sets) or set (fields with templates)");
        }
        const auto bound = [&](const char* key, double& into, bool required) {
            const YAML::Node b = n[key];
            if (!b) {
                if (required)
                    fail(n, field + "." + key, std::string("missing ") + key + ": expected a number with the field's unit, e.g. 10 rpm");
                return false;
            }
            std::string unit;
            if (!b.IsScalar() || !number_and_unit(b.Scalar(), into, unit))
                fail(b, field + "." + key, "expected a number with the field's unit, e.g. 10 rpm, got '" + yaml_text(b) + "'");
            if (std::string_view(key) == "min")
                v.unit = unit;
            else if (unit != v.unit)
                fail(b, field + "." + key,
                     "expected the unit of min ('" + (v.unit.empty() ? std::string("none") : v.unit) + "'), got '" +
                         (unit.empty() ? std::string("none") : unit) + "'");
            return true;
        };
        bound("min", v.min, true);
        bound("max", v.max, true);
        v.has_start = bound("start", v.start, false);
        if (!(v.max > v.min)) fail(n["max"], field + ".max", "expected max above min (" + study_value_text(v, v.min) + ")");
        if (v.has_start && (v.start < v.min || v.start > v.max)) fail(n["start"], field + ".start", "expected a start within min and max");
        if (const YAML::Node sc = n["scale"]) {
            if (!sc.IsScalar() || (sc.Scalar() != "linear" && sc.Scalar() != "log"))
                fail(sc, field + ".scale", "expected linear or log, got '" + yaml_text(sc) + "'");
            v.log_scale = sc.Scalar() == "log";
            if (v.log_scale && !(v.min > 0.0)) fail(sc, field + ".scale", "a log scale needs min above 0");
        }
        if (const YAML::Node in = n["integer"]) {
            if (!in.IsScalar() || (in.Scalar() != "true" && in.Scalar() != "false"))
                fail(in, field + ".integer", "expected true or false, got '" + yaml_text(in) + "'");
            v.integer = in.Scalar() == "true";
            if (v.integer && std::floor(v.max) < std::ceil(v.min) + 1.0)
                fail(in, field + ".integer", "expected at least two whole numbers between min and max");
        }
        // One field, one variable: two would write it in turn, the last one winning.
        for (const StudyVariable& other : s.variables)
            for (const auto& [p1, t1] : other.set)
                for (const auto& [p2, t2] : v.set)
                    if (p1 == p2)
                        fail(kv.first, field,
                             "sets " + p2 + " as variables." + other.name + " does (line " + std::to_string(other.origin.line) +
                                 "); expected each field set by one variable");
        s.variables.push_back(std::move(v));
    }

    if (const YAML::Node o = root["objective"]) {
        s.objective_origin = yaml_location(path, o);
        // A YAML::Node assigned to aliases the node it held (yaml-cpp): the figure's node is picked, not reassigned.
        if (o.IsMap()) {
            for (const auto& e : o)
                if (e.first.Scalar() != "figure" && e.first.Scalar() != "goal" && e.first.Scalar() != "component")
                    fail(e.first, "objective." + e.first.Scalar(), "unknown key of the objective; expected figure, goal, component");
            if (const YAML::Node c = o["component"]) {
                if (!c.IsScalar()) fail(c, "objective.component", "expected the name of a logged component");
                s.objective_component = c.Scalar();
            }
            if (!o["figure"]) fail(o, "objective.figure", "expected the figure to optimise, one of " + figures_text());
            if (const YAML::Node g = o["goal"]) {
                if (!g.IsScalar() || (g.Scalar() != "minimise" && g.Scalar() != "maximise"))
                    fail(g, "objective.goal", "expected minimise or maximise, got '" + yaml_text(g) + "'");
                s.maximise = g.Scalar() == "maximise";
            }
        }
        const YAML::Node figure = o.IsMap() ? o["figure"] : o;
        if (!figure.IsScalar() || !is_study_figure(figure.Scalar()))
            fail(figure, "objective", "expected one of " + figures_text() + ", got '" + yaml_text(figure) + "'");
        s.objective = figure.Scalar();
    }
    if (const YAML::Node cs = root["constraints"]) {
        if (!cs.IsSequence()) fail(cs, "constraints", "expected a list of {figure, max} or {figure, min}");
        for (std::size_t k = 0; k < cs.size(); ++k) {
            const YAML::Node c = cs[k];
            const std::string field = "constraints[" + std::to_string(k) + "]";
            if (!c.IsMap() || !c["figure"] || !c["figure"].IsScalar() || !is_study_figure(c["figure"].Scalar()))
                fail(c, field + ".figure", "expected {figure, max} or {figure, min} with a figure of " + figures_text());
            for (const auto& e : c)
                if (e.first.Scalar() != "figure" && e.first.Scalar() != "max" && e.first.Scalar() != "min" &&
                    e.first.Scalar() != "component")
                    fail(e.first, field + "." + e.first.Scalar(), "unknown key of a constraint; expected figure, max or min, component");
            const YAML::Node limit = c["max"] ? c["max"] : c["min"];
            if (!limit || (c["max"] && c["min"])) fail(c, field, "expected one limit: max or min (two sides: two constraints)");
            StudyConstraint sc{c["figure"].Scalar(), "", static_cast<bool>(c["max"]), 0.0, yaml_location(path, c)};
            if (const YAML::Node component = c["component"]) {
                if (!component.IsScalar()) fail(component, field + ".component", "expected the name of a logged component");
                sc.component = component.Scalar();
            }
            std::string unit;
            if (!limit.IsScalar() || !number_and_unit(limit.Scalar(), sc.limit, unit) || !unit.empty())
                fail(limit, field + (sc.is_max ? ".max" : ".min"),
                     "expected a plain number in the figure's SI unit (its name says it: _s, _per_s, _J_per_m2), got '" + yaml_text(limit) +
                         "'");
            s.constraints.push_back(sc);
        }
    }
    return s;
}

}  // namespace peensim
