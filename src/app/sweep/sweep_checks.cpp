#include "app/sweep/sweep_checks.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "app/checkpoint/checkpoint.h"
#include "app/render_module.h"
#include "geometry/cad_reader.h"
#include "model/component_mesh.h"
#include "scene/resolved_writer.h"
#include "scene/scene_difference.h"
#include "scene/scene_parser.h"
#include "scene/yaml_access.h"

namespace peensim {

namespace {

using Clock = std::chrono::steady_clock;

std::string file_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// How the scene parser names the override `text` an error came from.
std::array<std::string, 2> parser_mentions(const std::string& text) {
    return {" (in --set '" + text + "')", " (from --set '" + text + "')"};
}

// `e`, raised reading the scene with `texts` among the overrides, as the mistake of what was given
// at `origin` (`field`, `label`: "variant 'fast'"). The scene parser names the override it came
// from ("(in --set 'shot.count=-5')"); the user wrote no --set, so that part names `label` instead.
[[noreturn]] void blame(const InputError& e, const SourceLocation& origin, const std::string& field, const std::string& label,
                        const std::vector<std::string>& texts) {
    if (e.where().file != override_file_name)  // a combination the scene file's own values refuse
        throw InputError(origin, field, label + " makes the scene invalid: " + e.what());
    std::string problem = e.problem();
    for (const std::string& text : texts)
        for (const std::string& said : parser_mentions(text))
            if (const auto at = problem.find(said); at != std::string::npos)
                problem.replace(at, said.size(), " (" + label + ": " + text + ")");
    // "vary.shot.count" already says "shot.count"; "variants[1]" does not.
    const bool says_it =
        field.size() >= e.field().size() && field.compare(field.size() - e.field().size(), e.field().size(), e.field()) == 0;
    throw InputError(origin, field.empty() ? e.field() : (says_it ? field : field + ": " + e.field()), problem);
}

// Whether the override value `value` (a path, perhaps quoted) names the file `path`, as far as
// its name tells: the parser resolves a relative one against the scene, the value keeps it.
bool names_file(std::string value, const std::string& path) {
    while (!value.empty() && (value.front() == ' ' || value.front() == '"' || value.front() == '\'')) value.erase(value.begin());
    while (!value.empty() && (value.back() == ' ' || value.back() == '"' || value.back() == '\'')) value.pop_back();
    return !value.empty() && std::filesystem::path(value).filename() == std::filesystem::path(path).filename();
}

// Which of `texts` the parser's error names ("(in --set 'text')"), if any.
std::optional<std::size_t> named_setting(const InputError& e, const std::vector<std::string>& texts) {
    if (e.where().file != override_file_name) return std::nullopt;
    const std::string problem = e.problem();
    for (std::size_t k = 0; k < texts.size(); ++k)
        for (const std::string& said : parser_mentions(texts[k]))
            if (problem.find(said) != std::string::npos) return k;
    return std::nullopt;
}

bool ends_with_mesh(const std::string& setting_path) {
    return setting_path.size() >= 4 && setting_path.compare(setting_path.size() - 4, 4, "mesh") == 0;
}

// `e` (require_cad_reading's: this installation reads no STEP or IGES file) for `use`, the part of
// variant `v`, at the place that gave the part: the scene file's mesh: line; the variant's
// --vary, vary key or listed variant; or the sweep's own set (the sweep file's or study's `set`,
// or --set).
[[noreturn]] void blame_cad_part(const InputError& e, const CadMeshUse& use, const SweepPlan& plan, const SweepVariant& v,
                                 const SweepOverrides& where_set) {
    const std::string problem = e.problem_at_its_place();
    if (use.where.file != override_file_name) throw InputError(use.where, use.field, problem);
    for (std::size_t k = 0; k < v.set.size(); ++k) {
        const auto& [path, value] = v.set[k];
        if (!ends_with_mesh(path) || !names_file(value, use.path)) continue;
        if (k < v.set_origins.size()) {
            const SweepSettingOrigin& o = v.set_origins[k];
            throw InputError(o.where, o.field, o.label + " (" + path + "=" + value + "): " + problem);
        }
        const std::string said = "variant '" + v.name + "' (" + path + "=" + value + "): " + problem;
        if (plan.grid)
            for (const SweepAxis& a : plan.axes)
                if (a.path == path) throw InputError(a.origin, a.field.empty() ? a.path : a.field, said);
        throw InputError(v.origin, v.field.empty() ? use.field : v.field + ": " + use.field, said);
    }
    const auto given_in = [&](const std::vector<std::string>& texts) -> const std::string* {
        for (auto t = texts.rbegin(); t != texts.rend(); ++t) {  // the last one given wins
            const auto equals = t->find('=');
            if (equals != std::string::npos && ends_with_mesh(t->substr(0, equals)) && names_file(t->substr(equals + 1), use.path))
                return &*t;
        }
        return nullptr;
    };
    if (const std::string* text = given_in(where_set.from_command_line)) throw InputError({"--set"}, "", "'" + *text + "': " + problem);
    if (const std::string* text = given_in(where_set.from_file))
        throw InputError(where_set.file_origin, "set", "'" + *text + "': " + problem);
    throw InputError(use.where, use.field, problem);
}

// Progress of a long check: a line about once a second, after the first second.
class CheckProgress {
public:
    CheckProgress(std::ostream& out, std::string what, std::size_t total) : out_(out), what_(std::move(what)), total_(total) {}
    void done(std::size_t n) {
        const auto now = Clock::now();
        if (now < next_) return;
        next_ = now + std::chrono::seconds(1);
        out_ << "sweep: checking " << what_ << ": " << n << "/" << total_ << "\n" << std::flush;
    }

private:
    std::ostream& out_;
    std::string what_;
    std::size_t total_;
    Clock::time_point next_ = Clock::now() + std::chrono::seconds(1);
};

}  // namespace

SceneDescription read_sweep_scene(const std::string& scene_path, const SweepOverrides& o) {
    std::vector<std::string> all = o.from_file;
    all.insert(all.end(), o.from_command_line.begin(), o.from_command_line.end());
    if (!o.from_file.empty()) {
        try {
            (void)parse_scene_file(scene_path, o.from_file);
        } catch (const InputError& e) {
            if (e.where().file == override_file_name) blame(e, o.file_origin, "set", "set", o.from_file);
            throw;
        }
    }
    return parse_scene_file(scene_path, all);
}

void check_sweep_variants(const std::string& scene_path, SweepPlan& plan, const SweepOverrides& where_set, std::ostream& out) {
    // The scene's text read once (read_sweep_scene read the same file); each check parses it with its
    // overrides (a tree cannot be shared: overrides change it, and yaml-cpp's copies lose the lines).
    const std::string text = file_text(scene_path);
    const auto read = [&](const std::vector<std::string>& with) {
        std::vector<std::string> overrides = plan.overrides;
        overrides.insert(overrides.end(), with.begin(), with.end());
        return parse_scene_text(text, scene_path, overrides);
    };
    if (plan.grid && plan.axes.size() > 1 && plan.variants.size() > 1) {
        std::size_t values = 0;
        for (const SweepAxis& a : plan.axes) values += a.values.size();
        CheckProgress progress(out, "each value", values);
        std::size_t n = 0;
        for (const SweepAxis& a : plan.axes)
            for (const std::string& v : a.values) {
                const std::string setting = a.path + "=" + v;
                try {
                    (void)read({setting});
                } catch (const InputError& e) {
                    blame(e, a.origin, a.field.empty() ? a.path : a.field, "the value", {setting});
                }
                progress.done(++n);
            }
    }
    CheckProgress progress(out, "the variants", plan.variants.size());
    std::optional<std::pair<std::size_t, CadMeshUse>> cad;  // the first variant with a STEP or IGES part, and that part
    std::optional<std::size_t> animated;                    // the first variant whose runs record an animation
    for (std::size_t k = 0; k < plan.variants.size(); ++k) {
        const SweepVariant& v = plan.variants[k];
        std::vector<std::string> settings;
        for (const auto& [path, value] : v.set) settings.push_back(path + "=" + value);
        std::uint64_t seed = 0;
        try {
            const SceneDescription variant = read(settings);
            if (!cad)
                if (std::optional<CadMeshUse> use = first_cad_mesh(variant)) cad.emplace(k, std::move(*use));
            if (!animated && variant.render) animated = k;
            seed = variant.process.seed;
        } catch (const InputError& e) {
            if (const std::optional<std::size_t> at = named_setting(e, settings); at && *at < v.set_origins.size()) {
                const SweepSettingOrigin& o = v.set_origins[*at];
                blame(e, o.where, o.field, o.label, {settings[*at]});
            }
            blame(e, v.origin, v.field, "variant '" + v.name + "'", settings);
        }
        reseed_variant(plan, k, seed);
        progress.done(k + 1);
    }
    // A STEP or IGES part this installation cannot read at all: every run that has one would refuse
    // it, so none starts. Only the variants' own scenes count: a part every variant replaces is
    // never read.
    if (cad) {
        try {
            require_cad_reading(cad->second.path);
        } catch (const InputError& e) {
            blame_cad_part(e, cad->second, plan, plan.variants[cad->first], where_set);
        }
    }
    // The same for an animation without the render module: each run would stop before its first
    // step (exit 1, as `peensim run` does), and be retried once.
    if (animated) {
        try {
            (void)render_module();
        } catch (const std::runtime_error& e) {
            // Named by the variant only when the scene itself records none (an optimisation's
            // check settings are no variants of the user's).
            throw std::runtime_error((read({}).render ? std::string("the runs record an animation (the scene's render block)")
                                                      : "variant '" + plan.variants[*animated].name +
                                                            "' records an animation (its render block), as every run that has one would") +
                                     ": " + e.what());
        }
    }
}

void check_finished_runs(const std::string& scene_path, const SweepPlan& plan, const StaleRunWords& words) {
    std::string text;                    // the scene's text, read at the first finished run (a fresh sweep has none)
    std::vector<const SweepRun*> stale;  // of another scene: every one named, not one per attempt
    std::vector<bool> stale_finished;    // each of them finished (else: interrupted, its checkpoint)
    std::string first_difference;        // what differs for the first of them (scene_difference.h)
    for (const SweepRun& run : plan.runs) {
        // Its scene's hash: a finished run's summary's, an interrupted one's checkpoint's (a run
        // with neither starts afresh).
        std::string ran;
        bool finished = false;
        if (std::ifstream in(run.dir + "/summary.json"); in) {
            const auto j = nlohmann::json::parse(in, nullptr, false);
            finished = j.is_object() && j.value("finished", false);
            if (finished) ran = j.value("scene_hash", std::string());
            if (finished && ran.empty()) continue;  // not a peensim run's summary (a stand-in's): nothing to compare
        }
        if (!finished && std::filesystem::exists(run.dir + "/checkpoint.bin")) {
            try {
                ran = scene_hash_hex(load_checkpoint(run.dir + "/checkpoint.bin").scene_hash);
            } catch (const std::exception&) {
                continue;  // a damaged checkpoint: its run says so
            }
        } else if (!finished) {
            continue;
        }
        if (text.empty()) text = file_text(scene_path);
        const SceneDescription now = parse_scene_text(text, scene_path, run.overrides);
        if (ran == scene_hash_hex(scene_hash(now))) continue;
        if (stale.empty()) first_difference = scene_difference(run.dir + "/scene.resolved.yaml", now);
        stale.push_back(&run);
        stale_finished.push_back(finished);
    }
    if (stale.empty()) return;
    const SweepRun& first = *stale.front();
    const bool first_finished = stale_finished.front();
    const SweepVariant& v = plan.variants[first.variant];
    std::string values;
    for (const auto& [path, value] : v.set) values += (values.empty() ? "" : ", ") + path + "=" + value;
    std::string others;
    constexpr std::size_t kNamed = 5;  // runs named beyond the first; the rest counted
    for (std::size_t k = 1; k < stale.size() && k <= kNamed; ++k)
        others += (k > 1 ? ", " : "") + stale[k]->dir + (stale_finished[k] ? "" : " (interrupted)");
    if (stale.size() > kNamed + 1) others += " and " + std::to_string(stale.size() - kNamed - 1) + " more";
    const auto finished_count = static_cast<std::size_t>(std::count(stale_finished.begin(), stale_finished.end(), true));
    const bool one = stale.size() == 1;
    // What the job would do with them: skip the finished (their results compared as its own), and
    // resume the interrupted beside runs of this scene.
    std::string would;
    if (finished_count > 0)
        would += std::string("skip ") +
                 (one                              ? "it"
                  : finished_count == stale.size() ? "them"
                                                   : "the finished ones") +
                 " and compare " + (one ? "its" : "their") + " results as this " + words.entry + "'s";
    if (finished_count < stale.size())
        would += std::string(would.empty() ? "" : ", and ") + "resume " +
                 (one                   ? "it"
                  : finished_count == 0 ? "them"
                                        : "the interrupted ones") +
                 " beside runs of this scene";
    throw InputError({first.dir + (first_finished ? "/summary.json" : "/checkpoint.bin"), 0, 0},
                     first_finished ? "scene_hash" : "checkpoint",
                     "the run in " + first.dir + (first_finished ? " finished" : " was interrupted (its checkpoint.bin)") +
                         " with another scene (its text or a mesh file's bytes) or other values than this " + words.job + " gives " +
                         words.entry + " '" + v.name + "'" + (values.empty() ? std::string() : " (" + values + ")") +
                         (first_difference.empty() ? std::string() : "; what differs: " + first_difference) +
                         (others.empty() ? std::string() : "; so did " + others) + "; the " + words.job + " would " + would +
                         "; write this " + words.job + " to another folder, or remove " +
                         (one ? first.dir : std::string("those runs' folders")) + " to run " + (one ? "it" : "them") + " again");
}

}  // namespace peensim
