#include "scene/yaml_access.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "scene/yaml_load.h"

namespace peensim {

YAML::Node parse_yaml(const std::string& text, const std::string& file) {
    try {
        return load_yaml(text);
    } catch (const YAML::ParserException& e) {
        const int line = e.mark.line >= 0 ? e.mark.line + 1 : 0;
        const int column = e.mark.column >= 0 ? e.mark.column + 1 : 0;
        throw InputError(SourceLocation{file, line, column}, "", "invalid YAML: " + e.msg);
    }
}

namespace {

int one_based(int zero_based) { return zero_based >= 0 ? zero_based + 1 : 0; }

bool starts_field(std::string_view field, std::string_view prefix) {
    if (field.size() < prefix.size() || field.substr(0, prefix.size()) != prefix) return false;
    if (field.size() == prefix.size()) return true;
    const char next = field[prefix.size()];
    return next == '.' || next == '[';
}

const OverrideOrigin* override_of(const Cursor& at) {
    if (at.context == nullptr) return nullptr;
    // The last override wins, as when applying them.
    for (auto it = at.context->overrides.rbegin(); it != at.context->overrides.rend(); ++it)
        if (starts_field(at.field_path, it->field_path)) return &*it;
    return nullptr;
}

std::string last_key(std::string_view field_path) {
    const std::size_t dot = field_path.rfind('.');
    return std::string(dot == std::string_view::npos ? field_path : field_path.substr(dot + 1));
}

// The value of a key, or its schema default (as a YAML node), or nothing; errors if required.
std::optional<YAML::Node> value_or_default(const Cursor& c) {
    if (c.present()) return c.node;
    const SchemaEntry& e = c.entry();
    if (!e.default_value.empty()) return YAML::Load(std::string(e.default_value));
    if (e.required) fail(c, "missing required key '" + last_key(c.field_path) + "' (" + expected_text(e) + ")");
    return std::nullopt;
}

// "in (0, 1]" or "> 0".
std::string range_phrase(const Range& r) {
    const std::string t = r.text();
    return (!t.empty() && (t.front() == '(' || t.front() == '[')) ? "in " + t : t;
}

// Notes whether a dimensioned value was written with a unit (SceneContext::plain_quantities).
void note_unit_use(const Cursor& c, const std::string& text, std::string_view unit_for_plain) {
    const SchemaEntry& e = c.entry();
    // Only what the file says (not defaults); only lengths: a plain gravity or duration in SI is
    // natural, a plain length in a scene written in mm is the slip users made.
    if (c.context == nullptr || !c.present() || e.dimension == Dimension::dimensionless) return;
    std::string_view t(text);
    while (!t.empty() && (t.back() == ' ' || t.back() == '\t')) t.remove_suffix(1);
    while (!t.empty() && (t.front() == ' ' || t.front() == '+')) t.remove_prefix(1);
    double number = 0.0;
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), number);
    const bool plain = !t.empty() && ec == std::errc() && ptr == t.data() + t.size();
    if (!plain) {
        c.context->units_given = true;
        if (location_of(c).file != override_file_name) c.context->units_in_file = true;
    } else if (unit_for_plain.empty() && number != 0.0 && e.dimension == Dimension::length) {
        c.context->plain_quantities.push_back({location_of(c), c.field_path, std::string(t), e.dimension});
    }
}

double parse_element(const Cursor& c, const std::string& text, std::string_view unit_for_plain) {
    const SchemaEntry& e = c.entry();
    note_unit_use(c, text, unit_for_plain);
    try {
        return parse_quantity(text, e.dimension, unit_for_plain);
    } catch (const QuantityError& err) {
        fail(c, err.what());
    }
}

double parse_checked_quantity(const Cursor& c, const YAML::Node& value) {
    const SchemaEntry& e = c.entry();
    const std::string text = value.Scalar();
    const double v = parse_element(c, text, e.plain_number_unit);
    if (!e.range.contains(v)) {
        std::string problem = "expected " + std::string(dimension_noun(e.dimension)) + " " + range_phrase(e.range);
        if (e.dimension != Dimension::dimensionless) problem += " " + std::string(si_unit(e.dimension));
        problem += ", got '" + text + "'";
        if (format_si(v) != text) problem += " (= " + format_si(v) + " " + std::string(si_unit(e.dimension)) + ")";
        fail(c, problem);
    }
    return v;
}

