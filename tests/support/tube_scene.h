// The tube: shot bouncing vertically between the vibrating floor (the sonotrode, 20 kHz) and the
// chamber's static ceiling, the engine's side of the exact 1D reference
// (support/vibrating_floor_reference.h). Titanium floor, steel ceiling; gravity along -z.
#pragma once

#include <string>

#include "support/test_scene.h"

namespace peensim::testing {

inline constexpr double kTubeFrequencyHz = 20e3;
inline constexpr double kTubeGravity = 9.81;  // m/s2
inline const PairSpec kTubeFloorPair{0.9, 1.5, 0.71, 0.1};
inline const PairSpec kTubeCeilingPair{0.95, 2.0, 0.71, 0.1};

// A chamber `width_m` square and `height_m` high (the ceiling above the floor's rest position),
// `shot_count` shot of radius `radius_m`, floor amplitude `amplitude_m`, impacts on the floor and
// the ceiling logged. The shot are to be set by the caller (set_shot).
inline TestSceneSpec tube_scene(const std::string& scheme, double width_m, double height_m, int shot_count, double radius_m,
                                double amplitude_m, double duration_s) {
    TestSceneSpec spec;
    spec.scheme = scheme;
    spec.chamber_size_m = Vec3(width_m, width_m, height_m);
    spec.shot_count = shot_count;
    spec.shot_diameter_m = 2.0 * radius_m;
    spec.amplitude_m = amplitude_m;
    spec.frequency_hz = kTubeFrequencyHz;
    spec.gravity_m_per_s2 = Vec3(0, 0, -kTubeGravity);
    spec.duration_s = duration_s;
    spec.sonotrode = kTubeFloorPair;
    spec.chamber = kTubeCeilingPair;
    spec.log = {"sonotrode", "chamber"};
    return spec;
}

}  // namespace peensim::testing
