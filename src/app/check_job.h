// `peensim check`: validate a scene completely (parse, load meshes, build the model, place the
// shot) without running it, and print the resolved scene with every default filled in.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace peensim {

int check_job(const std::string& scene_path, const std::vector<std::string>& overrides, std::ostream& out, std::ostream& err);

}  // namespace peensim
