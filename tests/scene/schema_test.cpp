// The scene schema is consistent (parents, defaults in range, docs) and generates the reference.
#include <gtest/gtest.h>

#include <string>

#include "scene/schema.h"

namespace peensim {
namespace {

std::string parent_of(std::string_view path) {
    if (path.size() >= 2 && path.substr(path.size() - 2) == "[]") return std::string(path.substr(0, path.size() - 2));
    const std::size_t dot = path.rfind('.');
    return dot == std::string_view::npos ? std::string() : std::string(path.substr(0, dot));
}

TEST(SceneSchema, EveryEntryHasAParentAndADoc) {
    for (const SchemaEntry& e : scene_schema()) {
        if (e.path.empty()) continue;
        EXPECT_FALSE(e.doc.empty()) << e.path;
        const SchemaEntry* parent = find_schema_entry(parent_of(e.path));
        ASSERT_NE(parent, nullptr) << e.path;
        const bool container = parent->kind == ValueKind::map || parent->kind == ValueKind::named_map || parent->kind == ValueKind::list;
        EXPECT_TRUE(container) << e.path;
    }
}

TEST(SceneSchema, DefaultsAreValidValues) {
    for (const SchemaEntry& e : scene_schema()) {
        if (e.default_value.empty()) continue;
        EXPECT_FALSE(e.required) << e.path << " is required and has a default";
        if (e.kind == ValueKind::quantity) {
            const double v = parse_quantity(e.default_value, e.dimension, e.plain_number_unit);
            EXPECT_TRUE(e.range.contains(v)) << e.path;
        } else if (e.kind == ValueKind::choice) {
            bool found = false;
            for (std::string_view c : split_choices(e.choices)) found = found || c == e.default_value;
            EXPECT_TRUE(found) << e.path;
        }
    }
}

TEST(SceneSchema, ChildKeysComeFromTheTable) {
    EXPECT_EQ(join_names(schema_child_keys("process")), "duration, gravity, seed, until_coverage, until_coverage_of");
    EXPECT_EQ(join_names(schema_child_keys("")),
              "name, process, accuracy, shot, air, materials, contacts, components, sources, sinks, output, render");
    EXPECT_EQ(join_names(schema_child_keys("contacts.*")),
              "law, C0, V0, mu, f, restitution_by_hits, influence_distance, e, plastic_speed, characteristic_speed, tangential_ratio");
    EXPECT_EQ(join_names(schema_child_keys("components[].motion")), "type, axis_point, axis_direction, speed");
}

TEST(SceneSchema, RangesReadAsText) {
    EXPECT_EQ(find_schema_entry("accuracy.travel_fraction")->range.text(), "[0.001, 1]");
    EXPECT_EQ(find_schema_entry("contacts.*.mu")->range.text(), "[0, 1]");
    EXPECT_EQ(find_schema_entry("process.duration")->range.text(), "> 0");
    EXPECT_EQ(find_schema_entry("contacts.*.f")->range.text(), ">= 0");
    EXPECT_TRUE(find_schema_entry("shot.diameter")->range.contains(0.02));
    EXPECT_FALSE(find_schema_entry("shot.diameter")->range.contains(0.0));
}

TEST(SceneSchema, ReferenceListsEveryKeyAndUnit) {
    const std::string md = scene_reference_markdown();
    EXPECT_NE(md.find("| Key | Type | Unit (SI) | Default | Range | Description |"), std::string::npos);
    for (const SchemaEntry& e : scene_schema()) {
        if (e.path.empty()) continue;
        EXPECT_NE(md.find("| `" + std::string(e.path) + "` |"), std::string::npos) << e.path;
    }
    EXPECT_NE(md.find("| `shot.diameter` | number | m | from `sizes` | (0, 0.02] |"), std::string::npos) << md;
    EXPECT_NE(md.find("| `shot.sizes[].fraction` | number | - | required | (0, 1] |"), std::string::npos) << md;
    EXPECT_NE(md.find("| `process.gravity` | vector | m/s2 | `[0, 0, -9.81]` |"), std::string::npos) << md;
    EXPECT_NE(md.find("| angular speed | rad/s, deg/s, rpm, rev/min, rev/s |"), std::string::npos) << md;
}

TEST(SceneSchema, NamesAreChecked) {
    EXPECT_TRUE(is_valid_name("aluminium-2000"));
    EXPECT_TRUE(is_valid_name("gear_1"));
    EXPECT_FALSE(is_valid_name(""));
    EXPECT_FALSE(is_valid_name("my gear"));
    EXPECT_FALSE(is_valid_name("a.b"));
}

}  // namespace
}  // namespace peensim
