#include "output/part_view_html.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "output/markdown_html.h"
#include "output/part_view_js.h"
#include "output/xml_text.h"

namespace peensim {

namespace {

// Little-endian bytes of a typed array, base64 (JavaScript reads them through a typed array view;
// every platform we build on is little-endian, as x86-64 and AArch64 Linux are).
template <class T>
std::string array_base64(const std::vector<T>& values) {
    std::string bytes(values.size() * sizeof(T), '\0');
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return base64(bytes);
}

// A finite number for JSON (NaN and infinities have no JSON form).
double finite_or(double x, double fallback) { return std::isfinite(x) ? x : fallback; }

// </script> inside a script would end it early: the only sequence to break in inlined code.
std::string script_safe(const std::string& code) {
    std::string out;
    out.reserve(code.size());
    for (std::size_t i = 0; i < code.size(); ++i) {
        if (code.compare(i, 8, "</script") == 0 || code.compare(i, 8, "</SCRIPT") == 0) {
            out += "<\\/";
            i += 1;
            continue;
        }
        out += code[i];
    }
    return out;
}

constexpr const char* kViewStyle =
    ".pv{border:1px solid #ccc;margin:1em 0;padding:.5em}.pv canvas{width:100%;height:28em;display:block;cursor:crosshair}"
    ".pv-top{display:flex;gap:1em;align-items:center;flex-wrap:wrap;margin-bottom:.4em}"
    ".pv-bar{display:flex;align-items:center;gap:.4em;flex-wrap:wrap;max-width:100%}"
    ".pv-ramp{position:relative;display:inline-block;width:16em;height:.9em;border:1px solid #888}"
    ".pv-target{position:absolute;top:-.3em;bottom:-.3em;width:2px;background:#d00}.pv-key{display:inline-block;width:.9em;height:.9em;"
    "margin:0 .2em 0 .6em;vertical-align:middle}.pv-info{margin-top:.4em;min-height:2.6em}.pv-note{color:#555}";

}  // namespace

bool set_colour_range(PartViewField& field, bool from_zero) {
    std::vector<float> v;
    v.reserve(field.values.size());
    for (float x : field.values)
        if (std::isfinite(x)) v.push_back(x);
    if (v.empty()) return false;
    const auto [least, most] = std::minmax_element(v.begin(), v.end());
    field.lo = from_zero ? std::min(0.0, static_cast<double>(*least)) : static_cast<double>(*least);
    const double largest = *most;
    const std::size_t k = static_cast<std::size_t>(0.99 * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    field.hi = v[k] > field.lo ? static_cast<double>(v[k]) : largest;
    if (!(field.hi > field.lo)) field.hi = field.lo + 1.0;  // one value everywhere: any bar shows it
    field.clipped = largest > field.hi;
    return true;
}

std::string part_view_scripts(const std::string& three_js, const std::string& orbit_controls_js) {
    return std::string("<style>") + kViewStyle + "</style>\n<script>\n" + script_safe(three_js) + "\n</script>\n<script>\n" +
           script_safe(orbit_controls_js) + "\n</script>\n<script>\n" + kPartViewJs + "\n</script>\n";
}

std::string part_view_html(const PartView& view) {
    nlohmann::json data;
    data["name"] = view.name;
    data["positions"] = array_base64(view.positions_mm);
    data["indices"] = array_base64(view.indices);
    data["source"] = array_base64(view.source);
    data["fields"] = nlohmann::json::array();
    for (const PartViewField& f : view.fields) {
        data["fields"].push_back({{"name", f.name},
                                  {"label", f.label},
                                  {"unit", f.unit},
                                  {"values", array_base64(f.values)},
                                  {"lo", finite_or(f.lo, 0.0)},
                                  {"hi", finite_or(f.hi, 1.0)},
                                  {"target", f.target && std::isfinite(*f.target) ? nlohmann::json(*f.target) : nlohmann::json(nullptr)},
                                  {"digits", f.digits},
                                  {"categorical", f.categorical},
                                  {"clipped", f.clipped},
                                  {"grey", f.grey}});
    }
    data["shown"] = view.shown < view.fields.size() ? view.shown : 0;
    data["instances"] = view.instances;
    if (!view.instances.empty()) data["instance"] = array_base64(view.instance);
    data["offsets"] = view.offsets_mm;
    data["regions"] = nlohmann::json::array();
    for (const PartViewRegion& r : view.regions) data["regions"].push_back({{"name", r.name}, {"forecast", r.forecast}});
    std::string h = "<div class=\"pv\" data-part=\"" + xml_text(view.name) + "\">\n<div class=\"pv-top\"><b>" + xml_text(view.name) +
                    "</b><label>colour by <select></select></label><span class=\"pv-bar\"></span></div>\n<canvas></canvas>\n";
    h += "<div class=\"pv-info\">The 3D view needs JavaScript and WebGL.</div>\n";
    if (!view.note.empty()) h += "<div class=\"pv-note\">" + xml_text(view.note) + "</div>\n";
    h += "<script type=\"application/json\">" + script_safe(data.dump()) + "</script>\n</div>\n";
    return h;
}

}  // namespace peensim
