// OpenCASCADE's half of geometry/cad_reader.h: reads a STEP or IGES file and tessellates it under
// the contract described there. Built only into libpeensim_cad.so (module_entry.cpp), which a
// child process of peensim loads for each such part (geometry/cad_reader.cpp): OpenCASCADE's
// libraries cost every process that links them ~25 ms of start-up (their relocations and static
// constructors), which a run of STL parts must not pay.
#pragma once

#include <string>

#include "geometry/cad_reader.h"
#include "geometry/triangle_mesh.h"

namespace peensim {

// The tessellated surfaces of every solid and face in the file, in metres; throws InputError as
// read_cad_mesh (geometry/cad_reader.h) says.
TriangleMesh tessellate_cad_file(const std::string& path, const Tessellation& tessellation);

}  // namespace peensim
