// Regions of a component: its scene's `regions` entries turned into lists of triangles. A triangle
// belongs to a region when its centroid lies inside the selection (component frame, m), so a
// region's area is a sum of whole triangles. Pure computation: no file I/O, no printing.
#pragma once

#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "scene/scene_description.h"

namespace peensim {

struct Region {
    std::string name;
    std::vector<int> triangles;  // indices into the mesh's triangles, increasing
};

// One Region per name of each entry, in order (a `sectors` entry gives `count` regions, sector i
// centred at offset + i 2 pi / count). Angles are taken in [from, to) modulo a full turn, so
// sectors that tile the full turn put every triangle in exactly one of them.
// Throws InputError (at the entry's place in the scene file) for a `group` the mesh does not have.
std::vector<Region> select_regions(const TriangleMesh& mesh, const std::vector<RegionDesc>& regions);

}  // namespace peensim