std::vector<std::string> split_vector_text(const std::string& text) {
    std::vector<std::string> tokens;
    std::string token;
    for (char ch : text) {
        if (ch == ' ' || ch == '\t' || ch == ',') {
            if (!token.empty()) tokens.push_back(token);
            token.clear();
        } else {
            token += ch;
        }
    }
    if (!token.empty()) tokens.push_back(token);
    return tokens;
}

Vec3 parse_vector_node(const Cursor& c, const YAML::Node& value) {
    const SchemaEntry& e = c.entry();
    Vec3 out;
    if (value.IsSequence()) {
        if (value.size() != 3) fail(c, "expected " + expected_text(e) + ", got a list of " + std::to_string(value.size()));
        for (std::size_t i = 0; i < 3; ++i) {
            if (!value[i].IsScalar())
                fail(c, "expected " + expected_text(e) + ", element " + std::to_string(i) + " is " + describe_node(value[i]));
            out[static_cast<Eigen::Index>(i)] = parse_element(c, value[i].Scalar(), e.plain_number_unit);
        }
        return out;
    }
    // One string: "x y z", "x y z unit" (a unit after the last number only applies to all three)
    // or "x unit y unit z unit".
    struct Element {
        std::string number;
        std::string unit;
    };
    std::vector<Element> elements;
    for (const std::string& token : split_vector_text(value.Scalar())) {
        const std::size_t n = leading_number_length(token);
        if (n > 0) {
            elements.push_back({token.substr(0, n), token.substr(n)});
        } else if (!elements.empty() && elements.back().unit.empty()) {
            elements.back().unit = token;
        } else {
            fail(c, "expected " + expected_text(e) + ", got " + describe_node(value));
        }
    }
    if (elements.size() != 3) fail(c, "expected " + expected_text(e) + ", got " + describe_node(value));
    if (elements[0].unit.empty() && elements[1].unit.empty()) elements[0].unit = elements[1].unit = elements[2].unit;
    for (std::size_t i = 0; i < 3; ++i)
        out[static_cast<Eigen::Index>(i)] = parse_element(c, elements[i].number + " " + elements[i].unit, e.plain_number_unit);
    return out;
}

}  // namespace

const SchemaEntry& Cursor::entry() const {
    const SchemaEntry* e = find_schema_entry(schema_path);
    if (e == nullptr) fail(*this, "internal error: no schema entry for '" + schema_path + "'");
    return *e;
}

Cursor Cursor::child(std::string_view key) const {
    // The child is constructed around the found node, never assigned to a placeholder: a yaml-cpp
    // assignment merges the whole document's node set into the placeholder's (n log n a look-up,
    // so a scene's parse grew as its size squared: 5-10 ms for the gear, for every sweep variant).
    if (is_map())
        for (const auto& kv : node)
            if (kv.first.IsScalar() && kv.first.Scalar() == key)
                return Cursor{context, kv.second, schema_child_path(schema_path, key), schema_child_path(field_path, key),
                              (kv.second.IsScalar() && !kv.second.IsNull()) ? kv.second.Mark() : kv.first.Mark()};
    return Cursor{context, YAML::Node(YAML::NodeType::Undefined), schema_child_path(schema_path, key), schema_child_path(field_path, key),
                  mark};
}

Cursor Cursor::named_child(const YAML::Node& key, const YAML::Node& value) const {
    const std::string name = key.Scalar();
    return Cursor{context, value, schema_child_path(schema_path, "*"), schema_child_path(field_path, name), key.Mark()};
}

Cursor Cursor::item(std::size_t index) const {
    return Cursor{context, node[index], schema_path + "[]", field_path + "[" + std::to_string(index) + "]", node[index].Mark()};
}

