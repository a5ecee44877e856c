#include "common/units.h"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>

namespace peensim {
namespace {

// One accepted unit: SI value = number / divisor * multiplier. Dividing first keeps exact results
// where people expect them ("25 um" == 25e-6, "60 rpm" == 2 pi rad/s, "90 deg" == pi/2).
struct UnitDef {
    std::string_view symbol;
    Dimension dimension;
    double multiplier;
    double divisor;
};

constexpr double pi = std::numbers::pi;

// SI unit of each dimension first; the order is the order shown in messages and in the reference.
constexpr std::array unit_table{
    UnitDef{"m", Dimension::length, 1.0, 1.0},
    UnitDef{"cm", Dimension::length, 1.0, 100.0},
    UnitDef{"mm", Dimension::length, 1.0, 1e3},
    UnitDef{"um", Dimension::length, 1.0, 1e6},
    UnitDef{"\u00b5m", Dimension::length, 1.0, 1e6},  // micro sign
    UnitDef{"\u03bcm", Dimension::length, 1.0, 1e6},  // Greek small mu
    UnitDef{"nm", Dimension::length, 1.0, 1e9},
    UnitDef{"in", Dimension::length, 0.0254, 1.0},
    UnitDef{"s", Dimension::time, 1.0, 1.0},
    UnitDef{"ms", Dimension::time, 1.0, 1e3},
    UnitDef{"us", Dimension::time, 1.0, 1e6},
    UnitDef{"\u00b5s", Dimension::time, 1.0, 1e6},
    UnitDef{"\u03bcs", Dimension::time, 1.0, 1e6},
    UnitDef{"min", Dimension::time, 60.0, 1.0},
    UnitDef{"h", Dimension::time, 3600.0, 1.0},
    UnitDef{"Hz", Dimension::frequency, 1.0, 1.0},
    UnitDef{"kHz", Dimension::frequency, 1e3, 1.0},
    UnitDef{"MHz", Dimension::frequency, 1e6, 1.0},
    UnitDef{"1/s", Dimension::frequency, 1.0, 1.0},
    UnitDef{"m/s", Dimension::speed, 1.0, 1.0},
    UnitDef{"cm/s", Dimension::speed, 1.0, 100.0},
    UnitDef{"mm/s", Dimension::speed, 1.0, 1e3},
    UnitDef{"km/h", Dimension::speed, 1e3, 3600.0},
    UnitDef{"m/s2", Dimension::acceleration, 1.0, 1.0},
    UnitDef{"m/s^2", Dimension::acceleration, 1.0, 1.0},
    UnitDef{"m/s\u00b2", Dimension::acceleration, 1.0, 1.0},
    UnitDef{"mm/s2", Dimension::acceleration, 1.0, 1e3},
    UnitDef{"mm/s^2", Dimension::acceleration, 1.0, 1e3},
    UnitDef{"kg/m3", Dimension::density, 1.0, 1.0},
    UnitDef{"kg/m^3", Dimension::density, 1.0, 1.0},
    UnitDef{"kg/m\u00b3", Dimension::density, 1.0, 1.0},
    UnitDef{"g/cm3", Dimension::density, 1e3, 1.0},
    UnitDef{"g/cm^3", Dimension::density, 1e3, 1.0},
    UnitDef{"g/cm\u00b3", Dimension::density, 1e3, 1.0},
    UnitDef{"Pa", Dimension::stress, 1.0, 1.0},
    UnitDef{"kPa", Dimension::stress, 1e3, 1.0},
    UnitDef{"MPa", Dimension::stress, 1e6, 1.0},
    UnitDef{"GPa", Dimension::stress, 1e9, 1.0},
    UnitDef{"N/m2", Dimension::stress, 1.0, 1.0},
    UnitDef{"N/mm2", Dimension::stress, 1e6, 1.0},
    UnitDef{"rad", Dimension::angle, 1.0, 1.0},
    UnitDef{"deg", Dimension::angle, pi, 180.0},
    UnitDef{"\u00b0", Dimension::angle, pi, 180.0},  // degree sign
    UnitDef{"rad/s", Dimension::angular_speed, 1.0, 1.0},
    UnitDef{"deg/s", Dimension::angular_speed, pi, 180.0},
    UnitDef{"rpm", Dimension::angular_speed, 2.0 * pi, 60.0},
    UnitDef{"rev/min", Dimension::angular_speed, 2.0 * pi, 60.0},
    UnitDef{"rev/s", Dimension::angular_speed, 2.0 * pi, 1.0},
    UnitDef{"J/m2", Dimension::energy_per_area, 1.0, 1.0},
    UnitDef{"kJ/m2", Dimension::energy_per_area, 1000.0, 1.0},
    UnitDef{"mJ/mm2", Dimension::energy_per_area, 1000.0, 1.0},
    UnitDef{"mJ/m2", Dimension::energy_per_area, 1.0, 1000.0},
    UnitDef{"Pa s", Dimension::viscosity, 1.0, 1.0},
    UnitDef{"Pa*s", Dimension::viscosity, 1.0, 1.0},
    UnitDef{"Pa.s", Dimension::viscosity, 1.0, 1.0},
    UnitDef{"mPa s", Dimension::viscosity, 1.0, 1e3},
    UnitDef{"cP", Dimension::viscosity, 1.0, 1e3},
    UnitDef{"kg/s", Dimension::mass_flow, 1.0, 1.0},
    UnitDef{"kg/min", Dimension::mass_flow, 1.0, 60.0},
    UnitDef{"kg/h", Dimension::mass_flow, 1.0, 3600.0},
    UnitDef{"g/s", Dimension::mass_flow, 1e-3, 1.0},
    UnitDef{"g/min", Dimension::mass_flow, 1e-3, 60.0},
};

std::string_view trim(std::string_view s) {
    const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
    return s;
}

const UnitDef* find_unit(std::string_view symbol, Dimension dim) {
    for (const UnitDef& u : unit_table)
        if (u.symbol == symbol && u.dimension == dim) return &u;
    return nullptr;
}

const UnitDef* find_unit_any_dimension(std::string_view symbol) {
    for (const UnitDef& u : unit_table)
        if (u.symbol == symbol) return &u;
    return nullptr;
}

// Reads the leading number of `text`; returns the number of characters used (0 = no number).
std::size_t read_leading_number(std::string_view text, double& value) {
    std::size_t skip = 0;
    if (!text.empty() && text.front() == '+') skip = 1;  // from_chars does not take a '+'
    const char* first = text.data() + skip;
    const char* last = text.data() + text.size();
    if (first == last || !(std::isdigit(static_cast<unsigned char>(*first)) || *first == '.' || (*first == '-' && skip == 0)))
        return 0;  // also keeps from_chars from reading "inf" / "nan"
    const auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::general);
    if (ec != std::errc()) return 0;
    value += 0.0;  // a typed -0 is 0: the echo, the resolved scene and the files then print "0", never "-0"
    return static_cast<std::size_t>(ptr - text.data());
}

std::string units_hint(Dimension dim) {
    if (dim == Dimension::dimensionless) return "a plain number (or a percentage: \"98 %\")";
    return std::string(dimension_noun(dim)) + " (a number in " + std::string(si_unit(dim)) + ", or a number with one of the units " +
           accepted_units_text(dim) + ")";
}

}  // namespace

