#include "app/analysis/analysis_plots.h"

#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>

#include "common/shell_quote.h"
#include "output/atomic_file.h"

namespace fs = std::filesystem;

namespace peensim {

namespace {

// One histogram panel: the `quantity` column's value in <c>_histograms.csv and how to label it.
struct HistogramPanel {
    const char* quantity;
    const char* x_label;
};
constexpr std::array<HistogramPanel, 3> kHistogramPanels{{
    {"normal_speed", "normal impact speed v_n (m/s)"},
    {"impact_angle", "impact angle from the surface normal (deg)"},
    {"dent_diameter", "dent diameter, SAE J2277 eq. 10 (\u00b5m)"},
}};

// The absolute path of `gnuplot` on PATH, or "" if there is none.
std::string find_gnuplot() {
    const char* path = std::getenv("PATH");
    if (!path) return "";
    std::istringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        if (dir.empty()) dir = ".";
        const fs::path candidate = fs::path(dir) / "gnuplot";
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
    return "";
}

// `s` as a gnuplot single-quoted string (where '' stands for one quote).
std::string gnuplot_quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
    return q + "'";
}

// `s` inside a gnuplot enhanced-text title: _ ^ @ & { } would otherwise format the text.
std::string enhanced_text_escaped(const std::string& s) {
    std::string e;
    for (char c : s) {
        if (c == '_' || c == '^' || c == '@' || c == '&' || c == '{' || c == '}' || c == '~') e += '\\';
        e += c;
    }
    return e;
}

// The quantities of a histograms CSV (columns region,quantity,...,count) that have at least one
// counted impact on the whole component (region "all").
std::set<std::string> quantities_with_counts(const fs::path& csv) {
    std::set<std::string> found;
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
        if (!line.starts_with("all,")) continue;
        const auto first = line.find(',', 4);
        const auto last = line.rfind(',');
        if (first == std::string::npos || last == first) continue;
        if (std::strtoull(line.c_str() + last + 1, nullptr, 10) > 0) found.insert(line.substr(4, first - 4));
    }
    return found;
}

// Whether a CSV (header, then rows) has a number in its second column on some row: a coverage
// curve of a part with no peened area (every facet excluded or out of reach) has none, and gnuplot
// given no data fails with a message that does not belong in a report.
bool second_column_has_number(const fs::path& csv) {
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
        const auto comma = line.find(',');
        if (comma == std::string::npos) continue;
        const char* field = line.c_str() + comma + 1;
        char* end = nullptr;
        std::strtod(field, &end);
        if (end != field) return true;
    }
    return false;
}

// Lines common to every script: the output file name can be overridden with `gnuplot -e "out='x.png'"`.
std::string script_header(const std::string& stem) {
    std::ostringstream s;
    s << "# Written by peensim analyze; edit and rerun from this directory: gnuplot " << stem << ".gp\n"
      << "if (!exists(\"out\")) out = " << gnuplot_quoted(stem + ".png") << "\n"
      << "set terminal pngcairo enhanced size " << kPlotWidthPx << "," << kPlotHeightPx << " font 'sans,10'\n"
      << "set output out\n"
      << "set datafile separator ','\n"
      << "set grid\n";
    return s.str();
}

std::string coverage_script(const std::string& component, double target_percent) {
    const std::string csv = component + "_coverage.csv";
    std::ostringstream s;
    s << script_header(component + "_coverage") << "set title "
      << gnuplot_quoted(enhanced_text_escaped(component) + ": coverage vs time (SAE J2277)") << "\n"
      << "set xlabel 'simulated time (s)'\n"
      << "set ylabel 'coverage (%)'\n"
      // Early in a run coverage is a few %: zoom in then, so the curve stays readable.
      << "stats " << gnuplot_quoted(csv) << " using (100*$2) every ::1 nooutput\n"
      << "top = STATS_max > 50 ? 105 : (STATS_max > 0 ? 1.2*STATS_max : 1)\n"
      << "set yrange [0:top]\n"
      << "set key bottom right\n"
      << "plot " << gnuplot_quoted(csv) << " using 1:(100*$2) every ::1 with linespoints lw 2 pt 7 ps 0.6 title 'coverage', \\\n"
      << "     " << target_percent << " with lines dt 2 lc rgb 'gray40' title (top > " << target_percent << " ? 'target (" << target_percent
      << " %)' : '')\n";
    return s.str();
}

