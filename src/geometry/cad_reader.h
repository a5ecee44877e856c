// Reads a STEP (.step, .stp) or IGES (.iges, .igs) file with OpenCASCADE and tessellates its exact
// surfaces into a TriangleMesh in metres, under the contract of mesh_loader.h: welded vertices
// (so a closed solid comes out closed), triangles counter-clockwise seen from outside, a facet
// number and a group per triangle.
//
// Units: the file's own. OpenCASCADE converts the lengths of a STEP or IGES file from the unit the
// file declares (STEP: its LENGTH_UNIT; IGES: the global section's unit) into its session unit
// (millimetres unless `xstep.cascade.unit` says otherwise); the reader asks for that session unit
// and scales to metres. There is no unit to give: a scene's `mesh_unit` does not apply to these
// files (the scene parser refuses it).
//
// Tessellation (OpenCASCADE's BRepMesh_IncrementalMesh, absolute tolerances, on the faces' inside
// as on their edges): no point of a triangle lies farther than `chordal_m` from the surface it
// stands for, and no triangle edge turns the surface's normal by more than `angular_rad` (its
// normal is then within about half that of the true normal). The chordal tolerance bounds the
// position error, the angular one the normal error where surfaces curve tightly (fillets, small
// holes), where a chordal tolerance alone leaves a few wide facets.
// Default chordal tolerance 0.01 mm: a 2 mm shot's dents are 0.2-0.5 mm across and ~0.01 mm deep,
// so the facets stand within a dent's depth of the true surface; on a 5 mm radius it means
// facets of 7 deg and a normal within 3.6 deg of the true one. Default angular tolerance 5 deg:
// an impact normal within 2.5 deg of the true one (sin 2.5 deg = 4 % of the normal speed turned
// tangential; cos 2.5 deg loses 0.1 % of it), at 72 facets around any round, however small.
// docs/step-iges.md measures what the tolerance does to a run's results.
//
// Facets (TriangleMesh::source_facet): one per B-rep face, numbered from 0 in the order below;
// every triangle of a face carries its face's number. Groups: one per solid, "solid1",
// "solid2", ... in the file's order (OpenCASCADE's explorer order; product names are not read),
// then "surface" for faces that belong to no solid (a surface model: read like an open mesh
// file; the setup checks say it is open). A face met twice (an assembly placing one part twice)
// is numbered at each placement. Vertices are welded by position after the placements are
// applied (within 1e-9 of the model's size: OpenCASCADE gives each face its own triangulation,
// whose nodes on a shared edge coincide only in position); triangles of zero area after welding
// are dropped (dropped_degenerate_facets counts the faces that lose all theirs).
//
// OpenCASCADE is optional at build time (PEENSIM_HAVE_OCCT); without it every call throws an
// InputError that says which packages to install. With it, the reading itself is in the module
// libpeensim_cad.so (src/cad/), which a child process loads for each call (cad_reader.cpp says
// why): OpenCASCADE's libraries cost every process that links them ~25 ms of start-up, which a
// run of STL parts must not pay, and on some damaged files its reader dies of SIGSEGV.
#pragma once

#include <string>

#include "geometry/triangle_mesh.h"

namespace peensim {

struct Tessellation {
    double chordal_m = 0.01e-3;                                 // m, largest distance from a triangle to the exact surface (> 0)
    double angular_rad = 5.0 * 3.14159265358979323846 / 180.0;  // rad, largest turn of the surface normal along a triangle edge (> 0)
};

// Whether this build reads STEP and IGES (it was built with OpenCASCADE).
bool cad_reading_available();

// What libpeensim_cad.so exports (one C symbol returns it: peensim_cad_module). read: the file's
// mesh into `mesh`; false with the problem (the InputError's, for the file's field "mesh") when
// the file cannot be read.
struct CadModule {
    bool (*read)(const std::string& path, const Tessellation& tessellation, TriangleMesh& mesh, std::string& problem);
};

// Throws the InputError read_cad_mesh(path, ...) throws when this installation cannot read any
// STEP or IGES file (built without OpenCASCADE, or its module does not load), without reading
// `path`: what a sweep checks before it starts its runs. The module is tried in a child, as for a
// read, once per value of PEENSIM_CAD_MODULE.
void require_cad_reading(const std::string& path);

// The tessellated surfaces of every solid and face in the file, in metres.
// Throws InputError (file = path, field "mesh") if OpenCASCADE is not built in, the file cannot be
// read (empty, not STEP/IGES, a syntax error: OpenCASCADE's own message is quoted), holds no face
// (only curves or points, or nothing), a face cannot be tessellated, or no triangle of non-zero
// area results; or if a tolerance is not a positive finite number.
TriangleMesh read_cad_mesh(const std::string& path, const Tessellation& tessellation);

}  // namespace peensim
