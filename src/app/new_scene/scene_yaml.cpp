#include "app/new_scene/scene_yaml.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace peensim {

namespace {

// A length in mm with 3 decimals (1 um: finer than any mesh here), trailing zeros dropped.
std::string yaml_mm(double metres) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f", metres * 1e3);
    std::string s(buf);
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    if (s == "-0") s = "0";
    return s;
}
std::string mm_vector(const Vec3& v) { return "[" + yaml_mm(v.x()) + " mm, " + yaml_mm(v.y()) + " mm, " + yaml_mm(v.z()) + " mm]"; }
std::string yaml_number(double x, const char* format = "%.6g") {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, x);
    return buf;
}

// A direction as the scene writes it: its components, 0 or +-1 here.
std::string direction_vector(const Vec3& v) {  // + 0.0: no "-0"
    return "[" + yaml_number(v.x() + 0.0) + ", " + yaml_number(v.y() + 0.0) + ", " + yaml_number(v.z() + 0.0) + "]";
}
std::string degrees(double rad) { return yaml_number(rad * 180.0 / M_PI) + " deg"; }
std::string angle_frame(const AxisAngleFrame& f) {
    return "axis_point: " + mm_vector(f.axis_point_m) + ", axis_direction: " + direction_vector(f.axis_direction) +
           ", reference: " + direction_vector(f.reference);
}

void write_regions(std::ostream& y, const NewSceneRequest& r, const ProposedRegions& regions) {
    y << "    # Regions, in the part's own frame (its file's, in m after mesh_unit): the report gives each its\n"
         "    # coverage, its time to the target and its slowest spot. Edit or add your own (box, half_space,\n"
         "    # distance_to_axis, group...: see the scene reference). Areas no shot can reach are found by the\n"
         "    # analysis itself and reported, not counted.\n"
         "    regions:\n";
    if (r.turning_axis)
        y << "      # Turning about " << axis_name(*r.turning_axis) << ": the faces across the axis (the ends) and " << kProposedSectors
          << " sectors about it.\n";
    else
        y << "      # Still: by the way each face looks (within 45 deg of the direction; the rest in between is\n"
             "      # reported as the rest of the part). The sonotrode is below (-z).\n";
    if (!regions.left_out.empty()) {
        y << "      # Left out, as none of the part's surface lies in them:";
        for (const std::string& name : regions.left_out) y << " " << name;
        y << ".\n";
    }
    for (const RegionDesc& e : regions.entries) {
        if (e.facing)
            y << "      - {name: " << e.name << ", facing: {direction: " << direction_vector(e.facing->direction)
              << ", within: " << degrees(e.facing->within_rad) << "}}\n";
        else if (e.sectors)
            y << "      - name: " << e.name << "\n"
              << "        sectors: {" << angle_frame(e.sectors->frame) << ", count: " << e.sectors->count
              << ", width: " << degrees(e.sectors->width_rad) << ", offset: " << degrees(e.sectors->offset_rad)
              << ", name_prefix: " << e.sectors->name_prefix << "}\n";
        else if (e.sector)
            y << "      - {name: " << e.name << ", sector: {" << angle_frame(e.sector->frame) << ", from: " << degrees(e.sector->from_rad)
              << ", to: " << degrees(e.sector->to_rad) << "}}\n";
    }
}

}  // namespace