std::string histograms_script(const std::string& component, const std::set<std::string>& with_counts) {
    const std::string csv = gnuplot_quoted(component + "_histograms.csv");
    std::ostringstream s;
    s << script_header(component + "_histograms") << "set style fill solid 0.6 border -1\n"
      << "set ylabel 'impacts'\n"
      << "set lmargin 12\n"  // characters: the three panels' axes line up whatever their tick labels
      << "unset key\n"
      << "set multiplot layout 3,1 title " << gnuplot_quoted(enhanced_text_escaped(component) + ": impacts") << "\n";
    for (const HistogramPanel& p : kHistogramPanels) {
        s << "set xlabel '" << p.x_label << "'\n";
        if (with_counts.count(p.quantity)) {
            // Rows of other quantities map to NaN (1/0) and are skipped; the header row too.
            s << "set xrange [*:*]\nset yrange [0:*]\nunset label 1\nset format x\nset format y\n"
              << "plot " << csv << " using (strcol(1) eq 'all' && strcol(2) eq '" << p.quantity
              << "' ? ($3+$4)/2 : 1/0):6:($4-$3) with boxes lc rgb '#3070b0'\n";
        } else {
            s << "set xrange [0:1]\nset yrange [0:1]\nset format x ''\nset format y ''\n"
              << "set label 1 'no data (no impact, or the material has no yield\\_stress)' at graph 0.5,0.5 center\n"
              << "plot NaN\n";
        }
    }
    s << "unset multiplot\n";
    return s.str();
}

// Impacts and mean normal speed per region (from <c>_regions.csv): which teeth or faces get the shot.
std::string regions_script(const std::string& component) {
    const std::string csv = gnuplot_quoted(component + "_regions.csv");
    std::ostringstream s;
    s << script_header(component + "_regions") << "set style fill solid 0.6 border -1\n"
      << "set lmargin 12\nunset key\n"
      << "set xtics rotate by -45 noenhanced\n"
      << "set multiplot layout 2,1 title " << gnuplot_quoted(enhanced_text_escaped(component) + ": impacts per region") << "\n"
      << "set ylabel 'impacts per mm^2 per s'\nset yrange [0:*]\n"
      << "plot " << csv << " using 0:5:(0.7):xtic(1) every ::1 with boxes lc rgb '#3070b0'\n"
      << "set ylabel 'mean v_n (m/s)'\n"
      << "plot " << csv << " using 0:6:(0.7):xtic(1) every ::1 with boxes lc rgb '#c05020'\n"
      << "unset multiplot\n";
    return s.str();
}

// An Almen strip's dose vs time (from <c>_almen.csv), with its arc height when calibrated:
// `arc_height_column` 3 (the dose model's), 5 (the predictive model's), or 0 (none).
std::string almen_script(const std::string& component, int arc_height_column) {
    const std::string csv = gnuplot_quoted(component + "_almen.csv");
    std::ostringstream s;
    s << script_header(component + "_almen") << "set title " << gnuplot_quoted(enhanced_text_escaped(component) + ": Almen strip") << "\n"
      << "set xlabel 'simulated time (s)'\nset ylabel 'impact energy dose (J/m^2)'\nset key top left\n";
    if (arc_height_column > 0)
        s << "set y2label 'arc height (mm)'\nset y2tics\nset ytics nomirror\n"
          << "plot " << csv << " using 1:2 every ::1 with linespoints lw 2 pt 7 ps 0.6 title 'dose', \\\n"
          << "     " << csv << " using 1:" << arc_height_column << " every ::1 axes x1y2 with linespoints lw 2 pt 5 ps 0.6 title "
          << (arc_height_column == 5 ? "'arc height (predicted)'" : "'arc height (calibrated)'") << "\n";
    else
        s << "plot " << csv << " using 1:2 every ::1 with linespoints lw 2 pt 7 ps 0.6 title 'dose (arc height not calibrated)'\n";
    return s.str();
}

