#include "python/python_yaml.h"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>

#include "common/input_error.h"
#include "scene/yaml_load.h"

namespace py = pybind11;

namespace peensim::python {

namespace {

// Python's repr of a float is its shortest round-trip form, which the scene parser reads back exactly.
std::string number_text(const py::handle& value) { return py::str(py::repr(value)); }

// Where a value's errors point: the scene's name (a dict) or "<--set>" (an override), and its key path.
struct ValueSite {
    std::string file;
    int depth = 0;  // maps and lists open around the value
};

YAML::Node to_node(const py::handle& handle, const std::string& path, const ValueSite& site) {
    const py::object value = py::reinterpret_borrow<py::object>(handle);
    if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
    if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
    if (py::isinstance<py::str>(value)) return YAML::Node(value.cast<std::string>());
    // NumPy's scalars and arrays too: an integer type has __index__, a float type __float__.
    if (py::isinstance<py::int_>(value) || py::hasattr(value, "__index__")) return YAML::Node(number_text(py::int_(value)));
    if (py::isinstance<py::float_>(value) || py::hasattr(value, "__float__")) {
        const double x = py::float_(value);
        if (!std::isfinite(x))
            throw py::type_error((path.empty() ? std::string("the value") : path) + ": expected a finite number, got " +
                                 number_text(value));
        return YAML::Node(number_text(py::float_(x)));
    }
    const bool collection = py::isinstance<py::dict>(value) || py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) ||
                            py::hasattr(value, "tolist");
    // The command line's nesting limit, before recursing: a value 20 000 levels deep (or a dict
    // holding itself) would overflow the stack here, and its YAML text would grow as depth squared.
    const ValueSite inner{site.file, site.depth + 1};
    if (collection && inner.depth > kMaxYamlNesting) throw InputError({site.file, 0, 0}, path, yaml_nesting_problem());
    if (py::isinstance<py::dict>(value)) {
        YAML::Node map(YAML::NodeType::Map);
        for (const auto& [k, v] : value.cast<py::dict>()) {
            if (!py::isinstance<py::str>(k)) throw py::type_error(path + ": expected text keys, got " + std::string(py::str(py::repr(k))));
            const std::string key = k.cast<std::string>();
            map[key] = to_node(v, path.empty() ? key : path + "." + key, inner);
        }
        return map;
    }
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) || py::hasattr(value, "tolist")) {
        const py::list items = py::hasattr(value, "tolist") ? py::list(value.attr("tolist")()) : py::list(value);
        YAML::Node seq(YAML::NodeType::Sequence);
        for (std::size_t i = 0; i < items.size(); ++i) seq.push_back(to_node(items[i], path + "[" + std::to_string(i) + "]", inner));
        return seq;
    }
    throw py::type_error((path.empty() ? std::string("the value") : path) + ": expected a dict, list, str, number, bool or None, got " +
                         std::string(py::str(value.get_type().attr("__name__"))));
}

// Sequences of numbers in flow style ([0, 0, -9.81]), as scene files write vectors; the rest in blocks.
void flow_short_sequences(YAML::Node node) {
    if (node.IsSequence()) {
        bool scalars = true;
        for (const YAML::Node& item : node) scalars = scalars && item.IsScalar();
        if (scalars) node.SetStyle(YAML::EmitterStyle::Flow);
        for (YAML::Node item : node) flow_short_sequences(item);
    } else if (node.IsMap()) {
        for (auto item : node) flow_short_sequences(item.second);
    }
}

py::object scalar(const YAML::Node& node) {
    const std::string& s = node.Scalar();
    if (node.Tag() == "!") return py::str(s);  // quoted in the text: a string
    if (s == "true" || s == "True") return py::bool_(true);
    if (s == "false" || s == "False") return py::bool_(false);
    if (s == "null" || s == "~" || s.empty()) return py::none();
    std::int64_t i = 0;
    const char* end = s.data() + s.size();
    if (auto [p, ec] = std::from_chars(s.data(), end, i); p == end) {
        if (ec == std::errc()) return py::int_(i);
        // Digits beyond 64 bits: Python's int holds them exactly (a float would drop digits, and
        // a seed of 10**30 read back as 1e30 would no longer be the whole number it was).
        if (ec == std::errc::result_out_of_range) return py::reinterpret_steal<py::object>(PyLong_FromString(s.c_str(), nullptr, 10));
    }
    double x = 0.0;
    if (auto [p, ec] = std::from_chars(s.data(), end, x); ec == std::errc() && p == end) return py::float_(x);
    return py::str(s);
}

py::object to_python(const YAML::Node& node) {
    switch (node.Type()) {
        case YAML::NodeType::Map: {
            py::dict d;
            for (const auto& item : node) d[py::str(item.first.Scalar())] = to_python(item.second);
            return d;
        }
        case YAML::NodeType::Sequence: {
            py::list l;
            for (const auto& item : node) l.append(to_python(item));
            return l;
        }
        case YAML::NodeType::Scalar: return scalar(node);
        default: return py::none();
    }
}

}  // namespace

std::string to_yaml(const py::handle& value, const std::string& name) {
    YAML::Node node = to_node(value, "", ValueSite{name});
    flow_short_sequences(node);
    YAML::Emitter out;
    out << node;
    return std::string(out.c_str()) + "\n";
}

py::object from_yaml(const std::string& text, const std::string& name) {
    try {
        return to_python(load_yaml(text));
    } catch (const YAML::Exception& e) {
        throw InputError({name, e.mark.line + 1, e.mark.column + 1}, "", "expected YAML: " + e.msg);
    }
}

std::string override_value(const py::handle& value, const std::string& field, const std::string& file) {
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    YAML::Node node = to_node(value, field, ValueSite{file});
    flow_short_sequences(node);
    if (node.IsMap()) node.SetStyle(YAML::EmitterStyle::Flow);
    YAML::Emitter out;
    out << node;
    return out.c_str();
}

}  // namespace peensim::python
