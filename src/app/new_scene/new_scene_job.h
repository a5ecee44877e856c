// `peensim new PART`: a ready scene around a user's part. Reads the part, sizes a chamber and a
// sonotrode for it (scene_design.h), writes their meshes and a commented scene file, and prints
// what it chose and what to run next. Never writes over an existing file unless forced, and never
// over the part.
#pragma once

#include <iosfwd>
#include <string>

namespace peensim {

struct NewSceneOptions {
    std::string part_path;
    std::string unit;                // the part file's length unit: mm, cm, m, um, in ("": mm; a STEP or IGES file's own)
    std::string rotate_about;        // "", x, y or z: the part's own axis through its centre
    std::string rpm;                 // with rotate_about: the speed ("30", "30 rpm")
    std::string material = "steel";  // steel, aluminium, titanium
    std::string shot_diameter = "2 mm";
    std::string scene_path;    // "" = <part's name>.yaml in the current folder
    bool force = false;        // write over an earlier `new`'s files
    std::string command_line;  // for the scene's header
};

int new_scene_job(const NewSceneOptions& options, std::ostream& out, std::ostream& err);

}  // namespace peensim
