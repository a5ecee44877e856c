#include "scene/schema.h"

#include <array>
#include <deque>
#include <string>

#include <cmath>
#include "contact/law_registry.h"

namespace peensim {
namespace {

using K = ValueKind;
using D = Dimension;

// The scene file format. Sanity limits (shot diameter <= 20 mm, count <= 1e8) catch unit slips
// such as "2" (metres) for "2 mm"; they are not physical limits of the model.
// Laid out by hand as a table, one entry per line or two.
// clang-format off
const std::array schema_table{
    SchemaEntry{"", K::map, D::dimensionless, false, "", "", {}, "", "", "", "A scene file."},
    SchemaEntry{"name", K::text, D::dimensionless, false, "", "empty", {}, "", "", "",
                "Free text naming the scene in reports."},

    SchemaEntry{"process", K::map, D::dimensionless, true, "", "", {}, "", "", "",
                "Process parameters."},
    SchemaEntry{"process.duration", K::quantity, D::time, true, "", "", above(0), "", "", "",
                "Simulated process time."},
    SchemaEntry{"process.gravity", K::vector3, D::acceleration, false, "[0, 0, -9.81]", "", {}, "", "", "",
                "Gravity vector, world frame."},
    SchemaEntry{"process.seed", K::integer, D::dimensionless, false, "1", "",
                at_least(0), "", "", "",
                "Seed of the random numbers (shot placement, initial directions)."},
    SchemaEntry{"process.until_coverage", K::quantity, D::dimensionless, false, "", "none: run for `duration`", open_closed(0, 1), "", "", "",
                "Run until coverage reaches this share (e.g. `98 %`) on every area `until_coverage_of` names, counted as the "
                "analysis counts it (the peened area: reachable by the shot, outside excluded regions); `duration` is then the "
                "longest the run may go on. The run ends at the first restart point after the target is reached and says when "
                "each area reached it (`summary.json`'s `until_coverage`). `peensim run --until-coverage 98%` sets it."},
    SchemaEntry{"process.until_coverage_of", K::name_list, D::dimensionless, false, "",
                "every counted region of every logged part with a yield stress (a part without regions: its peened area)", {}, "", "", "",
                "The areas `until_coverage` waits for: `part` (its whole peened area) or `part/region`, each once; not a region marked `exclude` (coverage does not count it). A named region no shot can reach (the reach test of every sample) is not waited for, with a note; when every named area is such, the run exits 2 before its first step and leaves nothing in its directory."},

    SchemaEntry{"accuracy", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "Speed/accuracy settings."},
    SchemaEntry{"accuracy.travel_fraction", K::quantity, D::dimensionless, false, "0.25", "",
                closed(1e-3, 1), "", "", "",
                "Time stepping only: largest travel of anything in one step, as a fraction of the shot radius (eq. 7 uses 0.25)."},
    SchemaEntry{"accuracy.impact_speed", K::quantity, D::speed, false, "5 cm/s", "", above(0), "", "", "",
                "The line between an impact and sustained contact. A shot approaching a surface (relative to its "
                "moving material) or another shot at a normal speed at least this is an impact (restitution, "
                "logged); slower is sustained contact (the approach is removed, Coulomb friction acts, no rebound, "
                "not logged: counted once per landing in `slow_contacts_per_component`). See docs/design.md, \"Impacts "
                "and sustained contact\"."},
    SchemaEntry{"accuracy.scheme", K::choice, D::dimensionless, false, "event", "", {}, "step|event|soft", "", "",
                "Stepping scheme: `event`, event-driven (each shot flies exactly to its next collision, found in "
                "closed form or by root finding; `travel_fraction` unused), or `step`, time stepping (every shot "
                "advances by the step of eq. 7; contacts found at step ends and taken back to their exact touch time); "
                "both with instantaneous rigid impacts. `soft`: event-driven flights, and every impact a soft-sphere "
                "contact integrated while it lasts (every pair's law a soft-sphere one, `hertz-mindlin` or "
                "`linear-spring-dashpot`; materials with `youngs_modulus` and `poisson_ratio`). See docs/design.md, \"Choosing the stepping scheme\"."},
    SchemaEntry{"accuracy.soft_steps_per_contact", K::quantity, D::dimensionless, false, "20", "", closed(4, 10000), "", "", "",
                "Soft scheme only: integration steps per Hertz contact time (the duration of an elastic contact at "
                "the contact's approach speed); the soft contacts' accuracy knob (see docs/design.md, \"Soft-sphere contacts\")."},

    SchemaEntry{"shot", K::map, D::dimensionless, true, "", "", {}, "", "", "", "The shot: one size (`diameter`) or a mix (`sizes`)."},
    SchemaEntry{"shot.count", K::integer, D::dimensionless, true, "", "", closed(0, 1e8), "", "", "",
                "Number of shot placed on the sonotrode at the start (0: only what `sources` emit)."},
    SchemaEntry{"shot.diameter", K::quantity, D::length, false, "", "from `sizes`", open_closed(0, 0.02), "", "", "",
                "Shot diameter D, when all shot are of one size; else give `sizes`."},
    SchemaEntry{"shot.sizes", K::list, D::dimensionless, false, "", "one size, `diameter`", {}, "", "", "",
                "A mix of sizes (a sieve analysis, SAE J444), instead of `diameter`: up to 32 items of `diameter` and "
                "`fraction`, the fractions summing to 1 (within 0.005, then scaled to it). Each shot placed or emitted "
                "draws its size from the seed; a mass flow counts the mix's mean mass. See docs/user-guide.md, \"Shot size mixes\"."},
    SchemaEntry{"shot.sizes[]", K::map, D::dimensionless, false, "", "", {}, "", "", "", "One size of the mix."},
    SchemaEntry{"shot.sizes[].diameter", K::quantity, D::length, true, "", "", open_closed(0, 0.02), "", "", "",
                "This size's diameter; each diameter once."},
    SchemaEntry{"shot.sizes[].fraction", K::quantity, D::dimensionless, true, "", "", open_closed(0, 1), "", "", "",
                "This size's share of the mix, by mass or by count (`fractions_by`)."},
    SchemaEntry{"shot.fractions_by", K::choice, D::dimensionless, false, "mass", "", {}, "mass|count", "", "",
                "What the fractions of `sizes` share: `mass` (a sieve analysis; LIGGGHTS' discrete distributions) or "
                "`count` (the share of the shot)."},
    SchemaEntry{"shot.density", K::quantity, D::density, false, "", "from `material`", above(0), "", "", "",
                "Shot density; give either `density` or `material`, not both."},
    SchemaEntry{"shot.material", K::text, D::dimensionless, false, "", "none", {}, "", "", "",
                "A key of `materials` that defines `density`; instead of `density`."},
    SchemaEntry{"shot.initial_velocity", K::vector3, D::speed, false, "", "at rest", {}, "", "", "",
                "Initial velocity of every shot (world frame), at most 1000 m/s; not with `initial_speed`."},
    SchemaEntry{"shot.initial_speed", K::quantity, D::speed, false, "", "at rest", closed(0, 1000), "", "", "",
                "Initial speed in random directions on the upper hemisphere around the sonotrode axis; "
                "not with `initial_velocity`."},

    SchemaEntry{"air", K::map, D::dimensionless, false, "", "still air, no drag", {}, "", "", "",
                "The still air the shot fly through. Without drag (the default, right for ultrasonic peening) every "
                "flight is an exact parabola under gravity."},
    SchemaEntry{"air.drag", K::choice, D::dimensionless, false, "none", "", {}, "none|sphere", "", "",
                "Drag on the shot: `none`, or `sphere`, a smooth sphere's drag C_d(Re) rho |v| v pi R^2 / 2 (the standard "
                "drag curve: Clift, Grace & Weber 1978). A scene with drag runs with time stepping (`accuracy.scheme: "
                "event` is refused): the event scheme's kernels solve exact parabolas."},
    SchemaEntry{"air.density", K::quantity, D::density, false, "1.205 kg/m3", "", closed(1e-3, 100), "", "", "",
                "Air density (20 C, 1 atm by default)."},
    SchemaEntry{"air.viscosity", K::quantity, D::viscosity, false, "1.822e-5 Pa s", "", closed(1e-7, 1e-2), "", "", "",
                "Dynamic viscosity of the air, for the Reynolds number Re = rho |v| D / mu."},
    SchemaEntry{"air.drag_coefficient", K::quantity, D::dimensionless, false, "", "the standard drag curve C_d(Re)", open_closed(0, 100), "", "", "",
                "A constant drag coefficient instead of C_d(Re) (to compare with a code or a closed-form flight)."},
    SchemaEntry{"air.rebound_scatter", K::map, D::dimensionless, false, "", "off", {}, "", "", "",
                "Random rebounds (reference section 5: above Re* ~ 1600 and ~40 m/s the single-shot study saw the rebound "
                "leave in a random direction): an impact faster than `min_speed` whose Re* = rho |u - v'| D / mu (the study's: "
                "the air's velocity u at the contact, still or a nozzle's jet, against the rebound v'; `air.density`, "
                "`air.viscosity`) is at least `min_reynolds` rebounds turned by an angle uniform in [0, "
                "`spread`] towards a random direction of the surface's plane, its speed kept. Reproducible from the seed; "
                "the rigid schemes only (the soft scheme's contacts are forces)."},
    SchemaEntry{"air.rebound_scatter.spread", K::quantity, D::angle, true, "", "", closed(0, 1.5707963267948966), "", "", "",
                "Largest deflection of the rebound's direction (0 to 90 deg)."},
    SchemaEntry{"air.rebound_scatter.min_reynolds", K::quantity, D::dimensionless, false, "1500", "", closed(0, 1e7), "", "", "",
                "Relative Reynolds number Re* from which rebounds scatter (the study's cases at \"Re* ~ 1600\" have 1550-1700)."},
    SchemaEntry{"air.rebound_scatter.min_speed", K::quantity, D::speed, false, "40 m/s", "", closed(0, 1e4), "", "", "",
                "Impact speed (relative to the surface) from which rebounds scatter."},

    SchemaEntry{"materials", K::named_map, D::dimensionless, false, "", "none", {}, "", "", "",
                "Materials by name (`[A-Za-z0-9_-]+`)."},
    SchemaEntry{"materials.*", K::map, D::dimensionless, false, "", "", {}, "", "", "", "One material."},
    SchemaEntry{"materials.*.density", K::quantity, D::density, false, "", "none", above(0), "", "", "",
                "Density (needed if the shot names this material)."},
    SchemaEntry{"materials.*.yield_stress", K::quantity, D::stress, false, "", "none", above(0), "", "", "",
                "Yield stress, for dent diameters (eq. 10)."},
    SchemaEntry{"materials.*.youngs_modulus", K::quantity, D::stress, false, "", "none", closed(1e3, 1e13), "", "", "",
                "Young's modulus E, for soft-sphere contacts (laws `hertz-mindlin`, `linear-spring-dashpot`)."},
    SchemaEntry{"materials.*.poisson_ratio", K::quantity, D::dimensionless, false, "", "none", closed(-0.99, 0.5), "", "", "",
                "Poisson's ratio nu, for soft-sphere contacts (laws `hertz-mindlin`, `linear-spring-dashpot`)."},

    SchemaEntry{"contacts", K::named_map, D::dimensionless, false, "", "built-in `default`", {}, "", "", "",
                "Contact coefficients by pair: `shot-shot`, `shot-<material>` or `default` (every pair not "
                "listed)."},
    SchemaEntry{"contacts.*", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "One pair: its contact law and that law's parameters. A key left out takes the `default` pair's "
                "value when the `default` pair's law has it, else the law's own default."},
    // contacts.*.law and each law's parameters: generated from the law catalogue (law_entries).

    SchemaEntry{"components", K::list, D::dimensionless, true, "", "", {}, "", "", "",
                "The meshes. With `shot.count` above 0: at least one `sonotrode` (the shot are placed on the first) and one "
                "`chamber`; a scene fed by `sources` may have neither."},
    SchemaEntry{"components[]", K::map, D::dimensionless, false, "", "", {}, "", "", "", "One component."},
    SchemaEntry{"components[].name", K::text, D::dimensionless, true, "", "", {}, "", "", "",
                "Unique name (`[A-Za-z0-9_-]+`)."},
    SchemaEntry{"components[].role", K::choice, D::dimensionless, true, "", "", {},
                "sonotrode|chamber|part|fixture|almen", "", "",
                "What the component does. `sonotrode`: vibrates (`vibration`); there may be several, the shot are "
                "placed on the first one listed; a scene fed by `sources` may have none. `almen`: a virtual SAE Almen "
                "strip (static; impacts always logged; see `almen`)."},
    SchemaEntry{"components[].mesh", K::text, D::dimensionless, true, "", "", {}, "", "", "",
                "Mesh file (STL, OBJ, PLY, ...) or CAD file (STEP `.step`/`.stp`, IGES `.iges`/`.igs`: tessellated, see "
                "`tessellation`), relative to the scene file's directory."},
    SchemaEntry{"components[].mesh_unit", K::choice, D::dimensionless, false, "m", "", {}, "m|cm|mm|um|in", "",
                "", "Length unit of the mesh file's coordinates. Not for a STEP or IGES file: it states its own unit, "
                "which is used."},
    SchemaEntry{"components[].tessellation", K::map, D::dimensionless, false, "", "the defaults below", {}, "", "", "",
                "Only for a STEP or IGES file: how its exact surfaces become triangles (OpenCASCADE's mesher). One facet "
                "per B-rep face, one group per solid (`solid1`, `solid2`, ...). See docs/step-iges.md."},
    // Defaults: those of geometry/cad_reader.h's Tessellation (a test keeps them equal), reasoned there.
    SchemaEntry{"components[].tessellation.chordal", K::quantity, D::length, false, "0.01 mm", "", open_closed(0, 1e-3), "", "", "",
                "Largest distance from a triangle to the exact surface (a 2 mm shot's dent is ~0.01 mm deep)."},
    SchemaEntry{"components[].tessellation.angular", K::quantity, D::angle, false, "5 deg", "", open_closed(0, 0.7853981633974483), "",
                "", "", "Largest turn of the surface normal along a triangle edge (a facet's normal is within about half of it "
                "of the true one); binds on tight curves (fillets, holes), where the chordal tolerance leaves wide facets."},
    SchemaEntry{"components[].translation", K::vector3, D::length, false, "[0, 0, 0]", "", {}, "", "", "",
                "Position of the component frame in the world; `[x, y, z]`, `\"x y z unit\"` (one unit for all) "
                "or `\"x unit y unit z unit\"`."},
    SchemaEntry{"components[].rotation", K::map, D::dimensionless, false, "", "identity", {}, "", "", "",
                "Orientation (applied before the translation): `{axis, angle}`, `{euler_xyz}` or `{matrix}`."},
    SchemaEntry{"components[].rotation.axis", K::vector3, D::dimensionless, false, "", "", {}, "", "", "",
                "Rotation axis (normalised; not zero), with `angle`."},
    SchemaEntry{"components[].rotation.angle", K::quantity, D::angle, false, "", "", {}, "", "", "",
                "Rotation angle about `axis` (right-hand rule)."},
    SchemaEntry{"components[].rotation.euler_xyz", K::vector3, D::angle, false, "", "", {}, "", "", "deg",
                "Intrinsic rotations about X, then the new Y, then the newest Z (R = Rx Ry Rz); plain numbers "
                "are degrees."},
    SchemaEntry{"components[].rotation.matrix", K::matrix3, D::dimensionless, false, "", "", {}, "", "", "",
                "Rotation matrix (rows; component frame -> world), orthonormal with determinant +1."},
    SchemaEntry{"components[].material", K::text, D::dimensionless, false, "", "none (`default` contact)", {},
                "", "", "", "A key of `materials`; selects the `shot-<material>` contact pair."},
    SchemaEntry{"components[].vibration", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "Sinusoidal vibration A sin(2 pi F t + phase); required for a sonotrode, forbidden for "
                "others."},
    SchemaEntry{"components[].vibration.amplitude", K::quantity, D::length, true, "", "", at_least(0), "", "",
                "", "Amplitude A0."},
    SchemaEntry{"components[].vibration.frequency", K::quantity, D::frequency, true, "", "", at_least(0), "",
                "", "", "Frequency F (> 0 when the amplitude is > 0)."},
    SchemaEntry{"components[].vibration.phase", K::quantity, D::angle, false, "0", "", {}, "", "", "",
                "Phase at t = 0."},
    SchemaEntry{"components[].vibration.axis", K::vector3, D::dimensionless, false, "",
                "mean face normal", {}, "", "", "", "Direction of vibration (normalised; not zero)."},
    SchemaEntry{"components[].almen", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "Only for role `almen`: the strip's peened face and its arc-height calibration on a measured "
                "saturation curve: `calibration` (the predictive model, as `peensim almen-fit --calibrate` prints it), "
                "or the dose model h = a (1 - exp(-E / E_c)) (`saturation_arc_height`, `dose_constant`; E the normal "
                "impact energy per area). Without either, only the dose and the dents are reported."},
    SchemaEntry{"components[].almen.face_normal", K::vector3, D::dimensionless, false, "[0, 0, 1]", "", {}, "",
                "", "", "Outward normal of the peened face, component frame (normalised; not zero)."},
    SchemaEntry{"components[].almen.saturation_arc_height", K::quantity, D::length, false, "", "not calibrated",
                above(0), "", "", "", "Calibration a: the arc height the strip tends to (with `dose_constant`)."},
    SchemaEntry{"components[].almen.dose_constant", K::quantity, D::energy_per_area, false, "",
                "not calibrated", above(0), "", "", "",
                "Calibration E_c: the dose that raises the arc height to 63 % of a (with "
                "`saturation_arc_height`)."},
    SchemaEntry{"components[].almen.calibration", K::map, D::dimensionless, false, "", "not calibrated", {}, "", "", "",
                "The predictive model's calibration on one measured saturation curve and the run that reproduced it, "
                "as `peensim almen-fit CURVE --calibrate RUNDIR` prints it: the analysis then predicts this strip's "
                "saturation curve, J443 saturation time and intensity from its dents (docs/user-guide.md, \"Almen strips\"). "
                "Not with `saturation_arc_height` and `dose_constant`."},
    SchemaEntry{"components[].almen.calibration.saturation_arc_height", K::quantity, D::length, true, "", "", above(0), "", "", "",
                "a of the measured curve h = a (1 - exp(-(t / tau)^c))."},
    SchemaEntry{"components[].almen.calibration.time_constant", K::quantity, D::time, true, "", "", above(0), "", "", "",
                "tau of the measured curve (2P fit: 1 / b)."},
    SchemaEntry{"components[].almen.calibration.shape", K::quantity, D::dimensionless, false, "1", "", closed(0.05, 20), "", "", "",
                "c of the measured curve (1: the 2P form)."},
    SchemaEntry{"components[].almen.calibration.dent_size", K::quantity, D::length, true, "", "", above(0), "", "", "",
                "The calibration run's dent size on the strip's face (dent-area-weighted mean dent diameter, eq. 10)."},
    SchemaEntry{"components[].almen.calibration.covering_rate", K::quantity, D::frequency, true, "", "", above(0), "", "", "",
                "The calibration run's covering rate on the strip's face (dent area ratio per second, steady)."},
    SchemaEntry{"components[].almen.calibration.strip", K::choice, D::dimensionless, false, "", "not given", {}, "A|N|C", "", "",
                "The SAE J442 strip type of the measured curve, printed with the intensity (0.0118A)."},
    SchemaEntry{"components[].motion", K::map, D::dimensionless, false, "", "static", {}, "static", "", "",
                "`static`, or a rotation at constant speed; only for role `part`."},
    SchemaEntry{"components[].motion.type", K::choice, D::dimensionless, true, "", "", {}, "static|rotating",
                "", "", "Kind of motion."},
    SchemaEntry{"components[].motion.axis_point", K::vector3, D::length, false, "", "required if rotating", {}, "", "",
                "", "A point on the rotation axis (world frame)."},
    SchemaEntry{"components[].motion.axis_direction", K::vector3, D::dimensionless, false, "",
                "required if rotating", {}, "", "", "", "Axis direction (normalised; not zero), right-hand rule."},
    SchemaEntry{"components[].motion.speed", K::quantity, D::angular_speed, false, "", "required if rotating",
                {}, "", "", "", "Angular speed (signed)."},

    SchemaEntry{"components[].regions", K::list, D::dimensionless, false, "", "none", {}, "", "", "",
                "Named selections of the component's surface, reported separately by `peensim analyze` (and drawn by "
                "`peensim render-regions`). Component frame (the mesh frame after `mesh_unit`). Each item has a `name` "
                "and one or more conditions, all of which hold in the region: `sector` or `sectors`, `box`, "
                "`half_space`, `distance_to_axis`, `distance_to_point` (on the point of the surface), `facing`, "
                "`group` (on the triangle). A triangle counts with the share of its area inside; an impact with "
                "its point."},
    SchemaEntry{"components[].regions[]", K::map, D::dimensionless, false, "", "", {}, "", "", "", "One region."},
    SchemaEntry{"components[].regions[].name", K::text, D::dimensionless, true, "", "", {}, "", "", "",
                "Unique name on the component (`[A-Za-z0-9_-]+`)."},
    SchemaEntry{"components[].regions[].sector", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "Angular sector [from, to) about an axis; angles right-hand about `axis_direction`, from "
                "`reference` projected normal to the axis."},
    SchemaEntry{"components[].regions[].sector.axis_point", K::vector3, D::length, false, "[0, 0, 0]", "", {}, "",
                "", "", "A point on the axis."},
    SchemaEntry{"components[].regions[].sector.axis_direction", K::vector3, D::dimensionless, true, "", "", {}, "",
                "", "", "Axis direction (normalised; not zero)."},
    SchemaEntry{"components[].regions[].sector.reference", K::vector3, D::dimensionless, true, "", "", {}, "", "",
                "", "Direction of angle 0 (not along the axis)."},
    SchemaEntry{"components[].regions[].sector.from", K::quantity, D::angle, true, "", "", {}, "", "", "",
                "Start angle (included)."},
    SchemaEntry{"components[].regions[].sector.to", K::quantity, D::angle, true, "", "", {}, "", "", "",
                "End angle (excluded); from < to <= from + 360 deg."},
    SchemaEntry{"components[].regions[].sectors", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "`count` sectors of `width`, sector i centred at offset + i 360 deg / count, named "
                "`<name_prefix><i>` (i from 0); the item's `name` only names the entry."},
    SchemaEntry{"components[].regions[].sectors.axis_point", K::vector3, D::length, false, "[0, 0, 0]", "", {},
                "", "", "", "A point on the axis."},
    SchemaEntry{"components[].regions[].sectors.axis_direction", K::vector3, D::dimensionless, true, "", "", {},
                "", "", "", "Axis direction (normalised; not zero)."},
    SchemaEntry{"components[].regions[].sectors.reference", K::vector3, D::dimensionless, true, "", "", {}, "",
                "", "", "Direction of angle 0 (not along the axis)."},
    SchemaEntry{"components[].regions[].sectors.count", K::integer, D::dimensionless, true, "", "",
                closed(1, 3600), "", "", "", "Number of sectors."},
    SchemaEntry{"components[].regions[].sectors.width", K::quantity, D::angle, true, "", "",
                above(0), "", "", "", "Width of each sector (<= 360 deg)."},
    SchemaEntry{"components[].regions[].sectors.offset", K::quantity, D::angle, false, "0", "", {}, "", "", "",
                "Centre angle of sector 0."},
    SchemaEntry{"components[].regions[].sectors.name_prefix", K::text, D::dimensionless, false, "",
                "`<name>-`", {}, "", "", "", "Prefix of the sectors' region names."},
    SchemaEntry{"components[].regions[].box", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "Axis-aligned box (faces included)."},
    SchemaEntry{"components[].regions[].box.min", K::vector3, D::length, true, "", "", {}, "", "", "",
                "Lowest corner."},
    SchemaEntry{"components[].regions[].box.max", K::vector3, D::length, true, "", "", {}, "", "", "",
                "Highest corner (>= min in x, y and z)."},
    SchemaEntry{"components[].regions[].half_space", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "The side of a plane the normal points to (the plane included)."},
    SchemaEntry{"components[].regions[].half_space.point", K::vector3, D::length, false, "[0, 0, 0]", "", {}, "",
                "", "", "A point on the plane."},
    SchemaEntry{"components[].regions[].half_space.normal", K::vector3, D::dimensionless, true, "", "", {}, "",
                "", "", "Plane normal (normalised; not zero), pointing into the region."},
    SchemaEntry{"components[].regions[].distance_to_axis", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "Points whose distance to an axis is in [min, max] (a bore: max; an outer rim: min)."},
    SchemaEntry{"components[].regions[].distance_to_axis.axis_point", K::vector3, D::length, false, "[0, 0, 0]", "", {}, "",
                "", "", "A point on the axis."},
    SchemaEntry{"components[].regions[].distance_to_axis.axis_direction", K::vector3, D::dimensionless, true, "", "", {}, "",
                "", "", "Axis direction (normalised; not zero)."},
    SchemaEntry{"components[].regions[].distance_to_axis.min", K::quantity, D::length, false, "0", "", at_least(0), "", "", "",
                "Smallest distance (included)."},
    SchemaEntry{"components[].regions[].distance_to_axis.max", K::quantity, D::length, false, "", "no upper bound", above(0), "",
                "", "", "Largest distance (included; > min)."},
    SchemaEntry{"components[].regions[].distance_to_point", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "Points whose distance to a point is in [min, max] (a spot: max)."},
    SchemaEntry{"components[].regions[].distance_to_point.point", K::vector3, D::length, true, "", "", {}, "", "", "",
                "The point."},
    SchemaEntry{"components[].regions[].distance_to_point.min", K::quantity, D::length, false, "0", "", at_least(0), "", "", "",
                "Smallest distance (included)."},
    SchemaEntry{"components[].regions[].distance_to_point.max", K::quantity, D::length, false, "", "no upper bound", above(0), "",
                "", "", "Largest distance (included; > min)."},
    SchemaEntry{"components[].regions[].facing", K::map, D::dimensionless, false, "", "", {}, "", "", "",
                "Triangles whose normal (by the mesh's winding: outward on a closed part) is within an angle of a "
                "direction: flanks against end faces."},
    SchemaEntry{"components[].regions[].facing.direction", K::vector3, D::dimensionless, true, "", "", {}, "", "", "",
                "The direction (normalised; not zero)."},
    SchemaEntry{"components[].regions[].facing.within", K::quantity, D::angle, true, "", "", above(0),
                "", "", "", "Largest angle between the triangle's normal and `direction` (<= 180 deg)."},
    SchemaEntry{"components[].regions[].group", K::text, D::dimensionless, false, "", "", {}, "", "", "",
                "A named solid / sub-mesh of the mesh file (checked when the mesh is loaded)."},
    SchemaEntry{"components[].regions[].exclude", K::choice, D::dimensionless, false, "false", "", {}, "true|false", "", "",
                "`true`: the region is not to be peened (masked) or out of the shot's reach: its impacts are still "
                "logged and reported, but coverage, uniformity and the time to full coverage leave its area out."},

    SchemaEntry{"sources", K::list, D::dimensionless, false, "", "none", {}, "", "", "",
                "Shot sources: nozzles that emit shot during the run (conventional peening), hoppers that drop them. A scene with sources "
                "may have `shot.count: 0`, and then needs no sonotrode and no chamber. See docs/user-guide.md, \"Shot "
                "sources and sinks\"."},
    SchemaEntry{"sources[]", K::map, D::dimensionless, false, "", "", {}, "", "", "", "One source."},
    SchemaEntry{"sources[].name", K::text, D::dimensionless, true, "", "", {}, "", "", "",
                "Unique among sources and sinks (`[A-Za-z0-9_-]+`)."},
    SchemaEntry{"sources[].kind", K::choice, D::dimensionless, false, "nozzle", "", {}, "nozzle|hopper", "", "",
                "`nozzle`: shot leave an exit at a speed along an axis (the keys below down to `spread`); `hopper`: "
                "shot drop at rest out of an opening (`opening_min`, `opening_max`) and fall. Both take `rate` or "
                "`mass_flow`, `start` and `stop`."},
    SchemaEntry{"sources[].opening_min", K::vector3, D::length, false, "", "", {}, "", "", "",
                "`hopper`: lowest corner of the box its shot's centres start in, at points uniform over it (world "
                "frame; a flat box, min = max in z, is an opening in a plane)."},
    SchemaEntry{"sources[].opening_max", K::vector3, D::length, false, "", "", {}, "", "", "",
                "`hopper`: highest corner of that box (>= min in x, y and z)."},
    SchemaEntry{"sources[].position", K::vector3, D::length, false, "", "from `target`", {}, "", "", "",
                "Centre of the nozzle's exit (world frame): where the shot's centres start. Give `position` and "
                "`direction`, or `target` and `distance` (with `angle_of_attack`, `target_normal`, `azimuth`)."},
    SchemaEntry{"sources[].direction", K::vector3, D::dimensionless, false, "", "from `target`", {}, "", "", "",
                "Axis of the jet (normalised; not zero)."},
    SchemaEntry{"sources[].target", K::vector3, D::length, false, "", "none", {}, "", "", "",
                "The point the jet's axis aims at (world frame): the nozzle is placed `distance` from it, its axis at "
                "`angle_of_attack` to the surface whose normal is `target_normal`."},
    SchemaEntry{"sources[].distance", K::quantity, D::length, false, "", "none", above(0), "", "", "",
                "Distance from the nozzle's exit to `target` along its axis (with `target`)."},
    SchemaEntry{"sources[].angle_of_attack", K::quantity, D::angle, false, "90 deg", "", open_closed(0, 1.5707963267948966), "", "",
                "", "Angle between the jet's axis and the target surface (90 deg: along its normal)."},
    SchemaEntry{"sources[].target_normal", K::vector3, D::dimensionless, false, "", "against gravity (+z without it)", {}, "", "", "",
                "Normal of the target surface at `target`, pointing to the nozzle's side (normalised)."},
    SchemaEntry{"sources[].azimuth", K::quantity, D::angle, false, "0 deg", "", {}, "", "", "",
                "Side the nozzle leans from below 90 deg: the angle about `target_normal` from world x projected on "
                "the surface (y when the normal is along x)."},
    SchemaEntry{"sources[].speed", K::quantity, D::speed, false, "", "none (a nozzle needs it)", open_closed(0, 1000), "", "", "",
                "Mean speed of the shot leaving the nozzle (v0)."},
    SchemaEntry{"sources[].speed_spread", K::quantity, D::dimensionless, false, "0.05", "", closed(0, 0.9), "", "", "",
                "Spread of the exit speed: uniform in v0 (1 +- speed_spread)."},
    SchemaEntry{"sources[].air_speed", K::quantity, D::speed, false, "", "still air", open_closed(0, 1000), "", "", "",
                "The air's exit speed U_0: the nozzle blows a round free jet (B = 5.8, S = 0.094: a potential core at U_0 "
                "closing at 5.8 exit diameters, then U_0 5.8 D_n / s on the axis, half-width 0.094 s; see docs/user-guide.md, \"Air "
                "drag\") that the shot's drag (and rebound scatter's Re*) is taken against. Needs `air.drag: sphere` or "
                "`air.rebound_scatter`, and an exit diameter."},
    SchemaEntry{"sources[].rate", K::quantity, D::frequency, false, "", "from `mass_flow`", open_closed(0, 1e8), "", "", "",
                "Shot emitted per second, evenly spaced in time; give `rate` or `mass_flow`."},
    SchemaEntry{"sources[].mass_flow", K::quantity, D::mass_flow, false, "", "none", open_closed(0, 1e4), "", "", "",
                "Mass flow of shot (5-13 kg/min in conventional peening): `rate` = mass_flow / (rho pi D^3 / 6)."},
    SchemaEntry{"sources[].exit_radius", K::quantity, D::length, false, "0 m", "", closed(0, 1), "", "", "",
                "Radius of the nozzle's exit: centres start at points uniform over this disc, normal to `direction`."},
    SchemaEntry{"sources[].diameter", K::quantity, D::length, false, "", "2 exit_radius", closed(0, 2), "", "", "",
                "Inner diameter of the nozzle, instead of `exit_radius`."},
    SchemaEntry{"sources[].spread", K::quantity, D::angle, false, "0 deg", "", closed(0, 1.5707963267948966), "", "", "",
                "Half-angle of the jet's cone (its divergence): directions uniform over it."},
    SchemaEntry{"sources[].start", K::quantity, D::time, false, "0 s", "", at_least(0), "", "", "",
                "Time of the first emission."},
    SchemaEntry{"sources[].stop", K::quantity, D::time, false, "", "the run's end", above(0), "", "", "",
                "No emission at or after this time."},

    SchemaEntry{"sinks", K::list, D::dimensionless, false, "", "none", {}, "", "", "",
                "Shot sinks: where a shot is collected (taken out of the run and counted per sink), not lost."},
    SchemaEntry{"sinks[]", K::map, D::dimensionless, false, "", "", {}, "", "", "", "One sink."},
    SchemaEntry{"sinks[].name", K::text, D::dimensionless, true, "", "", {}, "", "", "",
                "Unique among sources and sinks (`[A-Za-z0-9_-]+`)."},
    SchemaEntry{"sinks[].region", K::choice, D::dimensionless, true, "", "", {}, "box|outside|mesh", "", "",
                "`box`: a shot whose centre enters the box (`min`, `max`, world frame) is collected (an outlet, a "
                "hopper); `mesh`: a shot whose centre enters a closed mesh's volume (`mesh`, `mesh_unit`, "
                "`translation`; a duct's mouth, a hopper of any shape; shot pass through its surface into it, it is no "
                "obstacle) is collected; `outside`: a shot leaving the assembly's bounds is collected instead of lost (an "
                "open setup)."},
    SchemaEntry{"sinks[].mesh", K::text, D::dimensionless, false, "", "", {}, "", "", "",
                "`mesh`: the closed mesh file (STL, OBJ, PLY...; STEP or IGES at the default tessellation, in its own unit; "
                "relative to the scene file)."},
    SchemaEntry{"sinks[].mesh_unit", K::choice, D::dimensionless, false, "m", "", {}, "m|cm|mm|um|in", "", "",
                "`mesh`: length unit of the mesh file's coordinates."},
    SchemaEntry{"sinks[].translation", K::vector3, D::length, false, "[0, 0, 0]", "", {}, "", "", "",
                "`mesh`: where the mesh's frame sits in the world."},
    SchemaEntry{"sinks[].min", K::vector3, D::length, false, "", "", {}, "", "", "",
                "`box`: lowest corner (world frame)."},
    SchemaEntry{"sinks[].max", K::vector3, D::length, false, "", "", {}, "", "", "",
                "`box`: highest corner (> min in x, y and z)."},

    SchemaEntry{"output", K::map, D::dimensionless, false, "", "", {}, "", "", "", "What to write."},
    SchemaEntry{"output.log", K::name_list, D::dimensionless, false, "", "every component with role `part`",
                {}, "", "", "", "Components whose impacts are logged (Almen strips always are)."},
    SchemaEntry{"output.directory", K::text, D::dimensionless, false, "", "from the command line", {}, "",
                "", "", "Output directory, relative to the working directory."},
    SchemaEntry{"output.checkpoint_interval", K::quantity, D::time, false, "60", "", above(0), "", "", "",
                "Wall-clock time between resume checkpoints."},
    SchemaEntry{"output.shot_positions", K::quantity, D::time, false, "", "off", above(0), "", "", "",
                "Simulated time between the steps of the shot-position series for ParaView (`paraview/shots.pvd`: "
                "every shot's centre, velocity, speed, diameter and index at 0, this, twice this... up to the run's "
                "end; at most 100 000 steps). Written while the run goes; a resumed run continues it, and resumes "
                "only with the same value. See docs/user-guide.md, \"ParaView files\"."},
    SchemaEntry{"output.coverage_steps", K::integer, D::dimensionless, false, "10", "", closed(0, 1000), "", "", "",
                "Times at which the analysis writes each logged part's per-triangle coverage for ParaView "
                "(`analysis/<part>_coverage_series.pvd`): at the analysed window's start (0 by default) and this many even steps to its end (the "
                "part's mesh each time: 52 bytes a triangle, 15.6 MB a step for 300k triangles). 0: none."},
    SchemaEntry{"output.smoothing_radius", K::quantity, D::length, false, "",
                "3 dents (eq. 10) at the part's mean normal speed (else 1 mm), widened to hold 25 impacts at its mean density",
                closed(1e-6, 1), "", "", "",
                "Radius of the surface over which `peensim analyze` smooths its per-area fields (the `*_smoothed` "
                "columns and the maps of `render-impacts`): the maps' resolution, the same whatever the mesh's "
                "tessellation; `analyze --smoothing-radius` overrides it. See docs/user-guide.md, \"Smoothed maps\"."},

    SchemaEntry{"render", K::map, D::dimensionless, false, "", "no animation", {}, "", "", "",
                "Record an off-screen animation while simulating (also `peensim run --render`): PNG frames "
                "every slow_motion / fps simulated seconds and an MP4."},
    SchemaEntry{"render.width", K::integer, D::dimensionless, false, "1280", "", closed(16, 7680), "", "", "",
                "Frame width, pixels."},
    SchemaEntry{"render.height", K::integer, D::dimensionless, false, "720", "", closed(16, 4320), "", "", "",
                "Frame height, pixels."},
    SchemaEntry{"render.fps", K::integer, D::dimensionless, false, "30", "", closed(1, 240), "", "", "",
                "Video frames per second."},
    SchemaEntry{"render.slow_motion", K::quantity, D::time, false, "20 ms", "", above(0), "", "", "",
                "Simulated time per second of video (20 ms: 50x slow motion)."},
    SchemaEntry{"render.start", K::quantity, D::time, false, "0", "", at_least(0), "", "", "",
                "Simulated time of the first frame."},
    SchemaEntry{"render.duration", K::quantity, D::time, false, "0.2", "", above(0), "", "", "",
                "Simulated time recorded (cut at the end of the run)."},
    SchemaEntry{"render.camera", K::map, D::dimensionless, false, "", "automatic framing", {}, "", "", "",
                "Where the camera looks from; without `position`, the chamber is framed from front-above."},
    SchemaEntry{"render.camera.position", K::vector3, D::length, false, "", "automatic", {}, "", "", "",
                "Camera position, world frame."},
    SchemaEntry{"render.camera.look_at", K::vector3, D::length, false, "", "the chamber's centre", {}, "", "",
                "", "The point at the image centre, world frame."},
    SchemaEntry{"render.camera.up", K::vector3, D::dimensionless, false, "[0, 0, 1]", "", {}, "", "", "",
                "World direction shown upward (normalised; not zero)."},
    SchemaEntry{"render.camera.fov", K::quantity, D::angle, false, "40 deg", "", open_open(0, M_PI), "", "", "",
                "Vertical field of view."},
    SchemaEntry{"render.speed_scale", K::quantity, D::speed, false, "5", "", above(0), "", "", "",
                "Normal impact speed at the top of the impact flashes' colour bar."},
    SchemaEntry{"render.video", K::choice, D::dimensionless, false, "mp4", "", {}, "mp4|none", "", "",
                "`mp4`: assemble the frames into animation.mp4 with ffmpeg (if installed); `none`: frames only."},
};
// clang-format on

std::string_view kind_name(const SchemaEntry& e) {
    switch (e.kind) {
        case K::map: return e.choices.empty() ? "map" : "map or word";
        case K::named_map: return "map of names";
        case K::list: return "list";
        case K::quantity: return "number";
        case K::integer: return "integer";
        case K::vector3: return "vector";
        case K::matrix3: return "3x3 matrix";
        case K::text: return "text";
        case K::choice: return "word";
        case K::name_list: return "list of names";
        case K::quantity_list: return "list of numbers";
    }
    return "";
}

std::string markdown_cell(std::string_view text) {
    std::string out;
    for (char c : text) {
        if (c == '|')
            out += "\\|";
        else
            out += c;
    }
    return out;
}

// The schema entries of the contact laws (contact/law_registry.h): `contacts.*.law`, then every
// parameter any law declares, once (laws that share a parameter declare it alike).
std::vector<SchemaEntry> law_entries() {
    static const std::string choices = [] {
        std::string c;
        for (const contact::LawEntry& law : contact::law_catalogue()) c += (c.empty() ? "" : "|") + std::string(law.name);
        return c;
    }();
    // The registry lists its default law first.
    static const std::string_view default_law = contact::law_catalogue().front().name;
    static const std::string law_doc = [] {
        std::string d = "The contact law of this pair (a `default` left out: `" + std::string(default_law) + "`):";
        for (const contact::LawEntry& law : contact::law_catalogue()) d += " `" + std::string(law.name) + "`: " + std::string(law.doc);
        return d;
    }();
    std::vector<SchemaEntry> out{
        SchemaEntry{"contacts.*.law", K::choice, D::dimensionless, false, default_law, "", {}, choices, "", "", law_doc}};
    static std::deque<std::string> paths;  // storage for the generated paths (entries hold views; a deque never moves them)
    static std::deque<std::string> docs;   // likewise for a key several laws declare: each law's doc
    for (const contact::LawEntry& law : contact::law_catalogue()) {
        for (const std::span<const contact::LawParameter> declared : {law.surface_parameters, law.shot_shot_parameters}) {
            for (const contact::LawParameter& p : declared) {
                const std::string path = "contacts.*." + std::string(p.name);
                SchemaEntry* known = nullptr;
                for (SchemaEntry& e : out)
                    if (e.path == path) known = &e;
                const std::string doc = "`" + std::string(law.name) + "`: " + std::string(p.doc);
                if (known != nullptr) {
                    // One key, several laws (same dimension and range: the catalogue test checks it).
                    if (known->doc.find(doc) != std::string_view::npos) continue;
                    docs.push_back(std::string(known->doc) + " " + doc);
                    known->doc = docs.back();
                    continue;
                }
                paths.push_back(path);
                docs.push_back(doc);
                out.push_back(SchemaEntry{paths.back(), p.list ? K::quantity_list : K::quantity, p.dimension, false, p.default_value,
                                          p.default_value.empty() ? "none (needed by the law)" : "", p.range, "", "", "", docs.back()});
            }
        }
    }
    return out;
}

const std::vector<SchemaEntry>& full_schema() {
    static const std::vector<SchemaEntry> table = [] {
        std::vector<SchemaEntry> t;
        for (const SchemaEntry& e : schema_table) {
            t.push_back(e);
            if (e.path == "contacts.*")
                for (const SchemaEntry& l : law_entries()) t.push_back(l);
        }
        return t;
    }();
    return table;
}

}  // namespace

std::span<const SchemaEntry> scene_schema() { return full_schema(); }

const SchemaEntry* find_schema_entry(std::string_view path) {
    for (const SchemaEntry& e : full_schema())
        if (e.path == path) return &e;
    return nullptr;
}

std::string schema_child_path(std::string_view parent, std::string_view key) {
    if (parent.empty()) return std::string(key);
    return std::string(parent) + "." + std::string(key);
}

std::vector<std::string_view> schema_child_keys(std::string_view map_path) {
    std::vector<std::string_view> keys;
    const std::string prefix = map_path.empty() ? std::string() : std::string(map_path) + ".";
    for (const SchemaEntry& e : full_schema()) {
        if (e.path.empty() || e.path.size() <= prefix.size() || e.path.substr(0, prefix.size()) != prefix) continue;
        const std::string_view rest = e.path.substr(prefix.size());
        if (rest.find_first_of(".[*") == std::string_view::npos) keys.push_back(rest);
    }
    return keys;
}

bool is_valid_name(std::string_view name) {
    if (name.empty()) return false;
    for (char c : name) {
        const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
        if (!ok) return false;
    }
    return true;
}

std::vector<std::string_view> split_choices(std::string_view choices) {
    std::vector<std::string_view> out;
    while (!choices.empty()) {
        const std::size_t bar = choices.find('|');
        out.push_back(choices.substr(0, bar));
        if (bar == std::string_view::npos) break;
        choices.remove_prefix(bar + 1);
    }
    return out;
}

std::string join_names(const std::vector<std::string_view>& names) {
    std::string out;
    for (std::string_view n : names) {
        if (!out.empty()) out += ", ";
        out += n;
    }
    return out;
}

std::string expected_text(const SchemaEntry& e) {
    switch (e.kind) {
        case K::map: {
            std::string s = "a map with keys " + join_names(schema_child_keys(e.path));
            if (!e.choices.empty()) s = std::string("'").append(e.choices).append("' or ").append(s);
            return s;
        }
        case K::named_map: return "a map of names to entries";
        case K::list: return "a list";
        case K::quantity: return std::string(dimension_noun(e.dimension));
        case K::integer: return "a whole number";
        case K::vector3: return "a vector of 3 numbers (" + std::string(si_unit(e.dimension)) + "), as [x, y, z] or \"x y z unit\"";
        case K::matrix3: return "a 3x3 matrix [[a, b, c], [d, e, f], [g, h, i]]";
        case K::text: return "a text";
        case K::choice: return "one of " + join_names(split_choices(e.choices));
        case K::name_list: return "a list of names, e.g. [a, b]";
        case K::quantity_list: {
            // "a number" -> "numbers", "a positive length" -> "positive lengths".
            std::string noun(dimension_noun(e.dimension));
            if (noun.rfind("a ", 0) == 0) noun.erase(0, 2);
            if (noun.rfind("an ", 0) == 0) noun.erase(0, 3);
            return "a list of one or more " + noun + "s, e.g. [0.4, 0.5]";
        }
    }
    return "a value";
}

std::string scene_reference_markdown() {
    std::string md;
    md += "### Scene file reference\n\n";
    md +=
        "Scene files are YAML. Quantities are plain numbers in SI units or text with a unit (\"2 mm\", "
        "\"20 kHz\", \"60 rpm\"). `[]` stands for each item of a list, `*` for a name you choose. "
        "Any value can be replaced from the command line with `--set path=value` "
        "(e.g. `--set shot.diameter=\"1 mm\"`, `--set components[gear].motion.speed=\"60 rpm\"`).\n\n";
    md += "| Key | Type | Unit (SI) | Default | Range | Description |\n";
    md += "|---|---|---|---|---|---|\n";
    for (const SchemaEntry& e : full_schema()) {
        if (e.path.empty()) continue;
        const bool has_unit = e.kind == K::quantity || e.kind == K::quantity_list || e.kind == K::vector3;
        const std::string unit = has_unit ? std::string(si_unit(e.dimension)) : std::string();
        std::string deflt;
        if (e.required)
            deflt = "required";
        else if (!e.default_value.empty())
            deflt = "`" + std::string(e.default_value) + "`";
        else
            deflt = std::string(e.default_note);
        std::string range = e.range.text();
        if (e.kind == K::choice) range = join_names(split_choices(e.choices));
        if (!e.plain_number_unit.empty())
            range += (range.empty() ? "" : "; ") + std::string("plain numbers in ") + std::string(e.plain_number_unit);
        md += "| `" + std::string(e.path) + "` | " + std::string(kind_name(e)) + " | " + markdown_cell(unit) + " | " +
              markdown_cell(deflt) + " | " + markdown_cell(range) + " | " + markdown_cell(e.doc) + " |\n";
    }
    md += "\n#### Units\n\n| Quantity | Accepted units (first is SI) |\n|---|---|\n";
    for (Dimension d : {D::length, D::time, D::frequency, D::speed, D::acceleration, D::density, D::stress, D::angle, D::angular_speed,
                        D::energy_per_area, D::viscosity, D::mass_flow}) {
        md += "| " + std::string(dimension_noun(d).substr(dimension_noun(d).find(' ') + 1)) + " | " +
              markdown_cell(accepted_units_text(d)) + " |\n";
    }
    return md;
}

}  // namespace peensim
