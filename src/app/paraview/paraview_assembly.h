// The whole assembly for ParaView, written by `peensim run` when it ends (finished or interrupted;
// not at its start, where a full disk would stop the run before its first checkpoint):
//
//   DIR/paraview/assembly.vtm               a multiblock, one block per component, named by it
//   DIR/paraview/assembly/<component>.vtp   its mesh in the world frame at t = 0
//
// Each block carries the cell array `role` (Int32: the ComponentRole code, 0 sonotrode, 1 chamber,
// 2 part, 3 fixture, 4 almen: colour by it) and field data naming it and saying how it moves, so a
// viewer can pose it at any time t (the closed form of model/kinematics.h):
//   component, role_name, motion ("fixed", "vibrating", "rotating")   texts
//   pose_rotation (9, row by row), pose_translation_m (3)              component frame -> world at rest
//   vibrating: vibration_axis (3), amplitude_m, frequency_hz, phase_rad
//              x_w(t) = R x_c + T + axis A sin(2 pi F t + phase)
//   rotating:  axis_point_m (3), axis_direction (3), angular_speed_rad_per_s
//              x_w(t) = P + Rot(u, omega t) (R x_c + T - P)
#pragma once

#include <string>

#include "model/model.h"

namespace peensim {

inline constexpr const char* kParaviewDirName = "paraview";  // in the run directory
inline constexpr const char* kAssemblyFileName = "assembly.vtm";

// Writes the files above (each atomically). Throws std::runtime_error when they cannot be written.
void write_paraview_assembly(const Model& model, const std::string& run_dir);

}  // namespace peensim
