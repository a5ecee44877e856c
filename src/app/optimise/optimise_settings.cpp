#include "app/optimise/optimise_settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <yaml-cpp/yaml.h>
#include <nlohmann/json.hpp>

#include "common/input_error.h"
#include "common/units.h"
#include "scene/overrides.h"
#include "scene/resolved_writer.h"
#include "scene/schema.h"
#include "scene/yaml_load.h"

namespace peensim {

namespace {

// A scene field's value as the scene has it (after the study's `set`; its default if the file
// leaves it out), in `unit`: the resolved scene's SI number over what one `unit` is in SI. Nothing
// for a path that does not lead to a number.
std::optional<double> scene_value(const SceneDescription& scene, const std::string& path, const std::string& unit) {
    const SchemaEntry* entry = override_schema_entry(path);
    if (entry == nullptr) return std::nullopt;
    YAML::Node node = load_yaml(resolved_scene_yaml(scene));
    std::size_t at = 0;
    while (at < path.size() && node) {
        std::size_t end = at;
        for (int depth = 0; end < path.size() && (depth > 0 || path[end] != '.'); ++end)
            depth += path[end] == '[' ? 1 : path[end] == ']' ? -1 : 0;
        const std::string segment = path.substr(at, end - at);
        const std::size_t bracket = segment.find('[');
        node = YAML::Node(node[segment.substr(0, bracket)]);
        if (bracket != std::string::npos) {
            const std::string selector = segment.substr(bracket + 1, segment.size() - bracket - 2);
            YAML::Node item;
            for (std::size_t k = 0; node.IsSequence() && k < node.size(); ++k)
                if ((node[k]["name"] && node[k]["name"].Scalar() == selector) || std::to_string(k) == selector) item = node[k];
            node = item;
        }
        at = end + 1;
    }
    double si = 0.0;
    if (!node || !node.IsScalar() || !parse_plain_number(node.Scalar(), si)) return std::nullopt;
    try {
        const double one = unit.empty() ? parse_quantity("1", entry->dimension, entry->plain_number_unit)
                                        : parse_quantity("1 " + unit, entry->dimension, entry->plain_number_unit);
        return one > 0.0 ? std::optional<double>(si / one) : std::nullopt;
    } catch (const std::exception&) {
        return std::nullopt;  // a unit the field does not take: the bounds' check says so
    }
}

}  // namespace

bool complete(const StudySetting& s) {
    for (const auto& v : s.values)
        if (!v) return false;
    return true;
}

double unit_of_value(const StudyVariable& v, double value) {
    const double u = v.log_scale ? std::log(value / v.min) / std::log(v.max / v.min) : (value - v.min) / (v.max - v.min);
    return std::clamp(u, 0.0, 1.0);
}

double value_of_unit(const StudyVariable& v, double u) {
    u = std::clamp(u, 0.0, 1.0);
    double x = v.log_scale ? v.min * std::pow(v.max / v.min, u) : v.min + u * (v.max - v.min);
    if (v.integer) x = std::clamp(std::round(x), std::ceil(v.min), std::floor(v.max));
    return std::stod(study_value_text(v, x));  // as the runs read it
}

Eigen::VectorXd unit_point(const Study& study, const StudySetting& s) {
    Eigen::VectorXd u(static_cast<Eigen::Index>(study.variables.size()));
    for (std::size_t i = 0; i < study.variables.size(); ++i)
        u(static_cast<Eigen::Index>(i)) = unit_of_value(study.variables[i], *s.values[i]);
    return u;
}

std::vector<std::pair<std::string, std::string>> setting_overrides(const Study& study, const StudySetting& s) {
    std::vector<std::pair<std::string, std::string>> out;
    for (std::size_t i = 0; i < study.variables.size(); ++i) {
        if (!s.values[i]) continue;
        const StudyVariable& v = study.variables[i];
        const std::string value = study_value_text(v, *s.values[i]);
        for (const auto& [path, pattern] : v.set) {
            std::string text = pattern;
            for (std::size_t at = text.find("{}"); at != std::string::npos; at = text.find("{}", at + value.size()))
                text.replace(at, 2, value);
            out.emplace_back(path, text);
        }
    }
    return out;
}

SweepPlan settings_plan(const Study& study, const std::vector<StudySetting>& settings, std::uint64_t base_seed,
                        const std::string& output_dir) {
    std::vector<SweepVariant> variants;
    std::vector<int> replicates;
    for (const StudySetting& s : settings) {
        SweepVariant v{s.name, setting_overrides(study, s), SourceLocation{study.path, 0, 0}, "setting " + s.name, {}};
        variants.push_back(std::move(v));
        replicates.push_back(s.seeds);
    }
    return plan_sweep_replicates(variants, replicates, base_seed, study.overrides, output_dir);
}

SweepFigure SettingFigures::at(std::size_t setting, const std::string& component, const std::string& figure) const {
    const auto c = by_component.find(component);
    if (c == by_component.end() || setting >= c->second.variants.size()) return {};
    const auto& figures = c->second.variants[setting].figures;
    const auto it = figures.find(figure);
    return it != figures.end() ? it->second : SweepFigure{};
}

std::size_t SettingFigures::runs(std::size_t setting) const { return setting < part().variants.size() ? part().variants[setting].runs : 0; }

SettingFigures read_setting_figures(const Study& study, const SweepPlan& plan) {
    SettingFigures f;
    f.by_component[""] = read_sweep_figures(plan);
    const auto add = [&](const std::string& component, const SourceLocation& where, const std::string& field) {
        if (component.empty() || f.by_component.count(component) > 0) return;
        SweepFigures figures = read_sweep_figures(plan, component);
        const bool logged =
            std::any_of(figures.variants.begin(), figures.variants.end(), [](const SweepVariantFigures& v) { return v.runs > 0; });
        const bool any_run =
            std::any_of(f.part().variants.begin(), f.part().variants.end(), [](const SweepVariantFigures& v) { return v.runs > 0; });
        if (!logged && any_run)
            throw InputError(where, field, "no run logs a component named '" + component + "'; expected one of the scene's output.log");
        f.by_component[component] = std::move(figures);
    };
    add(study.objective_component, study.objective_origin, "objective.component");
    for (std::size_t c = 0; c < study.constraints.size(); ++c)
        add(study.constraints[c].component, study.constraints[c].origin, "constraints[" + std::to_string(c) + "].component");
    return f;
}

std::string journal_text(const JournalIdentity& identity, const std::vector<StudySetting>& settings) {
    nlohmann::json j;
    j["study"] = identity.study;
    j["scene_fingerprint"] = identity.scene_fingerprint;
    j["settings"] = nlohmann::json::array();
    for (const StudySetting& s : settings) {
        nlohmann::json values = nlohmann::json::array();
        for (const auto& v : s.values) values.push_back(v ? nlohmann::json(*v) : nlohmann::json(nullptr));
        j["settings"].push_back({{"name", s.name}, {"values", values}, {"seeds", s.seeds}, {"round", s.round}, {"why", s.why}});
    }
    return j.dump(1) + "\n";
}

std::vector<StudySetting> read_journal(const std::string& text, JournalIdentity& identity) {
    const auto j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("settings")) throw std::runtime_error("not an optimisation journal");
    identity.study = j.value("study", "");
    identity.scene_fingerprint = j.value("scene_fingerprint", "");
    std::vector<StudySetting> out;
    for (const auto& s : j["settings"]) {
        StudySetting x;
        x.name = s.value("name", "");
        for (const auto& v : s.value("values", nlohmann::json::array()))
            x.values.push_back(v.is_number() ? std::optional<double>(v.get<double>()) : std::nullopt);
        x.seeds = s.value("seeds", 1);
        x.round = s.value("round", 0);
        x.why = s.value("why", "");
        out.push_back(std::move(x));
    }
    return out;
}

