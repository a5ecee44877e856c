// Measurements and sanity checks of a TriangleMesh: areas, enclosed volume, edge topology,
// bounds. All lengths in the mesh's own unit (m for meshes from load_mesh or a generator).
#pragma once

#include <cstddef>

#include "geometry/triangle_mesh.h"

namespace peensim {

// Unit normal of triangle t from its winding (right-hand rule: counter-clockwise corners
// around the normal); the zero vector for a degenerate triangle. File normals are never used.
Vec3 triangle_normal(const TriangleMesh& mesh, std::size_t t);

double triangle_area(const TriangleMesh& mesh, std::size_t t);  // m2
// Which edge of triangle t point p (m) lies on (within 1e-6 of its longest edge): k for the edge from
// corner k to corner (k + 1) % 3, the nearest at a corner; -1 inside. Where a sphere touching a
// convex edge or corner of the mesh touches it.
int triangle_edge_at(const TriangleMesh& mesh, std::size_t t, const Vec3& p);
inline bool on_triangle_edge(const TriangleMesh& mesh, std::size_t t, const Vec3& p) { return triangle_edge_at(mesh, t, p) >= 0; }
double surface_area(const TriangleMesh& mesh);  // m2, sum over all triangles

// m3, signed volume by the divergence theorem. For a closed mesh whose normals point out of
// the solid it is the solid's volume (positive); inward-facing normals give minus the volume.
// Meaningless for an open mesh.
double enclosed_volume(const TriangleMesh& mesh);

struct EdgeReport {
    std::size_t edges = 0;               // distinct undirected edges
    std::size_t boundary_edges = 0;      // used by exactly one triangle (a hole or an open rim)
    std::size_t non_manifold_edges = 0;  // used by three or more triangles
    std::size_t misoriented_edges = 0;   // used by two triangles that run it in the same direction
    // Watertight (is_closed): edges, each shared by exactly two triangles.
    bool closed() const { return edges > 0 && boundary_edges == 0 && non_manifold_edges == 0; }
};
EdgeReport edge_report(const TriangleMesh& mesh);

// Watertight: every edge is shared by exactly two triangles. (Orientation is a separate
// question: see EdgeReport::misoriented_edges and the sign of enclosed_volume.)
bool is_closed(const TriangleMesh& mesh);

struct Bounds {
    Vec3 min_m = Vec3::Zero();  // m, smallest x, y, z over the vertices used by triangles
    Vec3 max_m = Vec3::Zero();  // m, largest x, y, z
    Vec3 size_m() const { return max_m - min_m; }
};
// Axis-aligned bounds of the triangles' corners; zero bounds for a mesh without triangles.
Bounds bounds(const TriangleMesh& mesh);

}  // namespace peensim
