// Which facets of a component the shot can reach at all: a shot centre must fit beside the surface
// (a radius and a hair along its normal; a solid only on its outer side) inside the shot's cavity
// (with a sonotrode: the chamber's, which excludes the inside of closed parts and sealed pockets)
// and clear of every component, in the assembly at t = 0. A bore that an axle fills, or a root
// fillet narrower than the shot, reads 0: no peening time covers it, so coverage leaves it out.
// The same test `check` uses for a part's share of reachable surface (assembly_checks.h).
#pragma once

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
// radius can reach (0..1).
std::vector<double> reachable_fractions(const Model& model, std::size_t ci, ShotCavity* cavity);

}  // namespace peensim