Cursor root_cursor(const SceneContext& context, const YAML::Node& root) {
    YAML::Mark top;
    top.line = 0;
    top.column = 0;
    return Cursor{&context, root, "", "", top};
}

SourceLocation location_of(const Cursor& at) {
    if (override_of(at) != nullptr) return SourceLocation{std::string(override_file_name), 0, 0};
    const std::string file = at.context != nullptr ? at.context->file : std::string();
    return SourceLocation{file, one_based(at.mark.line), one_based(at.mark.column)};
}

void fail(const Cursor& at, const std::string& problem) {
    std::string full = problem;
    if (const OverrideOrigin* o = override_of(at)) full += " (from --set '" + o->text + "')";
    throw InputError(location_of(at), at.field_path.empty() ? std::string("(top level)") : at.field_path, full);
}

std::string describe_node(const YAML::Node& node) {
    if (!node.IsDefined() || node.IsNull()) return "nothing";
    if (node.IsScalar()) return "'" + node.Scalar() + "'";
    if (node.IsSequence()) return "a list";
    return "a map";
}

double read_quantity(const Cursor& c) {
    const std::optional<double> v = read_optional_quantity(c);
    if (!v) fail(c, "missing required key '" + last_key(c.field_path) + "' (" + expected_text(c.entry()) + ")");
    return *v;
}

std::optional<double> read_optional_quantity(const Cursor& c) {
    const std::optional<YAML::Node> value = value_or_default(c);
    if (!value) return std::nullopt;
    return parse_checked_quantity(c, *value);
}

std::vector<double> read_quantity_list(const Cursor& c) {
    const std::optional<YAML::Node> value = value_or_default(c);
    std::vector<double> out;
    if (!value) return out;
    if (!value->IsSequence() || value->size() == 0) fail(c, "expected " + expected_text(c.entry()) + ", got " + describe_node(*value));
    for (std::size_t k = 0; k < value->size(); ++k) {
        const YAML::Node item = (*value)[k];
        // The list's entry (unit, range), the item's place in the file. A new Cursor, not an
        // assignment to a copy's node: assigning a yaml-cpp Node overwrites the tree it refers to.
        const Cursor at{c.context, item, c.schema_path, c.field_path + "[" + std::to_string(k) + "]",
                        item.IsScalar() ? item.Mark() : c.mark};
        if (!item.IsScalar() || item.IsNull())
            fail(at, "expected " + std::string(dimension_noun(c.entry().dimension)) + ", got " + describe_node(item));
        out.push_back(parse_checked_quantity(at, item));
    }
    return out;
}

