// Work in a fixed number of chunks on any number of threads: every chunk once, the chunks' ranges
// tile the items, a failure reaches the caller, a cancelled thread starts no more,
// a call takes on the threads its count gains.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
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

// Work abandoned on its own thread: once its flag is set no more chunks start, on that thread and
// on its helpers, and the call throws ChunksCancelled; the calls of other threads go on.
TEST(ParallelChunks, ACancelledThreadStartsNoMoreChunks) {
    std::atomic<bool> cancel{false};
    std::atomic<int> ran{0};
    chunk_cancel = &cancel;
    // One thread takes the chunks in order: 0 to 3 run, then the flag stops the rest.
    EXPECT_THROW(for_each_chunk(
                     16,
                     [&](std::size_t c) {
                         ++ran;
                         if (c == 3) cancel = true;
                     },
                     1),
                 ChunksCancelled);
    EXPECT_EQ(ran.load(), 4);
    ran = 0;
    EXPECT_THROW(for_each_chunk(
                     8, [&](std::size_t) { ++ran; }, 4),
                 ChunksCancelled);
    EXPECT_EQ(ran.load(), 0);
    EXPECT_THROW(throw_if_chunks_cancelled(), ChunksCancelled);
    // Another thread never pointed its flag anywhere.
    std::thread([&] {
        for_each_chunk(
            8, [&](std::size_t) { ++ran; }, 2);
        throw_if_chunks_cancelled();
    }).join();
    EXPECT_EQ(ran.load(), 8);
    chunk_cancel = nullptr;
    for_each_chunk(
        8, [&](std::size_t) { ++ran; }, 2);
    EXPECT_EQ(ran.load(), 16);
}

TEST(ParallelChunks, TheThreadCountCanBeSetAndReset) {
    set_analysis_threads(3);
    EXPECT_EQ(analysis_threads(), 3u);
    std::atomic<unsigned> here{5};
    chunk_threads_here = &here;  // this thread's own: work done ahead beside a run
    EXPECT_EQ(analysis_threads(), 5u);
    std::thread([] { EXPECT_EQ(analysis_threads(), 3u); }).join();
    here = 0;  // the run gave its cores up: the default again
    EXPECT_EQ(analysis_threads(), 3u);
    chunk_threads_here = nullptr;
    EXPECT_EQ(analysis_threads(), 3u);
    set_analysis_threads(0);
    EXPECT_GE(analysis_threads(), 1u);
}

// A call begun on one thread takes on more at its next chunk once its count grows (the run it
// worked beside is done), and still runs each chunk once.
TEST(ParallelChunks, ACallTakesOnTheThreadsItsCountGainsWhileItRuns) {
    std::atomic<unsigned> here{1};
    chunk_threads_here = &here;
    std::mutex mutex;
    std::set<std::thread::id> threads;
    std::vector<int> ran(24, 0);
    for_each_chunk(ran.size(), [&](std::size_t c) {
        if (c == 0) here = 3;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        const std::lock_guard<std::mutex> lock(mutex);
        threads.insert(std::this_thread::get_id());
        ++ran[c];
    });
    chunk_threads_here = nullptr;
    EXPECT_EQ(std::count(ran.begin(), ran.end(), 1), 24);
    EXPECT_GE(threads.size(), 2u);
    EXPECT_LE(threads.size(), 3u);
    // An explicit count stays what it is.
    here = 1;
    chunk_threads_here = &here;
    threads.clear();
    for_each_chunk(
        8,
        [&](std::size_t c) {
            if (c == 0) here = 4;
            const std::lock_guard<std::mutex> lock(mutex);
            threads.insert(std::this_thread::get_id());
        },
        1);
    chunk_threads_here = nullptr;
    EXPECT_EQ(threads.size(), 1u);
}

}  // namespace
}  // namespace peensim