std::string_view dimension_noun(Dimension dim) {
    switch (dim) {
        case Dimension::length: return "a length";
        case Dimension::time: return "a time";
        case Dimension::frequency: return "a frequency";
        case Dimension::speed: return "a speed";
        case Dimension::acceleration: return "an acceleration";
        case Dimension::density: return "a density";
        case Dimension::stress: return "a stress";
        case Dimension::angle: return "an angle";
        case Dimension::angular_speed: return "an angular speed";
        case Dimension::energy_per_area: return "an energy per area";
        case Dimension::viscosity: return "a dynamic viscosity";
        case Dimension::mass_flow: return "a mass flow";
        case Dimension::dimensionless: return "a number";
    }
    return "a quantity";
}

std::string_view si_unit(Dimension dim) {
    if (dim == Dimension::dimensionless) return "-";
    for (const UnitDef& u : unit_table)
        if (u.dimension == dim) return u.symbol;  // the table lists the SI unit first
    return "-";
}

std::vector<std::string_view> accepted_units(Dimension dim) {
    std::vector<std::string_view> out;
    for (const UnitDef& u : unit_table)
        if (u.dimension == dim) out.push_back(u.symbol);
    return out;
}

std::string accepted_units_text(Dimension dim) {
    std::string out;
    for (std::string_view s : accepted_units(dim)) {
        if (!out.empty()) out += ", ";
        out += s;
    }
    return out.empty() ? std::string("none") : out;
}

std::size_t leading_number_length(std::string_view text) {
    double ignored = 0.0;
    return read_leading_number(text, ignored);
}

bool parse_plain_number(std::string_view text, double& value) {
    text = trim(text);
    double v = 0.0;
    const std::size_t used = read_leading_number(text, v);
    if (used == 0 || used != text.size() || !std::isfinite(v)) return false;
    value = v;
    return true;
}

double parse_quantity(std::string_view text, Dimension dim, std::string_view plain_number_unit) {
    const std::string_view trimmed = trim(text);
    const std::string quoted = "'" + std::string(trimmed) + "'";
    double number = 0.0;
    const std::size_t used = read_leading_number(trimmed, number);
    if (used == 0) throw QuantityError("expected " + units_hint(dim) + ", got " + quoted);
    if (!std::isfinite(number)) throw QuantityError("expected a finite number, got " + quoted);
    std::string_view symbol = trim(trimmed.substr(used));
    if (symbol.empty()) symbol = plain_number_unit;
    if (symbol.empty()) return number;  // SI
    // A fraction may be written in per cent ("98 %").
    if (dim == Dimension::dimensionless && symbol == "%") return number / 100.0;
    if (dim == Dimension::dimensionless) throw QuantityError("expected a plain number (or a percentage: \"98 %\"), got " + quoted);
    if (const UnitDef* u = find_unit(symbol, dim)) {
        const double si = number / u->divisor * u->multiplier;
        if (!std::isfinite(si)) throw QuantityError("value out of range: " + quoted);
        return si;
    }
    if (const UnitDef* other = find_unit_any_dimension(symbol)) {
        std::string other_noun(dimension_noun(other->dimension));
        throw QuantityError("'" + std::string(symbol) + "' is a unit of " + other_noun.substr(other_noun.find(' ') + 1) + ", but " +
                            std::string(dimension_noun(dim)) + " is expected (" + quoted +
                            "); accepted units: " + accepted_units_text(dim));
    }
    throw QuantityError("unknown unit '" + std::string(symbol) + "' in " + quoted + " for " + std::string(dimension_noun(dim)) +
                        "; accepted units: " + accepted_units_text(dim));
}

std::string format_si(double value) {
    if (value == 0.0) value = 0.0;  // -0 (typed, or a computed direction's) prints as 0
    std::array<char, 64> buf{};
    const auto [ptr, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), value);
    if (ec != std::errc()) return "nan";
    return std::string(buf.data(), ptr);
}

}  // namespace peensim