std::string new_scene_yaml(const SceneDesign& s, const NewSceneRequest& r, const PartMaterial& m, const ProposedRegions& regions,
                           const NewSceneFiles& f) {
    const double d = r.shot_diameter_m;
    std::ostringstream y;
    y << "# Written by `" << f.command << "`.\n"
      << "# A first scene around your part: an ultrasonic shot peening chamber sized for it, with the\n"
      << "# choices of the shipped gear case (scenes/gear.yaml) scaled to the part. Every choice is\n"
      << "# explained where it is made; change any of them and run again (or sweep them: `peensim sweep`).\n"
      << "# World frame: z up, the sonotrode's face at z = 0, its axis through the origin.\n"
      << "name: " << f.part_name << " (peensim new)\n"
      << "process:\n";
    if (s.turns > 0)
        y << "  # " << s.turns << (s.turns == 1 ? " whole turn at " : " whole turns at ") << yaml_number(r.rpm)
          << " rpm (the analysis counts whole turns), at least 5 s:\n"
          << "  # enough for a first forecast of the time to 98 % with its interval; the report says if it is not.\n";
    else
        y << "  # 5 s: enough for a first forecast of the time to 98 % with its interval; the report says if not.\n";
    y << "  duration: " << yaml_number(s.duration_s, "%.9g") << " s\n"
      << "  gravity: [0, 0, -9.81]\n"
      << "  seed: 1\n"
      << "shot:\n"
      << "  # " << s.shot_count << " shot: their cross-sections cover " << yaml_number(100.0 * s.shot_fill, "%.0f")
      << " % of the sonotrode's face (the gear case: 15.7 %).\n"
      << "  # More shot peen faster until they crowd each other; USP uses 1-3 mm bearing-steel balls.\n"
      << "  count: " << s.shot_count << "\n"
      << "  diameter: " << yaml_mm(d) << " mm\n"
      << "  material: steel\n"
      << "materials:\n"
      << "  steel: {density: 7.8 g/cm3}\n"
      << "  TA6V: {density: 4.43 g/cm3}\n"
      << "  # Your part's material: the yield stress sets the dents' size (eq. 10), hence the coverage.\n"
      << "  # " << yaml_number(m.yield_stress_mpa, "%.0f") << " MPa: " << m.yield_note << "; put your part's own.\n"
      << "  " << m.name << ": {density: " << yaml_number(m.density_g_cm3)
      << " g/cm3, yield_stress: " << yaml_number(m.yield_stress_mpa, "%.0f") << " MPa}\n"
      << "contacts:\n"
      << "  # Restitution (C0, V0) and friction (mu, f) of the CAD-based USP study's Table 2, by alloy family.\n"
      << "  shot-shot: {C0: 0.95, V0: 2.0 m/s}\n"
      << "  shot-TA6V: {C0: 0.9, V0: 1.5 m/s, mu: 0.9, f: 0.1}\n"
      << "  shot-steel: {C0: 0.95, V0: 2.0 m/s, mu: 0.8, f: 0.1}\n"
      << "  shot-" << m.name << ": {C0: " << yaml_number(m.C0) << ", V0: " << yaml_number(m.V0_m_s) << " m/s, mu: " << yaml_number(m.mu)
      << ", f: " << yaml_number(m.f) << "}\n"
      << "components:\n"
      << "  - name: sonotrode\n"
      << "    role: sonotrode\n"
      << "    # A titanium disk, " << yaml_mm(s.sonotrode_radius_m) << " mm in radius: the part's footprint ("
      << yaml_mm(s.envelope.footprint_radius_m) << " mm from the axis" << (r.turning_axis ? ", turning" : "") << ")\n"
      << "    # plus " << yaml_mm(s.sonotrode_margin_m)
      << " mm, so the shot rise under all of it. 20 kHz; 25 um as the gear case (USP: 20-80 um,\n"
      << "    # faster shot and more energy per dent with more).\n"
      << "    mesh: " << f.sonotrode_mesh << "\n"
      << "    mesh_unit: mm\n"
      << "    material: TA6V\n"
      << "    vibration: {amplitude: " << yaml_number(s.amplitude_m * 1e6) << " um, frequency: " << yaml_number(s.frequency_hz * 1e-3)
      << " kHz}\n"
      << "  - name: chamber\n"
      << "    role: chamber\n"
      << "    # Steel, open at the bottom where the sonotrode closes it: the lower section hugs the sonotrode\n"
      << "    # (" << yaml_mm(s.gap_m) << " mm gap, at most a quarter shot: none escape) up to z = " << yaml_mm(s.step_z_m)
      << " mm, the upper one leaves the part " << yaml_mm(s.upper_radius_m - s.envelope.footprint_radius_m) << " mm\n"
      << "    # to the wall (radius " << yaml_mm(s.upper_radius_m) << " mm); the lid is " << yaml_mm(s.lid_clearance_m)
      << " mm above the part's top, at z = " << yaml_mm(s.lid_z_m) << " mm.\n"
      << "    mesh: " << f.chamber_mesh << "\n"
      << "    mesh_unit: mm\n"
      << "    material: steel\n"
      << "  - name: " << f.part_name << "\n"
      << "    role: part\n"
      << "    mesh: " << f.part_mesh << "\n"
      << (f.unit_name.empty()
              ? std::string("    # A STEP or IGES file: its own unit, tessellated at the default tolerances (`tessellation`).\n")
              : "    mesh_unit: " + f.unit_name + "\n")
      << "    # Centred over the sonotrode, its lowest point" << (r.turning_axis ? " (of the solid it sweeps)" : "") << " "
      << yaml_mm(s.standoff_m) << " mm above it (the gear case: 20 mm).\n"
      << "    # Nothing holds it: add your fixture as a component with role: fixture.\n"
      << "    translation: " << mm_vector(s.translation_m) << "\n"
      << "    material: " << m.name << "\n";
    write_regions(y, r, regions);
    if (r.turning_axis)
        y << "    # Turning about its own " << axis_name(*r.turning_axis) << " axis through its centre (world " << mm_vector(s.axis_point_m)
          << ").\n"
          << "    motion: {type: rotating, axis_point: " << mm_vector(s.axis_point_m)
          << ", axis_direction: " << direction_vector(axis_unit(*r.turning_axis)) << ", speed: " << yaml_number(r.rpm) << " rpm}\n";
    y << "output:\n"
      << "  log: [" << f.part_name << "]\n";
    return y.str();
}

}  // namespace peensim
