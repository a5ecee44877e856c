#include "app/sweep_plan.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace peensim {

namespace {

std::string trimmed(const std::string& s) {
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// The last key of a scene path: "components[gear].motion.speed" -> "speed", "shot.diameter" -> "diameter".
std::string last_key(const std::string& path) {
    std::string key = path.substr(path.find_last_of('.') == std::string::npos ? 0 : path.find_last_of('.') + 1);
    return key.substr(0, key.find('['));
}

}  // namespace

SweepAxis parse_sweep_axis(const std::string& spec) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0)
        throw std::invalid_argument("--vary '" + spec + "': expected path=value1,value2,... (e.g. components[gear].motion.speed=30 rpm,60 rpm)");
    SweepAxis axis{trimmed(spec.substr(0, eq)), {}};
    std::string value;
    int depth = 0;
    for (char c : spec.substr(eq + 1)) {
        if (c == '[' || c == '{') ++depth;
        if (c == ']' || c == '}') --depth;
        if (c == ',' && depth == 0) {
            axis.values.push_back(trimmed(value));
            value.clear();
        } else {
            value += c;
        }
    }
    axis.values.push_back(trimmed(value));
    for (const std::string& v : axis.values)
        if (v.empty()) throw std::invalid_argument("--vary '" + spec + "': an empty value; expected values separated by commas");
    if (depth != 0) throw std::invalid_argument("--vary '" + spec + "': unbalanced brackets");
    return axis;
}

std::string sweep_variant_name(const std::vector<std::pair<std::string, std::string>>& set) {
    std::string name;
    for (const auto& [path, value] : set) {
        if (!name.empty()) name += '_';
        name += last_key(path) + '-';
        for (char c : value)
            if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '-') name += c;
    }
    return name.empty() ? std::string("base") : name;
}

std::string sweep_value(const SweepVariant& variant, const std::string& path) {
    for (const auto& [p, value] : variant.set)
        if (p == path) return value;
    return "";
}

namespace {

// The runs of plan.variants: `seeds` replicates each.
void add_runs(SweepPlan& plan, int seeds, std::uint64_t base_seed, const std::vector<std::string>& overrides, const std::string& output_dir) {
    if (seeds < 1) throw std::invalid_argument("--seeds: expected at least 1");
    plan.seeds = seeds;
    for (std::size_t v = 0; v < plan.variants.size(); ++v)
        for (int r = 0; r < seeds; ++r) {
            SweepRun run;
            run.variant = v;
            run.replicate = r;
            run.seed = base_seed + static_cast<std::uint64_t>(r);
            run.dir = output_dir + "/" + plan.variants[v].name + "/s" + std::to_string(r);
            run.overrides = overrides;
            for (const auto& [path, value] : plan.variants[v].set) run.overrides.push_back(path + "=" + value);
            run.overrides.push_back("process.seed=" + std::to_string(run.seed));
            plan.runs.push_back(std::move(run));
        }
}

bool valid_name(const std::string& name) {
    if (name.empty() || name == "sweep") return false;
    for (char c : name)
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '_')) return false;
    return name != "." && name != "..";
}

}  // namespace

SweepPlan plan_sweep_variants(const std::vector<SweepVariant>& variants, int seeds, std::uint64_t base_seed,
                              const std::vector<std::string>& overrides, const std::string& output_dir) {
    SweepPlan plan;
    std::set<std::string> names;
    for (const SweepVariant& v : variants) {
        if (!valid_name(v.name))
            throw std::invalid_argument("variant name '" + v.name + "': expected letters, digits, '.', '-' or '_' (and not 'sweep')");
        if (!names.insert(v.name).second) throw std::invalid_argument("variant name '" + v.name + "' is given twice");
        for (const auto& [path, value] : v.set) {
            auto axis = std::find_if(plan.axes.begin(), plan.axes.end(), [&](const SweepAxis& a) { return a.path == path; });
            if (axis == plan.axes.end()) axis = plan.axes.insert(plan.axes.end(), SweepAxis{path, {}});
            if (std::find(axis->values.begin(), axis->values.end(), value) == axis->values.end()) axis->values.push_back(value);
        }
    }
    plan.variants = variants;
    add_runs(plan, seeds, base_seed, overrides, output_dir);
    return plan;
}

SweepPlan plan_sweep(const std::vector<SweepAxis>& axes, int seeds, std::uint64_t base_seed, const std::vector<std::string>& overrides,
                     const std::string& output_dir) {
    if (seeds < 1) throw std::invalid_argument("--seeds: expected at least 1");
    SweepPlan plan;
    plan.axes = axes;
    std::set<std::string> paths;
    for (const SweepAxis& a : axes)
        if (!paths.insert(a.path).second) throw std::invalid_argument("--vary: '" + a.path + "' is varied twice; give its values in one --vary");
    // The grid, first axis slowest: an odometer over the axes' values (none: one variant, the scene).
    std::vector<std::size_t> at(axes.size(), 0);
    std::set<std::string> names;
    for (bool more = true; more;) {
        SweepVariant v;
        for (std::size_t k = 0; k < axes.size(); ++k) v.set.emplace_back(axes[k].path, axes[k].values[at[k]]);
        v.name = sweep_variant_name(v.set);
        // Values that differ only in dropped characters ("1 mm" and "1mm"): numbered to stay apart.
        for (int n = 2; !names.insert(v.name).second; ++n) v.name = sweep_variant_name(v.set) + "." + std::to_string(n);
        plan.variants.push_back(std::move(v));
        more = false;
        for (std::size_t k = axes.size(); k-- > 0;) {
            if (++at[k] < axes[k].values.size()) {
                more = true;
                break;
            }
            at[k] = 0;
        }
    }
    add_runs(plan, seeds, base_seed, overrides, output_dir);
    return plan;
}

}  // namespace peensim
