// Which facets of a component the shot can reach at all: a shot centre must fit beside the surface
// (a radius and a hair along its normal; a solid only on its outer side) inside the shot's cavity
// (with a sonotrode: the chamber's, which excludes the inside of closed parts and sealed pockets)
// and clear of every component, in the assembly at t = 0. A bore that an axle fills, or a root
// fillet narrower than the shot, reads 0: no peening time covers it, so coverage leaves it out.
// The same test `check` uses for a part's share of reachable surface (assembly_checks.h).
#pragma once

#include <functional>
#include <vector>

#include "model/model.h"
#include "model/shot_cavity.h"

namespace peensim {

// Probe points per triangle: one per (2 R)^2 of its area, at most kReachProbesPerEdge^2.
inline constexpr int kReachProbesPerEdge = 4;

// Whether a shot of radius R (m) fits beside the surface point x (world, m) of component c, whose
// unit normal there is n (world): on its outer side for a solid, on either side otherwise.
// cavity: the shot's cavity (nullptr without a sonotrode: the clearance test alone).
bool shot_fits_beside(const Model& model, ShotCavity* cavity, const Component& c, const Vec3& x, const Vec3& n, double R);

// Per triangle of component `ci`: the share of its probe points a shot of the model's smallest
// radius can reach (0..1). A preview (render-regions before any run); the analysis decides reach
// per coverage sample (analysis/sample_classes.h) with reach_test below.
std::vector<double> reachable_fractions(const Model& model, std::size_t ci, ShotCavity* cavity);

// The reach of component ci's surface in the assembly at t = 0 as a test of (point, triangle, shot
// radius): point (m) and triangle in the component's own frame, shot radius in m. The model and
// the cavity must outlive it. It answers as shot_fits_beside, but a point near the last one the
// calling thread asked about on the same triangle may take that one's answer without a distance
// query, when the shot centre's clearance there leaves room (exactly: the distance moves no more
// than the centre). Safe from several threads at once.
std::function<bool(const Vec3& point_m, std::size_t triangle, double shot_radius_m)> reach_test(const Model& model, std::size_t ci,
                                                                                                ShotCavity* cavity);

// The per-sample reach is probed at R / kReachProbesPerRadius (R the smallest shot radius).
inline constexpr double kReachProbesPerRadius = 4.0;

}  // namespace peensim
