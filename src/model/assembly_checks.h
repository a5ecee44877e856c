// Setup mistakes the assembly can hide, found before any shot flies. Users found each of these
// passing `check` and running with exit 0: a rod moved wholly outside the chamber (no impacts), a
// rod lowered into the vibrating sonotrode (5.7x the impacts), a part through the lid, two parts
// overlapping, a gear 0.45 m up instead of 0.045 m, a rotating gear orbiting through the wall
// (axis_point left at the origin), a part mesh with a missing cap (shot got inside it).
//
// Errors (exit 2; the run does not start):
// - a part, fixture or Almen strip out of the shot's reach: less than kMinReachable of its
//   surface has room for a shot centre in the chamber's cavity beside it (ShotCavity);
// - one that intersects the sonotrode, anywhere in its travel (at rest and at +-A0), or another
//   part, fixture or strip: an edge of one crosses a face of the other;
// - a rotating part whose swept volume (its (r, z) profile about the axis, turned a full turn)
//   meets fixed geometry;
// - an open part, fixture or strip whose opening (boundary edges) has room for a shot beside it:
//   an opening sealed by a chamber wall (the rod's ends) is fine.
// Warnings (errors with --strict): a part, fixture or strip passing through a chamber wall (a
// shaft through a wall is a real design: the warning says where); degenerate facets dropped.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/input_error.h"
#include "model/model.h"
#include "model/shot_cavity.h"

namespace peensim {

struct AssemblyIssue {
    bool error = true;         // false: a warning (an error with --strict)
    SourceLocation where;      // the component's entry in the scene file
    std::string field;         // "components[2]", "components[2].mesh", ...
    std::string message;       // what is wrong, where (mm), what to check
    std::optional<Vec3> at_m;  // m, world: the point it names (two meshes crossing), marked in the check picture
};

// What `check` prints about each component.
struct ComponentFacts {
    Vec3 lo = Vec3::Zero(),
         hi = Vec3::Zero();  // m, world bounds at t = 0 (rotating: a sphere about the axis point holding the swept solid)
    Vec3 rest_lo = Vec3::Zero(), rest_hi = Vec3::Zero();  // m, the mesh's own world bounds at t = 0, as placed
    // A turning part: the exact bounds of the solid it sweeps in a turn (each vertex's circle), and
    // its farthest vertex from the axis (m); NaN for anything else.
    Vec3 swept_lo = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    Vec3 swept_hi = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    double swept_radius_m = std::numeric_limits<double>::quiet_NaN();
    std::size_t triangles = 0;
    bool closed = false;  // watertight mesh
    // m, nearest distance to the sonotrode at rest less its amplitude, and to the chamber; NaN if
    // not measured (the sonotrode and chambers themselves).
    double clearance_to_sonotrode_m = std::numeric_limits<double>::quiet_NaN();
    double clearance_to_chamber_m = std::numeric_limits<double>::quiet_NaN();
    // -, fraction of its surface with room for a shot beside it in the cavity; NaN if not measured.
    double reachable_fraction = std::numeric_limits<double>::quiet_NaN();
};

struct AssemblyReport {
    std::vector<ComponentFacts> components;  // in the model's order
    std::vector<AssemblyIssue> issues;
    std::size_t errors() const;
    std::size_t warnings() const;
};

inline constexpr double kMinReachable = 0.2;  // -, of a part's surface (a strip on its holder: ~0.5)

// cavity: the shot's cavity about the sonotrode; null for a scene without one (fed by sources):
// then only the checks that need neither are made.
AssemblyReport check_assembly(const Model& model, ShotCavity* cavity);

}  // namespace peensim
