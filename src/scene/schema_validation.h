// The structural check of a scene tree against the schema, before any value is read: every key
// is known (else the valid keys are listed), no key appears twice, every node has the shape of its
// entry (map, list, scalar, vector), required keys are there, names are well formed.
#pragma once

#include "scene/yaml_access.h"

namespace peensim {

// Throws InputError at the first problem.
void check_structure(const Cursor& root);

}  // namespace peensim
