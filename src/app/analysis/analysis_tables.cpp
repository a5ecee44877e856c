#include "app/analysis/analysis_tables.h"

#include <charconv>
#include <cmath>
#include <future>
#include <sstream>

#include "analysis/region_stats.h"
#include "app/analysis/almen_analysis.h"
#include "app/analysis/analysis_format.h"
#include "common/parallel_chunks.h"
#include "output/atomic_file.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// The name of the region holding most of triangle t's area ("" for none).
std::string dominant_region_name(const ComponentAnalysis& c, std::size_t t) {
    const int r = c.regions.dominant_region(t);
    return r < 0 ? std::string() : c.regions.name(static_cast<std::size_t>(r));
}

void write_triangle_csv(const fs::path& path, const ComponentAnalysis& c, double duration) {
    const std::string header =
        "triangle,facet,area_mm2,impacts,impacts_per_mm2_s,mean_vn_mps,max_vn_mps,energy_J_per_m2,coverage,"
        "impacts_per_mm2_s_smoothed,impacts_smoothed_rel_error,mean_vn_mps_smoothed,energy_J_per_m2_smoothed,coverage_smoothed,"
        "smoothing_radius_mm,reachable,peened,excluded,region\n";
    const std::string radius_mm = fmt(c.smoothing->radius_m() * 1e3, 6);
    const auto whole = [](std::string& out, long long v) {
        char text[24];
        out.append(text, std::to_chars(text, text + sizeof text, v).ptr);
    };
    // The rows chunk by chunk on every core (a 500k-triangle part's ~10 M numbers), joined in
    // triangle order: the bytes a single pass writes.
    constexpr std::size_t kChunks = 64;
    const std::size_t triangles = c.fields->triangle_count();
    std::vector<std::string> rows(kChunks);
    for_each_chunk(kChunks, [&](std::size_t chunk) {
        const auto [begin, end] = chunk_range(triangles, kChunks, chunk);
        std::string& s = rows[chunk];
        for (std::size_t t = begin; t < end; ++t) {
            const SmoothedSums& m = c.smoothed[t];
            const auto field = [&s](const std::string& text) {
                s += text;
                s += ',';
            };
            whole(s, static_cast<long long>(t));
            s += ',';
            whole(s, c.mesh->source_facet.empty() ? static_cast<long long>(t) : static_cast<long long>(c.mesh->source_facet[t]));
            s += ',';
            field(fmt(c.fields->area_m2(t) * 1e6, 8));
            whole(s, static_cast<long long>(c.fields->count(t)));
            s += ',';
            field(fmt(c.fields->rate_per_mm2_s(t, duration), 6));
            field(fmt(c.fields->mean_normal_speed(t)));
            field(fmt(c.fields->max_normal_speed(t)));
            field(fmt(c.fields->energy_per_area(t), 6));
            field(c.coverage ? fmt(c.coverage->shown_triangle_coverage(t)) : "");
            field(fmt(m.impacts_per_m2() / 1e6 / duration, 6));
            field(fmt(m.relative_error(), 4));
            field(fmt(m.mean_normal_speed()));
            field(fmt(m.energy_J_per_m2(), 6));
            field(c.coverage ? fmt(m.coverage()) : "");
            field(radius_mm);
            field(c.reach.empty() ? "" : fmt(c.reach[t], 3));
            field(c.coverage ? fmt(c.coverage->peened_share(t), 3) : "");
            field(fmt(c.regions.excluded_fraction(t), 3));
            s += dominant_region_name(c, t);
            s += '\n';
        }
    });
    std::size_t size = header.size();
    for (const std::string& r : rows) size += r.size();
    std::string text;
    text.reserve(size);
    text += header;
    for (std::string& r : rows) {
        text += r;
        std::string().swap(r);  // its memory back as it is joined
    }
    write_file_atomically(path.string(), text);
}

