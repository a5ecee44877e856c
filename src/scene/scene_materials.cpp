// Materials and the contact coefficients of each material pair.
#include "scene/scene_sections.h"

#include <span>
#include <stdexcept>

#include "contact/law_registry.h"
#include "scene/schema_defaults.h"

namespace peensim {
namespace {

constexpr std::string_view default_pair_key = "default";
constexpr std::string_view shot_shot_key = "shot-shot";
constexpr std::string_view shot_prefix = "shot-";
constexpr std::string_view law_key = "law";

// The parameters the law declares for this kind of pair.
std::span<const contact::LawParameter> parameters_for(const contact::LawEntry& law, bool shot_shot) {
    return shot_shot ? law.shot_shot_parameters : law.surface_parameters;
}

std::string parameter_names(std::span<const contact::LawParameter> parameters) {
    std::string out = std::string(law_key);
    for (const contact::LawParameter& p : parameters) out += ", " + std::string(p.name);
    return out;
}

LawParameterValue read_parameter(const Cursor& at, const contact::LawParameter& p) {
    LawParameterValue v;
    v.name = std::string(p.name);
    if (p.list) {
        v.values = read_quantity_list(at);
    } else if (const std::optional<double> x = read_optional_quantity(at)) {
        v.values = {*x};
    }
    v.where = location_of(at);
    return v;
}

// The law a pair names (or inherits), checked against the kind of pair.
const contact::LawEntry& pair_law(const Cursor& pair, const std::string& key, const std::string& inherited) {
    const Cursor at = pair.child(law_key);
    const std::string name = at.present() ? read_choice(at) : inherited;
    const contact::LawEntry* law = contact::find_law(name);
    if (law == nullptr) fail(at, "unknown contact law '" + name + "'; expected one of: " + contact::law_names_text());
    if (key == shot_shot_key && law->make_shot_shot == nullptr) {
        std::string shot_shot_laws;
        for (const contact::LawEntry& e : contact::law_catalogue())
            if (e.make_shot_shot != nullptr) shot_shot_laws += (shot_shot_laws.empty() ? "" : ", ") + std::string(e.name);
        fail(at.present() ? at : pair,
             "law '" + name + "' is for shot-<material> pairs, not between shot; expected for shot-shot one of: " + shot_shot_laws);
    }
    return *law;
}

// Every key of the pair must be `law` or a parameter of its law.
void check_pair_keys(const Cursor& pair, const std::string& key, const contact::LawEntry& law) {
    if (!pair.is_map()) return;
    const std::span<const contact::LawParameter> parameters = parameters_for(law, key == shot_shot_key);
    for (const auto& kv : pair.node) {
        const std::string name = kv.first.Scalar();
        if (name == law_key) continue;
        bool declared = false;
        for (const contact::LawParameter& p : parameters) declared |= p.name == name;
        if (!declared) {
            // A pair that names no law takes the `default` pair's: say so, it is the likely slip.
            const std::string inherited = pair.child(law_key).present() || key == default_pair_key
                                              ? ""
                                              : " (the pair takes its law from the `default` pair; write `law:` in it to choose another)";
            fail(pair.child(name), "'" + name + "' is not a parameter of law '" + std::string(law.name) + "'" +
                                       (key == shot_shot_key ? " between shot" : "") + "; expected " + parameter_names(parameters) +
                                       inherited);
        }
    }
}

}  // namespace

const MaterialDesc* find_material(const std::vector<MaterialDesc>& materials, const std::string& name) {
    for (const MaterialDesc& m : materials)
        if (m.name == name) return &m;
    return nullptr;
}

std::string material_names(const std::vector<MaterialDesc>& materials) {
    if (materials.empty()) return "(none defined)";
    std::string out;
    for (const MaterialDesc& m : materials) out += (out.empty() ? "" : ", ") + m.name;
    return out;
}

std::vector<MaterialDesc> read_materials(const Cursor& c) {
    std::vector<MaterialDesc> out;
    if (!c.is_map()) return out;
    for (const auto& kv : c.node) {
        const Cursor m = c.named_child(kv.first, kv.second);
        MaterialDesc d;
        d.name = kv.first.Scalar();
        d.density_kg_per_m3 = read_optional_quantity(m.child("density"));
        d.yield_stress_pa = read_optional_quantity(m.child("yield_stress"));
        d.youngs_modulus_pa = read_optional_quantity(m.child("youngs_modulus"));
        d.poisson_ratio = read_optional_quantity(m.child("poisson_ratio"));
        d.where = location_of(m);
        out.push_back(std::move(d));
    }
    return out;
}

std::vector<ContactPairDesc> read_contacts(const Cursor& c, const std::vector<MaterialDesc>& materials) {
    // The `default` pair first (the law's defaults fill what it leaves out); the other pairs fall
    // back on it: its law (when that law serves the pair) and the values of its law's parameters.
    ContactPairDesc fallback;
    fallback.key = std::string(default_pair_key);
    const Cursor default_cursor = [&] {
        // Built once, never assigned: assigning a yaml-cpp Node overwrites the tree it refers to.
        if (c.is_map())
            for (const auto& kv : c.node)
                if (kv.first.Scalar() == default_pair_key) return c.named_child(kv.first, kv.second);
        return Cursor{c.context, YAML::Node(YAML::NodeType::Undefined), schema_child_path(c.schema_path, "*"),
                      schema_child_path(c.field_path, default_pair_key), c.mark};
    }();
    const bool default_given = default_cursor.present();
    // A pair's law when neither it nor the `default` pair names one: the schema's `contacts.*.law`.
    const std::string built_in_law = schema_default_word("contacts.*.law");
    const contact::LawEntry& default_law = pair_law(default_cursor, fallback.key, built_in_law);
    check_pair_keys(default_cursor, fallback.key, default_law);
    fallback.law = std::string(default_law.name);
    for (const contact::LawParameter& p : default_law.surface_parameters) {
        LawParameterValue v = read_parameter(default_cursor.child(p.name), p);
        if (!default_given) v.where = location_of(c);
        fallback.parameters.push_back(std::move(v));
    }
    fallback.where = location_of(default_cursor.present() ? default_cursor : c);

    const auto resolve = [&](const Cursor& pair, const std::string& key) {
        ContactPairDesc d;
        d.key = key;
        const bool shot_shot = key == shot_shot_key;
        const bool inherits_law = default_law.make_shot_shot != nullptr || !shot_shot;
        const contact::LawEntry& law = pair_law(pair, key, inherits_law ? fallback.law : built_in_law);
        check_pair_keys(pair, key, law);
        d.law = std::string(law.name);
        for (const contact::LawParameter& p : parameters_for(law, shot_shot)) {
            const Cursor at = pair.child(p.name);
            const LawParameterValue* from_default = nullptr;
            if (fallback.law == law.name)
                for (const LawParameterValue& v : fallback.parameters)
                    if (v.name == p.name) from_default = &v;
            if (!at.present() && from_default != nullptr && !from_default->values.empty()) {
                d.parameters.push_back(*from_default);
                continue;
            }
            LawParameterValue v = read_parameter(at, p);
            if (v.values.empty())
                fail(pair, "law '" + d.law + "' needs '" + std::string(p.name) + "' for pair '" + key + "' (" + expected_text(at.entry()) +
                               "); give it here or in the `default` pair");
            d.parameters.push_back(std::move(v));
        }
        d.where = location_of(pair);
        return d;
    };

    std::vector<ContactPairDesc> out;
    if (c.is_map()) {
        for (const auto& kv : c.node) {
            const std::string key = kv.first.Scalar();
            const Cursor pair = c.named_child(kv.first, kv.second);
            if (key == default_pair_key) {
                out.push_back(fallback);
                continue;
            }
            if (key != shot_shot_key) {
                const bool shot_material =
                    key.rfind(shot_prefix, 0) == 0 && find_material(materials, key.substr(shot_prefix.size())) != nullptr;
                if (!shot_material)
                    fail(pair, "unknown contact pair '" + key +
                                   "'; expected 'shot-shot', 'default' or "
                                   "'shot-<material>' with a material of: " +
                                   material_names(materials));
            }
            out.push_back(resolve(pair, key));
        }
    }
    if (!default_given) out.push_back(fallback);
    // Pairs the scene leaves out are built from the default by the model; a shot-shot pair that
    // cannot inherit the default's law is resolved here, so that every pair has its law's values.
    bool has_shot_shot = false;
    for (const ContactPairDesc& d : out) has_shot_shot |= d.key == shot_shot_key;
    bool default_serves_shot_shot = default_law.make_shot_shot != nullptr;
    for (const contact::LawParameter& p : default_law.shot_shot_parameters) {
        bool in_default = false;
        for (const LawParameterValue& v : fallback.parameters) in_default |= v.name == p.name;
        default_serves_shot_shot &= in_default;
    }
    if (!has_shot_shot && !default_serves_shot_shot) {
        const Cursor absent{c.context, YAML::Node(YAML::NodeType::Undefined), schema_child_path(c.schema_path, "*"),
                            schema_child_path(c.field_path, shot_shot_key), c.mark};
        out.push_back(resolve(absent, std::string(shot_shot_key)));
    }
    return out;
}

const std::vector<double>& ContactPairDesc::values(std::string_view name) const {
    for (const LawParameterValue& p : parameters)
        if (p.name == name) return p.values;
    throw std::out_of_range("contact pair '" + key + "' (law " + law + ") has no parameter '" + std::string(name) + "'");
}

}  // namespace peensim
