// The scene file `peensim new` writes: the design (scene_design.h) as YAML, each choice with a
// comment that says why, so the file teaches what to change.
#pragma once

#include <string>

#include "app/new_scene/proposed_regions.h"
#include "app/new_scene/scene_design.h"

namespace peensim {

struct NewSceneFiles {
    std::string part_name;     // the component's name (from the part file's name)
    std::string part_mesh;     // the part's file, as the scene refers to it (relative to the scene's folder)
    std::string unit_name;     // the part file's unit as the scene spells it (mm, cm, m, in); "": a STEP or IGES file's own
    std::string chamber_mesh;  // the generated meshes, relative to the scene's folder
    std::string sonotrode_mesh;
    std::string command;  // the command that wrote it (for the header)
};

std::string new_scene_yaml(const SceneDesign& design, const NewSceneRequest& request, const PartMaterial& material,
                           const ProposedRegions& regions, const NewSceneFiles& files);

}  // namespace peensim
