#include "app/sweep/sweep_plan.h"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "app/sweep/sweep_values.h"
#include "output/output_names.h"

namespace peensim {

namespace {

// The largest seed a scene takes (process.seed is a 64-bit whole number >= 0).
constexpr std::uint64_t kLargestSeed = static_cast<std::uint64_t>(std::numeric_limits<long long>::max());

std::string trimmed(const std::string& s) {
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// A spec as messages quote it: a --vary of 20 000 values is not repeated whole.
std::string quoted(const std::string& spec) {
    constexpr std::size_t kShown = 60;
    return "'" + (spec.size() <= kShown ? spec : spec.substr(0, kShown) + "...") + "'";
}

// The last key of a scene path: "components[gear].motion.speed" -> "speed", "shot.diameter" -> "diameter".
std::string last_key(const std::string& path) {
    std::string key = path.substr(path.find_last_of('.') == std::string::npos ? 0 : path.find_last_of('.') + 1);
    return key.substr(0, key.find('['));
}

std::string field_of(const SweepAxis& a) { return a.field.empty() ? a.path : a.field; }

}  // namespace

std::string sweep_seeds_problem(const std::string& given) {
    return "expected 1 to " + std::to_string(kMaxSweepSeeds) + " replicates per variant, got '" + given + "'";
}

SweepAxis parse_sweep_axis(const std::string& spec) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError({"--vary"}, "",
                         quoted(spec) + ": expected path=value1,value2,... (e.g. components[gear].motion.speed=30 rpm,60 rpm)");
    SweepAxis axis{trimmed(spec.substr(0, eq)), {}, {"--vary", 0, 0}, ""};
    std::string value;
    int depth = 0;
    for (std::size_t k = eq + 1; k < spec.size(); ++k) {
        const char c = spec[k];
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
    if (axis.values.size() > kMaxSweepValues)
        throw InputError({"--vary"}, axis.path,
                         std::to_string(axis.values.size()) + " values; expected at most " + std::to_string(kMaxSweepValues) +
                             " values per --vary (replicates of one variant: --seeds)");
    for (const std::string& v : axis.values)
        if (v.empty()) throw InputError({"--vary"}, axis.path, quoted(spec) + ": an empty value; expected values separated by commas");
    if (depth != 0) throw InputError({"--vary"}, axis.path, quoted(spec) + ": unbalanced brackets");
    return axis;
}

std::string sweep_variant_name(const std::vector<std::pair<std::string, std::string>>& set) {
    std::string name;
    for (const auto& [path, value] : set) {
        if (!name.empty()) name += '_';
        name += last_key(path) + '-';
        // A file's path names it by its file name: "mesh-rod.step", not "mesh-tmpstudyrod.step"
        // (two files of one name in two folders are numbered, as any collision is).
        const std::string shown = value.find('/') == std::string::npos ? value : value.substr(value.rfind('/') + 1);
        for (char c : shown)
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

// Before anything is built: the seeds, and the runs (`variants` x seeds; `variants` empty when it
// does not fit 64 bits) against kMaxSweepRuns. `what` names the variants ("20 x 20 values").
void check_size(std::optional<std::uint64_t> variants, int seeds, const SourceLocation& where, const std::string& field,
                const std::string& what) {
    if (seeds < 1 || seeds > kMaxSweepSeeds) throw InputError({"--seeds"}, "", sweep_seeds_problem(std::to_string(seeds)));
    std::uint64_t runs = 0;
    const bool fits = variants && !__builtin_mul_overflow(*variants, static_cast<std::uint64_t>(seeds), &runs);
    if (fits && runs <= kMaxSweepRuns) return;
    throw InputError(where, field,
                     what + " x " + std::to_string(seeds) + (seeds == 1 ? " seed" : " seeds") + " make " +
                         (fits ? std::to_string(runs) : "more than " + std::to_string(std::numeric_limits<std::uint64_t>::max())) +
                         " runs; expected at most " + std::to_string(kMaxSweepRuns) +
                         " runs in a sweep (fewer values or seeds, or split the study)");
}

// The runs of variant v: `seeds` replicates from `base_seed`, the seed's override last.
std::vector<SweepRun> runs_of(const SweepPlan& plan, std::size_t v, std::uint64_t base_seed) {
    const SweepVariant& variant = plan.variants[v];
    if (base_seed > kLargestSeed - static_cast<std::uint64_t>(plan.seeds - 1))
        throw InputError({"--seeds"}, "",
                         (variant.set.empty() ? std::string() : "variant '" + variant.name + "': ") + "process.seed " +
                             std::to_string(base_seed) + " and " + std::to_string(plan.seeds) + " replicates go past the largest seed, " +
                             std::to_string(kLargestSeed) + "; expected a smaller seed or fewer --seeds");
    std::vector<SweepRun> runs;
    for (int r = 0; r < plan.seeds; ++r) {
        SweepRun run;
        run.variant = v;
        run.replicate = r;
        run.seed = base_seed + static_cast<std::uint64_t>(r);
        run.dir = plan.output_dir + "/" + variant.name + "/s" + std::to_string(r);
        run.overrides = plan.overrides;
        for (const auto& [path, value] : variant.set) run.overrides.push_back(path + "=" + value);
        run.overrides.push_back("process.seed=" + std::to_string(run.seed));
        runs.push_back(std::move(run));
    }
    return runs;
}

void add_runs(SweepPlan& plan, int seeds, std::uint64_t base_seed, const std::vector<std::string>& overrides,
              const std::string& output_dir) {
    plan.seeds = seeds;
    plan.overrides = overrides;
    plan.output_dir = output_dir;
    plan.runs.reserve(plan.variants.size() * static_cast<std::size_t>(seeds));
    for (std::size_t v = 0; v < plan.variants.size(); ++v)
        for (SweepRun& run : runs_of(plan, v, base_seed)) plan.runs.push_back(std::move(run));
}

// A variant's name is its runs' directory, beside the sweep's own "sweep".
bool valid_name(const std::string& name) { return name != "sweep" && is_output_name(name); }

// An axis' values, each once: the same value written twice (or two ways) would be run twice.
void check_distinct(const SweepAxis& a) {
    std::map<std::string, std::string> seen;  // value key -> the value as first written
    for (const std::string& v : a.values) {
        const auto [at, fresh] = seen.emplace(sweep_value_key(a.path, v), v);
        if (fresh) continue;
        if (at->second == v) throw InputError(a.origin, field_of(a), "the value '" + v + "' is given twice; expected each value once");
        throw InputError(a.origin, field_of(a),
                         "'" + v + "' is the value '" + at->second + "' again (" + at->first + "); expected each value once");
    }
}

}  // namespace

void reseed_variant(SweepPlan& plan, std::size_t variant, std::uint64_t seed) {
    // The variant's runs are consecutive (variant by variant): replaced in place.
    const auto first = std::find_if(plan.runs.begin(), plan.runs.end(), [&](const SweepRun& r) { return r.variant == variant; });
    if (first == plan.runs.end() || first->seed == seed) return;
    std::vector<SweepRun> runs = runs_of(plan, variant, seed);
    std::move(runs.begin(), runs.end(), first);
}

SweepPlan plan_sweep_variants(const std::vector<SweepVariant>& variants, int seeds, std::uint64_t base_seed,
                              const std::vector<std::string>& overrides, const std::string& output_dir) {
    const SourceLocation where = variants.empty() ? SourceLocation{"--vary"} : variants.front().origin;
    check_size(variants.size(), seeds, where, "variants", std::to_string(variants.size()) + " variants");
    SweepPlan plan;
    std::set<std::string> names;
    std::map<std::string, const SweepVariant*> settings;  // what a variant sets (value keys) -> the first that does
    for (const SweepVariant& v : variants) {
        const std::string field = v.field.empty() ? std::string("variant") : v.field;
        if (!valid_name(v.name))
            throw InputError(v.origin, field + ".name",
                             "variant name '" + v.name + "': expected letters, digits, '.', '-' or '_' (and not 'sweep')");
        if (!names.insert(v.name).second) throw InputError(v.origin, field + ".name", "variant name '" + v.name + "' is given twice");
        std::map<std::string, std::string> keys;
        for (const auto& [path, value] : v.set) keys[path] = sweep_value_key(path, value);
        std::string setting;
        for (const auto& [path, key] : keys) setting += path + "=" + key + "\n";
        if (const auto [at, fresh] = settings.emplace(setting, &v); !fresh)
            throw InputError(v.origin, field + ".set",
                             "variant '" + v.name + "' sets the same values as variant '" + at->second->name +
                                 "'; expected each variant to differ (replicates of one variant: seeds)");
        for (const auto& setting_entry : v.set) {
            const auto& path = setting_entry.first;  // a name, not a structured binding: Clang before 16 cannot capture those
            const auto& value = setting_entry.second;
            auto axis = std::find_if(plan.axes.begin(), plan.axes.end(), [&](const SweepAxis& a) { return a.path == path; });
            if (axis == plan.axes.end()) axis = plan.axes.insert(plan.axes.end(), SweepAxis{path, {}, v.origin, field + ".set." + path});
            if (std::find(axis->values.begin(), axis->values.end(), value) == axis->values.end()) axis->values.push_back(value);
        }
    }
    plan.variants = variants;
    plan.grid = false;
    add_runs(plan, seeds, base_seed, overrides, output_dir);
    return plan;
}

SweepPlan plan_sweep(const std::vector<SweepAxis>& axes, int seeds, std::uint64_t base_seed, const std::vector<std::string>& overrides,
                     const std::string& output_dir) {
    // The grid's size first, from the counts alone: a grid too large is refused before it is built.
    std::optional<std::uint64_t> variants = 1;
    std::string grid;
    for (const SweepAxis& a : axes) {
        if (a.values.size() > kMaxSweepValues)
            throw InputError(a.origin, field_of(a),
                             std::to_string(a.values.size()) + " values; expected at most " + std::to_string(kMaxSweepValues) +
                                 " values per --vary (replicates of one variant: --seeds)");
        std::uint64_t product = 0;
        if (variants && !__builtin_mul_overflow(*variants, static_cast<std::uint64_t>(a.values.size()), &product))
            variants = product;
        else
            variants.reset();
        grid += (grid.empty() ? "" : " x ") + std::to_string(a.values.size());
    }
    const SourceLocation where = axes.empty() ? SourceLocation{"--seeds"} : axes.front().origin;
    check_size(variants, seeds, where, axes.size() == 1 ? field_of(axes.front()) : "",
               axes.empty() ? std::string("1 variant") : (axes.size() == 1 ? grid + " values" : "a grid of " + grid + " values"));
    std::set<std::string> paths;
    for (const SweepAxis& a : axes) {
        if (!paths.insert(a.path).second)
            throw InputError(a.origin, field_of(a), "'" + a.path + "' is varied twice; give its values in one --vary");
        check_distinct(a);
    }
    SweepPlan plan;
    plan.axes = axes;
    plan.variants.reserve(static_cast<std::size_t>(*variants));
    // The grid, first axis slowest: an odometer over the axes' values (none: one variant, the scene).
    std::vector<std::size_t> at(axes.size(), 0);
    std::set<std::string> names;
    for (bool more = true; more;) {
        SweepVariant v;
        for (std::size_t k = 0; k < axes.size(); ++k) v.set.emplace_back(axes[k].path, axes[k].values[at[k]]);
        v.name = sweep_variant_name(v.set);
        // Values that differ only in dropped characters ("a b" and "ab"): numbered to stay apart.
        for (int n = 2; !names.insert(v.name).second; ++n) v.name = sweep_variant_name(v.set) + "." + std::to_string(n);
        if (!axes.empty()) v.origin = axes.front().origin;  // a combination's errors: where the grid was given
        if (axes.size() == 1) v.field = field_of(axes.front());
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

SweepPlan plan_sweep_replicates(const std::vector<SweepVariant>& variants, const std::vector<int>& replicates, std::uint64_t base_seed,
                                const std::vector<std::string>& overrides, const std::string& output_dir) {
    SweepPlan plan = plan_sweep_variants(variants, 1, base_seed, overrides, output_dir);
    plan.runs.clear();
    int most = 1;
    for (std::size_t v = 0; v < plan.variants.size(); ++v) {
        const int count = v < replicates.size() ? replicates[v] : 1;
        if (count < 1 || count > kMaxSweepSeeds) throw InputError({"--seeds"}, "", sweep_seeds_problem(std::to_string(count)));
        plan.seeds = count;
        for (SweepRun& run : runs_of(plan, v, base_seed)) plan.runs.push_back(std::move(run));
        most = std::max(most, count);
    }
    plan.seeds = most;
    return plan;
}

}  // namespace peensim
