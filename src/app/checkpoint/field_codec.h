// Bytes of a checkpoint's fields, written and read by walking the one field list
// (checkpoint_fields.h): values in native (little-endian) order, a list as its length then its
// items, counters as (name, count) pairs so that a renamed or missing counter is an error and
// never a shifted one.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/byte_stream.h"
#include "common/vec.h"
#include "engine/contact_states.h"
#include "engine/saved_state.h"
#include "output/speed_histogram.h"

namespace peensim {

class FieldWriter {
public:
    explicit FieldWriter(ByteWriter& out) : out_(out) {}

    template <class T>
    void value(const char*, const T& v, std::uint32_t) {
        put(v);
    }
    template <class T>
    void array(const char*, const std::vector<T>& v, std::uint32_t, Extent) {
        out_.put_vector(v);
    }
    template <class R, class Each>
    void records(const char*, const std::vector<R>& v, std::uint32_t, Extent, Each each) {
        out_.put<std::uint64_t>(v.size());
        for (const R& r : v) each(r, *this);
    }
    template <class Counters>
    void counters(const char*, const Counters& c, std::uint32_t) {
        std::uint64_t n = 0;
        c.for_each([&](const char*, std::uint64_t) { ++n; });
        out_.put(n);
        c.for_each([&](const char* name, std::uint64_t count) {
            out_.put_string(name);
            out_.put(count);
        });
    }
    void contact_states(const char*, const ContactStates& c, std::uint32_t) {
        out_.put(c.resolutions());
        out_.put<std::uint64_t>(c.entries().size());
        for (const auto& [key, entry] : c.entries()) {
            out_.put(key.first);
            out_.put(key.second);
            out_.put(entry.seen);
            out_.put_vector(entry.values);
        }
    }

private:
    template <class T>
    void put(const T& v) {
        out_.put(v);
    }
    void put(const Vec3& v) {
        for (int k = 0; k < 3; ++k) out_.put(v[k]);
    }
    void put(const SpeedHistogram& h) { out_.put_string(h.serialize()); }

    ByteWriter& out_;
};

// Throws std::runtime_error (from ByteReader: "<what>: truncated", or naming the field) on bytes
// that do not hold the list; load_checkpoint turns that into an input error naming the file.
class FieldReader {
public:
    explicit FieldReader(ByteReader& in) : in_(in) {}

    template <class T>
    void value(const char*, T& v, std::uint32_t) {
        get(v);
    }
    template <class T>
    void array(const char*, std::vector<T>& v, std::uint32_t, Extent) {
        v = in_.get_vector<T>();
    }
    template <class R, class Each>
    void records(const char* name, std::vector<R>& v, std::uint32_t, Extent, Each each) {
        const auto n = in_.get<std::uint64_t>();
        // Every record takes at least a byte: a larger count is damage, not a reason to allocate.
        if (n > in_.remaining()) in_.fail(std::string("more ") + name + " than the file has bytes");
        v.assign(n, R{});
        for (R& r : v) each(r, *this);
    }
    template <class Counters>
    void counters(const char* name, Counters& c, std::uint32_t) {
        const auto n = in_.get<std::uint64_t>();
        std::uint64_t declared = 0;
        c.for_each([&](const char*, std::uint64_t&) { ++declared; });
        if (n != declared) in_.fail(std::to_string(n) + " " + name + " counters, expected " + std::to_string(declared));
        for (std::uint64_t k = 0; k < n; ++k) {
            const std::string counter = in_.get_string();
            const auto count = in_.get<std::uint64_t>();
            bool known = false;
            c.for_each([&](const char* declared_name, std::uint64_t& value) {
                if (counter == declared_name) value = count, known = true;
            });
            if (!known) in_.fail(std::string("an unknown ") + name + " counter '" + counter + "'");
        }
    }
    void contact_states(const char* name, ContactStates& c, std::uint32_t) {
        const auto resolutions = in_.get<std::uint64_t>();
        const auto n = in_.get<std::uint64_t>();
        if (n > in_.remaining()) in_.fail(std::string("more ") + name + " than the file has bytes");
        std::map<ContactStates::Key, ContactStates::Entry> entries;
        for (std::uint64_t k = 0; k < n; ++k) {
            ContactStates::Key key;
            key.first = in_.get<int>();
            key.second = in_.get<int>();
            ContactStates::Entry e;
            e.seen = in_.get<std::uint64_t>();
            e.values = in_.get_vector<double>();
            entries.emplace(key, std::move(e));
        }
        c.restore(resolutions, std::move(entries));
    }

private:
    template <class T>
    void get(T& v) {
        v = in_.get<T>();
    }
    void get(Vec3& v) {
        for (int k = 0; k < 3; ++k) v[k] = in_.get<double>();
    }
    void get(SpeedHistogram& h) { h = SpeedHistogram::deserialize(in_.get_string()); }

    ByteReader& in_;
};

}  // namespace peensim