std::string plan_text(const SweepPlan& plan) {
    nlohmann::json j;
    j["variants"] = nlohmann::json::array();
    for (const SweepVariant& v : plan.variants) j["variants"].push_back(v.name);
    j["runs"] = nlohmann::json::array();
    for (const SweepRun& r : plan.runs)
        j["runs"].push_back(
            {{"variant", r.variant}, {"replicate", r.replicate}, {"seed", r.seed}, {"dir", r.dir}, {"overrides", r.overrides}});
    return j.dump();
}

SweepPlan plan_from_text(const std::string& text) {
    const auto j = nlohmann::json::parse(text);
    SweepPlan plan;
    plan.grid = false;
    for (const auto& v : j["variants"]) plan.variants.push_back({v.get<std::string>(), {}, {}, "", {}});
    for (const auto& r : j["runs"]) {
        SweepRun run;
        run.variant = r["variant"].get<std::size_t>();
        run.replicate = r["replicate"].get<int>();
        run.seed = r["seed"].get<std::uint64_t>();
        run.dir = r["dir"].get<std::string>();
        run.overrides = r["overrides"].get<std::vector<std::string>>();
        plan.runs.push_back(std::move(run));
    }
    return plan;
}

ObjectiveScale ObjectiveScale::of(const Study& study) {
    const std::string& f = study.objective;
    return {f.size() > 2 && f.compare(f.size() - 2, 2, "_s") == 0, study.maximise ? -1.0 : 1.0};
}

void fill_starts(Study& study, const SceneDescription& scene) {
    for (StudyVariable& v : study.variables) {
        if (v.has_start) continue;
        const bool one_field = v.set.size() == 1 && v.set.front().second == "{}";
        if (one_field && override_schema_entry(v.set.front().first) == nullptr)
            throw InputError(
                v.origin, "variables." + v.name + ".path",
                "'" + v.set.front().first + "' is no scene field; expected a path as --set takes it, e.g. components[gear].motion.speed");
        const std::optional<double> value = one_field ? scene_value(scene, v.set.front().first, v.unit) : std::nullopt;
        if (!value)
            throw InputError(v.origin, "variables." + v.name + ".start",
                             one_field
                                 ? "the scene gives " + v.set.front().first + " no number to start from; expected start: (a value in " +
                                       (v.unit.empty() ? std::string("plain numbers") : v.unit) + ")"
                                 : "a variable that sets several fields has no one scene value to start from; expected start:");
        const double x = std::stod(study_value_text(v, *value));
        if (x < v.min || x > v.max)
            throw InputError(v.origin, "variables." + v.name + ".start",
                             "the scene's own value, " + study_value_text(v, x) +
                                 ", is outside min and max; expected a start within them " + "(give start:, or widen the bounds)");
        v.has_start = true;
        v.start = x;
    }
}

}  // namespace peensim