// Which column of an Almen CSV's first data row holds an arc height: 5 (predicted), 3 (the dose
// model's), or 0 (neither).
int almen_arc_height_column(const fs::path& csv) {
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    std::getline(in, line);
    std::vector<std::string> fields(1);
    for (const char ch : line) {
        if (ch == ',')
            fields.emplace_back();
        else
            fields.back() += ch;
    }
    if (fields.size() >= 5 && !fields[4].empty()) return 5;
    if (fields.size() >= 3 && !fields[2].empty()) return 3;
    return 0;
}

// Runs `gnuplot script` in `dir` rendering to `png`.tmp, then renames it to `png`.
// Returns "" on success, else what went wrong (gnuplot's own messages).
std::string render(const std::string& gnuplot, const fs::path& dir, const std::string& script_name, const std::string& png_name) {
    const std::string tmp_name = png_name + ".tmp";
    const std::string command = "cd " + shell_quoted(dir.string()) + " && " + shell_quoted(gnuplot) + " -e " +
                                shell_quoted("out=" + gnuplot_quoted(tmp_name)) + " " + shell_quoted(script_name) + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return "cannot start gnuplot";
    std::string messages;
    std::array<char, 512> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe)) messages += buffer.data();
    const int status = ::pclose(pipe);
    std::error_code ec;
    if (status != 0 || !fs::exists(dir / tmp_name, ec) || fs::file_size(dir / tmp_name, ec) == 0) {
        fs::remove(dir / tmp_name, ec);
        return script_name + ": gnuplot failed" + (messages.empty() ? std::string() : ": " + messages);
    }
    fs::rename(dir / tmp_name, dir / png_name, ec);
    if (ec) return png_name + ": " + ec.message();
    return "";
}

}  // namespace

std::string gnuplot_string(const std::string& s) { return gnuplot_quoted(s); }
std::string gnuplot_text(const std::string& s) { return enhanced_text_escaped(s); }

std::string plot_with_gnuplot(const std::string& dir, const std::string& stem, const std::string& script) {
    const std::string gnuplot = find_gnuplot();
    if (gnuplot.empty()) return std::string(kNoGnuplotNote);
    write_file_atomically((fs::path(dir) / (stem + ".gp")).string(), script);
    return render(gnuplot, fs::path(dir), stem + ".gp", stem + ".png");
}

std::vector<std::string> write_analysis_plots(const std::string& analysis_dir, const std::vector<std::string>& components,
                                              double target_coverage, std::string& note) {
    note.clear();
    std::vector<std::string> written;
    const std::string gnuplot = find_gnuplot();
    if (gnuplot.empty()) {
        note = kNoGnuplotNote;
        return written;
    }
    const fs::path dir(analysis_dir);
    auto plot = [&](const std::string& stem, const std::string& script) {
        write_file_atomically((dir / (stem + ".gp")).string(), script);
        const std::string problem = render(gnuplot, dir, stem + ".gp", stem + ".png");
        if (problem.empty())
            written.push_back((dir / (stem + ".png")).string());
        else
            note += (note.empty() ? "" : "; ") + problem;
    };
    for (const std::string& c : components) {
        const fs::path coverage = dir / (c + "_coverage.csv");
        if (fs::exists(coverage) && second_column_has_number(coverage)) {
            plot(c + "_coverage", coverage_script(c, target_coverage * 100.0));
        } else if (fs::exists(coverage)) {
            std::error_code ec;
            fs::remove(dir / (c + "_coverage.png"), ec);  // a previous analysis's: not this one's
            note += (note.empty() ? "" : "; ") + c + "_coverage.png not drawn: " + c +
                    " has no peened area (every facet excluded or out of the shot's reach), so no coverage to plot";
        }
        const fs::path histograms = dir / (c + "_histograms.csv");
        if (fs::exists(histograms)) plot(c + "_histograms", histograms_script(c, quantities_with_counts(histograms)));
        if (fs::exists(dir / (c + "_regions.csv"))) plot(c + "_regions", regions_script(c));
        const fs::path almen = dir / (c + "_almen.csv");
        if (fs::exists(almen)) plot(c + "_almen", almen_script(c, almen_arc_height_column(almen)));
    }
    return written;
}

}  // namespace peensim
