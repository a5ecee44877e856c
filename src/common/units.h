// Physical quantities written by people ("2 mm", "20 kHz", "60 rpm") -> SI doubles, and back.
// Every unit is tied to one dimension, so "2 kHz" given for a length is rejected with the list of
// units that would have been accepted. A plain number means SI (m, s, Hz, m/s, m/s2, kg/m3, Pa, rad,
// rad/s) unless the caller names another unit for plain numbers (Euler angles are in degrees).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace peensim {

inline constexpr double kMetresPerInch = 0.0254;  // m, exact (Almen intensities are quoted in inches)

enum class Dimension {
    length,           // m
    time,             // s
    frequency,        // Hz
    speed,            // m/s
    acceleration,     // m/s2
    density,          // kg/m3
    stress,           // Pa
    angle,            // rad
    angular_speed,    // rad/s
    energy_per_area,  // J/m2 (a kinetic-energy dose)
    viscosity,        // Pa s (dynamic viscosity)
    mass_flow,        // kg/s
    dimensionless,    // -
};

// Thrown for a malformed number, an unknown unit or a unit of the wrong dimension. The message
// says what was expected (the accepted units); callers add the file, line and field.
class QuantityError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// "a length", "a frequency", ... (for messages).
std::string_view dimension_noun(Dimension dim);

// The SI unit symbol of a dimension ("m", "m/s2", "-" for dimensionless).
std::string_view si_unit(Dimension dim);

// Every unit symbol accepted for a dimension, SI unit first ("m, cm, mm, um, µm, nm, in").
std::vector<std::string_view> accepted_units(Dimension dim);
std::string accepted_units_text(Dimension dim);

// Parses "2 mm", "2mm", "1e-3", "1e-3 m", "60 rpm" into SI. `plain_number_unit` is the unit of a
// number written without one ("" = SI). Rejects non-finite numbers. Throws QuantityError.
double parse_quantity(std::string_view text, Dimension dim, std::string_view plain_number_unit = {});

// Length of the number at the start of `text` ("-5mm" -> 2), 0 if it does not start with one.
std::size_t leading_number_length(std::string_view text);

// Parses a plain decimal number ("2", "-1.5e-3", "+4"), nothing else; false if it is not one.
bool parse_plain_number(std::string_view text, double& value);

// Shortest text that reads back to exactly `value` ("0.002", "20000", "6.283185307179586"); -0 as "0".
std::string format_si(double value);

}  // namespace peensim
