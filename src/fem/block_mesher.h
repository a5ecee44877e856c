// The target block under a patch: a box of the part's material meshed with 8-node bricks on a
// tensor-product grid, uniform (element size h) in a fine zone under the impacts and growing
// geometrically away from it, sideways and in depth. Patch frame: the surface is z = 0, the
// material is z < 0, x and y span the tangent plane. A quarter model keeps x >= 0, y >= 0 (the
// planes x = 0 and y = 0 are symmetry planes). Pure computation: no I/O.
#pragma once

#include <vector>

#include "fem/hex_mesh.h"

namespace peensim {

struct BlockMeshSpec {
    double half_width_m = 0.0;       // m, the block spans [-w, w] in x and y (quarter: [0, w])
    double depth_m = 0.0;            // m, the block spans [-depth, 0] in z
    double fine_half_width_m = 0.0;  // m, uniform elements for |x|, |y| <= this (clipped to the block)
    double fine_depth_m = 0.0;       // m, uniform elements for z >= -this (clipped to the block)
    double element_size_m = 0.0;     // m, h: edge of the fine zone's elements
    double growth = 1.3;             // -, ratio of neighbouring element edges outside the fine zone (>= 1)
    bool quarter = false;            // quarter model (x >= 0, y >= 0)
};

struct BlockMesh {
    HexMesh mesh;
    std::vector<double> xs, ys, zs;               // m, grid coordinates, increasing (zs from -depth to 0)
    std::vector<int> top, bottom;                 // node indices on z = 0 and z = -depth
    std::vector<int> x_min, x_max, y_min, y_max;  // node indices on the four sides
    std::vector<int> top_elements;                // elements of the top layer: their face S2 is the surface
    std::vector<int> profile;                     // top nodes on y = 0, x >= 0, by increasing x (the dent profile)
    std::vector<int> axis_elements;  // the column of elements under the centre (x, y in [0, h]), top first: the residual stress vs depth
};

// Grid coordinates from 0 to `length`: uniform edges of about `h` up to `fine` (the count rounded
// up, so edges are <= h), then edges growing by `growth` until `length` (the last ones scaled to end
// exactly there, never below the last fine edge). Throws std::invalid_argument for non-positive sizes.
std::vector<double> graded_axis(double length, double fine, double h, double growth);

// Throws std::invalid_argument for an impossible spec (non-positive sizes, growth < 1).
BlockMesh mesh_block(const BlockMeshSpec& spec);

// The elements mesh_block(spec) would make, from its grid lines alone (nothing meshed): for a
// limit checked before the work. Throws as mesh_block does.
double block_element_count(const BlockMeshSpec& spec);

}  // namespace peensim
