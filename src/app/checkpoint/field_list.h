// The names of a checkpoint's fields and the format version that added each, in file order
// ("lost[].radius_m", "health.search_fallbacks"): what an older file lacks, and what the tests
// hold the version to.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/vec.h"
#include "engine/contact_states.h"
#include "engine/saved_state.h"

namespace peensim {

struct FieldName {
    std::string name;
    std::uint32_t since = 0;
};

class FieldLister {
public:
    template <class T>
    void value(const char* name, T&, std::uint32_t since) {
        add(name, since);
    }
    template <class T>
    void array(const char* name, std::vector<T>&, std::uint32_t since, Extent) {
        add(name, since);
    }
    template <class R, class Each>
    void records(const char* name, std::vector<R>&, std::uint32_t since, Extent, Each each) {
        add(name, since);
        const std::string outer = prefix_;
        prefix_ += std::string(name) + "[].";
        R one{};
        each(one, *this);
        prefix_ = outer;
    }
    template <class Counters>
    void counters(const char* name, Counters& c, std::uint32_t since) {
        c.for_each([&](const char* counter, auto&) { add((std::string(name) + "." + counter).c_str(), since); });
    }
    void contact_states(const char* name, ContactStates&, std::uint32_t since) { add(name, since); }

    const std::vector<FieldName>& names() const { return names_; }

private:
    void add(const char* name, std::uint32_t since) { names_.push_back({prefix_ + name, since}); }

    std::vector<FieldName> names_;
    std::string prefix_;
};

}  // namespace peensim