long long read_integer(const Cursor& c) {
    const std::optional<YAML::Node> value = value_or_default(c);
    if (!value) fail(c, "missing required key '" + last_key(c.field_path) + "' (a whole number)");
    const SchemaEntry& e = c.entry();
    const std::string text = value->Scalar();
    const std::string beyond_64_bits =
        "(beyond 64 bits: at most " + std::to_string(std::numeric_limits<long long>::max()) + " either side of 0)";
    long long v = 0;
    const char* first = text.data() + (!text.empty() && text.front() == '+' ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(first, text.data() + text.size(), v);
    // Digits beyond 64 bits: refused here, before the exponent form below could read them as a
    // double in range (1e23 is >= 0) and convert it out of range (the seed became 2^63).
    if (ec == std::errc::result_out_of_range && ptr == text.data() + text.size())
        fail(c, "expected a whole number " + range_phrase(e.range) + ", got '" + text + "' " + beyond_64_bits);
    if (ec != std::errc() || ptr != text.data() + text.size()) {
        // Also a whole number written with an exponent (count: 1e5), checked against the range
        // and the 64-bit bounds before it is converted, so nothing out of range wraps.
        constexpr double kBeyond = 9223372036854775808.0;  // 2^63: the first double a long long cannot hold
        double d = 0.0;
        const auto [dptr, dec] = std::from_chars(first, text.data() + text.size(), d);
        if (dec != std::errc() || dptr != text.data() + text.size() || !std::isfinite(d) || d != std::floor(d) || !e.range.contains(d))
            fail(c, "expected a whole number " + range_phrase(e.range) + ", got '" + text + "'");
        if (d >= kBeyond || d < -kBeyond)
            fail(c, "expected a whole number " + range_phrase(e.range) + ", got '" + text + "' " + beyond_64_bits);
        return static_cast<long long>(d);
    }
    if (!e.range.contains(static_cast<double>(v))) fail(c, "expected a whole number " + range_phrase(e.range) + ", got '" + text + "'");
    return v;
}

Vec3 read_vector(const Cursor& c) {
    const std::optional<Vec3> v = read_optional_vector(c);
    if (!v) fail(c, "missing required key '" + last_key(c.field_path) + "' (" + expected_text(c.entry()) + ")");
    return *v;
}

std::optional<Vec3> read_optional_vector(const Cursor& c) {
    const std::optional<YAML::Node> value = value_or_default(c);
    if (!value) return std::nullopt;
    return parse_vector_node(c, *value);
}

std::optional<Vec3> read_optional_direction(const Cursor& c) {
    std::optional<Vec3> v = read_optional_vector(c);
    if (!v) return v;
    const double norm = v->norm();
    if (!(norm > 0.0)) fail(c, "expected a direction, got the zero vector");
    if (std::abs(norm - 1.0) <= unit_length_tolerance) return v;
    return Vec3(*v / norm);
}

Mat3 read_matrix(const Cursor& c) {
    const std::optional<YAML::Node> value = value_or_default(c);
    if (!value) fail(c, "missing required key '" + last_key(c.field_path) + "' (" + expected_text(c.entry()) + ")");
    const std::string expected = "expected " + expected_text(c.entry());
    if (!value->IsSequence() || value->size() != 3) fail(c, expected + ", got " + describe_node(*value));
    Mat3 m;
    for (std::size_t r = 0; r < 3; ++r) {
        const YAML::Node row = (*value)[r];
        if (!row.IsSequence() || row.size() != 3) fail(c, expected + ", row " + std::to_string(r) + " is " + describe_node(row));
        for (std::size_t k = 0; k < 3; ++k) {
            double x = 0.0;
            if (!row[k].IsScalar() || !parse_plain_number(row[k].Scalar(), x))
                fail(c, expected + ", element [" + std::to_string(r) + "][" + std::to_string(k) + "] is " + describe_node(row[k]));
            m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = x;
        }
    }
    return m;
}

std::string read_text(const Cursor& c) {
    const std::optional<YAML::Node> value = value_or_default(c);
    if (!value) return std::string();
    if (!value->IsScalar()) fail(c, "expected " + expected_text(c.entry()) + ", got " + describe_node(*value));
    return value->Scalar();
}

std::string read_choice(const Cursor& c) {
    const SchemaEntry& e = c.entry();
    const std::optional<YAML::Node> value = value_or_default(c);
    if (!value) fail(c, "missing required key '" + last_key(c.field_path) + "' (" + expected_text(e) + ")");
    const std::string word = value->IsScalar() ? value->Scalar() : std::string();
    for (std::string_view choice : split_choices(e.choices))
        if (choice == word) return word;
    for (std::string_view planned : split_choices(e.planned))
        if (planned == word) fail(c, "'" + word + "' is not available yet; expected " + expected_text(e));
    fail(c, "expected " + expected_text(e) + ", got " + describe_node(*value));
}

std::vector<std::string> read_names(const Cursor& c) {
    std::vector<std::string> names;
    const std::optional<YAML::Node> value = value_or_default(c);
    if (!value) return names;
    if (!value->IsSequence()) fail(c, "expected " + expected_text(c.entry()) + ", got " + describe_node(*value));
    for (const YAML::Node& n : *value) {
        if (!n.IsScalar()) fail(c, "expected " + expected_text(c.entry()) + ", an item is " + describe_node(n));
        names.push_back(n.Scalar());
    }
    return names;
}

}  // namespace peensim
