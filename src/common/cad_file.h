// Which mesh files are CAD files (STEP, IGES): exact surfaces that geometry/cad_reader.h tessellates,
// in the length unit the file states, rather than triangles in a unit the scene gives. Here in
// common/ because the scene parser (which may not include geometry/) refuses `mesh_unit` on them
// and takes `tessellation` only for them.
#pragma once

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

namespace peensim {

// "step" of "dir/Part.STEP": the file name's extension in lower case, "" if it has none.
inline std::string lower_extension(std::string_view path) {
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of('/');
    if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return {};
    std::string ext(path.substr(dot + 1));
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return ext;
}

// By the extension, case-insensitive: .iges, .igs (IGES 5.3).
inline bool is_iges_file(std::string_view path) {
    const std::string ext = lower_extension(path);
    return ext == "iges" || ext == "igs";
}

// By the extension, case-insensitive: .step, .stp (ISO 10303-21) or an IGES file.
inline bool is_cad_file(std::string_view path) {
    const std::string ext = lower_extension(path);
    return ext == "step" || ext == "stp" || is_iges_file(path);
}

}  // namespace peensim
