#include "app/sweep/sweep_checks.h"

#include <chrono>
#include <fstream>
#include <sstream>

#include "model/component_mesh.h"
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

// `e`, raised reading the scene with `texts` among the overrides, as the mistake of what was given
// at `origin` (`field`, `label`: "variant 'fast'"). The scene parser names the override it came
// from ("(in --set 'shot.count=-5')"); the user wrote no --set, so that part names `label` instead.
[[noreturn]] void blame(const InputError& e, const SourceLocation& origin, const std::string& field, const std::string& label,
                        const std::vector<std::string>& texts) {
    if (e.where().file != override_file_name)  // a combination the scene file's own values refuse
        throw InputError(origin, field, label + " makes the scene invalid: " + e.what());
    std::string problem = e.problem();
    for (const std::string& text : texts)
        for (const std::string& said : {" (in --set '" + text + "')", " (from --set '" + text + "')"})
            if (const auto at = problem.find(said); at != std::string::npos)
                problem.replace(at, said.size(), " (" + label + ": " + text + ")");
    // "vary.shot.count" already says "shot.count"; "variants[1]" does not.
    const bool says_it =
        field.size() >= e.field().size() && field.compare(field.size() - e.field().size(), e.field().size(), e.field()) == 0;
    throw InputError(origin, field.empty() ? e.field() : (says_it ? field : field + ": " + e.field()), problem);
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

void check_sweep_variants(const std::string& scene_path, SweepPlan& plan, std::ostream& out) {
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
    // A STEP or IGES part this installation cannot read: every run would refuse it, so nothing
    // starts (the scene's own part blamed at its mesh: field, a variant's on the variant).
    check_cad_meshes_readable(read({}));
    CheckProgress progress(out, "the variants", plan.variants.size());
    for (std::size_t k = 0; k < plan.variants.size(); ++k) {
        const SweepVariant& v = plan.variants[k];
        std::vector<std::string> settings;
        for (const auto& [path, value] : v.set) settings.push_back(path + "=" + value);
        std::uint64_t seed = 0;
        try {
            const SceneDescription variant = read(settings);
            check_cad_meshes_readable(variant);
            seed = variant.process.seed;
        } catch (const InputError& e) {
            blame(e, v.origin, v.field, "variant '" + v.name + "'", settings);
        }
        reseed_variant(plan, k, seed);
        progress.done(k + 1);
    }
}

}  // namespace peensim
