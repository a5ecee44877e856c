// A triangle mesh in its component's own frame (metres), as loaded from a mesh file.
// Vertices are welded (identical positions share one index) so that edges are shared;
// every triangle remembers the facet of the source file it came from.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/vec.h"

namespace peensim {

struct TriangleMesh {
    std::vector<Vec3> vertices;                 // m, component frame
    std::vector<std::array<int, 3>> triangles;  // indices into vertices, counter-clockwise seen from the normal side
    std::vector<int> source_facet;              // per triangle: facet index in the mesh file (0-based)
    std::vector<std::string> group_names;       // named solids / sub-meshes of the file ("" if unnamed)
    std::vector<int> group_of_triangle;         // per triangle: index into group_names
    std::size_t dropped_degenerate_facets = 0;  // facets of the file dropped by the loader: zero area after welding
    std::string declared_unit;                  // a STEP or IGES file's own length unit as it names it ("MM", "INCH"); "" for mesh files

    std::size_t triangle_count() const { return triangles.size(); }
    const Vec3& corner(std::size_t t, int k) const { return vertices[static_cast<std::size_t>(triangles[t][static_cast<std::size_t>(k)])]; }
};

}  // namespace peensim
