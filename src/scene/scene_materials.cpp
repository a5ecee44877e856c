// Materials and the contact coefficients of each material pair.
#include "scene/scene_sections.h"

namespace peensim {
namespace {

constexpr std::string_view default_pair_key = "default";
constexpr std::string_view shot_shot_key = "shot-shot";
constexpr std::string_view shot_prefix = "shot-";

// A coefficient written for this pair, or the `default` pair's value when left out.
double coefficient_or(const Cursor& pair, std::string_view key, double fallback) {
    const Cursor c = pair.child(key);
    return c.present() ? read_quantity(c) : fallback;
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
        d.where = location_of(m);
        out.push_back(std::move(d));
    }
    return out;
}

std::vector<ContactPairDesc> read_contacts(const Cursor& c, const std::vector<MaterialDesc>& materials) {
    // The `default` pair first (schema defaults fill what it leaves out); the other pairs fall back on it.
    ContactPairDesc fallback;
    fallback.key = std::string(default_pair_key);
    bool default_given = false;
    if (c.is_map()) {
        for (const auto& kv : c.node) {
            if (kv.first.Scalar() != default_pair_key) continue;
            const Cursor pair = c.named_child(kv.first, kv.second);
            fallback.C0 = read_quantity(pair.child("C0"));
            fallback.V0_m_per_s = read_quantity(pair.child("V0"));
            fallback.mu = read_quantity(pair.child("mu"));
            fallback.f = read_quantity(pair.child("f"));
            fallback.where = location_of(pair);
            default_given = true;
        }
    }
    if (!default_given) {
        // An absent pair: its reads give the schema defaults.
        const Cursor builtin{c.context, YAML::Node(YAML::NodeType::Undefined), schema_child_path(c.schema_path, "*"),
                             schema_child_path(c.field_path, default_pair_key), c.mark};
        fallback.C0 = read_quantity(builtin.child("C0"));
        fallback.V0_m_per_s = read_quantity(builtin.child("V0"));
        fallback.mu = read_quantity(builtin.child("mu"));
        fallback.f = read_quantity(builtin.child("f"));
        fallback.where = location_of(c);
    }

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
                const bool shot_material = key.rfind(shot_prefix, 0) == 0 &&
                                           find_material(materials, key.substr(shot_prefix.size())) != nullptr;
                if (!shot_material)
                    fail(pair, "unknown contact pair '" + key + "'; expected 'shot-shot', 'default' or "
                               "'shot-<material>' with a material of: " + material_names(materials));
            } else {
                for (std::string_view unused : {"mu", "f"})
                    if (pair.child(unused).present())
                        fail(pair.child(unused), "'" + std::string(unused) + "' is not used for shot-shot; "
                                                 "expected only C0 and V0 there");
            }
            ContactPairDesc d;
            d.key = key;
            d.C0 = coefficient_or(pair, "C0", fallback.C0);
            d.V0_m_per_s = coefficient_or(pair, "V0", fallback.V0_m_per_s);
            d.mu = coefficient_or(pair, "mu", fallback.mu);
            d.f = coefficient_or(pair, "f", fallback.f);
            d.where = location_of(pair);
            out.push_back(std::move(d));
        }
    }
    if (!default_given) out.push_back(fallback);
    return out;
}

}  // namespace peensim
