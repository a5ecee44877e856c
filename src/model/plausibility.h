// Values far outside the process window, which a valid scene may still hold by a slip: warnings
// (errors with --strict), each saying what was probably meant. Users found `amplitude: 25` (25 m:
// the run took 457 s for 0.05 s and lost 137 of 140 shot) and an inch STL read as mm (a 2.5 mm
// gear) passing without a word.
// - the sonotrode's amplitude above 1 mm, its frequency outside 1-100 kHz;
// - a shot larger than a tenth of the chamber's smallest inner extent;
// - gravity neither ~9.81 m/s2 nor zero (weightless);
// - a mesh whose size is implausible in its mesh_unit (a part or chamber under 1 mm or over 2 m
//   across; a part under a twentieth of the chamber, which inches would make plausible), naming
//   the unit it probably is (not for a STEP or IGES file: it states its own unit);
// - a plain number for a length in a scene that gives units elsewhere (the parser notes them);
// - a rotating part whose rim runs faster than kPlausibleRimSpeed_m_per_s (an error above
//   kLargestRimSpeed_m_per_s: no part survives it, and the run would crawl);
// - shot starting faster than kPlausibleStartSpeed_m_per_s.
#pragma once

#include <vector>

#include "model/assembly_checks.h"
#include "model/model.h"

namespace peensim {

inline constexpr double kLargestPlausibleMesh_m = 2.0;         // m across: a larger part or chamber is a unit slip (or no USP chamber)
inline constexpr double kSmallestPlausibleMesh_m = 1e-3;       // m across
inline constexpr double kPlausibleRimSpeed_m_per_s = 100.0;    // m/s
inline constexpr double kLargestRimSpeed_m_per_s = 1000.0;     // m/s: sources[].speed's limit too
inline constexpr double kPlausibleStartSpeed_m_per_s = 100.0;  // m/s

std::vector<AssemblyIssue> plausibility_issues(const Model& model);

}  // namespace peensim
