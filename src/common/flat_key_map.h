// A hash map from 64-bit keys to small values in two flat arrays (open addressing, linear
// probing): for the grids of the analysis (cube keys -> cell or voxel numbers), looked up tens of
// millions of times a run, where std::unordered_map's node per entry costs a cache miss a look-up.
// Keys are any 64-bit value but kEmpty; an insertion may move the values (hold numbers, not
// pointers, across insertions). No erase.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace peensim {

template <class V>
class FlatKeyMap {
public:
    static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // the one key a map cannot hold

    FlatKeyMap() { reserve(0); }
    explicit FlatKeyMap(std::size_t expected) { reserve(expected); }

    // Room for n keys without growing.
    void reserve(std::size_t n) {
        const std::size_t wanted = std::bit_ceil(std::max<std::size_t>(16, 2 * n));  // at most half full
        if (wanted > keys_.size()) rehash(wanted);
    }

    const V* find(std::uint64_t key) const {
        for (std::size_t i = slot(key);; i = (i + 1) & mask_) {
            if (keys_[i] == key) return &values_[i];
            if (keys_[i] == kEmpty) return nullptr;
        }
    }
    V* find(std::uint64_t key) { return const_cast<V*>(std::as_const(*this).find(key)); }
    bool contains(std::uint64_t key) const { return find(key) != nullptr; }

    // The value of key, inserting `value` if it has none; whether it was inserted.
    std::pair<V*, bool> try_emplace(std::uint64_t key, const V& value) {
        if (2 * (size_ + 1) > keys_.size()) rehash(2 * keys_.size());
        std::size_t i = slot(key);
        for (; keys_[i] != kEmpty; i = (i + 1) & mask_)
            if (keys_[i] == key) return {&values_[i], false};
        keys_[i] = key;
        values_[i] = value;
        ++size_;
        return {&values_[i], true};
    }
    V& operator[](std::uint64_t key) { return *try_emplace(key, V{}).first; }

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }

    // f(key, value) for every entry, in no particular order.
    template <class F>
    void for_each(F&& f) const {
        for (std::size_t i = 0; i < keys_.size(); ++i)
            if (keys_[i] != kEmpty) f(keys_[i], values_[i]);
    }

private:
    // Fibonacci hashing: the key's product's top bits, so keys that differ only in high bits
    // (a cube's z) spread as well as those that differ in low ones.
    std::size_t slot(std::uint64_t key) const { return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_); }

    void rehash(std::size_t capacity) {
        std::vector<std::uint64_t> keys(capacity, kEmpty);
        std::vector<V> values(capacity);
        keys.swap(keys_);
        values.swap(values_);
        mask_ = capacity - 1;
        shift_ = 64 - std::countr_zero(capacity);
        size_ = 0;
        for (std::size_t i = 0; i < keys.size(); ++i)
            if (keys[i] != kEmpty) try_emplace(keys[i], values[i]);
    }

    std::vector<std::uint64_t> keys_;
    std::vector<V> values_;
    std::size_t mask_ = 0;
    int shift_ = 64;
    std::size_t size_ = 0;
};

}  // namespace peensim