// The per-triangle fields as VTK cell data (same names and units as the CSV columns).
std::vector<CellField> cell_fields(const ComponentAnalysis& c, double duration) {
    const std::size_t n = c.fields->triangle_count();
    std::vector<CellField> f{
        {"impacts", 1, {}}, {"impacts_per_mm2_s", 1, {}}, {"mean_vn_mps", 1, {}}, {"max_vn_mps", 1, {}}, {"energy_J_per_m2", 1, {}}};
    if (c.coverage) f.push_back({"coverage", 1, {}});
    // The smoothed fields (NaN where they are undefined: no impact within the radius for the mean
    // speed), and the radius on every cell, so that the file says what it holds.
    f.push_back({"impacts_per_mm2_s_smoothed", 1, {}});
    f.push_back({"mean_vn_mps_smoothed", 1, {}});
    f.push_back({"energy_J_per_m2_smoothed", 1, {}});
    if (c.coverage) f.push_back({"coverage_smoothed", 1, {}});
    f.push_back({"smoothing_radius_mm", 1, {}});
    if (!c.reach.empty()) f.push_back({"reachable", 1, {}});
    if (c.coverage) f.push_back({"peened", 1, {}});
    if (!c.regions.empty()) f.push_back({"excluded", 1, {}}), f.push_back({"region", 1, {}});
    for (CellField& x : f) x.values.reserve(n);
    for (std::size_t t = 0; t < n; ++t) {
        const double mean = c.fields->mean_normal_speed(t);
        const SmoothedSums& m = c.smoothed[t];
        std::size_t k = 0;
        f[k++].values.push_back(static_cast<double>(c.fields->count(t)));
        f[k++].values.push_back(c.fields->rate_per_mm2_s(t, duration));
        f[k++].values.push_back(std::isfinite(mean) ? mean : 0.0);  // ParaView: 0 where nothing hit
        f[k++].values.push_back(c.fields->max_normal_speed(t));
        f[k++].values.push_back(c.fields->energy_per_area(t));
        if (c.coverage) f[k++].values.push_back(c.coverage->shown_triangle_coverage(t));
        f[k++].values.push_back(m.impacts_per_m2() / 1e6 / duration);
        f[k++].values.push_back(m.mean_normal_speed());
        f[k++].values.push_back(m.energy_J_per_m2());
        if (c.coverage) f[k++].values.push_back(m.coverage());
        f[k++].values.push_back(c.smoothing->radius_m() * 1e3);
        if (!c.reach.empty()) f[k++].values.push_back(c.reach[t]);
        if (c.coverage) f[k++].values.push_back(c.coverage->peened_share(t));
        if (!c.regions.empty()) {
            f[k++].values.push_back(c.regions.excluded_fraction(t));
            f[k++].values.push_back(static_cast<double>(c.regions.dominant_region(t)));  // index into <c>_regions.csv's rows, -1: none
        }
    }
    return f;
}

std::string interval(double low, double high) { return fmt(low) + "," + (std::isinf(high) ? std::string("inf") : fmt(high)); }

// The forecast's columns: status, time to the target with its interval (s of peening), the run
// length that would give a number (too_short).
std::string forecast_columns(const AreaForecast& f) {
    std::string s = std::string(status_name(f.status)) + ',';
    const bool timed = f.status == AreaForecast::Status::reached || f.status == AreaForecast::Status::forecast ||
                       f.status == AreaForecast::Status::too_short;
    s += timed ? fmt(f.time_s, 6) + ',' + interval(f.low_s, f.high_s) : std::string(",,");
    s += ',' + (f.status == AreaForecast::Status::too_short ? (std::isinf(f.run_for_s) ? std::string("inf") : fmt(f.run_for_s, 6)) : "");
    return s;
}

void write_regions_csv(const fs::path& path, const ComponentAnalysis& c, double duration) {
    std::ostringstream s;
    s << "region,triangles,area_mm2,impacts,impacts_per_mm2_s,mean_vn_mps,max_vn_mps,energy_J_per_m2,coverage,excluded,peened_area_mm2,"
         "unreachable_area_mm2,time_to_target_status,time_to_target_s,time_to_target_low_s,time_to_target_high_s,run_for_s\n";
    for (std::size_t r = 0; r < c.regions.size(); ++r) {
        const RegionStats x = region_stats(c.regions, r, c.region_tallies[r], c.coverage.get(), duration);
        s << c.regions.name(r) << ',' << x.triangles << ',' << fmt(x.area_m2 * 1e6, 8) << ',' << x.impacts << ','
          << fmt(x.impacts_per_mm2_s, 6) << ',' << fmt(x.mean_normal_speed) << ',' << fmt(x.max_normal_speed) << ','
          << fmt(x.energy_per_area, 6) << ',' << fmt(x.coverage) << ',' << (c.regions.excluded(r) ? "true" : "false") << ','
          << fmt(x.peened_area_m2 * 1e6, 8) << ',' << fmt(x.unreachable_area_m2 * 1e6, 8) << ',';
        s << (c.coverage && r < c.forecast.regions.size() ? forecast_columns(c.forecast.regions[r]) : std::string(",,,,,")) << '\n';
    }
    write_file_atomically(path.string(), s.str());
}

