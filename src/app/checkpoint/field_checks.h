// The checks every field of a checkpoint gets from the one field list (checkpoint_fields.h): a
// list has the length its extent says (one per shot, per component, ...), and every floating
// value is a number (a shot's only while it is active: a lost shot's slot keeps what it had).
// What a field means (a time within the run, a shot inside the assembly, a contact between a pair
// that exists) is checked by check_resumable.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "common/vec.h"
#include "engine/contact_states.h"
#include "engine/saved_state.h"
#include "output/speed_histogram.h"

namespace peensim {

// Each extent's expected length (Extent::free's unused), indexed by the extent.
using ExtentLengths = std::array<std::size_t, static_cast<std::size_t>(Extent::free) + 1>;

// Throws std::runtime_error naming the field ("shots.vx: expected 16 values, one per shot, got
// 15"; "lost[2].where_m: not a number"; "shot 3: shots.x is not a number").
class FieldChecker {
public:
    // `active`: the shot slots in use.
    FieldChecker(const ExtentLengths& lengths, const std::vector<unsigned char>& active) : lengths_(lengths), active_(active) {}

    template <class T>
    void value(const char* name, const T& v, std::uint32_t) {
        if (!finite(v)) fail(name, "not a number");
    }
    void value(const char*, const SpeedHistogram&, std::uint32_t) {}  // checked as it is read

    template <class T>
    void array(const char* name, const std::vector<T>& v, std::uint32_t, Extent extent) {
        check_length(name, v.size(), extent);
        if constexpr (std::is_floating_point_v<T>) {
            for (std::size_t i = 0; i < v.size(); ++i) {
                if (std::isfinite(v[i])) continue;
                if (extent != Extent::shots) fail(name + std::string("[") + std::to_string(i) + "]", "not a number");
                if (i < active_.size() && active_[i] != 0)
                    throw std::runtime_error("shot " + std::to_string(i) + ": " + prefix_ + name + " is not a number");
            }
        }
    }
    template <class R, class Each>
    void records(const char* name, const std::vector<R>& v, std::uint32_t, Extent extent, Each each) {
        check_length(name, v.size(), extent);
        const std::string outer = prefix_;
        for (std::size_t k = 0; k < v.size(); ++k) {
            prefix_ = outer + name + "[" + std::to_string(k) + "].";
            each(v[k], *this);
        }
        prefix_ = outer;
    }
    template <class Counters>
    void counters(const char*, const Counters&, std::uint32_t) {}  // any count is a count
    void contact_states(const char* name, const ContactStates& c, std::uint32_t) {
        for (const auto& [key, entry] : c.entries())
            for (double x : entry.values)
                if (!std::isfinite(x))
                    fail(name, "the contact of shot " + std::to_string(key.first) + " with component " + std::to_string(key.second) +
                                   " holds a value that is not a number");
    }

private:
    static bool finite(const Vec3& v) { return v.allFinite(); }
    template <std::size_t N>
    static bool finite(const std::array<double, N>& v) {
        return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
    }
    template <class T>
    static bool finite(const T& v) {
        if constexpr (std::is_floating_point_v<T>)
            return std::isfinite(v);
        else
            return true;
    }
    void check_length(const char* name, std::size_t n, Extent extent) const {
        if (extent == Extent::free) return;
        static constexpr std::array<const char*, std::tuple_size_v<ExtentLengths>> kEach{
            "shot slot", "component", "logged component", "shot source", "shot sink", "shot size", ""};
        const std::size_t expected = lengths_[static_cast<std::size_t>(extent)];
        if (n != expected)
            fail(name, "expected " + std::to_string(expected) + " values, one per " + kEach[static_cast<std::size_t>(extent)] + ", got " +
                           std::to_string(n));
    }
    [[noreturn]] void fail(const std::string& name, const std::string& problem) const {
        throw std::runtime_error(prefix_ + name + ": " + problem);
    }

    ExtentLengths lengths_;
    const std::vector<unsigned char>& active_;
    std::string prefix_;
};

}  // namespace peensim
