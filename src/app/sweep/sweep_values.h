// When two values a sweep gives a scene field are the same value written differently ("1 mm",
// "1mm" and "0.001 m" of a length; "1", "+1" and "1e0" of a whole number; "[0,0,-9.81]" and
// "[0, 0, -9.81 m/s2]" of a vector): a sweep that ran both would run one variant twice.
#pragma once

#include <string>

namespace peensim {

// The value `text` gives the scene field `path` (an override path), in a form in which two
// writings of one value agree: numbers of the field's dimension in SI (the schema's unit for
// plain numbers applied), lists and maps element by element, other text as YAML reads it. Text
// the field cannot take stays as written (the variant's check refuses it).
std::string sweep_value_key(const std::string& path, const std::string& text);

}  // namespace peensim
