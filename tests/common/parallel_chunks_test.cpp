// Work in a fixed number of chunks on any number of threads: every chunk once, the chunks' ranges
// tile the items, a failure reaches the caller.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "common/parallel_chunks.h"

namespace peensim {
namespace {

TEST(ParallelChunks, EveryChunkRunsOnceOnAnyNumberOfThreads) {
    for (unsigned threads : {1u, 2u, 3u, 16u}) {
        std::vector<std::atomic<int>> runs(37);
        for_each_chunk(
            runs.size(), [&](std::size_t c) { ++runs[c]; }, threads);
        for (const auto& r : runs) EXPECT_EQ(r.load(), 1) << threads << " threads";
    }
    for_each_chunk(0, [](std::size_t) { FAIL() << "no chunk to run"; });
}

TEST(ParallelChunks, TheRangesTileTheItems) {
    for (std::size_t n : {0u, 1u, 5u, 1000u})
        for (std::size_t chunks : {1u, 3u, 32u}) {
            std::size_t next = 0;
            for (std::size_t c = 0; c < chunks; ++c) {
                const auto [begin, end] = chunk_range(n, chunks, c);
                EXPECT_EQ(begin, next);
                EXPECT_LE(begin, end);
                next = end;
            }
            EXPECT_EQ(next, n);
        }
}

TEST(ParallelChunks, AFailureInAChunkReachesTheCaller) {
    EXPECT_THROW(for_each_chunk(
                     8,
                     [](std::size_t c) {
                         if (c == 5) throw std::runtime_error("chunk 5");
                     },
                     2),
                 std::runtime_error);
}

TEST(ParallelChunks, TheThreadCountCanBeSetAndReset) {
    set_analysis_threads(3);
    EXPECT_EQ(analysis_threads(), 3u);
    set_analysis_threads(0);
    EXPECT_GE(analysis_threads(), 1u);
}

}  // namespace
}  // namespace peensim
