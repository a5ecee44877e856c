// The flat hash map of the analysis's grids: every key found after any number of insertions and
// growths, absent keys not, each entry visited once.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>

#include "analysis/cube_keys.h"
#include "common/flat_key_map.h"

namespace peensim {
namespace {

TEST(FlatKeyMap, HoldsWhatAnOrderedMapHoldsThroughGrowth) {
    FlatKeyMap<std::uint32_t> map;  // starts small: grows many times
    std::map<std::uint64_t, std::uint32_t> truth;
    std::mt19937_64 rng(7);
    for (std::uint32_t i = 0; i < 200000; ++i) {
        // Cube keys of a block of space (neighbours differ in a few bits) and random keys.
        const std::uint64_t key = i % 2 == 0 ? cube_key(i % 97, (i / 97) % 89, i / (97 * 89), static_cast<int>(i % 7) - 1) : rng();
        const auto [value, added] = map.try_emplace(key, i);
        const auto [it, truth_added] = truth.try_emplace(key, i);
        ASSERT_EQ(added, truth_added);
        ASSERT_EQ(*value, it->second);
    }
    EXPECT_EQ(map.size(), truth.size());
    for (const auto& [key, value] : truth) {
        const std::uint32_t* found = map.find(key);
        ASSERT_NE(found, nullptr);
        EXPECT_EQ(*found, value);
    }
    for (int i = 0; i < 1000; ++i) {
        const std::uint64_t absent = rng();
        EXPECT_EQ(map.contains(absent), truth.count(absent) == 1);
    }
    std::size_t visited = 0;
    map.for_each([&](std::uint64_t key, std::uint32_t value) {
        ++visited;
        EXPECT_EQ(truth.at(key), value);
    });
    EXPECT_EQ(visited, truth.size());
}

TEST(FlatKeyMap, IndexingAddsADefaultValueOnce) {
    FlatKeyMap<double> map(4);
    EXPECT_TRUE(map.empty());
    map[42] += 1.5;
    map[42] += 2.0;
    map[0] += 1.0;  // key 0 is a key like any other
    EXPECT_EQ(map.size(), 2u);
    EXPECT_EQ(*map.find(42), 3.5);
    EXPECT_EQ(*map.find(0), 1.0);
    EXPECT_EQ(map.find(43), nullptr);
}

}  // namespace
}  // namespace peensim
