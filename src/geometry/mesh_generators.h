// Every mesh generator in one include. All work in metres and give outward normals on closed
// solids; the chamber surfaces (box_open with Facing::inward, stepped_tube_chamber) face the
// cavity instead.
#pragma once

#include "geometry/blade_mesh.h"
#include "geometry/box_mesh.h"
#include "geometry/cylinder_mesh.h"
#include "geometry/spur_gear_mesh.h"
#include "geometry/spur_gear_profile.h"
#include "geometry/spur_gear_resolution.h"
#include "geometry/stepped_chamber_mesh.h"