// Coverage of every region against time (one column per region).
void write_region_curves_csv(const fs::path& path, const ComponentAnalysis& c, const AnalysisWindow& window) {
    std::ostringstream s;
    s << "time_s";
    for (std::size_t r = 0; r < c.regions.size(); ++r) s << ',' << c.regions.name(r);
    s << '\n';
    for (std::size_t k = 0; k < c.curve.size(); ++k) {
        s << fmt(window.from_s + c.curve[k].time_s, 8);
        for (std::size_t r = 0; r < c.regions.size(); ++r) s << ',' << fmt(c.region_curves[r][k].coverage, 6);
        s << '\n';
    }
    write_file_atomically(path.string(), s.str());
}

// One block of rows per region: "all" (the whole component) first, then the scene's regions.
void write_histograms_csv(const fs::path& path, const ComponentAnalysis& c) {
    std::ostringstream s;
    s << "region,quantity,bin_low,bin_high,unit,count\n";
    auto rows = [&](const std::string& region, const char* q, const Histogram& h, double scale, const char* unit) {
        for (std::size_t b = 0; b < h.bins.size(); ++b)
            s << region << ',' << q << ',' << fmt(static_cast<double>(b) * h.width * scale, 6) << ','
              << fmt(static_cast<double>(b + 1) * h.width * scale, 6) << ',' << unit << ',' << h.bins[b] << '\n';
    };
    auto block = [&](const std::string& region, const ImpactHistograms& h) {
        rows(region, "normal_speed", h.normal_speed, 1.0, "m/s");
        rows(region, "impact_angle", h.angle, 1.0, "deg");
        rows(region, "dent_diameter", h.dent, 1e6, "um");
    };
    block("all", c.histograms);
    for (std::size_t r = 0; r < c.regions.size(); ++r) block(c.regions.name(r), c.region_histograms[r]);
    write_file_atomically(path.string(), s.str());
}

void write_curve_csv(const fs::path& path, const ComponentAnalysis& c, const AnalysisWindow& window) {
    std::ostringstream s;
    s << "time_s,coverage\n";
    for (const CoveragePoint& p : c.curve) s << fmt(window.from_s + p.time_s, 8) << ',' << fmt(p.coverage, 6) << '\n';
    write_file_atomically(path.string(), s.str());
}

void write_jet_csv(const fs::path& path, const ComponentAnalysis& c) {
    std::ostringstream s;
    s << "first_impact,impacts,end_time_s,share_at_least_0_9_v0" << (c.jet_normal_meaningful ? ",share_keeping_0_9_jet_normal_speed" : "")
      << '\n';
    for (const JetWindow& w : c.jet->windows()) {
        s << w.first_impact << ',' << w.impacts << ',' << fmt(w.end_time_s, 8) << ',' << fmt(w.fast_share(), 6);
        if (c.jet_normal_meaningful) s << ',' << fmt(w.normal_kept_share(), 6);
        s << '\n';
    }
    write_file_atomically(path.string(), s.str());
}

}  // namespace

void write_triangle_tables(const fs::path& dir, const ComponentAnalysis& c, const AnalysisWindow& window) {
    const double duration = window.length_s();
    // The two per-triangle files, the largest (a 500k-triangle part: a second each), side by side.
    std::future<void> vtp =
        std::async(std::launch::async, [&] { write_mesh_vtp((dir / (c.name + ".vtp")).string(), *c.mesh, cell_fields(c, duration)); });
    try {
        write_triangle_csv(dir / (c.name + "_triangles.csv"), c, duration);
    } catch (...) {
        vtp.wait();  // it reads c: done before the error leaves
        throw;
    }
    vtp.get();
}

void write_component_tables(const fs::path& dir, const ComponentAnalysis& c, const AnalysisWindow& window) {
    const double duration = window.length_s();
    write_histograms_csv(dir / (c.name + "_histograms.csv"), c);
    if (c.coverage) write_curve_csv(dir / (c.name + "_coverage.csv"), c, window);
    if (!c.regions.empty()) write_regions_csv(dir / (c.name + "_regions.csv"), c, duration);
    if (!c.regions.empty() && c.coverage) write_region_curves_csv(dir / (c.name + "_region_coverage.csv"), c, window);
    if (c.almen) write_almen_csv(dir / (c.name + "_almen.csv"), *c.almen, window.from_s);
    if (c.jet) write_jet_csv(dir / (c.name + "_jet.csv"), c);
}

}  // namespace peensim
